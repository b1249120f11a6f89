// glTF accessors and encodings against hand-computed values: sparse and bufferView-less accessors, normalised and quantized integers, integers written as floats, meshopt, Draco, WebP, GPU instancing, texture fallbacks, and files with nothing to draw.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#if SR_CODEC_ENCODERS
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <webp/encode.h>
#endif
#if SR_HAVE_AVIF
#include <avif/avif.h>
#endif

#include "GltfTestUtil.hpp"
#include "ObjTestUtil.hpp"
#include "Resources/Animation.hpp"
#include "Resources/FileIO.hpp"
#include "Resources/Gltf/Document.hpp"
#include "Resources/Gltf/GltfLoader.hpp"

using namespace sr;
using namespace sr::objtest;
using sr::gltftest::Asset;

namespace {

Result<Model> loadText(const std::string& dir, const std::string& name, const std::string& text) {
    return loadGltf(writeText(dir, name, text));
}

void checkVec(Vec3 v, float x, float y, float z, float margin = 1e-6f) {
    CHECK(v.x == Approx(x).margin(margin));
    CHECK(v.y == Approx(y).margin(margin));
    CHECK(v.z == Approx(z).margin(margin));
}

std::string primitive(const std::string& attributes, int indices = -1, const std::string& more = "") {
    std::string p = "{\"attributes\":{" + attributes + "}";
    if (indices >= 0) p += ",\"indices\":" + std::to_string(indices);
    return p + more + "}";
}

} // namespace

TEST_CASE("glTF sparse accessors: positions substituted at the sparse indices, over a buffer view or over zeros", "[resources][gltf][sparse]") {
    const std::string dir = freshDir("gltf-sparse");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const std::vector<std::uint16_t> sparseIndices{1, 2};
    const std::vector<float> sparseValues{5, 0, 0, 0, 7, 0};
    const int iv = a.view(sparseIndices.data(), 4);
    const int vv = a.view(sparseValues.data(), 24);
    // Accessor over the positions with vertices 1 and 2 replaced.
    const std::string sparse = ",\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":" + std::to_string(iv) +
                               ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}";
    const int over = a.rawAccessor("{\"bufferView\":" + std::to_string(pos) + ",\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"" + sparse + "}");
    // The same without a buffer view: zeros, then the sparse values.
    const int zeros = a.rawAccessor("{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"" + sparse + "}");
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(over)) + "]},{\"primitives\":[" +
               primitive("\"POSITION\":" + std::to_string(zeros)) + "]}]";
    a.nodes = "[{\"mesh\":0},{\"mesh\":1}]";
    a.scenes = "[{\"nodes\":[0,1]}]";
    auto r = loadText(dir, "sparse.gltf", a.embedded());
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Mesh& m = r.value().mesh;
    REQUIRE(m.vertexCount() == 6); // no NORMAL: three vertices per triangle
    checkVec(m.positions[0], 0, 0, 0);
    checkVec(m.positions[1], 5, 0, 0);
    checkVec(m.positions[2], 0, 7, 0);
    checkVec(m.positions[3], 0, 0, 0);
    checkVec(m.positions[4], 5, 0, 0);
    checkVec(m.positions[5], 0, 7, 0);

    // Sparse indices out of range or not increasing: one-line errors.
    Asset bad = a;
    const std::vector<std::uint16_t> backwards{2, 1};
    const int bv = bad.view(backwards.data(), 4);
    const int broken = bad.rawAccessor("{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":" +
                                       std::to_string(bv) + ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}}");
    bad.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(broken)) + "]}]";
    bad.nodes = "[{\"mesh\":0}]";
    bad.scenes = "[{\"nodes\":[0]}]";
    auto e = loadText(dir, "backwards.gltf", bad.embedded());
    REQUIRE_FALSE(e.ok());
    CHECK(contains(e.error(), "backwards.gltf"));
    CHECK(contains(e.error(), "not strictly increasing"));
}

TEST_CASE("glTF sparse morph targets and animation outputs", "[resources][gltf][sparse]") {
    const std::string dir = freshDir("gltf-sparse-morph");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int nrm = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const std::vector<std::uint8_t> idx{2};
    const std::vector<float> delta{0, 0, 3};
    const int iv = a.view(idx.data(), 1);
    const int vv = a.view(delta.data(), 12);
    // Target 0 moves vertex 2 by (0, 0, 3); a bufferView-less sparse accessor, as exporters write it.
    const int target = a.rawAccessor("{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" +
                                     std::to_string(iv) + ",\"componentType\":5121},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}}");
    a.meshes = "[{\"weights\":[0.5],\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm) +
               "},\"targets\":[{\"POSITION\":" + std::to_string(target) + "}]}]}]";
    a.nodes = "[{\"mesh\":0}]";
    auto r = loadText(dir, "morph.gltf", a.embedded());
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    // The rest pose at weight 0.5: vertex 2 at z = 1.5, the others unmoved.
    checkVec(r.value().mesh.positions[0], 0, 0, 0);
    checkVec(r.value().mesh.positions[2], 0, 1, 1.5f);
}

