// libFuzzer target: a glTF 2.0 asset (.gltf JSON or .glb bytes, in memory) must load or fail with one line, never crash or hang.
//
// Input: the file's bytes (GLB when they start with "glTF"). An external buffer "t.bin" (a valid
// triangle: 3 float VEC3 positions, then 3 u16 indices) and an image "t.ppm" are written once at
// start-up next to the fuzzed file, so the seeds' external references load too.
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "FuzzModel.hpp"
#include "Resources/Animation.hpp"
#include "Resources/Gltf/GltfLoader.hpp"

namespace {

std::string gDir; // a private temporary directory, with a trailing '/'

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gDir = sr::fuzz::makePrivateDir("sr-fuzz-gltf");
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::uint16_t indices[3] = {0, 1, 2};
    unsigned char bin[42];
    std::memcpy(bin, positions, 36);
    std::memcpy(bin + 36, indices, 6);
    sr::fuzz::writeFile(gDir + "t.bin", bin, sizeof bin);
    sr::fuzz::writeTinyImage(gDir + "t.ppm");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Small limits keep single runs fast; the checks themselves are what is being fuzzed.
    sr::LoadOptions options;
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
        sr::fuzz::checkModel(r.value());
        // An animated file poses at any time without touching anything outside its mesh.
        if (const auto& animation = r.value().animation) {
            sr::Mesh mesh = r.value().mesh;
            for (const double t : {0.0, 0.37, 1e6}) animation->pose(t, -1, mesh);
            animation->pose(0.5, 0, mesh);
            assert(mesh.positions.size() == r.value().mesh.positions.size() && mesh.normals.size() == r.value().mesh.normals.size());
        }
    } else {
        sr::fuzz::checkError(r.error(), "fuzz.gltf");
    }
    return 0;
}
