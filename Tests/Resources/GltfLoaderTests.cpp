// The glTF 2.0 loader: node transforms, primitive modes, index types, attributes and materials on hand-built assets; every variant of a file (embedded, .bin, .glb) alike; bad files are one-line errors; and, natively, world-space triangles equal those of assimp's OBJ export.
#include "TestFramework.hpp"

#include <algorithm>
#include <iterator>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "Resources/FileIO.hpp"
#include "Resources/Gltf/GltfLoader.hpp"
#include "Resources/Image.hpp"
#include "Resources/ObjLoader.hpp"
#include "GltfTestUtil.hpp"
#include "ObjTestUtil.hpp"

using namespace sr;
using namespace sr::objtest;
using sr::gltftest::Asset;

namespace {

// The one-triangle asset: (0,0,0), (1,0,0), (0,1,0), u16 indices, under `nodes` (mesh 0).
Asset triangleAsset(const std::string& nodes) {
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int idx = a.indices({0, 1, 2}, 5123);
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"indices\":" +
               std::to_string(idx) + "}]}]";
    a.nodes = nodes;
    return a;
}

Result<Model> load(const std::string& dir, const std::string& name, const std::string& text) {
    return loadGltf(writeText(dir, name, text));
}

void checkVec(Vec3 v, float x, float y, float z) {
    CHECK(v.x == Approx(x).margin(1e-6));
    CHECK(v.y == Approx(y).margin(1e-6));
    CHECK(v.z == Approx(z).margin(1e-6));
}

// The loader's error for `text`: must fail, in one line naming the file.
std::string errorOf(const std::string& dir, const std::string& name, const std::string& text) {
    auto r = load(dir, name, text);
    REQUIRE_FALSE(r.ok());
    INFO(r.error());
    CHECK(contains(r.error(), name));
    CHECK(r.error().find('\n') == std::string::npos);
    return r.error();
}

} // namespace

TEST_CASE("glTF nodes: nested TRS and matrix transforms place the vertices in world space", "[resources][gltf]") {
    const std::string dir = freshDir("gltf-nodes");
    // Node 0: T(10, 0, 0) R(90 degrees about z) S(2), child node 1: a matrix T(0, 0, 5), the mesh.
    // World = T R S T5: (0,0,0) -> (0,0,5) -> (0,0,10) -> (0,0,10) -> (10, 0, 10)
    //                   (1,0,0) -> (1,0,5) -> (2,0,10) -> (0,2,10) -> (10, 2, 10)
    //                   (0,1,0) -> (0,1,5) -> (0,2,10) -> (-2,0,10) -> (8, 0, 10)
    const Asset a = triangleAsset(
        "[{\"translation\":[10,0,0],\"rotation\":[0,0,0.7071067811865476,0.7071067811865476],\"scale\":[2,2,2],"
        "\"children\":[1]},{\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1],\"mesh\":0}]");
    auto r = load(dir, "nodes.gltf", a.embedded());
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.mesh.vertexCount() == 3);
    REQUIRE(m.mesh.indices == std::vector<std::uint32_t>{0, 1, 2});
    checkVec(m.mesh.positions[0], 10, 0, 10);
    checkVec(m.mesh.positions[1], 10, 2, 10);
    checkVec(m.mesh.positions[2], 8, 0, 10);
    // No NORMAL: the area-weighted normal of the world-space triangle, (0,2,0) x (-2,0,0) = +z.
    for (const Vec3& n : m.mesh.normals) checkVec(n, 0, 0, 1);
    CHECK_FALSE(m.normalsFromFile);
    CHECK_FALSE(m.hasUvs);
    checkVec(m.boundsMin, 8, 0, 10);
    checkVec(m.boundsMax, 10, 2, 10);
    REQUIRE(m.ranges.size() == 1);
    CHECK(m.ranges[0].material == 0); // the glTF default material, appended
    CHECK(m.ranges[0].indexCount == 3);
}

TEST_CASE("glTF primitives: triangles, strips and fans; u8, u16, u32 and no indices", "[resources][gltf]") {
    const std::string dir = freshDir("gltf-modes");
    Asset a;
    std::vector<float> p;
    for (int k = 0; k < 6; ++k) p.insert(p.end(), {float(k), float(k * k), 0.0f});
    const int six = a.floats(p, "VEC3");
    const int five = a.floats(std::vector<float>(p.begin(), p.begin() + 15), "VEC3");
    const int u8 = a.indices({0, 1, 2, 3, 4}, 5121);
    const int u32 = a.indices({4, 3, 2, 1, 0}, 5125);
    // With normals (without, each triangle would get vertices of its own: the flat-normal test).
    std::vector<float> up;
    for (int k = 0; k < 6; ++k) up.insert(up.end(), {0.0f, 0.0f, 1.0f});
    const int n6 = a.floats(up, "VEC3");
    const int n5 = a.floats(std::vector<float>(up.begin(), up.begin() + 15), "VEC3");
    const auto attr = [](int acc, int nrm) {
        return "{\"POSITION\":" + std::to_string(acc) + ",\"NORMAL\":" + std::to_string(nrm) + "}";
    };
    a.meshes = "[{\"primitives\":[{\"attributes\":" + attr(six, n6) + "},"                                     // triangles, no indices
               "{\"attributes\":" + attr(five, n5) + ",\"indices\":" + std::to_string(u8) + ",\"mode\":5}," // strip
               "{\"attributes\":" + attr(five, n5) + ",\"indices\":" + std::to_string(u32) + ",\"mode\":6}]}]"; // fan
    a.nodes = "[{\"mesh\":0}]";
    auto r = load(dir, "modes.gltf", a.embedded());
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.mesh.vertexCount() == 6 + 5 + 5);
    // Triangles: 0..5. Strip over 6..10 (glTF: triangle i is (i, i+1, i+2) for even i and
    // (i+1, i, i+2) for odd i, the winding kept): (6,7,8), (8,7,9), (8,9,10). Fan over the
    // indices 4,3,2,1,0 of 11..15 (glTF: triangle i is (i+1, i+2, 0)): (14,13,15), (13,12,15),
    // (12,11,15).
    const std::vector<std::uint32_t> expected{0, 1, 2, 3, 4, 5, 6, 7, 8, 8, 7, 9, 8, 9, 10, 14, 13, 15, 13, 12, 15, 12, 11, 15};
    CHECK(m.mesh.indices == expected);
    REQUIRE(m.ranges.size() == 1);
    CHECK(m.ranges[0].indexCount == expected.size());
}

TEST_CASE("glTF: a mirroring node keeps front faces counter-clockwise; normals go by the inverse transpose",
          "[resources][gltf]") {
    const std::string dir = freshDir("gltf-mirror");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const float s = 0.70710678f;
    const int nrm = a.floats({s, s, 0, s, s, 0, s, s, 0}, "VEC3");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" +
               std::to_string(nrm) + "}}]}]";
    SECTION("scale (-1, 1, 1): the triangle's winding is reversed") {
        a.nodes = "[{\"scale\":[-1,1,1],\"mesh\":0}]";
        auto r = load(dir, "mirror.gltf", a.embedded());
        REQUIRE(r.ok());
        const Mesh& mesh = r.value().mesh;
        CHECK(mesh.indices == std::vector<std::uint32_t>{0, 2, 1});
        const Vec3 p0 = mesh.positions[mesh.indices[0]], p1 = mesh.positions[mesh.indices[1]], p2 = mesh.positions[mesh.indices[2]];
        const Vec3 n = cross(p1 - p0, p2 - p0);
        CHECK(n.z > 0.0f); // counter-clockwise seen from +z, as in the file
        // The normal (1,1,0)/sqrt2 mirrored: (-1, 1, 0)/sqrt2.
        checkVec(mesh.normals[0], -s, s, 0);
        CHECK(r.value().normalsFromFile);
    }
    SECTION("scale (2, 1, 1): the normal (1,1,0)/sqrt2 becomes (1/2, 1, 0) normalised") {
        a.nodes = "[{\"scale\":[2,1,1],\"mesh\":0}]";
        auto r = load(dir, "stretch.gltf", a.embedded());
        REQUIRE(r.ok());
        CHECK(r.value().mesh.indices == std::vector<std::uint32_t>{0, 1, 2});
        checkVec(r.value().mesh.normals[1], 0.4472136f, 0.8944272f, 0); // (0.5, 1, 0) / sqrt(1.25)
        checkVec(r.value().mesh.positions[1], 2, 0, 0);
    }
}

TEST_CASE("glTF points, lines, line loops and strips become world-space line sets", "[resources][gltf][lines]") {
    const std::string dir = freshDir("gltf-lines");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 5, 5, 5}, "VEC3"); // 5 vertices
    const int idx = a.indices({0, 1, 2, 3}, 5123);
    const auto prim = [&](int mode, bool indexed) {
        return "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}" +
               (indexed ? ",\"indices\":" + std::to_string(idx) : std::string()) + ",\"mode\":" + std::to_string(mode) + "}";
    };
    a.meshes = "[{\"primitives\":[" + prim(0, false) + "," + prim(1, true) + "," + prim(2, true) + "," + prim(3, true) + "]}]";
    a.nodes = "[{\"translation\":[10,0,0],\"mesh\":0}]";
    auto r = load(dir, "lines.gltf", a.embedded());
    REQUIRE(r.ok());
    const Model& m = r.value();
    CHECK(m.mesh.triangleCount() == 0);
    REQUIRE(m.lineSets.size() == 4);
    CHECK(m.lineSets[0].points);
    CHECK(m.lineSets[0].indices == std::vector<std::uint32_t>{0, 1, 2, 3, 4});
    CHECK_FALSE(m.lineSets[1].points);
    CHECK(m.lineSets[1].indices == std::vector<std::uint32_t>{0, 1, 2, 3}); // LINES: pairs
    CHECK(m.lineSets[2].indices == std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3, 3, 0}); // LINE_LOOP closes
    CHECK(m.lineSets[3].indices == std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3});       // LINE_STRIP
    checkVec(m.lineSets[0].positions[2], 11, 1, 0); // world space: the node's translation applied
    checkVec(m.boundsMin, 10, 0, 0);                // bounds from the lines alone
    checkVec(m.boundsMax, 15, 5, 5);
}

TEST_CASE("glTF TEXCOORD_0: float or normalised u16, v flipped to OBJ's convention", "[resources][gltf]") {
    const std::string dir = freshDir("gltf-uv");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uvFloat = a.floats({0.25f, 0.125f, 1, 0, 0, 1}, "VEC2");
    const int uvShort = a.normalizedShorts({0, 65535, 65535, 0, 32768, 16384}, "VEC2");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" +
               std::to_string(uvFloat) + "}},{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" +
               std::to_string(uvShort) + "}},{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
    a.nodes = "[{\"mesh\":0}]";
    auto r = load(dir, "uv.gltf", a.embedded());
    REQUIRE(r.ok());
    const Model& m = r.value();
    CHECK(m.hasUvs);
    REQUIRE(m.mesh.uvs.size() == 9);
    // glTF (0, 0) is the image's top-left; ours (OBJ) v = 0 is its bottom row: v' = 1 - v.
    CHECK(m.mesh.uvs[0].x == 0.25f);
    CHECK(m.mesh.uvs[0].y == 0.875f);
    CHECK(m.mesh.uvs[1].y == 1.0f);
    CHECK(m.mesh.uvs[3].x == 0.0f); // 0 / 65535
    CHECK(m.mesh.uvs[3].y == 0.0f); // 1 - 65535 / 65535
    CHECK(m.mesh.uvs[4].x == 1.0f);
    CHECK(m.mesh.uvs[5].x == Approx(32768.0 / 65535.0).epsilon(1e-7));
    CHECK(m.mesh.uvs[5].y == Approx(1.0 - 16384.0 / 65535.0).epsilon(1e-7));
    for (std::size_t i = 6; i < 9; ++i) CHECK(m.mesh.uvs[i].x == 0.0f); // a primitive without uvs
}

