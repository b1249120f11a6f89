// Tests of loading well-formed OBJ/MTL files: triangulation, de-duplication, normals, uvs, materials, textures, ranges.
#include "TestFramework.hpp"

#include <cmath>
#include <filesystem>

#include "ObjTestUtil.hpp"
#include "Resources/ObjLoader.hpp"

using namespace sr;
using namespace sr::objtest;

namespace {

// The cube [-1,1]^3 as explicit CCW-outward triangles; each face (a,b,c,d) becomes (a,b,c),(a,c,d).
const char* kCubeVertices = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n";
const char* kCubeFaces[6][4] = {{"2", "3", "7", "6"}, {"8", "7", "3", "4"}, {"5", "6", "7", "8"},
                                {"1", "5", "8", "4"}, {"1", "2", "6", "5"}, {"1", "4", "3", "2"}};

std::string cubeObj(bool withNormals) {
    std::string s = kCubeVertices;
    if (withNormals) s += "vn 2 0 0\nvn 0 3 0\nvn 0 0 0.5\nvn -1 0 0\nvn 0 -1 0\nvn 0 0 -1\n";
    for (int f = 0; f < 6; ++f) {
        const auto fv = [&](int k) {
            return std::string(kCubeFaces[f][k]) + (withNormals ? "//" + std::to_string(f + 1) : "");
        };
        s += "f " + fv(0) + " " + fv(1) + " " + fv(2) + "\n";
        s += "f " + fv(0) + " " + fv(2) + " " + fv(3) + "\n";
    }
    return s;
}

// Index of the mesh vertex at position p (first match), or -1.
int vertexAt(const Mesh& mesh, Vec3 p) {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (mesh.positions[i].x == p.x && mesh.positions[i].y == p.y && mesh.positions[i].z == p.z) return int(i);
    return -1;
}

void checkVec(Vec3 v, double x, double y, double z) {
    CHECK(v.x == Approx(x).margin(1e-6));
    CHECK(v.y == Approx(y).margin(1e-6));
    CHECK(v.z == Approx(z).margin(1e-6));
}

} // namespace