TEST_CASE("glTF integer attributes: normalised when the accessor says so, their integer value when not", "[resources][gltf][quantization]") {
    const std::string dir = freshDir("gltf-quantized");
    // KHR_mesh_quantization: positions as unnormalised shorts (scaled by the node; elements padded
    // to 8 bytes, the extension's alignment), normals as normalised bytes (padded to 4), uvs as
    // normalised signed shorts and as unnormalised unsigned bytes. Counts and component types
    // written as "3.0": JSON numbers, integral.
    Asset b;
    const std::vector<std::int16_t> pos8{0, 0, 0, 0, 1000, 0, 0, 0, 0, -2000, 0, 0};
    const std::vector<std::int8_t> nrm{0, 0, 127, 0, 0, 0, 127, 0, 0, -127, 0, 0};
    const std::vector<std::int16_t> uv{0, 0, 32767, 0, 0, -32767};
    const std::vector<std::uint8_t> uvBytes{0, 0, 2, 0, 0, 3};
    const int pv8 = b.view(pos8.data(), pos8.size() * 2);
    b.setView(pv8, "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":24,\"byteStride\":8}");
    const int nv4 = b.view(nrm.data(), nrm.size());
    b.setView(nv4, "{\"buffer\":0,\"byteOffset\":24,\"byteLength\":12,\"byteStride\":4}");
    const int uvv2 = b.view(uv.data(), uv.size() * 2);
    const int ubv2 = b.view(uvBytes.data(), uvBytes.size());
    const int P = b.rawAccessor("{\"bufferView\":" + std::to_string(pv8) + ",\"componentType\":5122.0,\"count\":3.0,\"type\":\"VEC3\"}");
    const int N = b.rawAccessor("{\"bufferView\":" + std::to_string(nv4) + ",\"componentType\":5120,\"normalized\":true,\"count\":3,\"type\":\"VEC3\"}");
    const int T = b.rawAccessor("{\"bufferView\":" + std::to_string(uvv2) + ",\"componentType\":5122,\"normalized\":true,\"count\":3,\"type\":\"VEC2\"}");
    const int U = b.rawAccessor("{\"bufferView\":" + std::to_string(ubv2) + ",\"componentType\":5121,\"count\":3,\"type\":\"VEC2\"}");
    b.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(P) + ",\"NORMAL\":" + std::to_string(N) + ",\"TEXCOORD_0\":" + std::to_string(T)) +
               "]},{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(P) + ",\"NORMAL\":" + std::to_string(N) + ",\"TEXCOORD_0\":" + std::to_string(U)) + "]}]";
    // The dequantization transform: a scale of 1/1000 (gltfpack's node scale).
    b.nodes = "[{\"mesh\":0,\"scale\":[0.001,0.001,0.001]},{\"mesh\":1,\"scale\":[0.001,0.001,0.001]}]";
    b.scenes = "[{\"nodes\":[0,1]}]";
    b.extra = ",\"extensionsUsed\":[\"KHR_mesh_quantization\"],\"extensionsRequired\":[\"KHR_mesh_quantization\"]";
    auto r = loadText(dir, "quantized.gltf", b.embedded());
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Mesh& m = r.value().mesh;
    REQUIRE(m.vertexCount() == 6);
    checkVec(m.positions[0], 0, 0, 0);
    checkVec(m.positions[1], 1, 0, 0);  // 1000 x 0.001: the integer value, not 1000 / 32767
    checkVec(m.positions[2], 0, -2, 0);
    checkVec(m.normals[0], 0, 0, 1);     // 127 / 127
    checkVec(m.normals[2], 0, -1, 0);    // max(-127 / 127, -1), renormalised
    // uvs: v flipped (1 - v); signed normalised: 32767 -> 1, -32767 -> -1.
    CHECK(m.uvs[1].x == Approx(1.0f));
    CHECK(m.uvs[2].y == Approx(2.0f));
    // Unnormalised bytes: their integer values (2, 0) and (0, 3).
    CHECK(m.uvs[4].x == Approx(2.0f));
    CHECK(m.uvs[5].y == Approx(1.0f - 3.0f));
}

TEST_CASE("glTF buffers: a data: URI inside a GLB, an unused buffer without a uri, an unread buffer without a uri is an error when read", "[resources][gltf]") {
    const std::string dir = freshDir("gltf-buffers");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(pos)) + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    // As a GLB whose buffer 0 is a data: URI (no BIN chunk used) and buffer 1 has no uri.
    std::string json = a.embedded();
    json.replace(json.find("}],\"bufferViews\""), 2, "},{\"byteLength\":64}]");
    const std::vector<unsigned char> glb = [&] {
        std::string j = json;
        while (j.size() % 4) j += ' ';
        std::vector<unsigned char> out;
        const auto u32 = [&](std::uint32_t v) {
            for (int k = 0; k < 4; ++k) out.push_back((unsigned char)(v >> (8 * k)));
        };
        u32(0x46546C67u);
        u32(2);
        u32(std::uint32_t(20 + j.size()));
        u32(std::uint32_t(j.size()));
        u32(0x4E4F534Au);
        out.insert(out.end(), j.begin(), j.end());
        return out;
    }();
    const std::string file = dir + "/datauri.glb";
    REQUIRE(writeFileBytes(file, glb.data(), glb.size()).ok());
    auto r = loadGltf(file);
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    checkVec(r.value().mesh.positions[1], 1, 0, 0);
    // Buffers nothing reads: a data: URI that is not base64 (RFC 2397: the characters,
    // percent-decoded) and a URI we do not fetch: the file loads.
    std::string unread = json;
    const std::string unused = "{\"byteLength\":64}";
    unread.replace(unread.find(unused), unused.size(),
                   "{\"byteLength\":3,\"uri\":\"data:application/gltf-buffer,a%20b\"},{\"byteLength\":8,\"uri\":\"http://example.com/b.bin\"}");
    auto u = loadText(dir, "unread.gltf", unread);
    INFO((u ? std::string() : u.error()));
    CHECK(u.ok());
    auto text = gltf::decodeDataUri("data:application/gltf-buffer,a%20b");
    REQUIRE(text.ok());
    CHECK(text.value() == std::vector<unsigned char>{'a', ' ', 'b'});
    auto b64 = gltf::decodeDataUri("data:application/octet-stream;base64,AAEC/w==");
    REQUIRE(b64.ok());
    CHECK(b64.value() == std::vector<unsigned char>{0, 1, 2, 255});
    // A view into the uri-less buffer: an error naming it.
    std::string reads = json;
    reads.replace(reads.find("\"buffer\":0"), 10, "\"buffer\":1");
    auto e = loadText(dir, "nouri.gltf", reads);
    REQUIRE_FALSE(e.ok());
    CHECK(contains(e.error(), "nouri.gltf"));
    CHECK(contains(e.error(), "no uri"));
}