TEST_CASE("glTF COLOR_0: float RGB, normalised u8 and u16 RGBA; white where a primitive has none; bad ones refused",
          "[resources][gltf][pbr]") {
    const std::string dir = freshDir("gltf-colour");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int rgb = a.floats({0.25f, 0.5f, 0.75f, 1, 0, 0, 0, 0.125f, 2}, "VEC3");
    const int rgba8 = a.unsignedBytes({255, 0, 51, 102, 0, 255, 0, 255, 128, 128, 128, 0}, "VEC4");
    const int rgba16 = a.normalizedShorts({65535, 0, 13107, 65535, 0, 65535, 0, 32768, 1, 2, 3, 4}, "VEC4");
    const auto prim = [&](int colour) {
        return "{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
               (colour >= 0 ? ",\"COLOR_0\":" + std::to_string(colour) : std::string()) + "}}";
    };
    a.meshes = "[{\"primitives\":[" + prim(-1) + "," + prim(rgb) + "," + prim(rgba8) + "," + prim(rgba16) + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    std::string text = a.embedded();
    // The u8 accessor is normalised (COLOR_0 allows no other integers).
    const std::string u8 = "\"componentType\":5121";
    REQUIRE(text.find(u8) != std::string::npos);
    text.replace(text.find(u8), u8.size(), u8 + ",\"normalized\":true");
    auto r = load(dir, "colour.gltf", text);
    REQUIRE(r.ok());
    const Mesh& mesh = r.value().mesh;
    REQUIRE(mesh.hasColours());
    REQUIRE(mesh.colours.size() == 12);
    const auto check = [&](std::size_t i, float red, float green, float blue, float alpha) {
        INFO("vertex " << i);
        CHECK(mesh.colours[i].r == Approx(red).epsilon(1e-6));
        CHECK(mesh.colours[i].g == Approx(green).epsilon(1e-6));
        CHECK(mesh.colours[i].b == Approx(blue).epsilon(1e-6));
        CHECK(mesh.colours[i].a == Approx(alpha).epsilon(1e-6));
    };
    for (std::size_t i = 0; i < 3; ++i) check(i, 1, 1, 1, 1); // the primitive before the first colours: white
    check(3, 0.25f, 0.5f, 0.75f, 1); // RGB: alpha 1
    check(5, 0, 0.125f, 2, 1);       // float colours as written
    check(6, 1, 0, 0.2f, 0.4f);      // u8 / 255
    check(8, 128.0f / 255, 128.0f / 255, 128.0f / 255, 0);
    check(9, 1, 0, 0.2f, 1);         // u16 / 65535
    check(11, 1.0f / 65535, 2.0f / 65535, 3.0f / 65535, 4.0f / 65535);
    // Refused: integers not normalised, two components, a count that differs from POSITION's.
    Asset b;
    const int bpos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int raw = b.unsignedBytes({1, 2, 3, 4, 5, 6, 7, 8, 9}, "VEC3");
    const int two = b.floats({1, 1, 1, 1, 1, 1}, "VEC2");
    const int short4 = b.floats({1, 1, 1, 1, 1, 1, 1, 1}, "VEC4");
    for (const int colour : {raw, two, short4}) {
        b.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(bpos) + ",\"COLOR_0\":" +
                   std::to_string(colour) + "}}]}]";
        b.nodes = "[{\"mesh\":0}]";
        const std::string e = errorOf(dir, "badcolour.gltf", b.embedded());
        INFO(e);
        if (colour == short4) CHECK(contains(e, "COLOR_0: count differs from POSITION's"));
        else CHECK(contains(e, "COLOR_0: must be float or normalised unsigned byte/short VEC3 or VEC4"));
    }
}

TEST_CASE("glTF materials: metallic-roughness mapped to Blinn-Phong; one range per material in first use",
          "[resources][gltf][materials]") {
    const std::string dir = freshDir("gltf-materials");
    Asset a = triangleAsset("");
    const std::string prim = "{\"attributes\":{\"POSITION\":0},\"indices\":1";
    a.meshes = "[{\"primitives\":[" + prim + ",\"material\":1}," + prim + "}," + prim + ",\"material\":0}]}," + "{\"primitives\":[" +
               prim + ",\"material\":2}," + prim + ",\"material\":1}]}]";
    a.nodes = "[{\"mesh\":0,\"children\":[1]},{\"mesh\":1}]";
    a.materials = "[{\"name\":\"paint\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.4,0.2,1],"
                  "\"metallicFactor\":0,\"roughnessFactor\":0.5}},"
                  "{\"name\":\"gold\",\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.5,0.25,1],"
                  "\"metallicFactor\":1,\"roughnessFactor\":0}},"
                  "{\"name\":\"default\"}]";
    auto r = load(dir, "materials.gltf", a.embedded());
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.materials.size() == 4); // the file's three, then the default for the primitive without one
    // paint: kd = base (metal 0), ks = 0.04, shininess 2 / 0.5^4 - 2 = 30.
    CHECK(m.materials[0].name == "paint");
    CHECK(m.materials[0].kd.r == 0.8f);
    CHECK(m.materials[0].kd.b == 0.2f);
    CHECK(m.materials[0].ks.g == 0.04f);
    CHECK(m.materials[0].shininess == 30.0f);
    // gold: kd = 0 (metal 1), ks = base, roughness 0: the largest shininess, 1024.
    CHECK(m.materials[1].kd.r == 0.0f);
    CHECK(m.materials[1].ks.r == 1.0f);
    CHECK(m.materials[1].ks.g == 0.5f);
    CHECK(m.materials[1].ks.b == 0.25f);
    CHECK(m.materials[1].shininess == 1024.0f);
    // The glTF defaults (base 1, metallic 1, roughness 1): kd 0, ks 1, shininess 2 / 1 - 2 = 0 -> 1.
    CHECK(m.materials[2].kd.g == 0.0f);
    CHECK(m.materials[2].ks.g == 1.0f);
    CHECK(m.materials[2].shininess == 1.0f);
    for (const Material& mat : m.materials) {
        CHECK(mat.fromFile);
        CHECK_FALSE(mat.hasMap);
    }
    // doubleSided: false unless the file says true (glTF's default).
    CHECK_FALSE(m.materials[0].doubleSided);
    CHECK(m.materials[1].doubleSided);
    CHECK_FALSE(m.materials[2].doubleSided);
    // First use: gold (mesh 0), none (the default material, appended: 3), paint, "default"
    // (mesh 1), and gold again joins its range.
    REQUIRE(m.ranges.size() == 4);
    const int order[] = {1, 3, 0, 2};
    for (std::size_t i = 0; i < 4; ++i) CHECK(m.ranges[i].material == order[i]);
    CHECK(m.ranges[0].indexCount == 6);
    CHECK(m.ranges[3].firstIndex + m.ranges[3].indexCount == m.mesh.indices.size());
}

TEST_CASE("glTF: a primitive without NORMAL gets flat normals, one vertex per triangle corner", "[resources][gltf]") {
    const std::string dir = freshDir("gltf-flat");
    // A roof: two triangles sharing the ridge (0,1,0)-(0,1,1), one sloping to -x, one to +x.
    // Smoothed, the ridge vertices would get the average (0,1,0); flat, each triangle keeps its own.
    Asset a;
    const int pos = a.floats({0, 1, 0, 0, 1, 1, -1, 0, 0, 1, 0, 0}, "VEC3");
    const int idx = a.indices({0, 1, 2, 1, 0, 3}, 5123);
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"indices\":" +
               std::to_string(idx) + "}]}]";
    a.nodes = "[{\"mesh\":0}]";
    auto r = load(dir, "roof.gltf", a.embedded());
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.mesh.vertexCount() == 6);
    CHECK(m.mesh.indices == std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5});
    checkVec(m.mesh.positions[0], 0, 1, 0);
    checkVec(m.mesh.positions[3], 0, 1, 1);
    checkVec(m.mesh.positions[5], 1, 0, 0);
    // (p1 - p0) x (p2 - p0): (0,0,1) x (-1,-1,0) = (1,-1,0) -> normalised; the other (0,0,-1) x (1,-1,-1).
    const float h = 0.70710678f;
    for (int k = 0; k < 3; ++k) checkVec(m.mesh.normals[std::size_t(k)], h, -h, 0);
    for (int k = 3; k < 6; ++k) checkVec(m.mesh.normals[std::size_t(k)], -h, -h, 0);
    CHECK_FALSE(m.normalsFromFile);
}

