// libFuzzer target: OBJ text (in memory) plus an optional MTL file must load or fail with one line, never crash or hang.
//
// Input: OBJ text, optionally followed by the separator line "%%MTL%%" and the text of the
// material library, which is written to <tmp>/f.mtl before each run (removed when absent). The
// seeds say "mtllib f.mtl" and "map_Kd t.ppm"; t.ppm (a valid 2x2 image) and t.bin (not an
// image) are written once at start-up, so texture loading and the checkerboard fallback run too.
#include <unistd.h>

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "Resources/FileIO.hpp"
#include "Resources/Model.hpp"
#include "Resources/ObjLoader.hpp"

namespace {

std::string gDir; // a private temporary directory, with a trailing '/'

void writeFile(const std::string& path, const void* data, std::size_t size) {
    if (!sr::writeFileBytes(path, data, size)) {
        std::fprintf(stderr, "FuzzObj: cannot write %s\n", path.c_str());
        std::abort();
    }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    char templ[] = "/tmp/sr-fuzz-obj-XXXXXX";
    if (!mkdtemp(templ)) {
        std::perror("FuzzObj: mkdtemp");
        std::abort();
    }
    gDir = std::string(templ) + "/";
    const char ppm[] = "P6\n2 2\n255\n\xff\x00\x00\x00\xff\x00\x00\x00\xff\xff\xff\xff";
    writeFile(gDir + "t.ppm", ppm, sizeof ppm - 1);
    writeFile(gDir + "t.bin", "not an image", 12);
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
        writeFile(mtlPath, data + objSize + sepLen - 1, size - (objSize + sepLen - 1));
    } else {
        std::remove(mtlPath.c_str());
    }

    // Small limits keep single runs fast; the checks themselves are what is being fuzzed.
    sr::ObjOptions options;
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

    if (r.ok()) {
        const sr::Model& m = r.value();
        const std::size_t nv = m.mesh.positions.size();
        assert(m.mesh.normals.size() == nv);
        assert(!m.hasUvs || m.mesh.uvs.size() == nv);
        assert(m.mesh.indices.size() % 3 == 0 && !m.mesh.indices.empty());
        for (std::uint32_t i : m.mesh.indices) assert(i < nv);
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
        assert(!e.empty() && e.find('\n') == std::string::npos && e.find("fuzz.obj") != std::string::npos);
        (void)e;
    }
    return 0;
}