TEST_CASE("glTF files with nothing to draw load empty, with a warning", "[resources][gltf]") {
    const std::string dir = freshDir("gltf-empty");
    auto none = loadText(dir, "noscene.gltf", "{\"asset\":{\"version\":\"2.0\"}}");
    INFO((none ? std::string() : none.error()));
    REQUIRE(none.ok());
    CHECK(none.value().mesh.vertexCount() == 0);
    REQUIRE(none.value().warnings.size() == 1);
    CHECK(contains(none.value().warnings[0], "no scene"));
    auto empty = loadText(dir, "empty.gltf", "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{}]}");
    REQUIRE(empty.ok());
    CHECK(empty.value().mesh.indices.empty());
    REQUIRE(empty.value().warnings.size() == 1);
    CHECK(contains(empty.value().warnings[0], "nothing to draw"));
}

#if SR_CODEC_ENCODERS // the libraries' encoders make the compressed files

TEST_CASE("EXT_meshopt_compression: attributes, octahedral normals and triangle indices decode to the original values", "[resources][gltf][meshopt]") {
    const std::string dir = freshDir("gltf-meshopt");
    // A quad: four float positions (12 bytes each), two triangles.
    const std::vector<float> positions{0, 0, 0, 2, 0, 0, 2, 3, 0, 0, 3, 0};
    const std::vector<std::uint32_t> indices{0, 1, 2, 0, 2, 3};
    std::vector<unsigned char> vtx(meshopt_encodeVertexBufferBound(4, 12));
    vtx.resize(meshopt_encodeVertexBuffer(vtx.data(), vtx.size(), positions.data(), 4, 12));
    std::vector<unsigned char> idx(meshopt_encodeIndexBufferBound(6, 4));
    idx.resize(meshopt_encodeIndexBuffer(idx.data(), idx.size(), indices.data(), 6));
    // Normals through the octahedral filter (8-bit, 4 bytes a normal), then the vertex codec.
    const std::vector<float> normals{0, 0, 1, 0, 0, 0, 1, 0, 0.6f, 0, 0.8f, 0, 0, 0.6f, 0.8f, 0};
    std::vector<std::int8_t> oct(16);
    meshopt_encodeFilterOct(oct.data(), 4, 4, 8, normals.data());
    std::vector<unsigned char> nrm(meshopt_encodeVertexBufferBound(4, 4));
    nrm.resize(meshopt_encodeVertexBuffer(nrm.data(), nrm.size(), oct.data(), 4, 4));

    Asset a;
    const std::size_t vo = a.nextOffset();
    a.view(vtx.data(), vtx.size());
    const std::size_t io = a.nextOffset();
    a.view(idx.data(), idx.size());
    const std::size_t no = a.nextOffset();
    a.view(nrm.data(), nrm.size());
    const auto ext = [](const char* name, std::size_t offset, std::size_t length, int stride, int count, const char* mode, const char* filter) {
        return std::string("{\"buffer\":1,\"byteLength\":") + std::to_string(stride * count) + ",\"byteStride\":" + std::to_string(stride) +
               ",\"extensions\":{\"" + name + "\":{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" +
               std::to_string(length) + ",\"byteStride\":" + std::to_string(stride) + ",\"count\":" + std::to_string(count) +
               ",\"mode\":\"" + mode + "\",\"filter\":\"" + filter + "\"}}}";
    };
    // Views 0-2 are the compressed bytes; views 3-5 the decoded ones (their buffer 1: the fallback).
    a.setView(0, "{\"buffer\":0,\"byteOffset\":" + std::to_string(vo) + ",\"byteLength\":" + std::to_string(vtx.size()) + "}");
    const int P = a.rawAccessor("{\"bufferView\":3,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"}");
    const int I = a.rawAccessor("{\"bufferView\":4,\"componentType\":5125,\"count\":6,\"type\":\"SCALAR\"}");
    const int N = a.rawAccessor("{\"bufferView\":5,\"componentType\":5120,\"normalized\":true,\"count\":4,\"type\":\"VEC3\"}");
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(P) + ",\"NORMAL\":" + std::to_string(N), I) + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    for (const char* name : {"EXT_meshopt_compression", "KHR_meshopt_compression"}) {
        Asset b = a;
        b.extra = std::string(",\"extensionsUsed\":[\"") + name + "\"],\"extensionsRequired\":[\"" + name + "\"]";
        std::string json = b.embedded();
        // Append the three compressed views and the uri-less fallback buffer.
        const std::string views = "," + ext(name, vo, vtx.size(), 12, 4, "ATTRIBUTES", "NONE") + "," +
                                  ext(name, io, idx.size(), 4, 6, "TRIANGLES", "NONE") + "," + ext(name, no, nrm.size(), 4, 4, "ATTRIBUTES", "OCTAHEDRAL");
        json.insert(json.find("],\"accessors\""), views);
        json.replace(json.find("}],\"bufferViews\""), 2, "},{\"byteLength\":1024,\"extensions\":{\"" + std::string(name) + "\":{\"fallback\":true}}}]");
        auto r = loadText(dir, std::string(name) + ".gltf", json);
        INFO(name << ": " << (r ? std::string() : r.error()));
        REQUIRE(r.ok());
        const Mesh& m = r.value().mesh;
        REQUIRE(m.vertexCount() == 4);
        for (std::size_t v = 0; v < 4; ++v) {
            checkVec(m.positions[v], positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
            // 8-bit octahedral: within 1/127 per component of the original unit normal.
            checkVec(m.normals[v], normals[4 * v], normals[4 * v + 1], normals[4 * v + 2], 0.02f);
        }
        CHECK(m.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});

        // A corrupt stream: one line naming the file and the view.
        std::string corrupt = json;
        const std::size_t at = corrupt.find("\"byteLength\":" + std::to_string(vtx.size()) + ",\"byteStride\":12,\"count\"");
        REQUIRE(at != std::string::npos);
        corrupt.replace(at, 13 + std::to_string(vtx.size()).size(), "\"byteLength\":5");
        auto e = loadText(dir, "corrupt.gltf", corrupt);
        REQUIRE_FALSE(e.ok());
        CHECK(contains(e.error(), "corrupt.gltf"));
        CHECK(contains(e.error(), "buffer view 3"));
        CHECK(e.error().find('\n') == std::string::npos);
    }
}