TEST_CASE("glTF materials: the metallic-roughness input, emissive strength and the maps' slots",
          "[resources][gltf][materials][pbr]") {
    const std::string dir = freshDir("gltf-pbr");
    Image one;
    one.width = one.height = 1;
    one.rgba = {10, 20, 30, 255};
    for (const char* name : {"base.png", "mr.png", "em.png", "nrm.png", "occ.png", "spec.png", "specc.png", "cc.png", "ccr.png", "ccn.png", "sh.png", "shr.png"})
        REQUIRE(writeImage(dir + "/" + name, one).ok());
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" +
               std::to_string(uv) + "},\"material\":0},{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
               ",\"TEXCOORD_0\":" + std::to_string(uv) + "},\"material\":1}]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.materials = "[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,0.125,0.75],\"metallicFactor\":0.3,"
                  "\"roughnessFactor\":0.6,\"baseColorTexture\":{\"index\":0},\"metallicRoughnessTexture\":{\"index\":1}},"
                  "\"emissiveFactor\":[1,0.5,0],\"emissiveTexture\":{\"index\":2},"
                  "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4},"
                  "\"KHR_materials_specular\":{\"specularTexture\":{\"index\":5},\"specularColorTexture\":{\"index\":6}},"
                  "\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1,\"clearcoatTexture\":{\"index\":7},"
                  "\"clearcoatRoughnessTexture\":{\"index\":8},\"clearcoatNormalTexture\":{\"index\":9}},"
                  "\"KHR_materials_sheen\":{\"sheenColorFactor\":[0.5,1.5,0.25],\"sheenRoughnessFactor\":0.75,"
                  "\"sheenColorTexture\":{\"index\":10},\"sheenRoughnessTexture\":{\"index\":11}}},"
                  "\"normalTexture\":{\"index\":3,\"scale\":0.5},\"occlusionTexture\":{\"index\":4,\"strength\":0.25}},"
                  "{\"name\":\"plain\"}]";
    a.extra = ",\"extensionsUsed\":[\"KHR_materials_emissive_strength\",\"KHR_materials_specular\",\"KHR_materials_clearcoat\","
              "\"KHR_materials_sheen\"],"
              "\"images\":[{\"uri\":\"base.png\"},{\"uri\":\"mr.png\"},{\"uri\":\"em.png\"},{\"uri\":\"nrm.png\"},{\"uri\":\"occ.png\"},"
              "{\"uri\":\"spec.png\"},{\"uri\":\"specc.png\"},{\"uri\":\"cc.png\"},{\"uri\":\"ccr.png\"},{\"uri\":\"ccn.png\"},"
              "{\"uri\":\"sh.png\"},{\"uri\":\"shr.png\"}],"
              "\"textures\":[{\"source\":0},{\"source\":1},{\"source\":2},{\"source\":3},{\"source\":4},"
              "{\"source\":5},{\"source\":6},{\"source\":7},{\"source\":8},{\"source\":9},{\"source\":10},{\"source\":11}]";
    auto r = load(dir, "pbr.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.materials.size() == 2);
    const Material& k = m.materials[0];
    REQUIRE(k.pbr.has_value());
    CHECK(k.pbr->baseColor.r == 0.5f);
    CHECK(k.pbr->baseColor.g == 0.25f);
    CHECK(k.pbr->baseColor.b == 0.125f);
    CHECK(k.pbr->baseColor.a == 0.75f);
    CHECK(k.pbr->metallic == Approx(0.3f));
    CHECK(k.pbr->roughness == Approx(0.6f));
    checkVec(k.pbr->emissive, 4.0f, 2.0f, 0.0f); // emissiveFactor x emissiveStrength
    CHECK(k.pbr->normalScale == 0.5f);
    CHECK(k.pbr->occlusionStrength == 0.25f);
    CHECK_FALSE(k.pbr->unlit);
    // KHR_materials_sheen: its colour clamped to [0, 1], its roughness.
    checkVec(k.pbr->sheenColor, 0.5f, 1.0f, 0.25f);
    CHECK(k.pbr->sheenRoughness == 0.75f);
    // Twelve distinct images: twelve textures, each map in the slot of its own image.
    CHECK(m.textures.size() == 12);
    REQUIRE(m.texturePaths.size() == m.textures.size());
    const auto imageOf = [&](int texture) {
        return texture >= 0 && std::size_t(texture) < m.texturePaths.size()
                   ? m.texturePaths[std::size_t(texture)].substr(m.texturePaths[std::size_t(texture)].find_last_of('/') + 1)
                   : std::string("(none)");
    };
    CHECK(imageOf(k.texture) == "base.png");
    const std::pair<MapSlot, const char*> expected[] = {
        {MapSlot::MetallicRoughness, "mr.png"}, {MapSlot::Emissive, "em.png"},       {MapSlot::Normal, "nrm.png"},
        {MapSlot::Occlusion, "occ.png"},        {MapSlot::Specular, "spec.png"},     {MapSlot::SpecularColour, "specc.png"},
        {MapSlot::Clearcoat, "cc.png"},         {MapSlot::ClearcoatRoughness, "ccr.png"}, {MapSlot::ClearcoatNormal, "ccn.png"},
        {MapSlot::SheenColour, "sh.png"},       {MapSlot::SheenRoughness, "shr.png"}};
    // Every slot but the glossiness (KHR_materials_pbrSpecularGlossiness replaces the metallic-
    // roughness block: its own test checks that slot).
    static_assert(std::size(expected) == kMapSlots - 1, "every slot is checked");
    for (const auto& [slot, name] : expected) {
        INFO(kMapSlotNames[std::size_t(slot)]);
        CHECK(imageOf(k.maps[slot]) == name);
    }
    // The spec's defaults: base 1, metallic 1, roughness 1, no emission, no maps.
    const Material& plain = m.materials[1];
    REQUIRE(plain.pbr.has_value());
    CHECK(plain.pbr->baseColor.g == 1.0f);
    CHECK(plain.pbr->metallic == 1.0f);
    CHECK(plain.pbr->roughness == 1.0f);
    checkVec(plain.pbr->emissive, 0, 0, 0);
    checkVec(plain.pbr->sheenColor, 0, 0, 0); // no sheen
    CHECK(plain.maps[MapSlot::MetallicRoughness] == -1);
    CHECK(plain.maps[MapSlot::Normal] == -1);
}

TEST_CASE("glTF texCoord: a material's maps read the uv set they name (TEXCOORD_1, or KHR_texture_transform's texCoord)",
          "[resources][gltf][pbr]") {
    const std::string dir = freshDir("gltf-texcoord");
    Image one;
    one.width = one.height = 1;
    one.rgba = {200, 100, 50, 255};
    REQUIRE(writeImage(dir + "/t.png", one).ok());
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv0 = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    const int uv1 = a.floats({0.5f, 0.25f, 0.75f, 0.5f, 0.125f, 1}, "VEC2");
    const auto prim = [&](int material) {
        return "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv0) +
               ",\"TEXCOORD_1\":" + std::to_string(uv1) + "},\"material\":" + std::to_string(material) + "}";
    };
    a.meshes = "[{\"primitives\":[" + prim(0) + "," + prim(1) + "," + prim(2) + "," + prim(3) + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    // 0: an occlusion map alone on TEXCOORD_1. 1: base colour on TEXCOORD_1, emissive too.
    // 2: KHR_texture_transform's texCoord 1 overrides the reference's 0, with a scale of 2.
    // 3: base colour on TEXCOORD_0, occlusion on TEXCOORD_1: the base colour's set baked, and
    // each map's own address (the raw sets kept beside).
    a.materials = R"([{"occlusionTexture":{"index":0,"texCoord":1}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":1}},"emissiveTexture":{"index":0,"texCoord":1}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"texCoord":1,"scale":[2,2]}}}}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},"occlusionTexture":{"index":0,"texCoord":1}}])";
    a.extra = ",\"images\":[{\"uri\":\"t.png\"}],\"textures\":[{\"source\":0}]";
    auto r = load(dir, "texcoord.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.mesh.uvs.size() == 12);
    // Ours: v' = 1 - v (OBJ's convention).
    const auto check = [&](std::size_t k, float u, float v) {
        INFO("vertex " << k);
        CHECK(m.mesh.uvs[k].x == Approx(u).margin(1e-7));
        CHECK(m.mesh.uvs[k].y == Approx(1.0f - v).margin(1e-7));
    };
    for (std::size_t p = 0; p < 2; ++p) {
        check(3 * p, 0.5f, 0.25f);
        check(3 * p + 1, 0.75f, 0.5f);
        check(3 * p + 2, 0.125f, 1.0f);
    }
    check(6, 1.0f, 0.5f);
    check(7, 1.5f, 1.0f);
    check(8, 0.25f, 2.0f);
    check(9, 0.0f, 0.0f);
    check(10, 1.0f, 0.0f);
    check(11, 0.0f, 1.0f);
    CHECK(m.warnings.empty());
    // Materials 0-2 read one set each: no addresses. Material 3: the base colour on set 0, the
    // occlusion on set 1, and every vertex carries both raw sets (zeros for none: all have them here).
    for (std::size_t k = 0; k < 3; ++k) CHECK_FALSE(m.materials[k].addressing.has_value());
    REQUIRE(m.materials[3].addressing.has_value());
    const MapAddressing& addressing = *m.materials[3].addressing;
    CHECK(addressing.base.uvSet == 0);
    CHECK(addressing[MapSlot::Occlusion].uvSet == 1);
    REQUIRE(m.mesh.hasUvSets());
    for (std::size_t k = 0; k < 12; ++k) {
        INFO("vertex " << k);
        const std::size_t i = k % 3;
        const float u0[3] = {0, 1, 0}, v0[3] = {0, 0, 1}, u1[3] = {0.5f, 0.75f, 0.125f}, v1[3] = {0.25f, 0.5f, 1};
        CHECK(m.mesh.uvSets[0][k].x == (k < 9 ? 0.0f : u0[i]));
        CHECK(m.mesh.uvSets[0][k].y == (k < 9 ? 0.0f : 1.0f - v0[i]));
        CHECK(m.mesh.uvSets[1][k].x == (k < 9 ? 0.0f : u1[i]));
        CHECK(m.mesh.uvSets[1][k].y == (k < 9 ? 0.0f : 1.0f - v1[i]));
    }
}

TEST_CASE("glTF per texture reference: each map's transform and sampler where the maps do not share them",
          "[resources][gltf][pbr][addressing]") {
    const std::string dir = freshDir("gltf-addressing");
    Image one;
    one.width = one.height = 1;
    one.rgba = {200, 100, 50, 255};
    REQUIRE(writeImage(dir + "/t.png", one).ok());
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv0 = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    const int red = a.floats({1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");
    std::string prims;
    for (int k = 0; k < 5; ++k)
        prims += std::string(k ? "," : "") + "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" +
                 std::to_string(uv0) + (k == 4 ? ",\"COLOR_0\":" + std::to_string(red) : std::string()) +
                 "},\"material\":" + std::to_string(k) + "}";
    a.meshes = "[{\"primitives\":[" + prims + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    // 0: the emissive map offset (0.5, 0.25) and scaled (2, 3), the base colour not.
    // 1: the normal map through another sampler (clamp / mirror, NEAREST) than the base colour's.
    // 2: one map, wrapS and wrapT apart (the draw's, each axis its own). 3: two maps through one
    // transform and one sampler (shared). 4: material 1 again, on a primitive with red vertex
    // colours: left out beside the normal map (one varying too many), with a warning.
    a.materials = R"([{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},
          "emissiveTexture":{"index":0,"extensions":{"KHR_texture_transform":{"offset":[0.5,0.25],"scale":[2,3]}}}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},"normalTexture":{"index":1}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":2}}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":3}},"occlusionTexture":{"index":3}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},"normalTexture":{"index":1}}])";
    a.extra = ",\"extensionsUsed\":[\"KHR_texture_transform\"],\"images\":[{\"uri\":\"t.png\"}],"
              "\"textures\":[{\"source\":0},{\"source\":0,\"sampler\":0},{\"source\":0,\"sampler\":1},"
              "{\"source\":0,\"sampler\":2}],\"samplers\":[{\"wrapS\":33071,\"wrapT\":33648,\"minFilter\":9728},"
              "{\"wrapS\":33071,\"wrapT\":10497},{\"wrapS\":33071,\"wrapT\":33071,\"minFilter\":9728}]";
    auto r = load(dir, "addressing.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.warnings.size() == 1);
    CHECK(contains(m.warnings[0], "material 4: its maps read their own uv sets or transforms and it has a normal map: its "
                                  "primitives' vertex colours (COLOR_0) are not drawn"));
    REQUIRE(m.materials.size() == 5);
    CHECK(m.materials[4].addressing.has_value());
    // 0: glTF (u, v) -> (2 u + 0.5, 3 v + 0.25); on stored uvs (s, t) = (u, 1 - v):
    // s' = 2 s + 0.5, t' = 1 - (3 (1 - t) + 0.25) = 3 t - 2.25.
    REQUIRE(m.materials[0].addressing.has_value());
    const MapAddressing& t = *m.materials[0].addressing;
    const float expected[2][3] = {{2, 0, 0.5f}, {0, 3, -2.25f}}, identity[2][3] = {{1, 0, 0}, {0, 1, 0}};
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 3; ++col) {
            CHECK(t[MapSlot::Emissive].m[row][col] == Approx(expected[row][col]).margin(1e-6));
            CHECK(t.base.m[row][col] == identity[row][col]);
        }
    const Vec2 moved = t[MapSlot::Emissive].apply({0.1f, 0.8f}); // glTF (0.1, 0.2) -> (0.7, 0.85): stored (0.7, 0.15)
    CHECK(moved.x == Approx(0.7f).margin(1e-6));
    CHECK(moved.y == Approx(0.15f).margin(1e-6));
    // 1: the base colour repeats (no sampler), the normal map clamps on u and mirrors on v, nearest.
    REQUIRE(m.materials[1].addressing.has_value());
    const MapAddressing& s = *m.materials[1].addressing;
    CHECK(s.base.wrap == WrapModes{WrapMode::Repeat, WrapMode::Repeat});
    CHECK_FALSE(s.base.filter.has_value());
    CHECK(s[MapSlot::Normal].wrap == WrapModes{WrapMode::Clamp, WrapMode::Mirror});
    CHECK(s[MapSlot::Normal].filter == TextureFilter::Nearest);
    // 2: wrapS clamp and wrapT repeat on its one map: the draw's wrap.
    CHECK_FALSE(m.materials[2].addressing.has_value());
    CHECK(m.materials[2].wrap == WrapModes{WrapMode::Clamp, WrapMode::Repeat});
    // 3: shared: the draw's sampler is theirs, no addresses.
    CHECK_FALSE(m.materials[3].addressing.has_value());
    CHECK(m.materials[3].wrap == WrapModes{WrapMode::Clamp, WrapMode::Clamp});
    CHECK(m.materials[3].filter == TextureFilter::Nearest);
    // The raw sets are kept (TEXCOORD_1 absent: zeros).
    REQUIRE(m.mesh.hasUvSets());
    CHECK(m.mesh.uvSets[0][1].x == 1.0f);
    CHECK(m.mesh.uvSets[1][1].x == 0.0f);
}

