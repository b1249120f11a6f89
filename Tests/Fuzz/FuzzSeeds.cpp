// Writes the fuzz seed corpora: tiny OBJ/MTL texts, glTF files (plain, meshopt, Draco, WebP) and PNG/BMP/TGA/JPEG/PPM/PGM images made here (no third-party files).
// Usage: sr_fuzz_seeds DIR   -> DIR/obj/*, DIR/gltf/* and DIR/image/* (the directories are created).
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

// A private, uninstrumented copy of the writer (static functions): its JPEG encoder shifts
// negative values, which the sanitizers of the fuzz build would stop at. Not part of sr_resources.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include "stb_image_write.h"

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <webp/encode.h>

namespace {

bool gOk = true;

void put(const std::string& path, const std::string& bytes) {
    std::ofstream out(std::filesystem::u8path(path), std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out.flush()) {
        std::fprintf(stderr, "sr_fuzz_seeds: cannot write %s\n", path.c_str());
        gOk = false;
    }
}

void appendTo(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

// A w x h image with `comp` channels, values varying in x, y and channel.
std::vector<unsigned char> pixels(int w, int h, int comp) {
    std::vector<unsigned char> p(std::size_t(w) * std::size_t(h) * std::size_t(comp));
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<unsigned char>(i * 37 + 11);
    return p;
}

std::string base64(const std::string& bytes) {
    static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        unsigned v = unsigned((unsigned char)bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= unsigned((unsigned char)bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= (unsigned char)bytes[i + 2];
        out += kAlphabet[(v >> 18) & 63u];
        out += kAlphabet[(v >> 12) & 63u];
        out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63u] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[v & 63u] : '=';
    }
    return out;
}

// The encoded glTF seeds: a meshopt-compressed triangle (vertices, indices, octahedral normals),
// a Draco-compressed one, and a triangle textured with a lossless WebP, each in a data: URI.
void encodedSeeds(const std::string& gl) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const unsigned indices[3] = {0, 1, 2};
    const std::string head = "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],";
    const auto uri = [](const std::string& bytes) { return "data:application/octet-stream;base64," + base64(bytes); };
    {
        std::string vtx(meshopt_encodeVertexBufferBound(3, 12), '\0'), idx(meshopt_encodeIndexBufferBound(3, 3), '\0');
        vtx.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(&vtx[0]), vtx.size(), positions, 3, 12));
        idx.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(&idx[0]), idx.size(), indices, 3));
        const float normals[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0.6f, 0, 0.8f, 0};
        signed char oct[12];
        meshopt_encodeFilterOct(oct, 3, 4, 8, normals);
        std::string nrm(meshopt_encodeVertexBufferBound(3, 4), '\0');
        nrm.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(&nrm[0]), nrm.size(), oct, 3, 4));
        const std::string data = vtx + idx + nrm;
        const auto view = [&](std::size_t offset, std::size_t length, int stride, const char* mode, const char* filter) {
            return "{\"buffer\":1,\"byteLength\":" + std::to_string(stride * 3) + ",\"byteStride\":" + std::to_string(stride) +
                   ",\"extensions\":{\"EXT_meshopt_compression\":{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
                   ",\"byteLength\":" + std::to_string(length) + ",\"byteStride\":" + std::to_string(stride) +
                   ",\"count\":3,\"mode\":\"" + mode + "\",\"filter\":\"" + filter + "\"}}}";
        };
        put(gl + "meshopt.gltf",
            head + "\"extensionsUsed\":[\"EXT_meshopt_compression\"],\"extensionsRequired\":[\"EXT_meshopt_compression\"],"
                   "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":2},\"indices\":1}]}],"
                   "\"buffers\":[{\"byteLength\":" + std::to_string(data.size()) + ",\"uri\":\"" + uri(data) + "\"},"
                   "{\"byteLength\":64,\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}],"
                   "\"bufferViews\":[" + view(0, vtx.size(), 12, "ATTRIBUTES", "NONE") + "," + view(vtx.size(), idx.size(), 4, "TRIANGLES", "NONE") +
                   "," + view(vtx.size() + idx.size(), nrm.size(), 4, "ATTRIBUTES", "OCTAHEDRAL") + "],"
                   "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                   "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"},"
                   "{\"bufferView\":2,\"componentType\":5120,\"normalized\":true,\"count\":3,\"type\":\"VEC3\"}]}");
    }
    {
        draco::TriangleSoupMeshBuilder builder;
        builder.Start(1);
        const int att = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
        builder.SetAttributeValuesForFace(att, draco::FaceIndex(0), positions, positions + 3, positions + 6);
        std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
        draco::Encoder encoder;
        draco::EncoderBuffer out;
        if (!mesh || !encoder.EncodeMeshToBuffer(*mesh, &out).ok()) {
            std::fprintf(stderr, "sr_fuzz_seeds: the Draco encoder failed\n");
            gOk = false;
            return;
        }
        const std::string data(out.data(), out.size());
        put(gl + "draco.gltf",
            head + "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],"
                   "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"extensions\":{\"KHR_draco_mesh_compression\":"
                   "{\"bufferView\":0,\"attributes\":{\"POSITION\":" + std::to_string(mesh->attribute(att)->unique_id()) + "}}}}]}],"
                   "\"buffers\":[{\"byteLength\":" + std::to_string(data.size()) + ",\"uri\":\"" + uri(data) + "\"}],"
                   "\"bufferViews\":[{\"buffer\":0,\"byteLength\":" + std::to_string(data.size()) + "}],"
                   "\"accessors\":[{\"componentType\":5126,\"count\":" + std::to_string(mesh->num_points()) + ",\"type\":\"VEC3\"},"
                   "{\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]}");
    }
    {
        const auto rgba = pixels(4, 4, 4);
        std::uint8_t* webp = nullptr;
        const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), 4, 4, 16, &webp);
        const std::string image(reinterpret_cast<const char*>(webp), size);
        WebPFree(webp);
        std::string geometry(reinterpret_cast<const char*>(positions), 36);
        const float uvs[6] = {0, 0, 1, 0, 0, 1};
        geometry.append(reinterpret_cast<const char*>(uvs), 24);
        put(gl + "webp.gltf",
            head + "\"extensionsUsed\":[\"EXT_texture_webp\"],\"extensionsRequired\":[\"EXT_texture_webp\"],"
                   "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"material\":0}]}],"
                   "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
                   "\"textures\":[{\"extensions\":{\"EXT_texture_webp\":{\"source\":0}}}],"
                   "\"images\":[{\"uri\":\"data:image/webp;base64," + base64(image) + "\"}],"
                   "\"buffers\":[{\"byteLength\":60,\"uri\":\"" + uri(geometry) + "\"}],"
                   "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":24}],"
                   "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                   "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}]}");
    }
}

