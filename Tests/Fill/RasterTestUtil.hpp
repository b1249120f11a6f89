// Shared helpers of the rasterizer tests: vertex builders, scanline coverage lists, hit counters.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "Raster/Fill/ScanlineFill.hpp"
#include "Raster/Geometry/Vertex.hpp"
#include "Raster/Setup/TriangleSetup.hpp"

namespace sr::test {

inline ScreenVertex vtx(float x, float y, float z = 0.5f, float invW = 1.0f) {
    ScreenVertex v;
    v.x = x;
    v.y = y;
    v.z = z;
    v.invW = invW;
    return v;
}

// A vertex exactly on the 1/256 grid: fixed-point coordinates given as integers.
inline ScreenVertex vtxFixed(std::int64_t fx, std::int64_t fy) {
    return vtx(float(fx) / 256.0f, float(fy) / 256.0f);
}

// Pixel indices y * width + x (ascending) covered by the scanline filler.
inline std::vector<int> scanCoverage(const ScreenVertex& a, const ScreenVertex& b,
                                     const ScreenVertex& c, int width, int height) {
    std::vector<int> out;
    const std::optional<TriangleSetup> t = setupTriangle(a, b, c, 0);
    if (!t) return out;
    forEachSpan(*t, Scissor{0, 0, width, height}, [&](int y, int x0, int x1) {
        for (int x = x0; x < x1; ++x) out.push_back(y * width + x);
    });
    return out;
}

// Adds one to counts[y * width + x] for every pixel the scanline filler covers.
inline void countHits(std::vector<int>& counts, const ScreenVertex& a, const ScreenVertex& b,
                      const ScreenVertex& c, int width, int height) {
    const std::optional<TriangleSetup> t = setupTriangle(a, b, c, 0);
    if (!t) return;
    forEachSpan(*t, Scissor{0, 0, width, height}, [&](int y, int x0, int x1) {
        for (int x = x0; x < x1; ++x) ++counts[std::size_t(y * width + x)];
    });
}

inline float uniform(std::mt19937& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}
inline int uniformInt(std::mt19937& rng, int lo, int hi) { // inclusive
    return std::uniform_int_distribution<int>(lo, hi)(rng);
}

} // namespace sr::test