TEST_CASE("glTF tangents for a normal map: generated from the uvs, or the file's through the node", "[resources][gltf][pbr]") {
    const std::string dir = freshDir("gltf-tangents");
    Image one;
    one.width = one.height = 1;
    one.rgba = {128, 128, 255, 255};
    REQUIRE(writeImage(dir + "/n.png", one).ok());
    // A quad in the z = 0 plane facing +z. Texcoords: glTF u along +x, glTF v along -y (v grows
    // down the image, y up): dp/du = +x, and n x t = +y is "up" in the image: w = +1. The second
    // primitive mirrors u (u along -x): t = -x, and n x t = -y, opposite our dp/dv: w = -1.
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int nrm = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int uv = a.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
    const int uvMirror = a.floats({1, 1, 0, 1, 0, 0, 1, 0}, "VEC2");
    const int tan = a.floats({0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1}, "VEC4");
    const int idx = a.indices({0, 1, 2, 0, 2, 3}, 5123);
    const auto prim = [&](int uvs, int tangents) {
        return "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm) +
               ",\"TEXCOORD_0\":" + std::to_string(uvs) + (tangents >= 0 ? ",\"TANGENT\":" + std::to_string(tangents) : "") +
               "},\"indices\":" + std::to_string(idx) + ",\"material\":0}";
    };
    a.meshes = "[{\"primitives\":[" + prim(uv, -1) + "," + prim(uvMirror, -1) + "]},{\"primitives\":[" + prim(uv, tan) + "]}]";
    // Mesh 1 under a node rotated 90 degrees about z: the file's tangent (0, 1, 0) becomes (-1, 0, 0).
    a.nodes = "[{\"mesh\":0},{\"mesh\":1,\"rotation\":[0,0,0.7071067811865476,0.7071067811865476]}]";
    a.scenes = "[{\"nodes\":[0,1]}]";
    a.materials = "[{\"normalTexture\":{\"index\":0}}]";
    a.extra = ",\"images\":[{\"uri\":\"n.png\"}],\"textures\":[{\"source\":0}]";
    auto r = load(dir, "tangents.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.mesh.tangents.size() == m.mesh.positions.size());
    REQUIRE(m.mesh.positions.size() == 12);
    for (std::size_t k = 0; k < 4; ++k) {
        checkVec(Vec3{m.mesh.tangents[k].x, m.mesh.tangents[k].y, m.mesh.tangents[k].z}, 1, 0, 0);
        CHECK(m.mesh.tangents[k].w == 1.0f);
    }
    for (std::size_t k = 4; k < 8; ++k) {
        checkVec(Vec3{m.mesh.tangents[k].x, m.mesh.tangents[k].y, m.mesh.tangents[k].z}, -1, 0, 0);
        CHECK(m.mesh.tangents[k].w == -1.0f);
    }
    for (std::size_t k = 8; k < 12; ++k) {
        checkVec(Vec3{m.mesh.tangents[k].x, m.mesh.tangents[k].y, m.mesh.tangents[k].z}, -1, 0, 0);
        CHECK(m.mesh.tangents[k].w == 1.0f);
    }
}

TEST_CASE("glTF tangents for a normal map at its own address: along its own uv set and transform",
          "[resources][gltf][pbr][addressing]") {
    const std::string dir = freshDir("gltf-tangents-addressed");
    Image one;
    one.width = one.height = 1;
    one.rgba = {128, 128, 255, 255};
    REQUIRE(writeImage(dir + "/n.png", one).ok());
    // The quad of the tangents test (z = 0, facing +z). TEXCOORD_0: u along +x (tangent +x).
    // TEXCOORD_1: u along +y, v along +x (glTF v grows down the image; ours, 1 - v, along -x):
    // tangent +y, and n x t = -x along our dp/dv: w = +1.
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int nrm = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int uv0 = a.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
    const int uv1 = a.floats({0, 0, 0, 1, 1, 1, 1, 0}, "VEC2");
    const int idx = a.indices({0, 1, 2, 0, 2, 3}, 5123);
    const auto prim = [&](int material) {
        return "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm) +
               ",\"TEXCOORD_0\":" + std::to_string(uv0) + ",\"TEXCOORD_1\":" + std::to_string(uv1) +
               "},\"indices\":" + std::to_string(idx) + ",\"material\":" + std::to_string(material) + "}";
    };
    a.meshes = "[{\"primitives\":[" + prim(0) + "," + prim(1) + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    // 0: the normal map on TEXCOORD_1 beside a base colour on TEXCOORD_0. 1: the normal map
    // turned a quarter by its transform (u' = v, along -y: tangent -y; v' = -u, ours along +x:
    // n x t = +x, w = +1) beside an untransformed base colour.
    a.materials = R"([{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},"normalTexture":{"index":0,"texCoord":1}},
        {"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},
         "normalTexture":{"index":0,"extensions":{"KHR_texture_transform":{"rotation":1.5707963267948966}}}}])";
    a.extra = ",\"extensionsUsed\":[\"KHR_texture_transform\"],\"images\":[{\"uri\":\"n.png\"}],\"textures\":[{\"source\":0}]";
    auto r = load(dir, "tangents-addressed.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.materials[0].addressing.has_value());
    REQUIRE(m.materials[1].addressing.has_value());
    REQUIRE(m.mesh.tangents.size() == 8);
    for (std::size_t k = 0; k < 8; ++k) {
        INFO("vertex " << k);
        const Vec4 t = m.mesh.tangents[k];
        checkVec(Vec3{t.x, t.y, t.z}, 0, k < 4 ? 1 : -1, 0);
        CHECK(t.w == 1.0f);
    }
}

TEST_CASE("glTF KHR_texture_transform: offset, rotation and scale baked into the material's uvs", "[resources][gltf][pbr]") {
    const std::string dir = freshDir("gltf-uvtransform");
    Image one;
    one.width = one.height = 1;
    one.rgba = {10, 20, 30, 255};
    REQUIRE(writeImage(dir + "/t.png", one).ok());
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0.25f, 0.5f}, "VEC2");
    std::string prims;
    for (int k = 0; k < 3; ++k)
        prims += std::string(k ? "," : "") + "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" +
                 std::to_string(uv) + "},\"material\":" + std::to_string(k) + "}";
    a.meshes = "[{\"primitives\":[" + prims + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    // 0: offset (0.5, 0) and scale (2, 2); 1: a quarter turn; 2: none.
    a.materials = "[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0,\"extensions\":{\"KHR_texture_transform\":"
                  "{\"offset\":[0.5,0],\"scale\":[2,2]}}}}},"
                  "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0,\"extensions\":{\"KHR_texture_transform\":"
                  "{\"rotation\":1.5707963267948966}}}}},"
                  "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]";
    a.extra = ",\"extensionsUsed\":[\"KHR_texture_transform\"],\"extensionsRequired\":[\"KHR_texture_transform\"],"
              "\"images\":[{\"uri\":\"t.png\"}],\"textures\":[{\"source\":0}]";
    auto r = load(dir, "uvt.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.mesh.uvs.size() == 9);
    // Stored as (u, 1 - v) (OBJ's convention) after the transform in glTF's uv space.
    const auto check = [&](std::size_t i, double u, double v) {
        CHECK(double(m.mesh.uvs[i].x) == Approx(u).margin(1e-6));
        CHECK(double(m.mesh.uvs[i].y) == Approx(1.0 - v).margin(1e-6));
    };
    check(0, 0.5, 0.0); // (0, 0) -> (2 * 0 + 0.5, 0)
    check(1, 2.5, 0.0);
    check(2, 1.0, 1.0); // (0.25, 0.5) -> (1, 1)
    // Rotation r: u' = cos r u + sin r v, v' = -sin r u + cos r v: a quarter turn maps (u, v) to (v, -u).
    check(3, 0.0, 0.0);
    check(4, 0.0, -1.0);
    check(5, 0.5, -0.25);
    check(8, 0.25, 0.5);
}

TEST_CASE("glTF: embedded, external .bin and .glb forms of one asset load the same model", "[resources][gltf]") {
    const std::string dir = freshDir("gltf-forms");
    const Asset a = triangleAsset("[{\"translation\":[1,2,3],\"mesh\":0}]");
    REQUIRE(writeFileBytes(dir + "/tri.bin", a.buffer().data(), a.buffer().size()).ok());
    const std::vector<unsigned char> glb = a.glb();
    REQUIRE(writeFileBytes(dir + "/tri.glb", glb.data(), glb.size()).ok());
    auto embedded = load(dir, "embedded.gltf", a.embedded());
    auto external = load(dir, "external.gltf", a.json("tri.bin"));
    auto binary = loadGltf(dir + "/tri.glb");
    auto viaModel = loadModel(dir + "/tri.glb");
    for (auto* r : {&embedded, &external, &binary, &viaModel}) {
        INFO((r->ok() ? std::string() : r->error()));
        REQUIRE(r->ok());
        CHECK(r->value().mesh.indices == std::vector<std::uint32_t>{0, 1, 2});
        checkVec(r->value().mesh.positions[2], 1, 3, 3);
    }
    CHECK(isGltfPath("a/B.GLB"));
    CHECK(isGltfPath("x.gltf"));
    CHECK_FALSE(isGltfPath("x.obj"));
    CHECK_FALSE(isGltfPath("gltf"));
}

TEST_CASE("glTF cameras: perspective camera nodes in world space, in node order; orthographic ones skipped",
          "[resources][gltf][cameras]") {
    const std::string dir = freshDir("gltf-cameras");
    // Node 0 holds the mesh and two children: node 1 at (1, 2, 3) turned 90 degrees about +y
    // (its -z view axis becomes -x) with camera 0; node 2 scaled by 2 (the up vector is
    // renormalised) with the orthographic camera 1 and a child node 3 at (0, 0, 10) with camera 2.
    Asset a = triangleAsset("[{\"mesh\":0,\"children\":[1,2]},"
                            "{\"translation\":[1,2,3],\"rotation\":[0,0.7071067811865476,0,0.7071067811865476],\"camera\":0},"
                            "{\"scale\":[2,2,2],\"camera\":1,\"children\":[3]},{\"translation\":[0,0,10],\"camera\":2}]");
    a.extra = ",\"cameras\":[{\"type\":\"perspective\",\"name\":\"side\",\"perspective\":{\"yfov\":0.5,\"znear\":0.1,\"zfar\":50}},"
              "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":1,\"ymag\":1,\"znear\":0.1,\"zfar\":10}},"
              "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1.0,\"znear\":0.5}}]";
    auto r = load(dir, "cameras.gltf", a.embedded());
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.cameras.size() == 2);
    const ModelCamera& side = m.cameras[0];
    CHECK(side.name == "side");
    checkVec(side.eye, 1, 2, 3);
    checkVec(side.target, 0, 2, 3); // eye + (-1, 0, 0)
    checkVec(side.up, 0, 1, 0);
    CHECK(side.yfovDegrees == Approx(0.5 * 180.0 / 3.14159265358979).epsilon(1e-12));
    CHECK(side.znear == 0.1);
    CHECK(side.zfar == 50.0);
    const ModelCamera& far = m.cameras[1];
    checkVec(far.eye, 0, 0, 20); // scale 2 x (0, 0, 10)
    checkVec(far.target, 0, 0, 19);
    checkVec(far.up, 0, 1, 0); // (0, 2, 0) renormalised
    CHECK(far.zfar == 0.0);    // none: infinite
    REQUIRE(m.warnings.size() == 1);
    CHECK(contains(m.warnings[0], "orthographic"));
    CHECK(contains(m.warnings[0], "cameras.gltf"));

    a.extra = ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0,\"znear\":0.1}},"
              "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":1,\"ymag\":1,\"znear\":0.1,\"zfar\":10}},"
              "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1.0,\"znear\":0.5}}]";
    auto bad = load(dir, "badcamera.gltf", a.embedded());
    REQUIRE_FALSE(bad.ok());
    CHECK(contains(bad.error(), "camera 0"));
}