TEST_CASE("KHR_draco_mesh_compression: the decoded triangles are the original ones, in Draco's order", "[resources][gltf][draco]") {
    const std::string dir = freshDir("gltf-draco");
    // Two triangles of a quad, encoded losslessly enough (14-bit positions over a 2x3 box).
    const float quad[2][3][3] = {{{0, 0, 0}, {2, 0, 0}, {2, 3, 0}}, {{0, 0, 0}, {2, 3, 0}, {0, 3, 0}}};
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int att = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    for (int t = 0; t < 2; ++t)
        builder.SetAttributeValuesForFace(att, draco::FaceIndex(t), quad[t][0], quad[t][1], quad[t][2]);
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    REQUIRE(mesh);
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    draco::EncoderBuffer out;
    REQUIRE(encoder.EncodeMeshToBuffer(*mesh, &out).ok());
    const std::size_t points = mesh->num_points();
    const int id = int(mesh->attribute(att)->unique_id());

    Asset a;
    const int view = a.view(out.data(), out.size());
    const int P = a.rawAccessor("{\"componentType\":5126,\"count\":" + std::to_string(points) + ",\"type\":\"VEC3\"}");
    const int I = a.rawAccessor("{\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}");
    a.meshes = "[{\"primitives\":[" +
               primitive("\"POSITION\":" + std::to_string(P), I,
                         ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":" + std::to_string(view) +
                             ",\"attributes\":{\"POSITION\":" + std::to_string(id) + "}}}") +
               "]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.extra = ",\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]";
    auto r = loadText(dir, "draco.gltf", a.embedded());
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Mesh& m = r.value().mesh;
    REQUIRE(m.indices.size() == 6);
    // Each decoded triangle is one of the originals (Draco may reorder triangles and rotate their
    // vertices, never flip them), positions within the 14-bit step (3 / 2^14).
    int matched[2] = {0, 0};
    for (std::size_t t = 0; t < 2; ++t) {
        for (int o = 0; o < 2; ++o)
            for (int rot = 0; rot < 3; ++rot) {
                bool same = true;
                for (int k = 0; k < 3; ++k) {
                    const Vec3 p = m.positions[m.indices[3 * t + std::size_t((k + rot) % 3)]];
                    same = same && std::fabs(p.x - quad[o][k][0]) < 1e-3f && std::fabs(p.y - quad[o][k][1]) < 1e-3f && std::fabs(p.z - quad[o][k][2]) < 1e-3f;
                }
                if (same) ++matched[o];
            }
    }
    CHECK(matched[0] == 1);
    CHECK(matched[1] == 1);

    // A truncated stream, and accessors that disagree with the stream: one-line errors.
    Asset t = a;
    t.setView(view, "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" + std::to_string(out.size() / 2) + "}");
    auto e = loadText(dir, "truncated.gltf", t.embedded());
    REQUIRE_FALSE(e.ok());
    CHECK(contains(e.error(), "truncated.gltf"));
    CHECK(contains(e.error(), "KHR_draco_mesh_compression"));
    std::string wrongCount = a.embedded();
    wrongCount.replace(wrongCount.find("\"count\":6"), 9, "\"count\":9");
    auto w = loadText(dir, "count.gltf", wrongCount);
    REQUIRE_FALSE(w.ok());
    CHECK(contains(w.error(), "count.gltf"));
    CHECK(contains(w.error(), "triangles"));
}

