// Regression tests for the inputs the fuzzers (Tests/Fuzz) found: each builds the bytes in code and expects a clean one-line error.
#include "TestFramework.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "Resources/Gltf/GltfLoader.hpp"
#include "Resources/Image.hpp"
#include "Resources/ObjLoader.hpp"

using namespace sr;

namespace {

std::string be32(std::uint32_t v) {
    return {char(v >> 24), char((v >> 16) & 255), char((v >> 8) & 255), char(v & 255)};
}

// Decodes `bytes` as "fuzz.bin" and returns the error, which must be one line naming the file.
std::string decodeError(const std::string& bytes) {
    const auto r = decodeImage(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "fuzz.bin");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().rfind("fuzz.bin: ", 0) == 0);
    CHECK(r.error().find('\n') == std::string::npos);
    CHECK(r.error().find('\r') == std::string::npos);
    return r.error();
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// PNG signature + an IHDR for a 3x2 RGB8 image (stb does not check CRCs: they are zero here).
std::string pngStart() {
    return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + "IHDR" + be32(3) + be32(2) + std::string("\x08\x02\x00\x00\x00", 5) +
           be32(0);
}

// The smallest baseline JPEG: one 8x8 grey component, quantiser 1, a DC and an AC Huffman
// table (0 and 0) with one 1-bit code each (DC category 0, AC end-of-block), and the entropy-coded
// bits "0" (DC difference 0) "0" (EOB) padded with ones: every pixel decodes to 128.
std::string baselineJpeg() {
    std::string jpg("\xFF\xD8", 2);
    jpg += std::string("\xFF\xDB\x00\x43\x00", 5) + std::string(64, '\x01');                  // DQT
    jpg += std::string("\xFF\xC0\x00\x0B\x08\x00\x08\x00\x08\x01\x01\x11\x00", 13);         // SOF0
    const std::string oneCode = std::string("\x01", 1) + std::string(15, '\0') + std::string(1, '\0');
    jpg += std::string("\xFF\xC4\x00\x26", 4) + std::string(1, '\x00') + oneCode + "\x10" + oneCode; // DHT
    jpg += std::string("\xFF\xDA\x00\x08\x01\x01\x00\x00\x3F\x00", 10);                      // SOS
    jpg += std::string("\x3F\xFF\xD9", 3);                                                    // data, EOI
    return jpg;
}

// Offset of the (first) SOS marker.
std::size_t sosOffset(const std::string& jpg) {
    const std::size_t at = jpg.find("\xFF\xDA");
    REQUIRE(at != std::string::npos);
    return at;
}

} // namespace

TEST_CASE("fuzz: a JPEG scan that selects a Huffman table no DHT defined is refused (stb 2.27 reads stale heap)",
          "[resources][image][fuzz]") {
    const std::string good = baselineJpeg();
    {
        const auto r = decodeImage(reinterpret_cast<const unsigned char*>(good.data()), good.size(), "good.jpg");
        REQUIRE(r.ok()); // the walk must not refuse a well-formed file
        REQUIRE(r.value().width == 8);
        REQUIRE(r.value().height == 8);
        CHECK(int(r.value().texel(7, 7)[0]) == 128);
    }
    const std::size_t sos = sosOffset(good);
    REQUIRE(good[sos + 4] == '\x01'); // one component: selector at sos + 5, its DC/AC table byte at sos + 6
    std::string dcMissing = good;
    dcMissing[sos + 6] = '\x20'; // DC table 2 (never defined), AC table 0
    CHECK(has(decodeError(dcMissing), "corrupt JPEG (a scan uses Huffman table DC 2"));
    std::string acMissing = good;
    acMissing[sos + 6] = '\x03'; // DC table 0, AC table 3 (never defined)
    CHECK(has(decodeError(acMissing), "Huffman table AC 3"));
    // The tables must be defined before the scan: move the DHT segment behind the scan header.
    const std::size_t dht = good.find("\xFF\xC4");
    REQUIRE(dht != std::string::npos);
    REQUIRE(dht < sos);
    const std::size_t dhtLength = std::size_t(static_cast<unsigned char>(good[dht + 2])) << 8 |
                                  static_cast<unsigned char>(good[dht + 3]);
    std::string late = good;
    late.erase(dht, 2 + dhtLength);
    const std::size_t lateSos = sosOffset(late);
    late.insert(lateSos + 2 + ((std::size_t(static_cast<unsigned char>(late[lateSos + 2])) << 8) |
                               static_cast<unsigned char>(late[lateSos + 3])),
                good.substr(dht, 2 + dhtLength));
    CHECK(has(decodeError(late), "Huffman table DC 0"));
}