TEST_CASE("glTF lights (KHR_lights_punctual): placed by their nodes, colour x intensity", "[resources][gltf][lights]") {
    const std::string dir = freshDir("gltf-lights");
    // Node 1: the directional light 0, turned 90 degrees about +y (its -z shines along -x, so the
    // direction TO it is +x). Node 2 at (1, 2, 3): the point light 1. Node 3 at (0, 5, 0) turned
    // -90 degrees about +x (its -z points down, -y): the spot 2. Light 0 is placed twice (node 4
    // under node 2, i.e. at (1, 2, 3) + (0, 0, -1), turned like node 2: not at all).
    Asset a = triangleAsset("[{\"mesh\":0,\"children\":[1,2,3]},"
                            "{\"rotation\":[0,0.7071067811865476,0,0.7071067811865476],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
                            "{\"translation\":[1,2,3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}},\"children\":[4]},"
                            "{\"translation\":[0,5,0],\"rotation\":[-0.7071067811865476,0,0,0.7071067811865476],"
                            "\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}},"
                            "{\"translation\":[0,0,-1],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}]");
    const std::string lights = "\"lights\":[{\"type\":\"directional\",\"color\":[1,0.5,0.25],\"intensity\":2},"
                               "{\"type\":\"point\",\"intensity\":10,\"range\":7},"
                               "{\"type\":\"spot\",\"color\":[0,1,0],\"spot\":{\"innerConeAngle\":0.25,\"outerConeAngle\":0.5}}]";
    a.extra = ",\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{" + lights + "}}";
    auto r = load(dir, "lights.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const std::vector<Light>& l = r.value().lights;
    REQUIRE(l.size() == 4); // depth-first node order: 1, 2, 4, 3
    CHECK(l[0].type == LightType::Directional);
    checkVec(l[0].toLight, 1, 0, 0);
    CHECK(l[0].colour.r == 2.0f);
    CHECK(l[0].colour.g == 1.0f);
    CHECK(l[0].colour.b == 0.5f);
    CHECK(l[1].type == LightType::Point);
    checkVec(l[1].position, 1, 2, 3);
    CHECK(l[1].colour.g == 10.0f); // no color: white
    CHECK(l[1].range == 7.0f);
    CHECK(l[2].type == LightType::Directional);
    checkVec(l[2].toLight, 0, 0, 1); // node 4 is not turned: shines along -z
    CHECK(l[3].type == LightType::Spot);
    checkVec(l[3].position, 0, 5, 0);
    checkVec(l[3].spotDirection, 0, -1, 0);
    CHECK(l[3].range == 0.0f);
    CHECK(l[3].colour.r == 0.0f);
    CHECK(l[3].colour.g == 1.0f);
    // The cone: factor 1 at the inner angle, 0 at the outer one.
    CHECK(std::cos(0.25f) * l[3].coneScale + l[3].coneOffset == Approx(1.0f).margin(1e-5));
    CHECK(std::cos(0.5f) * l[3].coneScale + l[3].coneOffset == Approx(0.0f).margin(1e-5));

    SECTION("broken lights are errors naming the light") {
        const auto withLights = [&](const std::string& list) {
            Asset b = triangleAsset("[{\"mesh\":0,\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}]");
            b.extra = ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":" + list + "}}";
            return b.embedded();
        };
        CHECK(contains(errorOf(dir, "cone.gltf", withLights("[{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.6,\"outerConeAngle\":0.5}}]")),
                       "light 0: spot cone"));
        CHECK(contains(errorOf(dir, "colour.gltf", withLights("[{\"type\":\"point\",\"color\":[1,2,0]}]")), "light 0: color"));
        CHECK(contains(errorOf(dir, "intensity.gltf", withLights("[{\"type\":\"point\",\"intensity\":-1}]")), "intensity"));
        Asset missing = triangleAsset("[{\"mesh\":0,\"extensions\":{\"KHR_lights_punctual\":{\"light\":3}}}]");
        CHECK(contains(errorOf(dir, "missing.gltf", missing.embedded()), "node 0: KHR_lights_punctual: light 3"));
    }
}

TEST_CASE("glTF samplers: wrap and filter per material, as one wrap mode and one filter", "[resources][gltf][materials]") {
    const std::string dir = freshDir("gltf-samplers");
    Image one;
    one.width = one.height = 1;
    one.rgba = {10, 20, 30, 255};
    REQUIRE(writeImage(dir + "/t.png", one).ok());
    const auto asset = [](const std::string& samplers, int materials) {
        Asset a;
        const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
        const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
        const int idx = a.indices({0, 1, 2}, 5123);
        std::string prims, mats, textures;
        for (int k = 0; k < materials; ++k) {
            prims += std::string(k ? "," : "") + "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" +
                     std::to_string(uv) + "},\"indices\":" + std::to_string(idx) + ",\"material\":" + std::to_string(k) + "}";
            mats += std::string(k ? "," : "") + "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":" + std::to_string(k) + "}}}";
            // Texture k uses sampler k; the last one none.
            textures += std::string(k ? "," : "") + "{\"source\":0" +
                        (k + 1 < materials ? ",\"sampler\":" + std::to_string(k) : std::string()) + "}";
        }
        a.meshes = "[{\"primitives\":[" + prims + "]}]";
        a.nodes = "[{\"mesh\":0}]";
        a.materials = "[" + mats + "]";
        a.extra = ",\"images\":[{\"uri\":\"t.png\"}],\"textures\":[" + textures + "],\"samplers\":" + samplers;
        return a;
    };
    // 0: clamp both, NEAREST; 1: mirror / repeat (each axis its own), LINEAR_MIPMAP_LINEAR;
    // 2: magFilter NEAREST only; 3: nothing said (repeat, the settings' filter); 4: no sampler.
    const Asset a = asset("[{\"wrapS\":33071,\"wrapT\":33071,\"minFilter\":9728},"
                          "{\"wrapS\":33648,\"wrapT\":10497,\"minFilter\":9987,\"magFilter\":9729},"
                          "{\"magFilter\":9728},{}]",
                          5);
    auto r = load(dir, "samplers.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const std::vector<Material>& m = r.value().materials;
    REQUIRE(m.size() == 5);
    for (const Material& mat : m) CHECK(mat.texture == 0);
    CHECK(m[0].wrap == WrapModes{WrapMode::Clamp, WrapMode::Clamp});
    CHECK(m[0].filter == TextureFilter::Nearest);
    CHECK(m[1].wrap == WrapModes{WrapMode::Mirror, WrapMode::Repeat});
    CHECK(m[1].filter == TextureFilter::Trilinear);
    CHECK(m[2].wrap == WrapModes{WrapMode::Repeat, WrapMode::Repeat});
    CHECK(m[2].filter == TextureFilter::Nearest);
    CHECK(m[3].wrap == WrapModes{WrapMode::Repeat, WrapMode::Repeat});
    CHECK_FALSE(m[3].filter.has_value());
    CHECK_FALSE(m[4].wrap.has_value());
    CHECK_FALSE(m[4].filter.has_value());
    CHECK(r.value().warnings.empty());
    for (const Material& mat : m) CHECK_FALSE(mat.addressing.has_value()); // one map each: the draw's sampler

    CHECK(contains(errorOf(dir, "badwrap.gltf", asset("[{\"wrapS\":1234},{}]", 2).embedded()), "sampler 0: wrapS 1234"));
    CHECK(contains(errorOf(dir, "badfilter.gltf", asset("[{\"minFilter\":7},{}]", 2).embedded()), "sampler 0: minFilter 7"));
    CHECK(contains(errorOf(dir, "nosampler.gltf", asset("[]", 2).embedded()), "texture 0: sampler 0 does not exist"));
}

