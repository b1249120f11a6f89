// libFuzzer target: OBJ text (in memory) plus an optional MTL file must load or fail with one line, never crash or hang.
//
// Input: OBJ text, optionally followed by the separator line "%%MTL%%" and the text of the
// material library, which is written to <tmp>/f.mtl before each run (removed when absent). The
// seeds say "mtllib f.mtl" and "map_Kd t.ppm"; t.ppm (a valid 2x2 image) and t.bin (not an
// image) are written once at start-up, so texture loading and the checkerboard fallback run too.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "FuzzModel.hpp"
#include "Resources/ObjLoader.hpp"

namespace {

std::string gDir; // a private temporary directory, with a trailing '/'

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gDir = sr::fuzz::makePrivateDir("sr-fuzz-obj");
    sr::fuzz::writeTinyImage(gDir + "t.ppm");
    sr::fuzz::writeFile(gDir + "t.bin", "not an image", 12);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const char kSeparator[] = "\n%%MTL%%\n";
    const std::size_t sepLen = sizeof kSeparator - 1;
    std::size_t objSize = size;
    for (std::size_t i = 0; i + sepLen <= size; ++i) {
        if (std::memcmp(data + i, kSeparator, sepLen) == 0) {
            objSize = i + 1; // keep the OBJ's last newline
            break;
        }
    }
    const std::string mtlPath = gDir + "f.mtl";
    if (objSize < size) {
        sr::fuzz::writeFile(mtlPath, data + objSize + sepLen - 1, size - (objSize + sepLen - 1));
    } else {
        std::remove(mtlPath.c_str());
    }

    // Small limits keep single runs fast; the checks themselves are what is being fuzzed.
    sr::LoadOptions options;
    options.limits.maxMaterials = 256;
    options.limits.maxVertices = 1 << 16;
    options.limits.maxTriangles = 1 << 16;
    options.limits.maxPolygonWork = 1 << 22;
    options.limits.maxMemoryBytes = std::size_t(256) << 20;
    options.limits.maxTextureBytes = std::size_t(16) << 20;

    // Copy the OBJ part into an exactly sized heap block so ASan sees any read past its end.
    unsigned char* obj = static_cast<unsigned char*>(std::malloc(objSize ? objSize : 1));
    if (objSize) std::memcpy(obj, data, objSize);
    const sr::Result<sr::Model> r = sr::loadObjFromMemory(obj, objSize, gDir + "fuzz.obj", options);
    std::free(obj);

    if (r.ok()) sr::fuzz::checkModel(r.value());
    else sr::fuzz::checkError(r.error(), "fuzz.obj");
    return 0;
}
