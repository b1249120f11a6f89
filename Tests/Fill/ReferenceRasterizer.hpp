// Reference triangle rasterizer for tests: per-pixel int64 edge functions, obviously correct, slow.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "Raster/Geometry/Vertex.hpp"

namespace sr::ref {

// Snapping as the contract states it (Conventions.hpp, RasterLimits.hpp): the nearest multiple of
// 1/256, ties towards +infinity. Written independently of Raster/Setup/FixedPoint.hpp on purpose.
std::int64_t snap(float v);

// Pixel indices y * width + x (ascending) whose centres the triangle covers under the D3D10
// top-left rule, evaluated per pixel with exact int64 edge functions over the bounding box
// clipped to [0, width) x [0, height). Zero-area triangles cover nothing.
std::vector<int> coverage(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                          int width, int height);

// The same for the sample point at (ox, oy) from every pixel centre (in 1/256 pixel, |o| < 256):
// pixel indices whose sample point the triangle covers (multisampling's per-sample coverage).
std::vector<int> sampleCoverage(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2, int width,
                                int height, std::int64_t ox, std::int64_t oy);

// One covered pixel with its attributes from barycentrics in double: z linear in screen space,
// varyings perspective-correct (sum b_i v_i / w_i divided by sum b_i / w_i).
struct Fragment {
    int x = 0, y = 0;
    double z = 0.0;
    double invW = 0.0;
    std::array<double, kMaxVaryings> varyings{};
};
std::vector<Fragment> rasterize(const ScreenVertex& v0, const ScreenVertex& v1,
                                const ScreenVertex& v2, int varyingCount, int width, int height);

} // namespace sr::ref