TEST_CASE("glTF alpha modes with a base colour texture: the per-fragment rule beside the constant one",
          "[resources][gltf][materials][transparency]") {
    const std::string dir = freshDir("gltf-texel-alpha");
    Image one;
    one.width = one.height = 1;
    one.rgba = {10, 20, 30, 255};
    REQUIRE(writeImage(dir + "/t.png", one).ok());
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    std::string prims;
    for (int k = 0; k < 5; ++k)
        prims += std::string(k ? "," : "") + "{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                 ",\"TEXCOORD_0\":" + std::to_string(uv) + "},\"material\":" + std::to_string(k) + "}";
    a.meshes = "[{\"primitives\":[" + prims + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    // 0: MASK, cutoff 0.3, factor alpha 0.8; 1: MASK with the default cutoff 0.5, factor 0.25 (below
    // it: the constant rule drops the surface); 2: BLEND, factor 0.6; 3: OPAQUE with a factor
    // alpha 0.2 (ignored); 4: untextured MASK (nothing per fragment to read: the constant rule).
    a.materials = "[{\"alphaMode\":\"MASK\",\"alphaCutoff\":0.3,\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.8],"
                  "\"baseColorTexture\":{\"index\":0}}},"
                  "{\"alphaMode\":\"MASK\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.25],\"baseColorTexture\":{\"index\":0}}},"
                  "{\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.6],\"baseColorTexture\":{\"index\":0}}},"
                  "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.2],\"baseColorTexture\":{\"index\":0}}},"
                  "{\"alphaMode\":\"MASK\",\"alphaCutoff\":0.9,\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.95]}}]";
    a.extra = ",\"images\":[{\"uri\":\"t.png\"}],\"textures\":[{\"source\":0}]";
    auto r = load(dir, "alpha.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const std::vector<Material>& m = r.value().materials;
    REQUIRE(m.size() == 5);
    CHECK(m[0].alpha == 1.0f); // 0.8 >= 0.3: kept by the constant rule
    CHECK(m[0].texelAlpha.mode == AlphaMode::Mask);
    CHECK(m[0].texelAlpha.factor == 0.8f);
    CHECK(m[0].texelAlpha.cutoff == 0.3f);
    CHECK(m[1].alpha == 0.0f);
    CHECK(m[1].texelAlpha.mode == AlphaMode::Mask);
    CHECK(m[1].texelAlpha.factor == 0.25f);
    CHECK(m[1].texelAlpha.cutoff == 0.5f);
    CHECK(m[2].alpha == 0.6f);
    CHECK(m[2].texelAlpha.mode == AlphaMode::Blend);
    CHECK(m[2].texelAlpha.factor == 0.6f);
    CHECK(m[3].alpha == 1.0f);
    CHECK(m[3].texelAlpha.mode == AlphaMode::Off);
    CHECK(m[4].alpha == 1.0f);
    CHECK(m[4].texture == -1);
}

TEST_CASE("glTF: bad files are one-line errors naming the file and the problem", "[resources][gltf][errors]") {
    const std::string dir = freshDir("gltf-errors");
    SECTION("an index out of range") {
        Asset a;
        const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
        const int idx = a.indices({0, 1, 5}, 5125);
        a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"indices\":" + std::to_string(idx) + "}]}]";
        a.nodes = "[{\"mesh\":0}]";
        CHECK(contains(errorOf(dir, "index.gltf", a.embedded()), "index 5"));
    }
    SECTION("an accessor beyond its buffer view") {
        Asset a = triangleAsset("[{\"mesh\":0}]");
        a.rawAccessor("{\"bufferView\":0,\"componentType\":5126,\"count\":1000,\"type\":\"VEC3\"}");
        a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":2}}]}]";
        CHECK(contains(errorOf(dir, "beyond.gltf", a.embedded()), "do not fit"));
    }
    SECTION("a missing .bin") {
        const Asset a = triangleAsset("[{\"mesh\":0}]");
        CHECK(contains(errorOf(dir, "nobin.gltf", a.json("gone.bin")), "gone.bin"));
    }
    SECTION("recursive nodes") {
        const Asset a = triangleAsset("[{\"children\":[1]},{\"children\":[0],\"mesh\":0}]");
        CHECK(contains(errorOf(dir, "loop.gltf", a.embedded()), "reached twice"));
    }
    SECTION("a hierarchy deeper than the limit") {
        std::string nodes = "[";
        for (int i = 0; i < 70; ++i) nodes += "{\"children\":[" + std::to_string(i + 1) + "]},";
        nodes += "{\"mesh\":0}]";
        CHECK(contains(errorOf(dir, "deep.gltf", triangleAsset(nodes).embedded()), "deeper than 64"));
    }
    SECTION("a scene that does not exist") {
        Asset a = triangleAsset("[{\"mesh\":0}]");
        a.scenes = "[]";
        const std::string e = errorOf(dir, "noscene.gltf", a.embedded());
        CHECK(contains(e, "scene 0 does not exist"));
    }
    SECTION("positions that are not finite") {
        Asset a;
        const int pos = a.floats({0, 0, 0, std::numeric_limits<float>::infinity(), 0, 0, 0, 1, 0}, "VEC3");
        a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
        a.nodes = "[{\"mesh\":0}]";
        CHECK(contains(errorOf(dir, "inf.gltf", a.embedded()), "not finite"));
    }
    SECTION("a required extension SoftRaster does not read") {
        Asset a = triangleAsset("[{\"mesh\":0}]");
        a.extra = ",\"extensionsUsed\":[\"KHR_materials_pbrFuture\"],\"extensionsRequired\":[\"KHR_materials_pbrFuture\"]";
        CHECK(contains(errorOf(dir, "future.gltf", a.embedded()), "requires the extension KHR_materials_pbrFuture"));
    }
    SECTION("wrong JSON types and not JSON at all") {
        Asset a = triangleAsset("[{\"mesh\":\"zero\"}]");
        errorOf(dir, "types.gltf", a.embedded());
        errorOf(dir, "text.gltf", "this is not JSON");
        errorOf(dir, "empty.glb", "glTF");
    }
    SECTION("vertex counts that are not whole triangles or segments") {
        Asset a;
        const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3"); // 4 vertices
        a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
        a.nodes = "[{\"mesh\":0}]";
        CHECK(contains(errorOf(dir, "tri4.gltf", a.embedded()), "not a multiple of 3"));
        const int idx = a.indices({0, 1, 2}, 5121);
        a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"indices\":" +
                   std::to_string(idx) + ",\"mode\":1}]}]";
        CHECK(contains(errorOf(dir, "lines3.gltf", a.embedded()), "not a multiple of 2"));
    }
    SECTION("properties of the wrong JSON type (the glTF 2.0 schema)") {
        Asset a = triangleAsset("[{\"mesh\":0,\"name\":42}]");
        CHECK(contains(errorOf(dir, "name.gltf", a.embedded()), "nodes[0].name: expected a string"));
        a = triangleAsset("[{\"mesh\":0,\"scale\":\"big\"}]");
        CHECK(contains(errorOf(dir, "scale.gltf", a.embedded()), "nodes[0].scale"));
        a = triangleAsset("[{\"mesh\":0}]");
        a.materials = "[{\"pbrMetallicRoughness\":[\"not an object\"]}]";
        CHECK(contains(errorOf(dir, "pbr.gltf", a.embedded()), "materials[0].pbrMetallicRoughness: expected an object"));
        a.materials = "[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":-1}}}]";
        CHECK(contains(errorOf(dir, "index.gltf", a.embedded()), "unsigned integer"));
        a.materials = "[{\"extensions\":{\"KHR_materials_unlit\":\"yes\"}}]";
        CHECK(contains(errorOf(dir, "ext.gltf", a.embedded()), "KHR_materials_unlit: expected an object"));
        a.materials = "[{\"extras\":{\"name\":7}}]"; // extras are free-form
        CHECK(load(dir, "extras.gltf", a.embedded()).ok());
    }
    SECTION("POSITION of the wrong type") {
        Asset a;
        const int pos = a.floats({0, 0, 0, 1, 0, 0}, "VEC2");
        a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
        a.nodes = "[{\"mesh\":0}]";
        CHECK(contains(errorOf(dir, "vec2.gltf", a.embedded()), "POSITION: must be float, byte or short VEC3"));
    }
}

#ifndef _WIN32
// The glTF 2.0 files of Debian's assimp-testmodels (valid and malformed), natively: each loads or
// fails with one line; and the valid ones' world-space triangles equal those of the same model
// exported to OBJ by assimp (assimp-utils), an independent glTF reader, read by our OBJ loader.
namespace {

const std::string kAssimpGltf = "/usr/share/assimp/models/glTF2";

using Triangle = std::array<Vec3, 3>;

std::vector<Triangle> triangles(const Model& m) {
    std::vector<Triangle> out;
    for (std::size_t t = 0; t + 2 < m.mesh.indices.size(); t += 3)
        out.push_back({m.mesh.positions[m.mesh.indices[t]], m.mesh.positions[m.mesh.indices[t + 1]],
                       m.mesh.positions[m.mesh.indices[t + 2]]});
    return out;
}

// How many triangles of `a` have no partner in `b`: a triangle of b, not yet taken, with the same
// vertices in the same cyclic order (the winding) within `tol`. Candidates are found through a
// grid of the centroids (cells of 4 tol, the 27 around a centroid searched).
std::size_t unmatched(const std::vector<Triangle>& a, const std::vector<Triangle>& b, float tol) {
    const auto key = [&](const Triangle& t, int dx, int dy, int dz) {
        const Vec3 c = (t[0] + t[1] + t[2]) / 3.0f;
        const float cell = 4.0f * tol;
        return std::array<long long, 3>{(long long)std::floor(c.x / cell) + dx, (long long)std::floor(c.y / cell) + dy,
                                        (long long)std::floor(c.z / cell) + dz};
    };
    std::map<std::array<long long, 3>, std::vector<std::size_t>> grid;
    for (std::size_t i = 0; i < b.size(); ++i) grid[key(b[i], 0, 0, 0)].push_back(i);
    std::vector<std::uint8_t> taken(b.size(), 0);
    const auto near = [&](Vec3 p, Vec3 q) { return std::fabs(p.x - q.x) <= tol && std::fabs(p.y - q.y) <= tol && std::fabs(p.z - q.z) <= tol; };
    std::size_t missing = 0;
    for (const Triangle& t : a) {
        bool found = false;
        for (int dx = -1; dx <= 1 && !found; ++dx)
            for (int dy = -1; dy <= 1 && !found; ++dy)
                for (int dz = -1; dz <= 1 && !found; ++dz) {
                    const auto it = grid.find(key(t, dx, dy, dz));
                    if (it == grid.end()) continue;
                    for (std::size_t j : it->second) {
                        if (taken[j]) continue;
                        const Triangle& u = b[j];
                        for (int r = 0; r < 3 && !found; ++r)
                            if (near(t[0], u[std::size_t(r)]) && near(t[1], u[std::size_t((r + 1) % 3)]) &&
                                near(t[2], u[std::size_t((r + 2) % 3)]))
                                found = true;
                        if (found) {
                            taken[j] = 1;
                            break;
                        }
                    }
                }
        missing += !found;
    }
    return missing;
}

} // namespace

TEST_CASE("glTF files of assimp-testmodels: each loads or fails in one line; the malformed ones fail",
          "[resources][gltf][assimp]") {
    if (!std::filesystem::is_directory(kAssimpGltf)) FAIL(kAssimpGltf + " missing: scripts/install-deps.sh test installs assimp-testmodels");
    int loaded = 0, failed = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(kAssimpGltf)) {
        const std::string path = entry.path().string();
        if (!isGltfPath(path)) continue;
        LoadOptions options;
        options.loadTextures = false;
        auto r = loadGltf(path, options);
        INFO(path << ": " << (r.ok() ? "loaded" : r.error()));
        if (r.ok()) {
            ++loaded;
            // Valid files without anything to draw load empty, saying so.
            const bool empty = r.value().mesh.triangleCount() == 0 && r.value().lineSets.empty();
            CHECK((!empty || (!r.value().warnings.empty() && contains(r.value().warnings.back(), "nothing to draw"))));
            CHECK(indicesValid(r.value().mesh));
        } else {
            ++failed;
            CHECK(contains(r.error(), path));
            CHECK(r.error().find('\n') == std::string::npos);
        }
    }
    CHECK(loaded >= 10);
    CHECK(failed >= 5);
    for (const char* bad : {"IndexOutOfRange/IndexOutOfRange.gltf", "IndexOutOfRange/AllIndicesOutOfRange.gltf",
                            "MissingBin/BoxTextured.gltf", "RecursiveNodes/RecursiveNodes.gltf",
                            "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "IncorrectVertexArrays/Cube.gltf",
                            "TestNoRootNode/NoScene.gltf", // "scene": 0 with no scenes: a dangling index
                            "SchemaFailures/sceneWrongType.gltf", "wrongTypes/badArray.gltf", "wrongTypes/badExtension.gltf",
                            "wrongTypes/badNumber.gltf", "wrongTypes/badObject.gltf", "wrongTypes/badString.gltf",
                            "wrongTypes/badUint.gltf", "BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf"}) {
        const std::string path = kAssimpGltf + "/" + bad;
        INFO(path);
        REQUIRE(std::filesystem::exists(path));
        CHECK_FALSE(loadGltf(path).ok());
    }
    // Valid and empty: a scene without nodes.
    for (const char* empty : {"TestNoRootNode/SceneWithoutNodes.gltf"}) {
        auto r = loadGltf(kAssimpGltf + "/" + empty);
        INFO(empty << ": " << (r.ok() ? "loaded" : r.error()));
        REQUIRE(r.ok());
        CHECK(r.value().mesh.triangleCount() == 0);
        REQUIRE(r.value().warnings.size() == 1);
        CHECK(contains(r.value().warnings[0], "nothing to draw"));
    }
}