TEST_CASE("EXT_texture_webp: a lossless WebP texture decodes to the PNG's bytes; other formats fall back or are refused", "[resources][gltf][webp]") {
    const std::string dir = freshDir("gltf-webp");
    const Image ramp = rampImage(16, 8);
    std::uint8_t* webp = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(ramp.rgba.data(), ramp.width, ramp.height, ramp.width * 4, &webp);
    REQUIRE(size > 0);
    const std::vector<unsigned char> webpBytes(webp, webp + size);
    WebPFree(webp);
    REQUIRE(writeFileBytes(dir + "/ramp.webp", webpBytes.data(), webpBytes.size()).ok());
    REQUIRE(writeImage(dir + "/ramp.png", ramp).ok());

    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    const int view = a.view(webpBytes.data(), webpBytes.size());
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv), -1, ",\"material\":0") + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.materials = "[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]";
    const auto withTexture = [&](const std::string& texture, const std::string& images, const std::string& required) {
        Asset b = a;
        b.extra = ",\"textures\":[" + texture + "],\"images\":" + images + ",\"extensionsUsed\":[" + required + "],\"extensionsRequired\":[" + required + "]";
        return b.embedded();
    };
    // WebP in the buffer (EXT_texture_webp, no fallback), and as a file with a PNG fallback.
    const std::string inBuffer = withTexture("{\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}}",
                                             "[{\"bufferView\":" + std::to_string(view) + ",\"mimeType\":\"image/webp\"}]", "\"EXT_texture_webp\"");
    const std::string asFile = withTexture("{\"source\":1,\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}}",
                                           "[{\"uri\":\"ramp.webp\"},{\"uri\":\"ramp.png\"}]", "\"EXT_texture_webp\"");
    for (const std::string& json : {inBuffer, asFile}) {
        auto r = loadText(dir, "webp.gltf", json);
        INFO((r ? std::string() : r.error()));
        REQUIRE(r.ok());
        REQUIRE(r.value().textures.size() == 1);
        CHECK(r.value().warnings.empty());
        CHECK(r.value().textures[0].width == 16);
        CHECK(r.value().textures[0].rgba == ramp.rgba);
    }
    // KHR_texture_basisu with a PNG fallback: the PNG; without one: refused, naming the texture.
    auto fb = loadText(dir, "basisu.gltf", withTexture("{\"source\":1,\"extensions\":{\"KHR_texture_basisu\":{\"source\":0}}}",
                                                         "[{\"uri\":\"x.ktx2\"},{\"uri\":\"ramp.png\"}]", "\"KHR_texture_basisu\""));
    INFO((fb ? std::string() : fb.error()));
    REQUIRE(fb.ok());
    CHECK(fb.value().textures[0].rgba == ramp.rgba);
    auto no = loadText(dir, "basisu-only.gltf", withTexture("{\"extensions\":{\"KHR_texture_basisu\":{\"source\":0}}}",
                                                             "[{\"uri\":\"x.ktx2\"}]", "\"KHR_texture_basisu\""));
    REQUIRE_FALSE(no.ok());
    CHECK(contains(no.error(), "basisu-only.gltf"));
    CHECK(contains(no.error(), "texture 0"));
    CHECK(contains(no.error(), "KHR_texture_basisu"));
    // A corrupt WebP: the checkerboard and a warning naming the image.
    std::vector<unsigned char> broken = webpBytes;
    broken.resize(broken.size() / 2);
    REQUIRE(writeFileBytes(dir + "/broken.webp", broken.data(), broken.size()).ok());
    auto c = loadText(dir, "broken.gltf", withTexture("{\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}}", "[{\"uri\":\"broken.webp\"}]",
                                                      "\"EXT_texture_webp\""));
    REQUIRE(c.ok());
    REQUIRE(c.value().warnings.size() == 1);
    CHECK(contains(c.value().warnings[0], "broken.webp"));
    CHECK(c.value().textures[0].width == 8); // the checkerboard
}

#endif // SR_CODEC_ENCODERS