// Big-endian 32-bit, for the PNG header seed.
std::string be32(unsigned v) {
    return {char(v >> 24), char((v >> 16) & 255), char((v >> 8) & 255), char(v & 255)};
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: sr_fuzz_seeds DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::u8path(dir + "/obj"), ec);
    std::filesystem::create_directories(std::filesystem::u8path(dir + "/image"), ec);
    std::filesystem::create_directories(std::filesystem::u8path(dir + "/gltf"), ec);
    const std::string o = dir + "/obj/", im = dir + "/image/", gl = dir + "/gltf/";

    // --- OBJ (+ MTL after the "%%MTL%%" line; see FuzzObj.cpp) ---
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    put(o + "triangle.obj", tri + "f 1 2 3\n");
    put(o + "quad-normals.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n");
    put(o + "relative.obj", "o a\n" + tri + "f -3 -2 -1\ng b\nv 0 0 1\nf 1 2 -1\ns 1\n");
    put(o + "textured.obj", "mtllib f.mtl\n" + tri + "vt 0 0\nvt 1 0\nvt 0 1\nusemtl A\nf 1/1 2/2 3/3\n"
                            "usemtl B\nf 3/3/1 2/2/1 1/1/1\nvn 0 0 -1\n%%MTL%%\n"
                            "newmtl A\nKd 1 0 0\nmap_Kd t.ppm\n\nnewmtl B\nmap_Kd -s 2 2 1 t.bin\nNs 10\nd 0.5\n");
    put(o + "polygon.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 2 2 0\nv 0 2 0\nv -1 1 0\nf 1 2 3 4 5 6\nl 1 2\np 3\n");
    put(o + "numbers.obj", "v 1e3 -2.5E-2 +.5\nv 0x10 1e38 -0\nv 3.4e38 1 2\n# comment\r\nf 1 2 3\r\n");
    put(o + "bom-crlf.obj", "\xEF\xBB\xBFv 0 0 0\r\nv 1 0 0\r\nv 0 1 0 1\r\nvt 0.5 0.5 0\r\nf 1/1 2/1 3/1\r\n");
    put(o + "missing-mtl.obj", "mtllib none.mtl\nusemtl X\n" + tri + "vt 0 0\nf 1/1 2/1 3/1\n");
    put(o + "mtl-only.obj", "mtllib f.mtl\n" + tri + "vt 0 0\nusemtl M\nf 1/1 2/1 3/1\n%%MTL%%\n"
                            "newmtl M\nKa 0 0 0\nKs 1 1 1\nmap_Kd sub\\t.ppm\nmap_Ka t.ppm\nnewmtl N\n");

    // --- glTF (FuzzGltf.cpp writes t.bin, a triangle: 36 bytes of positions, 6 of u16 indices) ---
    const std::string views = "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
                              "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                              "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]";
    const std::string head = "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],";
    const std::string mesh = "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":0}]}],"
                             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.5,0.25,1],\"metallicFactor\":0.5}}],";
    put(gl + "external.gltf", head + "\"nodes\":[{\"translation\":[1,2,3],\"rotation\":[0,0,0.6,0.8],\"scale\":[1,2,-1],"
                                     "\"children\":[1]},{\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,5,1],\"mesh\":0}]," + mesh +
                                     "\"buffers\":[{\"byteLength\":42,\"uri\":\"t.bin\"}]," + views + "}");
    // The same buffer as a data URI (base64 of the 42 bytes), and a strip without indices.
    const std::string b64 = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA";
    put(gl + "embedded.gltf", head + "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
                                     "\"mode\":5}]}],\"buffers\":[{\"byteLength\":42,\"uri\":\"data:application/octet-stream;base64," +
                                     b64 + "\"}]," + views + "}");
    // Lights (KHR_lights_punctual: directional, point with range, spot), a double-sided material
    // and a sampler on a texture whose image is missing (a warning).
    put(gl + "lights.gltf",
        head + "\"nodes\":[{\"mesh\":0,\"children\":[1,2,3]},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
               "{\"translation\":[0,2,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
               "{\"translation\":[0,0,3],\"rotation\":[0,0.38268343,0,0.92387953],\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}}],"
               "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"material\":0}]}],"
               "\"materials\":[{\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
               "\"textures\":[{\"source\":0,\"sampler\":0}],\"images\":[{\"uri\":\"gone.png\"}],"
               "\"samplers\":[{\"wrapS\":33071,\"wrapT\":33648,\"minFilter\":9987,\"magFilter\":9728}],"
               "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
               "{\"type\":\"directional\",\"color\":[1,0.5,0.5],\"intensity\":2},{\"type\":\"point\",\"range\":5},"
               "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.1,\"outerConeAngle\":0.6}}]}},"
               "\"buffers\":[{\"byteLength\":42,\"uri\":\"t.bin\"}]," + views + "}");
    // Animation: a two-joint skin (weights summing to 2 and to 1), a morph target with mesh
    // weights, a LINEAR rotation clip on a joint and a STEP weights clip (base64 of 316 bytes:
    // positions, indices, key times, rotations, morph deltas, weights, joints, skin weights, two
    // inverse bind matrices).
    {
        const std::string data =
            "AAAAAAAAAEAAAAAAzczMPQAAAEAAAAAAAAAAAAAAAEDNzMw9AAABAAIAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAPMENT/zBDU/"
            "AAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8BAQAAAQAAAAABAAAAAIA/AACAPwAAAAAAAAAAAAAAQAAAAAAAAAAA"
            "AAAAAAAAAD8AAAA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/"
            "AACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAgL8AAAAAAACAPw==";
        std::string v = "\"bufferViews\":[";
        const int spans[9][2] = {{0, 36}, {36, 6}, {44, 8}, {52, 32}, {84, 36}, {120, 8}, {128, 12}, {140, 48}, {188, 128}};
        for (int k = 0; k < 9; ++k)
            v += std::string(k ? "," : "") + "{\"buffer\":0,\"byteOffset\":" + std::to_string(spans[k][0]) +
                 ",\"byteLength\":" + std::to_string(spans[k][1]) + "}";
        v += "],\"accessors\":["
             "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
             "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
             "{\"bufferView\":2,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\"},"
             "{\"bufferView\":3,\"componentType\":5126,\"count\":2,\"type\":\"VEC4\"},"
             "{\"bufferView\":4,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
             "{\"bufferView\":5,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\"},"
             "{\"bufferView\":6,\"componentType\":5121,\"count\":3,\"type\":\"VEC4\"},"
             "{\"bufferView\":7,\"componentType\":5126,\"count\":3,\"type\":\"VEC4\"},"
             "{\"bufferView\":8,\"componentType\":5126,\"count\":2,\"type\":\"MAT4\"}]";
        put(gl + "animated.gltf",
            "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
            "\"nodes\":[{\"mesh\":0,\"skin\":0},{\"children\":[2]},{\"translation\":[0,1,0]}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"JOINTS_0\":6,\"WEIGHTS_0\":7},\"indices\":1,"
            "\"targets\":[{\"POSITION\":4}]}],\"weights\":[0.5]}],"
            "\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":8}],"
            "\"animations\":[{\"samplers\":[{\"input\":2,\"output\":3},{\"input\":2,\"output\":5,\"interpolation\":\"STEP\"}],"
            "\"channels\":[{\"sampler\":0,\"target\":{\"node\":2,\"path\":\"rotation\"}},"
            "{\"sampler\":1,\"target\":{\"node\":0,\"path\":\"weights\"}}]}],"
            "\"buffers\":[{\"byteLength\":316,\"uri\":\"data:application/octet-stream;base64," + data + "\"}]," + v + "}");
    }
    // A GLB with the triangle in its BIN chunk.
    {
        std::string json = head + "\"nodes\":[{\"mesh\":0}]," + mesh + "\"buffers\":[{\"byteLength\":42}]," + views + "}";
        while (json.size() % 4) json += ' ';
        std::string bin(42, '\0');
        const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        const unsigned short indices[3] = {0, 1, 2};
        std::memcpy(&bin[0], positions, 36);
        std::memcpy(&bin[36], indices, 6);
        bin.resize(44, '\0');
        const auto le32 = [](unsigned v) { return std::string{char(v & 255), char((v >> 8) & 255), char((v >> 16) & 255), char(v >> 24)}; };
        put(gl + "binary.glb", "glTF" + le32(2) + le32(unsigned(12 + 8 + json.size() + 8 + bin.size())) + le32(unsigned(json.size())) +
                                   "JSON" + json + le32(unsigned(bin.size())) + std::string("BIN\0", 4) + bin);
    }

    encodedSeeds(gl);

    // --- images ---
    for (int comp : {1, 3, 4}) {
        const auto p = pixels(3, 2, comp);
        std::string png, bmp, tga, jpg;
        stbi_write_png_to_func(appendTo, &png, 3, 2, comp, p.data(), 3 * comp);
        stbi_write_bmp_to_func(appendTo, &bmp, 3, 2, comp, p.data());
        stbi_write_tga_to_func(appendTo, &tga, 3, 2, comp, p.data());
        stbi_write_jpg_to_func(appendTo, &jpg, 3, 2, comp, p.data(), 90);
        const std::string c = std::to_string(comp);
        put(im + "c" + c + ".png", png);
        put(im + "c" + c + ".bmp", bmp);
        put(im + "c" + c + ".tga", tga);
        put(im + "c" + c + ".jpg", jpg);
    }
    put(im + "rgb.ppm", "P6\n2 2\n255\n" + std::string("\xff\x00\x00\x00\xff\x00\x00\x00\xff\xff\xff\xff", 12));
    put(im + "grey.pgm", "P5 3 1 255 " + std::string("\x01\x80\xff", 3));
    put(im + "huge.ppm", "P6\n100000 100000\n255\n");
    put(im + "huge.png", "\x89PNG\r\n\x1a\n" + be32(13) + "IHDR" + be32(100000) + be32(100000) +
                             std::string("\x08\x06\x00\x00\x00", 5) + be32(0));
    return gOk ? 0 : 1;
}