TEST_CASE("OBJ quads follow tinyobjloader's shorter-diagonal rule and vertices are de-duplicated", "[resources][obj]") {
    const std::string dir = freshDir("quad");
    // |p2-p0|^2 = 4 < |p3-p1|^2 = 16: split along 0-2 -> (0,1,2),(0,2,3).
    auto a = loadObj(writeText(dir, "kite.obj", "v 0 0 0\nv 1 -2 0\nv 2 0 0\nv 1 2 0\nf 1 2 3 4\n"));
    REQUIRE(a.ok());
    CHECK(a.value().mesh.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
    CHECK(a.value().mesh.vertexCount() == 4);
    // A square: a tie, so (0,1,3),(1,2,3); vertices are numbered in first-use order v1, v2, v4, v3.
    auto b = loadObj(writeText(dir, "square.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
    REQUIRE(b.ok());
    const Model& m = b.value();
    CHECK(m.mesh.indices == std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2});
    REQUIRE(m.mesh.vertexCount() == 4);
    checkVec(m.mesh.positions[2], 0, 1, 0);
    checkVec(m.mesh.positions[3], 1, 1, 0);
    for (const Vec3& n : m.mesh.normals) checkVec(n, 0, 0, 1);
    CHECK_FALSE(m.hasUvs);
    CHECK(m.mesh.uvs.empty());
    CHECK_FALSE(m.normalsFromFile);
    REQUIRE(m.ranges.size() == 1);
    CHECK(m.ranges[0].indexCount == 6);
    CHECK(m.ranges[0].material == -1);
    CHECK(m.warnings.empty());
}

TEST_CASE("OBJ cube without vn gets area-weighted vertex normals", "[resources][obj]") {
    const std::string dir = freshDir("cube-computed");
    auto r = loadObj(writeText(dir, "cube.obj", cubeObj(false)));
    REQUIRE(r.ok());
    const Model& m = r.value();
    CHECK(m.mesh.triangleCount() == 12);
    CHECK(m.mesh.vertexCount() == 8);
    CHECK_FALSE(m.normalsFromFile);
    // Corner (1,1,1): in 2 triangles of +X, 1 of +Y, 2 of +Z, each cross product of length 4:
    // (8,4,8) -> (2,1,2)/3. Corner (-1,-1,-1): 2 of each of -X, -Y, -Z -> -(1,1,1)/sqrt(3).
    const int c7 = vertexAt(m.mesh, Vec3(1, 1, 1));
    const int c1 = vertexAt(m.mesh, Vec3(-1, -1, -1));
    REQUIRE(c7 >= 0);
    REQUIRE(c1 >= 0);
    checkVec(m.mesh.normals[std::size_t(c7)], 2.0 / 3, 1.0 / 3, 2.0 / 3);
    const double s = -1.0 / std::sqrt(3.0);
    checkVec(m.mesh.normals[std::size_t(c1)], s, s, s);
}

TEST_CASE("OBJ cube with vn uses the file's normals, normalised", "[resources][obj]") {
    const std::string dir = freshDir("cube-vn");
    auto r = loadObj(writeText(dir, "cube.obj", cubeObj(true)));
    REQUIRE(r.ok());
    const Model& m = r.value();
    CHECK(m.normalsFromFile);
    CHECK(m.mesh.triangleCount() == 12);
    CHECK(m.mesh.vertexCount() == 24); // each corner once per face: (v, vn) triples differ
    const double expected[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
    for (std::size_t t = 0; t < 12; ++t)
        for (int k = 0; k < 3; ++k) {
            const double* e = expected[t / 2];
            checkVec(m.mesh.normals[m.mesh.indices[t * 3 + std::size_t(k)]], e[0], e[1], e[2]);
        }
}

TEST_CASE("OBJ zero-length vn falls back to the computed normal, a lone degenerate triangle to +Z", "[resources][obj]") {
    const std::string dir = freshDir("zero-vn");
    auto r = loadObj(writeText(dir, "z.obj", "v 0 0 0\nv 0 0 1\nv 0 0 2\nvn 0 0 0\nf 1//1 2//1 3//1\n"));
    REQUIRE(r.ok());
    for (const Vec3& n : r.value().mesh.normals) checkVec(n, 0, 0, 1);
}

TEST_CASE("OBJ bounds cover every v entry, used or not; relative indices work", "[resources][obj]") {
    const std::string dir = freshDir("bounds");
    auto r = loadObj(writeText(dir, "b.obj", "v 10 -5 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv -7 20 -30\n"));
    REQUIRE(r.ok());
    const Model& m = r.value();
    checkVec(m.boundsMin, -7, -5, -30);
    checkVec(m.boundsMax, 10, 20, 3);
    CHECK(m.mesh.vertexCount() == 3);
    checkVec(m.mesh.positions[0], 0, 0, 0);
}

TEST_CASE("OBJ textured quad: MTL with backslash paths, a subfolder texture, uvs and ranges", "[resources][obj]") {
    const std::string dir = freshDir("textured");
    std::filesystem::create_directories(std::filesystem::u8path(dir + "/maps"));
    REQUIRE(writeImage(dir + "/tex.png", rampImage(4, 2)).ok());
    REQUIRE(writeImage(dir + "/maps/sub.png", rampImage(2, 3)).ok());
    writeText(dir, "quad.mtl",
              "newmtl A\nKd 1 0 0\nmap_Kd .\\tex.png\r\nnewmtl B\nmap_Kd maps\\sub.png  \nnewmtl C\nmap_Kd ./tex.png\n"
              "newmtl Plain\nKd 0 1 0\n");
    const std::string obj = "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                            "usemtl A\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
                            "usemtl C\nf 1/1 2/2 4\n"      // same texture as A: same range; no vt -> (0,0)
                            "usemtl B\nf 1/1 2/2 3/3\n"
                            "usemtl Plain\nf 1/1 2/2 3/3\n"
                            "usemtl Nope\nf 1/1 2/2 3/3\n" // unknown material: no material, untextured
                            "usemtl A\nf 2/2 3/3 4/4\n";
    auto r = loadObj(writeText(dir, "quad.obj", obj));
    REQUIRE(r.ok());
    const Model& m = r.value();
    CHECK(m.hasUvs);
    REQUIRE(m.mesh.uvs.size() == m.mesh.positions.size());
    REQUIRE(m.materials.size() == 4);
    CHECK(m.materials[0].name == "A");
    CHECK(m.materials[0].texture == 0);
    CHECK(m.materials[1].texture == 1);
    CHECK(m.materials[2].texture == 0); // "./tex.png" resolves to the same path as ".\tex.png"
    CHECK(m.materials[3].texture == -1);
    REQUIRE(m.textures.size() == 2);
    CHECK(m.texturePaths[0] == dir + "/./tex.png");
    CHECK(m.texturePaths[1] == dir + "/maps/sub.png");
    CHECK(m.textures[0].width == 4);
    CHECK(m.textures[0].height == 2);
    CHECK(int(m.textures[0].texel(3, 1)[0]) == 120); // stored top row first, as written
    CHECK(int(m.textures[0].texel(3, 1)[1]) == 40);
    CHECK(m.textures[1].width == 2);
    CHECK(m.textures[1].height == 3);
    // The MTL values as tinyobjloader reads them: A's Kd line; B has a map and no Kd line, but
    // tinyobjloader's "map_Kd without Kd gets 0.6" default does not apply once any earlier
    // material of the file had a Kd line (its flag is per file), so B's Kd stays black (the
    // reference renderer's "textured and black = the texture alone" rule covers this);
    // Plain's Kd; no Ks or Ns lines anywhere (0 and 1).
    CHECK(m.materials[0].kd.r == 1.0f);
    CHECK(m.materials[0].kd.g == 0.0f);
    CHECK(m.materials[1].kd.r == 0.0f);
    CHECK(m.materials[1].kd.b == 0.0f);
    CHECK(m.materials[3].kd.g == 1.0f);
    CHECK(m.materials[3].kd.r == 0.0f);
    for (const Material& mat : m.materials) {
        CHECK(mat.fromFile);
        CHECK(mat.ks.r == 0.0f);
        CHECK(mat.shininess == 1.0f);
    }
    CHECK(m.materials[0].hasMap);
    CHECK_FALSE(m.materials[3].hasMap);
    // One range per material, in order of first use: A,A,A (faces 1, 2, 7) | C | B | Plain | Nope (none).
    REQUIRE(m.ranges.size() == 5);
    CHECK(m.ranges[0].indexCount == 9);
    CHECK(m.ranges[0].material == 0);
    CHECK(m.ranges[1].material == 2);
    CHECK(m.ranges[1].firstIndex == 9);
    CHECK(m.ranges[1].texture == 0);
    CHECK(m.ranges[2].material == 1);
    CHECK(m.ranges[2].firstIndex == 12);
    CHECK(m.ranges[3].material == 3);
    CHECK(m.ranges[3].texture == -1);
    CHECK(m.ranges[4].material == -1);
    CHECK(m.ranges[4].texture == -1);
    CHECK(m.ranges[4].firstIndex + m.ranges[4].indexCount == 21);
    for (const DrawRange& d : m.ranges) CHECK(d.texture == (d.material >= 0 ? m.materials[std::size_t(d.material)].texture : -1));
    // The C face's third vertex has no vt: uv (0,0); its v4 with vt 4 elsewhere is another vertex.
    const std::uint32_t noVt = m.mesh.indices[m.ranges[1].firstIndex + 2];
    CHECK(m.mesh.uvs[noVt].x == 0.0f);
    CHECK(m.mesh.uvs[noVt].y == 0.0f);
    CHECK(m.mesh.uvs[m.mesh.indices[5]].x == 0.0f);
    CHECK(m.mesh.uvs[m.mesh.indices[5]].y == 1.0f);
    CHECK(noVt != m.mesh.indices[5]);
}

TEST_CASE("OBJ material with a missing or broken texture gets the checkerboard and a warning", "[resources][obj]") {
    const std::string dir = freshDir("missing-tex");
    writeText(dir, "broken.png", "this is not a PNG");
    writeText(dir, "m.mtl", "newmtl Gone\nmap_Kd gone.png\nnewmtl Broken\nmap_Kd broken.png\n");
    auto r = loadObj(writeText(dir, "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                                            "usemtl Gone\nf 1/1 2/1 3/1\nusemtl Broken\nf 1/1 3/1 2/1\n"));
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.textures.size() == 2);
    for (const Image& t : m.textures) {
        CHECK(t.width == 8);
        CHECK(t.height == 8);
        CHECK(int(t.texel(0, 0)[0]) == 255);
        CHECK(int(t.texel(1, 0)[0]) == 0);
    }
    REQUIRE(m.warnings.size() == 2);
    CHECK(contains(m.warnings[0], "gone.png"));
    CHECK(contains(m.warnings[0], "no such file"));
    CHECK(contains(m.warnings[0], "'Gone'"));
    CHECK(contains(m.warnings[1], "broken.png"));
    CHECK(contains(m.warnings[1], "not a decodable image"));
}

TEST_CASE("OBJ with a missing MTL loads untextured with a warning", "[resources][obj]") {
    const std::string dir = freshDir("missing-mtl");
    auto r = loadObj(writeText(dir, "m.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                                            "usemtl X\nf 1/1 2/1 3/1\n"));
    REQUIRE(r.ok());
    const Model& m = r.value();
    CHECK(m.textures.empty());
    CHECK(m.ranges.size() == 1);
    CHECK(m.ranges[0].material == -1);
    REQUIRE_FALSE(m.warnings.empty());
    CHECK(contains(m.warnings[0], "nowhere.mtl: no such file"));
}

TEST_CASE("OBJ texture override replaces every material, even for faces without one", "[resources][obj]") {
    const std::string dir = freshDir("override");
    REQUIRE(writeImage(dir + "/over.png", rampImage(3, 3)).ok());
    writeText(dir, "m.mtl", "newmtl A\nmap_Kd missing.png\n");
    const std::string obj = writeText(dir, "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                                                    "f 1/1 2/1 3/1\nusemtl A\nf 1/1 3/1 2/1\n");
    LoadOptions o;
    o.textureOverride = dir + "/over.png";
    auto r = loadObj(obj, o);
    REQUIRE(r.ok());
    const Model& m = r.value();
    REQUIRE(m.textures.size() == 1);
    CHECK(m.textures[0].width == 3);
    CHECK(m.warnings.empty()); // the material's own missing map is never read
    // Two ranges: the face without a material (the override's stand-in material, not from the
    // MTL: the fixed values at render time), then material A; both with the override texture.
    REQUIRE(m.ranges.size() == 2);
    REQUIRE(m.materials.size() == 2);
    CHECK(m.ranges[0].material == 1);
    CHECK_FALSE(m.materials[1].fromFile);
    CHECK(m.ranges[1].material == 0);
    CHECK(m.materials[0].fromFile);
    for (const DrawRange& d : m.ranges) CHECK(d.texture == 0);
    for (const Material& mat : m.materials) CHECK(mat.texture == 0);

    o.textureOverride = dir + "/nope.png";
    auto bad = loadObj(obj, o);
    REQUIRE_FALSE(bad.ok());
    CHECK(contains(bad.error(), "nope.png"));

    // Without any vt the override is ignored with a warning (as glref does).
    o.textureOverride = dir + "/over.png";
    auto noUv = loadObj(writeText(dir, "n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), o);
    REQUIRE(noUv.ok());
    CHECK(noUv.value().textures.empty());
    CHECK(noUv.value().warnings.size() == 1);
}

TEST_CASE("OBJ loadTextures=false keeps texture slots but decodes nothing", "[resources][obj]") {
    const std::string dir = freshDir("no-decode");
    writeText(dir, "m.mtl", "newmtl A\nmap_Kd a.png\n");
    LoadOptions o;
    o.loadTextures = false;
    auto r = loadObj(writeText(dir, "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl A\nf 1/1 2/1 3/1\n"), o);
    REQUIRE(r.ok());
    REQUIRE(r.value().textures.size() == 1);
    CHECK(r.value().textures[0].width == 0);
    CHECK(r.value().warnings.empty());
}

TEST_CASE("OBJ with a UTF-8 BOM, CRLF lines and comments loads every vertex", "[resources][obj]") {
    const std::string dir = freshDir("bom");
    auto r = loadObj(writeText(dir, "bom.obj", "\xEF\xBB\xBFv 0 0 0\r\n# c\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n"));
    REQUIRE(r.ok());
    CHECK(r.value().mesh.triangleCount() == 1);
    checkVec(r.value().boundsMin, 0, 0, 0);
}

TEST_CASE("Real models: glmark2 bunny and assimp spider load like glref", "[resources][obj]") {
    const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
    if (std::filesystem::exists(bunny)) {
        auto r = loadObj(bunny);
        REQUIRE(r.ok());
        const Model& m = r.value();
        CHECK(m.mesh.triangleCount() == 69666);
        CHECK(m.mesh.vertexCount() == 34835); // glref: "34835 indexed vertices"
        CHECK_FALSE(m.normalsFromFile);
        CHECK_FALSE(m.hasUvs);
        CHECK(m.ranges.size() == 1);
        CHECK(indicesValid(m.mesh));
    } else {
        WARN("skipped: " << bunny << " is not installed (apt install glmark2-data)");
    }
    const std::string spider = "/usr/share/assimp/models/OBJ/spider.obj";
    if (std::filesystem::exists(spider)) {
        auto r = loadObj(spider);
        REQUIRE(r.ok());
        const Model& m = r.value();
        CHECK(m.mesh.triangleCount() == 1368); // glref: 1368 triangles, 974 indexed vertices,
        CHECK(m.mesh.vertexCount() == 974);    // normals from OBJ, textures=5, draw runs=6
        CHECK(m.normalsFromFile);
        CHECK(m.hasUvs);
        CHECK(m.textures.size() == 5);
        // glref's 6 runs in file order (SpiderTex | Skin | BeinTex | Skin | BeinTex | Augentex)
        // are 4 ranges here, one per texture used (Brusttex's map is used by no face).
        CHECK(m.ranges.size() == 4);
        for (const Image& t : m.textures) CHECK(t.width > 8);
        CHECK(m.warnings.empty());
        CHECK(indicesValid(m.mesh));
    } else {
        WARN("skipped: " << spider << " is not installed (apt install assimp-testmodels)");
    }
}