TEST_CASE("fuzz: a JPEG Huffman table with more than 256 codes is refused (stb 2.27 writes out of bounds)",
          "[resources][image][fuzz]") {
    // DHT segment: class 0 table 0, sixteen code counts of 17 = 272 codes.
    const std::string dht = std::string("\xFF\xC4", 2) + std::string("\x01\x13", 2) + std::string(1, '\0') +
                            std::string(16, '\x11') + std::string(272, '\x01');
    CHECK(has(decodeError(std::string("\xFF\xD8", 2) + dht + "\xFF\xD9"), "Huffman table defines 272 codes"));
    // stb accepts 0xFF fill bytes before the SOI marker: so must the check.
    CHECK(has(decodeError(std::string("\xFF\xFF\xFF\xD8", 4) + dht), "Huffman table"));
}

TEST_CASE("fuzz: PNM header numbers above INT_MAX and 16-bit PNM are refused before stb reads them",
          "[resources][image][fuzz]") {
    CHECK(has(decodeError("P6\n0111111111111111111111111111111111111115\n5\n255\n"), "corrupt PNM header"));
    CHECK(has(decodeError("P5 # comment\n2 1 4294967296\n"), "corrupt PNM header"));
    // A 16-bit PNM overflowed stb's buffer in its 16 -> 8 bit conversion.
    CHECK(has(decodeError("P6\n5210\n5\n0520BM520BM"), "16-bit PNM"));
    CHECK(has(decodeError("P5\n2 1\n65535\n" + std::string(4, '\x7f')), "16-bit PNM"));
    // 8-bit still decodes.
    const std::string ok = "P6\n1 1\n255\n\x01\x02\x03";
    CHECK(decodeImage(reinterpret_cast<const unsigned char*>(ok.data()), ok.size(), "ok.ppm").ok());
}

TEST_CASE("fuzz: a PNG chunk claiming more bytes than the file has is refused without allocating",
          "[resources][image][fuzz]") {
    // 2 GiB IDAT in a 50-byte file: stb 2.27 would allocate the 2 GiB before reading.
    CHECK(has(decodeError(pngStart() + be32(0x80000000u) + "IDATxyz"), "chunk 'IDAT' claims 2147483648 bytes"));
    CHECK(has(decodeError(pngStart() + be32(1000) + "tEXt" + "abc"), "claims 1000 bytes"));
}

TEST_CASE("fuzz: stb's error text quoting file bytes stays on one line", "[resources][image][fuzz]") {
    // An unknown critical chunk: stb copies its type bytes (here a newline and form feeds) into the message.
    const std::string e = decodeError(pngStart() + be32(0) + "\x0c\n\x0c\x0c" + be32(0));
    CHECK(has(e, "PNG chunk not known"));
}

TEST_CASE("fuzz: a vertex-weight line with an id beyond int's range is refused before tinyobjloader",
          "[resources][obj][fuzz]") {
    // Found by sr_fuzz_obj: tinyobjloader converts "vw" joint ids with int(double) unchecked
    // (undefined behaviour for 1e38). The scan refuses such a line; ordinary weights still load.
    const std::string bad = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 1 1e38 0.5\nf 1 2 3\n";
    const auto r = loadObjFromMemory(reinterpret_cast<const unsigned char*>(bad.data()), bad.size(), "w.obj");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error() == "w.obj:4: vertex weight value '1e38' is not a number in int's range");
    const std::string good = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 1 0 0.5 2 0.5\nf 1 2 3\n";
    const auto ok = loadObjFromMemory(reinterpret_cast<const unsigned char*>(good.data()), good.size(), "w.obj");
    CHECK(ok.ok());
}

TEST_CASE("fuzz: a vertex-weight value that tinyobjloader would compute as NaN is refused", "[resources][obj][fuzz]") {
    // Found by sr_fuzz_obj (seed 1, 12-minute run): tinyobjloader computes "0e999" and ".e1384"
    // as 0 * pow(5, exponent) = 0 * inf = NaN and converts that to int (undefined behaviour),
    // while strtod reads them as 0. Values with an exponent above 300 are refused; a negative
    // exponent of any size and an ordinary exponent still load.
    for (const char* value : {".e1384", "0e999", "0.0e442", "-0E+500"}) {
        const std::string bad = std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 1 ") + value + " 0.5\nf 1 2 3\n";
        const auto r = loadObjFromMemory(reinterpret_cast<const unsigned char*>(bad.data()), bad.size(), "w.obj");
        INFO(value);
        REQUIRE_FALSE(r.ok());
        CHECK(r.error() == std::string("w.obj:4: vertex weight value '") + value + "' is not a number in int's range");
    }
    const std::string good = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 1 2e1 0.5 0e-999 5e-1\nf 1 2 3\n";
    const auto ok = loadObjFromMemory(reinterpret_cast<const unsigned char*>(good.data()), good.size(), "w.obj");
    CHECK(ok.ok());
}