// The share of `encoded`'s triangles that are also `plain`'s, each compared as the sorted set of
// its corners rounded to a grid 64 quantization steps wide (Draco and gltfpack reorder
// triangles and rotate their corners; quantization moves corners by up to a step, which now and
// then puts one in the next cell: nearly all, not all, agree when the decode is right, and
// almost none when it is not). `plain`'s degenerate triangles (two corners at one position) are
// left out: both encoders drop them.
static double sharedTriangles(const Mesh& encoded, const Mesh& plain, float step) {
    const auto keys = [&](const Mesh& m, bool solidOnly) {
        std::vector<std::array<long long, 9>> out;
        for (std::size_t t = 0; t < m.triangleCount(); ++t) {
            std::array<Vec3, 3> v;
            for (std::size_t k = 0; k < 3; ++k) v[k] = m.positions[m.indices[3 * t + k]];
            if (solidOnly && (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])) continue;
            std::array<std::array<long long, 3>, 3> c;
            for (std::size_t k = 0; k < 3; ++k)
                c[k] = {std::llround(v[k].x / (64 * step)), std::llround(v[k].y / (64 * step)), std::llround(v[k].z / (64 * step))};
            std::sort(c.begin(), c.end());
            out.push_back({c[0][0], c[0][1], c[0][2], c[1][0], c[1][1], c[1][2], c[2][0], c[2][1], c[2][2]});
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    const auto ke = keys(encoded, false), kp = keys(plain, true);
    std::vector<std::array<long long, 9>> common;
    std::set_intersection(ke.begin(), ke.end(), kp.begin(), kp.end(), std::back_inserter(common));
    INFO("step " << step << ", triangles " << ke.size() << " and " << kp.size() << " (not degenerate), the same " << common.size());
    // gltfpack keeps a few triangles whose corners are distinct vertices at one position (it
    // drops repeated indices, Draco repeated positions): the counts agree within 0.1%.
    CHECK(std::labs(long(ke.size()) - long(kp.size())) <= long(kp.size()) / 1000);
    return ke.empty() ? 0.0 : double(common.size()) / double(ke.size());
}

// The largest side of a model's bounds over 2^bits: the step of positions quantized to `bits`
// over the model (Draco's and gltfpack's default: 14 bits), doubled for the rounding of both.
static float quantizationStep(const Model& m, int bits) {
    const Vec3 lo = m.boundsMin, hi = m.boundsMax;
    return std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / float(1 << bits) * 2.0f;
}

// A Draco file as a pipeline wrote it (assimp-testmodels' 2CylinderEngine, KHR_draco_mesh_compression)
// against the same model uncompressed: the same triangles, positions within the quantization step.
TEST_CASE("glTF Draco: 2CylinderEngine decodes to the uncompressed model's triangles", "[resources][gltf][draco][assimp]") {
    LoadOptions options;
    options.loadTextures = false;
    auto draco = loadGltf(kAssimpGltf + "/draco/2CylinderEngine.gltf", options);
    auto plain = loadGltf(kAssimpGltf + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", options);
    INFO((draco.ok() ? std::string() : draco.error()));
    REQUIRE(draco.ok());
    REQUIRE(plain.ok());
    REQUIRE(draco.value().mesh.triangleCount() > 10000);
    CHECK(sharedTriangles(draco.value().mesh, plain.value().mesh, quantizationStep(plain.value(), 14)) > 0.95);
}

// The same model through gltfpack (Debian's, the pipeline most web glTF comes out of):
// quantized (KHR_mesh_quantization), then also meshopt-compressed (EXT_meshopt_compression), then
// also instanced (EXT_mesh_gpu_instancing): each the uncompressed model's triangles.
TEST_CASE("glTF gltfpack: quantized, meshopt and instanced files decode to the uncompressed model's triangles",
          "[resources][gltf][meshopt][quantization][instancing][assimp]") {
    if (std::system("command -v gltfpack >/dev/null 2>&1") != 0) FAIL("gltfpack not found: scripts/install-deps.sh test installs it");
    const std::string dir = freshDir("gltf-gltfpack");
    const std::string source = kAssimpGltf + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    LoadOptions options;
    options.loadTextures = false;
    auto plain = loadGltf(source, options);
    REQUIRE(plain.ok());
    for (const char* flags : {"", "-c", "-c -mi"}) {
        const std::string out = dir + "/packed" + std::to_string(std::strlen(flags)) + ".glb";
        INFO("gltfpack " << flags);
        REQUIRE(std::system(("gltfpack -i '" + source + "' -o '" + out + "' " + flags + " >/dev/null 2>&1").c_str()) == 0);
        const std::string json = [&] {
            auto bytes = readFileBytes(out);
            return bytes ? std::string(bytes.value().begin(), bytes.value().end()) : std::string();
        }();
        CHECK(contains(json, "KHR_mesh_quantization"));
        CHECK(contains(json, "EXT_meshopt_compression") == (flags[0] != 0));
        CHECK(contains(json, "EXT_mesh_gpu_instancing") == (std::strlen(flags) > 3));
        auto packed = loadGltf(out, options);
        INFO((packed.ok() ? std::string() : packed.error()));
        REQUIRE(packed.ok());
        // Instanced: each repeated part stored once, drawn at its places (its written-out copies
        // are the triangles compared).
        std::size_t drawn = 0;
        for (const DrawRange& r : packed.value().ranges) drawn += std::size_t(r.indexCount / 3) * std::max<std::size_t>(r.instances.size(), 1);
        const std::size_t stored = packed.value().mesh.triangleCount();
        if (std::strlen(flags) > 3) CHECK(stored < drawn);
        else CHECK(stored == drawn);
        Model written = packed.value();
        writeOutInstances(written);
        REQUIRE(written.mesh.triangleCount() == drawn);
        REQUIRE(drawn > 10000);
        CHECK(sharedTriangles(written.mesh, plain.value().mesh, quantizationStep(plain.value(), 14)) > 0.95);
    }
}

TEST_CASE("glTF world-space triangles equal assimp's OBJ export of the same file", "[resources][gltf][assimp]") {
    if (std::system("command -v assimp >/dev/null 2>&1") != 0) FAIL("assimp not found: scripts/install-deps.sh test installs assimp-utils");
    const std::string dir = freshDir("gltf-assimp");
    int compared = 0;
    for (const char* file : {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
                             "BoxTextured-glTF-Embedded/BoxTextured.gltf", "2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
                             "cameras/Cameras.gltf", "BoxTexcoords-glTF/boxTexcoords.gltf"}) {
        const std::string path = kAssimpGltf + "/" + file;
        INFO(path);
        REQUIRE(std::filesystem::exists(path));
        const std::string obj = dir + "/export" + std::to_string(compared) + ".obj";
        REQUIRE(std::system(("assimp export '" + path + "' '" + obj + "' >/dev/null 2>&1").c_str()) == 0);
        LoadOptions options;
        options.loadTextures = false;
        auto ours = loadGltf(path, options);
        auto theirs = loadObj(obj, options);
        REQUIRE(ours.ok());
        REQUIRE(theirs.ok());
        const auto a = triangles(ours.value()), b = triangles(theirs.value());
        REQUIRE(a.size() == b.size());
        // Tolerance: 1e-6 of the model's extent (both round a double or float transform to float).
        const Vec3 extent = ours.value().boundsMax - ours.value().boundsMin;
        const float tol = 1e-6f * std::max({extent.x, extent.y, extent.z, 1.0f});
        CHECK(unmatched(a, b, tol) == 0);
        ++compared;
    }
    CHECK(compared == 6);
}

// The exported OBJ's 'v', 'l' and 'p' lines, read directly (our OBJ loader reads faces only).
struct ObjLines {
    std::vector<Vec3> v;
    std::vector<std::array<int, 2>> segments;
    std::vector<int> points;
};
ObjLines readObjLines(const std::string& path) {
    ObjLines out;
    auto bytes = readFileBytes(path);
    REQUIRE(bytes.ok());
    const std::string text(bytes.value().begin(), bytes.value().end());
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        start = end + 1;
        float x = 0, y = 0, z = 0;
        int i = 0, j = 0;
        if (std::sscanf(line.c_str(), "v %f %f %f", &x, &y, &z) == 3) out.v.emplace_back(x, y, z);
        else if (std::sscanf(line.c_str(), "l %d %d", &i, &j) == 2) out.segments.push_back({i - 1, j - 1});
        else if (std::sscanf(line.c_str(), "p %d", &i) == 1) out.points.push_back(i - 1);
    }
    return out;
}

TEST_CASE("glTF-Asset-Generator's Mesh_PrimitiveMode set: every mode equals assimp's OBJ export", "[resources][gltf][assimp]") {
    if (std::system("command -v assimp >/dev/null 2>&1") != 0) FAIL("assimp not found: scripts/install-deps.sh test installs assimp-utils");
    const std::string set = kAssimpGltf + "/glTF-Asset-Generator/Mesh_PrimitiveMode";
    const std::string dir = freshDir("gltf-modes-assimp");
    const auto key = [](Vec3 p) { return std::array<long, 3>{std::lround(p.x * 1e5f), std::lround(p.y * 1e5f), std::lround(p.z * 1e5f)}; };
    for (int n = 0; n <= 15; ++n) {
        const std::string name = std::string("Mesh_PrimitiveMode_") + (n < 10 ? "0" : "") + std::to_string(n);
        const std::string path = set + "/" + name + ".gltf", obj = dir + "/" + name + ".obj";
        INFO(path);
        REQUIRE(std::filesystem::exists(path));
        REQUIRE(std::system(("assimp export '" + path + "' '" + obj + "' >/dev/null 2>&1").c_str()) == 0);
        LoadOptions options;
        options.loadTextures = false;
        auto ours = loadGltf(path, options);
        REQUIRE(ours.ok());
        const Model& m = ours.value();
        if (m.mesh.triangleCount() > 0) { // triangles, strips, fans
            auto theirs = loadObj(obj, options);
            REQUIRE(theirs.ok());
            const auto a = triangles(m), b = triangles(theirs.value());
            REQUIRE(a.size() == b.size());
            CHECK(unmatched(a, b, 1e-6f) == 0);
            continue;
        }
        // Points and lines: the same multisets of points and of (unordered) segments.
        const ObjLines theirs = readObjLines(obj);
        std::multiset<std::array<long, 3>> pa, pb;
        std::multiset<std::array<std::array<long, 3>, 2>> sa, sb;
        for (const LineSet& l : m.lineSets) {
            if (l.points) {
                for (std::uint32_t i : l.indices) pa.insert(key(l.positions[i]));
                continue;
            }
            for (std::size_t k = 0; k + 1 < l.indices.size(); k += 2) {
                auto e = std::array<std::array<long, 3>, 2>{key(l.positions[l.indices[k]]), key(l.positions[l.indices[k + 1]])};
                if (e[1] < e[0]) std::swap(e[0], e[1]);
                sa.insert(e);
            }
        }
        for (int i : theirs.points) pb.insert(key(theirs.v[std::size_t(i)]));
        for (const auto& s2 : theirs.segments) {
            auto e = std::array<std::array<long, 3>, 2>{key(theirs.v[std::size_t(s2[0])]), key(theirs.v[std::size_t(s2[1])])};
            if (e[1] < e[0]) std::swap(e[0], e[1]);
            sb.insert(e);
        }
        CHECK(pa.size() + sa.size() > 0);
        CHECK(pa == pb);
        CHECK(sa == sb);
    }
}
#endif

TEST_CASE("glTF: KHR_materials_unlit (required or not) marks the material unlit", "[resources][gltf][pbr]") {
    const std::string dir = freshDir("gltf-unlit");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":0},"
               "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":1}]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.materials = "[{\"extensions\":{\"KHR_materials_unlit\":{}}},{\"name\":\"lit\"}]";
    a.extra = ",\"extensionsUsed\":[\"KHR_materials_unlit\"],\"extensionsRequired\":[\"KHR_materials_unlit\"]";
    auto r = load(dir, "unlit.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    REQUIRE(r.value().materials.size() == 2);
    REQUIRE(r.value().materials[0].pbr.has_value());
    CHECK(r.value().materials[0].pbr->unlit);
    CHECK_FALSE(r.value().materials[1].pbr->unlit);
}

