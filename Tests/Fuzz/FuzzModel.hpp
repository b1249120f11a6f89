// What the model fuzz targets share: a private temporary directory, file writing that stops the run on failure, and the invariants of a loaded Model or of a load error.
#pragma once

#include <unistd.h>

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "Resources/FileIO.hpp"
#include "Resources/Model.hpp"

namespace sr::fuzz {

// A fresh directory /tmp/<prefix>-XXXXXX, with a trailing '/'.
inline std::string makePrivateDir(const char* prefix) {
    std::string templ = std::string("/tmp/") + prefix + "-XXXXXX";
    if (!mkdtemp(templ.data())) {
        std::perror("fuzz: mkdtemp");
        std::abort();
    }
    return templ + "/";
}

inline void writeFile(const std::string& path, const void* data, std::size_t size) {
    if (!writeFileBytes(path, data, size)) {
        std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
}

// A 2x2 PPM image, for the seeds' texture references.
inline void writeTinyImage(const std::string& path) {
    const char ppm[] = "P6\n2 2\n255\n\xff\x00\x00\x00\xff\x00\x00\x00\xff\xff\xff\xff";
    writeFile(path, ppm, sizeof ppm - 1);
}

// Every loaded model: one normal per vertex, uvs for all or none, triangles (or line / point
// sets; neither only with the warning that says so: a valid glTF file may draw nothing) with indices in range, ranges covering the indices once in order, material and texture
// references that exist, textures of the size they claim.
inline void checkModel(const Model& m) {
    const std::size_t nv = m.mesh.positions.size();
    assert(m.mesh.normals.size() == nv);
    assert(!m.hasUvs || m.mesh.uvs.size() == nv);
    assert(m.mesh.indices.size() % 3 == 0);
    assert(!m.mesh.indices.empty() || !m.lineSets.empty() ||
           (!m.warnings.empty() && m.warnings.back().find("nothing to draw") != std::string::npos));
    for (std::uint32_t i : m.mesh.indices) assert(i < nv);
    for (const LineSet& l : m.lineSets) {
        assert(!l.indices.empty() && (l.points || l.indices.size() % 2 == 0));
        for (std::uint32_t i : l.indices) assert(i < l.positions.size());
        (void)l;
    }
    std::size_t covered = 0;
    for (const DrawRange& d : m.ranges) {
        assert(d.firstIndex == covered);
        covered += d.indexCount;
        assert(d.texture < int(m.textures.size()));
        assert(d.material < int(m.materials.size()));
    }
    assert(covered == m.mesh.indices.size());
    for (const Image& t : m.textures) assert(t.rgba.size() == std::size_t(t.width) * std::size_t(t.height) * 4);
    (void)nv;
    (void)covered;
}

// A load error: one non-empty line naming the file.
inline void checkError(const std::string& e, const char* fileName) {
    assert(!e.empty() && e.find('\n') == std::string::npos && e.find(fileName) != std::string::npos);
    (void)e;
    (void)fileName;
}

} // namespace sr::fuzz
