// libFuzzer target: a glTF 2.0 asset (.gltf JSON or .glb bytes, in memory) must load or fail with one line, never crash or hang.
//
// Input: the file's bytes (GLB when they start with "glTF"). An external buffer "t.bin" (a valid
// triangle: 3 float VEC3 positions, then 3 u16 indices) and an image "t.ppm" are written once at
// start-up next to the fuzzed file, so the seeds' external references load too.
#include <unistd.h>

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "Resources/FileIO.hpp"
#include "Resources/GltfLoader.hpp"
#include "Resources/Model.hpp"

namespace {

std::string gDir; // a private temporary directory, with a trailing '/'

void writeFile(const std::string& path, const void* data, std::size_t size) {
    if (!sr::writeFileBytes(path, data, size)) {
        std::fprintf(stderr, "FuzzGltf: cannot write %s\n", path.c_str());
        std::abort();
    }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    char templ[] = "/tmp/sr-fuzz-gltf-XXXXXX";
    if (!mkdtemp(templ)) {
        std::perror("FuzzGltf: mkdtemp");
        std::abort();
    }
    gDir = std::string(templ) + "/";
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::uint16_t indices[3] = {0, 1, 2};
    unsigned char bin[42];
    std::memcpy(bin, positions, 36);
    std::memcpy(bin + 36, indices, 6);
    writeFile(gDir + "t.bin", bin, sizeof bin);
    const char ppm[] = "P6\n2 2\n255\n\xff\x00\x00\x00\xff\x00\x00\x00\xff\xff\xff\xff";
    writeFile(gDir + "t.ppm", ppm, sizeof ppm - 1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Small limits keep single runs fast; the checks themselves are what is being fuzzed.
    sr::ObjOptions options;
    options.limits.maxMaterials = 256;
    options.limits.maxVertices = 1 << 16;
    options.limits.maxTriangles = 1 << 16;
    options.limits.maxNodes = 4096;
    options.limits.maxMemoryBytes = std::size_t(64) << 20;
    options.limits.maxTextureBytes = std::size_t(16) << 20;

    // An exactly sized heap block so ASan sees any read past its end.
    unsigned char* bytes = static_cast<unsigned char*>(std::malloc(size ? size : 1));
    if (size) std::memcpy(bytes, data, size);
    const sr::Result<sr::Model> r = sr::loadGltfFromMemory(bytes, size, gDir + "fuzz.gltf", options);
    std::free(bytes);

    if (r.ok()) {
        const sr::Model& m = r.value();
        const std::size_t nv = m.mesh.positions.size();
        assert(m.mesh.normals.size() == nv);
        assert(!m.hasUvs || m.mesh.uvs.size() == nv);
        // Something to draw: triangles, or line / point primitives (each index in its set).
        assert(m.mesh.indices.size() % 3 == 0 && (!m.mesh.indices.empty() || !m.lineSets.empty()));
        for (std::uint32_t i : m.mesh.indices) assert(i < nv);
        for (const sr::LineSet& l : m.lineSets) {
            assert(!l.indices.empty() && (l.points || l.indices.size() % 2 == 0));
            for (std::uint32_t i : l.indices) assert(i < l.positions.size());
        }
        std::size_t covered = 0;
        for (const sr::DrawRange& d : m.ranges) {
            assert(d.firstIndex == covered);
            covered += d.indexCount;
            assert(d.texture < int(m.textures.size()));
            assert(d.material < int(m.materials.size()));
        }
        assert(covered == m.mesh.indices.size());
        for (const sr::Image& t : m.textures) assert(t.rgba.size() == std::size_t(t.width) * std::size_t(t.height) * 4);
        (void)covered;
    } else {
        const std::string& e = r.error();
        assert(!e.empty() && e.find('\n') == std::string::npos && e.find("fuzz.gltf") != std::string::npos);
        (void)e;
    }
    return 0;
}