#if SR_HAVE_AVIF
TEST_CASE("EXT_texture_avif: an AVIF texture decodes to its image, within the codec's loss; the PNG fallback is not read",
          "[resources][gltf][avif]") {
    const std::string dir = freshDir("gltf-avif");
    const Image ramp = rampImage(16, 8);
    // 8-bit 4:4:4 at the best quality the encoder has.
    avifImage* image = avifImageCreate(16, 8, 8, AVIF_PIXEL_FORMAT_YUV444);
    avifRGBImage rgb;
    avifRGBImageSetDefaults(&rgb, image);
    rgb.format = AVIF_RGB_FORMAT_RGBA;
    rgb.pixels = const_cast<std::uint8_t*>(ramp.rgba.data());
    rgb.rowBytes = 16 * 4;
    REQUIRE(avifImageRGBToYUV(image, &rgb) == AVIF_RESULT_OK);
    avifEncoder* encoder = avifEncoderCreate();
    encoder->minQuantizer = encoder->maxQuantizer = AVIF_QUANTIZER_BEST_QUALITY;
    avifRWData out = AVIF_DATA_EMPTY;
    REQUIRE(avifEncoderWrite(encoder, image, &out) == AVIF_RESULT_OK);
    REQUIRE(writeFileBytes(dir + "/ramp.avif", out.data, out.size).ok());
    avifRWDataFree(&out);
    avifEncoderDestroy(encoder);
    avifImageDestroy(image);

    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv), -1, ",\"material\":0") + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.materials = "[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}]";
    // The fallback names a file that does not exist: reading it would be a warning.
    a.extra = ",\"textures\":[{\"source\":1,\"extensions\":{\"EXT_texture_avif\":{\"source\":0}}}],"
              "\"images\":[{\"uri\":\"ramp.avif\"},{\"uri\":\"missing.png\"}],\"extensionsUsed\":[\"EXT_texture_avif\"]";
    auto r = loadText(dir, "avif.gltf", a.embedded());
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    CHECK(r.value().warnings.empty());
    REQUIRE(r.value().textures.size() == 1);
    const Image& t = r.value().textures[0];
    REQUIRE(t.width == 16);
    REQUIRE(t.height == 8);
    int worst = 0;
    for (std::size_t i = 0; i < t.rgba.size(); ++i) worst = std::max(worst, std::abs(int(t.rgba[i]) - int(ramp.rgba[i])));
    CHECK(worst <= 6);
    // A truncated AVIF: the checkerboard and a warning naming the file.
    auto bytes = readFileBytes(dir + "/ramp.avif");
    REQUIRE(bytes.ok());
    REQUIRE(writeFileBytes(dir + "/ramp.avif", bytes.value().data(), bytes.value().size() / 2).ok());
    auto c = loadText(dir, "truncated.gltf", a.embedded());
    REQUIRE(c.ok());
    REQUIRE(c.value().warnings.size() == 1);
    CHECK(contains(c.value().warnings[0], "ramp.avif"));
}
#endif

TEST_CASE("EXT_mesh_gpu_instancing: each instance's T R S placed before the node's transform", "[resources][gltf][instancing]") {
    const std::string dir = freshDir("gltf-instancing");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int nrm = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int t = a.floats({10, 0, 0, 0, 20, 0}, "VEC3");
    // Instance 1 turned 90 degrees about z and scaled by 2.
    const int r = a.floats({0, 0, 0, 1, 0, 0, 0.70710678f, 0.70710678f}, "VEC4");
    const int s = a.floats({1, 1, 1, 2, 2, 2}, "VEC3");
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm)) + "]}]";
    a.nodes = "[{\"mesh\":0,\"translation\":[0,0,5],\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":{\"TRANSLATION\":" +
              std::to_string(t) + ",\"ROTATION\":" + std::to_string(r) + ",\"SCALE\":" + std::to_string(s) + "}}}}]";
    a.extra = ",\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"],\"extensionsRequired\":[\"EXT_mesh_gpu_instancing\"]";
    auto m = loadText(dir, "instanced.gltf", a.embedded());
    INFO((m ? std::string() : m.error()));
    REQUIRE(m.ok());
    // Stored once, in the mesh's own space: one range drawn at the two places.
    REQUIRE(m.value().mesh.vertexCount() == 3);
    REQUIRE(m.value().mesh.indices.size() == 3);
    REQUIRE(m.value().ranges.size() == 1);
    CHECK(m.value().ranges[0].instances.size() == 2);
    CHECK(m.value().ranges[0].firstVertex == 0);
    CHECK(m.value().ranges[0].vertexCount == 3);
    checkVec(m.value().mesh.positions[1], 1, 0, 0);
    // The bounds are the places' (instance 1 reaches x = -2, y = 22).
    checkVec(m.value().boundsMin, -2, 0, 5, 1e-5f);
    checkVec(m.value().boundsMax, 11, 22, 5, 1e-5f);
    // Written out (the copies the places stand for), after the three stored vertices.
    Model written = m.value();
    writeOutInstances(written);
    const Mesh& mesh = written.mesh;
    REQUIRE(mesh.vertexCount() == 9);
    REQUIRE(written.ranges.size() == 1);
    REQUIRE(written.ranges[0].indexCount == 6);
    CHECK(written.ranges[0].instances.empty());
    // Instance 0: translated by (10, 0, 0), then the node's (0, 0, 5).
    checkVec(mesh.positions[3], 10, 0, 5);
    checkVec(mesh.positions[4], 11, 0, 5);
    // Instance 1: (1, 0, 0) -> scaled (2, 0, 0) -> turned (0, 2, 0) -> + (0, 20, 0) + (0, 0, 5).
    checkVec(mesh.positions[6], 0, 20, 5, 1e-5f);
    checkVec(mesh.positions[7], 0, 22, 5, 1e-5f);
    checkVec(mesh.positions[8], -2, 20, 5, 1e-5f);
    checkVec(mesh.normals[7], 0, 0, 1, 1e-6f);
    CHECK(std::vector<std::uint32_t>(mesh.indices.begin(), mesh.indices.end()) == std::vector<std::uint32_t>{3, 4, 5, 6, 7, 8});
    // Instances of different counts: refused.
    std::string bad = a.embedded();
    bad.replace(bad.find("\"SCALE\":" + std::to_string(s)), 8 + std::to_string(s).size(), "\"SCALE\":" + std::to_string(pos));
    auto e = loadText(dir, "counts.gltf", bad);
    REQUIRE_FALSE(e.ok());
    CHECK(contains(e.error(), "counts.gltf"));
    CHECK(contains(e.error(), "EXT_mesh_gpu_instancing"));
    // The limits count what is drawn: two draws of one triangle.
    const std::string file = writeText(dir, "limits.gltf", a.embedded());
    LoadOptions one;
    one.limits.maxInstanceDraws = 1;
    auto draws = loadGltf(file, one);
    REQUIRE_FALSE(draws.ok());
    CHECK(contains(draws.error(), "limits.gltf: more than 1 draws of instanced meshes"));
    LoadOptions oneTriangle;
    oneTriangle.limits.maxTriangles = 1;
    auto triangles = loadGltf(file, oneTriangle);
    REQUIRE_FALSE(triangles.ok());
    CHECK(contains(triangles.error(), "more than 1 triangles (each instance's counted)"));
    oneTriangle.limits.maxTriangles = 2;
    CHECK(loadGltf(file, oneTriangle).ok());
}

