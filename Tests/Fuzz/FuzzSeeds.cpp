// Writes the fuzz seed corpora: tiny OBJ/MTL texts and PNG/BMP/TGA/JPEG/PPM/PGM images made here (no third-party files).
// Usage: sr_fuzz_seeds DIR   -> DIR/obj/*, DIR/gltf/* and DIR/image/* (the directories are created).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

// A private, uninstrumented copy of the writer (static functions): its JPEG encoder shifts
// negative values, which the sanitizers of the fuzz build would stop at. Not part of sr_resources.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include "stb_image_write.h"

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