TEST_CASE("glTF KHR_materials_ior and _specular: the dielectric's F0 and specular weight, the unclamped F0 for its texture",
          "[resources][gltf][pbr]") {
    const std::string dir = freshDir("gltf-specular");
    Asset a = triangleAsset("[{\"mesh\":0}]");
    a.meshes = a.meshes.substr(0, a.meshes.size() - 4) + ",\"material\":0}]}]"; // (the primitive's material)
    a.materials = R"([{"extensions":{"KHR_materials_ior":{"ior":2.0}}},
        {"extensions":{"KHR_materials_specular":{"specularFactor":0.5,"specularColorFactor":[2,1,40]}}},
        {"extensions":{"KHR_materials_ior":{"ior":0},"KHR_materials_specular":{"specularTexture":{"index":0}}}},
        {"extensions":{"KHR_materials_ior":{"ior":1.5}}},
        {"pbrMetallicRoughness":{"metallicFactor":0,"baseColorFactor":[0.5,0.5,0.5,1]},
         "extensions":{"KHR_materials_ior":{"ior":2.0},"KHR_materials_specular":{"specularFactor":0.5}}},
        {}])";
    a.extra = R"(,"extensionsUsed":["KHR_materials_ior","KHR_materials_specular"],"extensionsRequired":["KHR_materials_ior"])";
    auto r = load(dir, "specular.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.materials.size() >= 6);
    const auto f0 = [&](std::size_t i) { return m.materials[i].pbr->dielectricF0; };
    const float third2 = float((1.0 / 3.0) * (1.0 / 3.0));
    CHECK(f0(0).x == third2);
    CHECK(f0(0).z == third2);
    CHECK(m.materials[0].pbr->specularWeight == 1.0f);
    CHECK(f0(1).x == float(0.2 * 0.2 * 2.0)); // ior 1.5 x the colour
    CHECK(f0(1).y == float(0.2 * 0.2));
    CHECK(f0(1).z == 1.0f);                  // 0.04 x 40, clamped to 1
    CHECK(m.materials[1].pbr->specularWeight == 0.5f);
    CHECK(m.materials[1].pbr->specularColorF0.z == float(0.2 * 0.2 * 40.0)); // before the clamp (a specularColorTexture's factor)
    CHECK(f0(2).x == 1.0f); // ior 0
    CHECK(f0(3).x == 0.04f); // ior 1.5 given: the default's value exactly
    CHECK(f0(5).x == 0.04f);
    CHECK(m.materials[5].pbr->specularWeight == 1.0f);
    // The Blinn-Phong mapping: ks = F0 x weight for a dielectric.
    CHECK(m.materials[4].ks.r == float(third2 * 0.5));
    CHECK(m.materials[5].ks.r == 1.0f); // a metal (the default metallic 1): its base colour
    CHECK(m.warnings.empty());
}

TEST_CASE("glTF KHR_materials_clearcoat: the coat's weight, roughness and normal scale, its maps", "[resources][gltf][pbr][clearcoat]") {
    const std::string dir = freshDir("gltf-clearcoat");
    Image one;
    one.width = one.height = 1;
    one.rgba = {200, 100, 50, 255};
    REQUIRE(writeImage(dir + "/t.png", one).ok());
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
               "},\"material\":0}]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.materials = R"([{"extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":0.8,"clearcoatRoughnessFactor":0.3,
            "clearcoatTexture":{"index":0},"clearcoatNormalTexture":{"index":0,"scale":0.5}}}},
        {"extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":2,"clearcoatRoughnessFactor":-1,"clearcoatRoughnessTexture":{"index":0}}}},
        {"extensions":{"KHR_materials_clearcoat":{}}},
        {"extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":"x","clearcoatRoughnessFactor":[1],"clearcoatNormalTexture":7}}}])";
    a.extra = R"(,"images":[{"uri":"t.png"}],"textures":[{"source":0}],)"
              R"("extensionsUsed":["KHR_materials_clearcoat"],"extensionsRequired":["KHR_materials_clearcoat"])";
    auto r = load(dir, "clearcoat.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.materials.size() >= 4);
    const PbrFactors& k0 = *m.materials[0].pbr;
    CHECK(k0.clearcoat == 0.8f);
    CHECK(k0.clearcoatRoughness == 0.3f);
    CHECK(k0.clearcoatNormalScale == 0.5f);
    CHECK(m.materials[0].maps[MapSlot::Clearcoat] >= 0);
    CHECK(m.materials[0].maps[MapSlot::ClearcoatNormal] >= 0);
    CHECK(m.materials[0].maps[MapSlot::ClearcoatRoughness] == -1);
    CHECK(m.materials[1].pbr->clearcoat == 1.0f);          // clamped into [0, 1]
    CHECK(m.materials[1].pbr->clearcoatRoughness == 0.0f); // out of range: the default
    CHECK(m.materials[1].maps[MapSlot::ClearcoatRoughness] >= 0);
    CHECK(m.materials[1].maps[MapSlot::Clearcoat] == -1);
    CHECK(m.materials[2].pbr->clearcoat == 0.0f); // the extension's defaults: no coat
    CHECK(m.materials[2].pbr->clearcoatNormalScale == 1.0f);
    CHECK(m.materials[3].pbr->clearcoat == 0.0f); // malformed: the defaults
    CHECK(m.materials[3].pbr->clearcoatRoughness == 0.0f);
    CHECK(m.materials[3].maps[MapSlot::ClearcoatNormal] == -1);
    CHECK(m.warnings.empty());
}

TEST_CASE("glTF KHR_materials_pbrSpecularGlossiness: diffuse, specular and glossiness as metallic-roughness inputs",
          "[resources][gltf][pbr][specgloss]") {
    const std::string dir = freshDir("gltf-specgloss");
    Image one;
    one.width = one.height = 1;
    one.rgba = {200, 100, 50, 128};
    REQUIRE(writeImage(dir + "/d.png", one).ok());
    REQUIRE(writeImage(dir + "/sg.png", one).ok());
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
               "},\"material\":0}]}]";
    a.nodes = "[{\"mesh\":0}]";
    // 0: factors alone. 1: both textures, over a metallic-roughness fallback (metal, another
    // texture) that the extension replaces. 2: the extension's defaults.
    a.materials = R"([{"extensions":{"KHR_materials_pbrSpecularGlossiness":{"diffuseFactor":[0.8,0.6,0.4,0.5],
            "specularFactor":[0.2,0.1,0.05],"glossinessFactor":0.7}}},
        {"pbrMetallicRoughness":{"metallicFactor":1,"baseColorTexture":{"index":1}},
         "extensions":{"KHR_materials_pbrSpecularGlossiness":{"diffuseTexture":{"index":0},"specularGlossinessTexture":{"index":1},
            "specularFactor":[0.5,0.25,1],"glossinessFactor":0.9}}},
        {"extensions":{"KHR_materials_pbrSpecularGlossiness":{}}},
        {"extensions":{"KHR_materials_pbrSpecularGlossiness":{"diffuseFactor":"red","specularFactor":[0.5],"glossinessFactor":7}}}])";
    a.extra = R"(,"images":[{"uri":"d.png"},{"uri":"sg.png"}],"textures":[{"source":0},{"source":1}],)"
              R"("extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],"extensionsRequired":["KHR_materials_pbrSpecularGlossiness"])";
    auto r = load(dir, "specgloss.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.materials.size() >= 4);
    const PbrFactors& k0 = *m.materials[0].pbr;
    // c_diff = diffuse x (1 - max(specular)) folded in; F0 = specular; roughness = 1 - glossiness.
    CHECK(k0.baseColor.r == float(0.8 * 0.8));
    CHECK(k0.baseColor.g == float(0.6 * 0.8));
    CHECK(k0.baseColor.b == float(0.4 * 0.8));
    CHECK(k0.baseColor.a == 0.5f);
    CHECK(k0.metallic == 0.0f);
    CHECK(k0.roughness == float(1.0 - 0.7));
    checkVec(k0.dielectricF0, 0.2f, 0.1f, 0.05f);
    CHECK(k0.specularWeight == 1.0f);
    CHECK_FALSE(k0.specularGlossiness); // nothing per pixel
    CHECK(m.materials[0].kd.r == float(0.8 * 0.8)); // the Blinn-Phong mapping: kd = c_diff, ks = F0
    CHECK(m.materials[0].ks.r == 0.2f);
    const Material& m1 = m.materials[1];
    const PbrFactors& k1 = *m1.pbr;
    CHECK(k1.specularGlossiness); // per pixel: the texture's alpha and RGB
    CHECK(k1.glossiness == 0.9f);
    CHECK(k1.metallic == 0.0f);          // not the fallback's metal
    CHECK(k1.baseColor.r == 1.0f);       // the diffuse, unfolded (the program scales it per pixel)
    checkVec(k1.specularColorF0, 0.5f, 0.25f, 1.0f);
    CHECK(m1.kd.r == float(1.0 * (1.0 - 1.0))); // kd with the factor's F0: max 1
    REQUIRE(m1.texture >= 0);
    CHECK(m1.maps[MapSlot::SpecularColour] >= 0);
    CHECK(m1.maps[MapSlot::Glossiness] == m1.maps[MapSlot::SpecularColour]); // one image: RGB and alpha
    CHECK(m1.texture != m1.maps[MapSlot::Glossiness]);                        // the diffuse texture, not the fallback's
    CHECK(m1.maps[MapSlot::MetallicRoughness] == -1);
    const PbrFactors& k2 = *m.materials[2].pbr;
    checkVec(k2.dielectricF0, 1.0f, 1.0f, 1.0f);
    CHECK(k2.baseColor.r == 0.0f); // specular 1 leaves no diffuse
    CHECK(k2.roughness == 0.0f);
    // Malformed values read as their defaults, clamped: no crash, no NaN.
    const PbrFactors& k3 = *m.materials[3].pbr;
    checkVec(k3.dielectricF0, 0.5f, 1.0f, 1.0f); // the missing channels: 1
    CHECK(k3.roughness == 0.0f);                 // glossiness 7, clamped to 1
    CHECK(k3.baseColor.r == 0.0f);               // diffuse 1 x (1 - 1)
    CHECK(m.warnings.empty());
    // An extension that is not an object is refused by the schema check, naming it.
    Asset bad = a;
    bad.materials = R"([{"extensions":{"KHR_materials_pbrSpecularGlossiness":[1,2]}}])";
    auto refused = load(dir, "bad.gltf", bad.embedded());
    REQUIRE_FALSE(refused.ok());
    CHECK(contains(refused.error(), "KHR_materials_pbrSpecularGlossiness: expected an object"));
}

TEST_CASE("glTF: a primitive without a material gets the specification's default material", "[resources][gltf][pbr]") {
    const std::string dir = freshDir("gltf-default-material");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
    a.nodes = "[{\"mesh\":0}]";
    auto r = load(dir, "nomaterial.gltf", a.embedded());
    INFO((r.ok() ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.ranges.size() == 1);
    REQUIRE(m.ranges[0].material >= 0);
    const Material& k = m.materials[std::size_t(m.ranges[0].material)];
    REQUIRE(k.pbr.has_value());
    CHECK(k.pbr->baseColor.r == 1.0f);
    CHECK(k.pbr->baseColor.g == 1.0f);
    CHECK(k.pbr->baseColor.b == 1.0f);
    CHECK(k.pbr->metallic == 1.0f);
    CHECK(k.pbr->roughness == 1.0f);
    CHECK_FALSE(k.doubleSided);
    CHECK(k.alpha == 1.0f);
    CHECK(k.texture == -1);
}