TEST_CASE("EXT_mesh_gpu_instancing: a mirroring instance is drawn from the faces reversed, its normals still outward",
          "[resources][gltf][instancing]") {
    const std::string dir = freshDir("gltf-instancing-mirror");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int nrm = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    // Instance 0 as it is; instance 1 mirrored in z (scale -1) and moved to z = -3; instance 2
    // scaled unevenly (no mirror).
    const int t = a.floats({0, 0, 0, 0, 0, -3, 5, 0, 0}, "VEC3");
    const int s = a.floats({1, 1, 1, 1, 1, -1, 3, 1, 1}, "VEC3");
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm)) + "]}]";
    a.nodes = "[{\"mesh\":0,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":{\"TRANSLATION\":" + std::to_string(t) +
              ",\"SCALE\":" + std::to_string(s) + "}}}}]";
    a.extra = ",\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"]";
    auto m = loadText(dir, "mirror.gltf", a.embedded());
    INFO((m ? std::string() : m.error()));
    REQUIRE(m.ok());
    // Two ranges over the one stored triangle: the faces kept (instances 0 and 2), reversed (1).
    REQUIRE(m.value().mesh.vertexCount() == 3);
    REQUIRE(m.value().ranges.size() == 2);
    CHECK(m.value().ranges[0].instances.size() == 2);
    REQUIRE(m.value().ranges[1].instances.size() == 1);
    CHECK(determinant(m.value().ranges[1].instances[0]) < 0.0f);
    const std::uint32_t* kept = m.value().mesh.indices.data() + m.value().ranges[0].firstIndex;
    const std::uint32_t* reversed = m.value().mesh.indices.data() + m.value().ranges[1].firstIndex;
    CHECK(std::vector<std::uint32_t>(kept, kept + 3) == std::vector<std::uint32_t>{0, 1, 2});
    CHECK(std::vector<std::uint32_t>(reversed, reversed + 3) == std::vector<std::uint32_t>{0, 2, 1});
    // Written out: every copy's face (in its index order) turns the way its normal points, the
    // mirrored one's towards -z.
    Model written = m.value();
    writeOutInstances(written);
    const Mesh& mesh = written.mesh;
    int checked = 0;
    for (const DrawRange& r : written.ranges)
        for (std::uint32_t k = 0; k < r.indexCount; k += 3) {
            const std::uint32_t* v = mesh.indices.data() + r.firstIndex + k;
            const Vec3 face = cross(mesh.positions[v[1]] - mesh.positions[v[0]], mesh.positions[v[2]] - mesh.positions[v[0]]);
            CHECK(dot(face, mesh.normals[v[0]]) > 0.0f);
            ++checked;
        }
    CHECK(checked == 3);
    checkVec(mesh.normals[mesh.indices[written.ranges[1].firstIndex]], 0, 0, -1, 1e-6f);
    checkVec(mesh.positions[mesh.indices[written.ranges[1].firstIndex + 1]], 0, 1, -3, 1e-6f); // (0, 1, 0) -> z flipped, moved
    checkVec(m.value().boundsMin, 0, 0, -3, 1e-6f);
    checkVec(m.value().boundsMax, 8, 1, 0, 1e-6f);
}