TEST_CASE("fuzz: a GLB whose header gives a length shorter than the header is refused (the JSON chunk's bound underflowed)",
          "[resources][gltf][fuzz]") {
    // "glTF", version 2, total length 4 (the file has 60 bytes), a JSON chunk of 40 bytes.
    const auto le32 = [](std::uint32_t v) { return std::string{char(v & 255), char((v >> 8) & 255), char((v >> 16) & 255), char(v >> 24)}; };
    const std::string glb = "glTF" + le32(2) + le32(4) + le32(40) + "JSON" + std::string(40, ' ');
    const auto r = loadGltfFromMemory(reinterpret_cast<const unsigned char*>(glb.data()), glb.size(), "fuzz.glb");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error() == "fuzz.glb: a GLB whose header gives a length of 4 bytes");
}

TEST_CASE("fuzz: an array of glTF objects holding something else is refused naming it (a string accessor threw from the JSON library)",
          "[resources][gltf][fuzz]") {
    const auto load = [](const std::string& json) {
        return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(), "fuzz.gltf");
    };
    const std::string asset = R"({"asset":{"version":"2.0"},)";
    const std::pair<const char*, const char*> cases[] = {
        {R"("accessors":[{"count":1},"x"]})", "accessors: expected an array of objects"},
        {R"("materials":[true]})", "materials: expected an array of objects"},
        {R"("meshes":[{"primitives":[3]}]})", "meshes[0].primitives: expected an array of objects"},
        {R"("scenes":[{"nodes":["a"]}]})", "scenes[0].nodes: expected an array of unsigned integers"},
        {R"("extensionsUsed":[7]})", "extensionsUsed: expected an array of strings"},
    };
    for (const auto& [json, problem] : cases) {
        const auto r = load(asset + json);
        INFO(json);
        REQUIRE_FALSE(r.ok());
        CHECK(r.error() == std::string("fuzz.gltf: ") + problem + " (glTF 2.0 schema)");
    }
    // The same properties as objects load (an empty scene list: nothing to draw, no error).
    CHECK(load(asset + R"("accessors":[],"materials":[{"doubleSided":true}],"extensionsUsed":["KHR_materials_unlit"]})").ok());
}

TEST_CASE("fuzz: a glTF property name with control characters in it is quoted on one line", "[resources][gltf][fuzz]") {
    // The schema check names the property's path; a name holding a newline (JSON's "\n" escape)
    // broke the one-line error.
    const std::string json = "{\"asset\":{\"version\":\"2.0\"},\"bufferViews\":[{\"buffer\":0,\"byteLength\":4,"
                             "\"ext\\nsions\":{\"x\\r\\t\\u0001\":{\"mode\":\"bad\"}}}]}";
    const auto r = loadGltfFromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(), "fuzz.gltf");
    REQUIRE_FALSE(r.ok());
    INFO(r.error());
    CHECK(r.error().find('\n') == std::string::npos);
    CHECK(r.error().find('\r') == std::string::npos);
    CHECK(r.error() == "fuzz.gltf: bufferViews[0].ext\\nsions.x\\r\\t\\x01.mode: expected an unsigned integer (glTF 2.0 schema)");
}

TEST_CASE("fuzz: malformed material extensions and texture references load with their defaults, never a throw",
          "[resources][gltf][fuzz]") {
    const auto load = [](const std::string& json) {
        return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(), "fuzz.gltf");
    };
    const std::string asset = R"({"asset":{"version":"2.0"},"materials":[)";
    const char* materials[] = {
        R"({"extensions":{"KHR_materials_ior":"x","KHR_materials_specular":7}})",
        R"({"extensions":{"KHR_materials_ior":{"ior":"1.5"},"KHR_materials_specular":{"specularColorFactor":[1,"a"],"specularFactor":-2}}})",
        R"({"extensions":{"KHR_materials_ior":{"ior":-3},"KHR_materials_specular":{"specularColorFactor":{"r":1},"specularTexture":3}}})",
        R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"texCoord":1e30}}}}})",
        R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"texCoord":18446744073709551615}}}}})",
        R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":[1]}}},"occlusionTexture":{"index":0,"texCoord":5}})",
    };
    for (const char* m : materials) {
        INFO(m);
        const auto r = load(asset + m + "]}");
        // A file with materials and nothing to draw: it loads (no scene), or is refused in one line.
        if (!r.ok()) CHECK(r.error().find('\n') == std::string::npos);
        else REQUIRE(!r.value().materials.empty());
        if (r.ok() && r.value().materials[0].pbr) {
            const PbrFactors& f = *r.value().materials[0].pbr;
            CHECK(std::isfinite(f.dielectricF0.x));
            CHECK(f.dielectricF0.x >= 0.0f);
            CHECK(f.dielectricF0.x <= 1.0f);
            CHECK(f.specularWeight >= 0.0f);
            CHECK(f.specularWeight <= 1.0f);
        }
    }
}