TEST_CASE("EXT_mesh_gpu_instancing in an animated file: each instance follows its node's animation; a skinned instanced mesh is refused",
          "[resources][gltf][instancing][animation]") {
    const std::string dir = freshDir("gltf-instancing-animated");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int nrm = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int t = a.floats({10, 0, 0, 0, 20, 0}, "VEC3");
    const int s = a.floats({1, 1, 1, 2, 2, 2}, "VEC3");
    const int input = a.floats({0, 1}, "SCALAR");
    const int moves = a.floats({0, 0, 5, 0, 4, 5}, "VEC3"); // the node from (0, 0, 5) to (0, 4, 5)
    a.meshes = "[{\"primitives\":[" + primitive("\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm)) + "]}]";
    a.nodes = "[{\"mesh\":0,\"translation\":[0,0,5],\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":{\"TRANSLATION\":" +
              std::to_string(t) + ",\"SCALE\":" + std::to_string(s) + "}}}}]";
    const std::string animation = ",\"animations\":[{\"samplers\":[{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(moves) +
                                  "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}]";
    a.extra = ",\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"],\"extensionsRequired\":[\"EXT_mesh_gpu_instancing\"]" + animation;
    auto m = loadText(dir, "animated.gltf", a.embedded());
    INFO((m ? std::string() : m.error()));
    REQUIRE(m.ok());
    Model model = std::move(m).value();
    REQUIRE(model.animation);
    REQUIRE(model.mesh.vertexCount() == 6);
    // At rest (the first key): instance 0 at (10, 0, 5), instance 1 scaled by 2 at (0, 20, 5).
    checkVec(model.mesh.positions[1], 11, 0, 5);
    checkVec(model.mesh.positions[4], 2, 20, 5);
    // At 0.5 s the node is at (0, 2, 5): each instance moves with it, its own transform kept.
    model.animation->pose(0.5, -1, model.mesh);
    checkVec(model.mesh.positions[0], 10, 2, 5);
    checkVec(model.mesh.positions[1], 11, 2, 5);
    checkVec(model.mesh.positions[3], 0, 22, 5);
    checkVec(model.mesh.positions[4], 2, 22, 5);
    checkVec(model.mesh.positions[5], 0, 24, 5);
    // A skinned mesh with instances: refused, naming the file and the extension.
    Asset skinned = a;
    skinned.nodes = "[{\"mesh\":0,\"skin\":0,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":{\"TRANSLATION\":" + std::to_string(t) +
                    "}}}},{}]";
    skinned.scenes = "[{\"nodes\":[0,1]}]";
    skinned.extra += ",\"skins\":[{\"joints\":[1]}]";
    auto e = loadText(dir, "skinned.gltf", skinned.embedded());
    REQUIRE_FALSE(e.ok());
    CHECK(contains(e.error(), "skinned.gltf"));
    CHECK(contains(e.error(), "EXT_mesh_gpu_instancing on a skinned mesh is not supported"));
}

TEST_CASE("KHR_materials_variants: a variant changes exactly its primitives' materials", "[resources][gltf][variants]") {
    const std::string dir = freshDir("gltf-variants");
    Asset a;
    const int p0 = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int p1 = a.floats({0, 0, 1, 1, 0, 1, 0, 1, 1}, "VEC3");
    const int p2 = a.floats({0, 0, 2, 1, 0, 2, 0, 1, 2}, "VEC3");
    // Primitive 0: material 0, "gold" -> 2. Primitive 1: material 1, "gold" and "steel" -> 0.
    // Primitive 2: material 1, no mappings.
    a.meshes = "[{\"primitives\":[" +
               primitive("\"POSITION\":" + std::to_string(p0), -1,
                         ",\"material\":0,\"extensions\":{\"KHR_materials_variants\":{\"mappings\":[{\"material\":2,\"variants\":[0]}]}}") +
               "," +
               primitive("\"POSITION\":" + std::to_string(p1), -1,
                         ",\"material\":1,\"extensions\":{\"KHR_materials_variants\":{\"mappings\":[{\"material\":0,\"variants\":[0,1]}]}}") +
               "," + primitive("\"POSITION\":" + std::to_string(p2), -1, ",\"material\":1") + "]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.materials = "[{\"name\":\"red\"},{\"name\":\"green\"},{\"name\":\"blue\"}]";
    a.extra = ",\"extensionsUsed\":[\"KHR_materials_variants\"],\"extensions\":{\"KHR_materials_variants\":{\"variants\":[{\"name\":\"gold\"},{\"name\":\"steel\"}]}}";
    const std::string file = writeText(dir, "variants.gltf", a.embedded());
    // The material of the triangle at depth z (one triangle per primitive, z = its index).
    const auto materialAt = [](const Model& m, float z) {
        for (const DrawRange& r : m.ranges)
            for (std::uint32_t k = r.firstIndex; k < r.firstIndex + r.indexCount; ++k)
                if (m.mesh.positions[m.mesh.indices[k]].z == z) return r.material;
        return -9;
    };
    const auto load = [&](const std::string& variant) {
        LoadOptions o;
        o.variant = variant;
        return loadGltf(file, o);
    };
    auto none = load("");
    REQUIRE(none.ok());
    CHECK(none.value().variants == std::vector<std::string>{"gold", "steel"});
    CHECK(none.value().variant == -1);
    CHECK(materialAt(none.value(), 0) == 0);
    CHECK(materialAt(none.value(), 1) == 1);
    CHECK(materialAt(none.value(), 2) == 1);
    auto gold = load("gold");
    REQUIRE(gold.ok());
    CHECK(gold.value().variant == 0);
    CHECK(materialAt(gold.value(), 0) == 2);
    CHECK(materialAt(gold.value(), 1) == 0);
    CHECK(materialAt(gold.value(), 2) == 1);
    auto steel = load("steel");
    REQUIRE(steel.ok());
    CHECK(materialAt(steel.value(), 0) == 0);
    CHECK(materialAt(steel.value(), 1) == 0);
    CHECK(materialAt(steel.value(), 2) == 1);
    auto unknown = load("chrome");
    REQUIRE_FALSE(unknown.ok());
    CHECK(contains(unknown.error(), "variants.gltf"));
    CHECK(contains(unknown.error(), "no material variant 'chrome' (its variants: gold, steel)"));
}
