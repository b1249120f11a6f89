// Texture level of detail: lambda = log2(rho) of OpenGL 4.5 core section 8.14.1, NaN/0/Inf safe.
#include "TextureLod.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace sr {

float mipLevel(float dudx, float dvdx, float dudy, float dvdy, int width, int height) {
    assert(width >= 1 && height >= 1);
    if (std::isnan(dudx) || std::isnan(dvdx) || std::isnan(dudy) || std::isnan(dvdy)) return 0.0f;
    const double w = width >= 1 ? double(width) : 1.0;
    const double h = height >= 1 ? double(height) : 1.0;
    // Squared footprints: |float| * 16384 squared stays far below double's range, so no overflow;
    // log2(rho) = log2(rho^2) / 2 saves the square roots.
    const double ax = double(dudx) * w, bx = double(dvdx) * h;
    const double ay = double(dudy) * w, by = double(dvdy) * h;
    const double rho2 = std::max(ax * ax + bx * bx, ay * ay + by * by); // +Inf for infinite input
    if (!(rho2 > 0.0)) return -kMaxAbsLod;
    const double lod = 0.5 * std::log2(rho2);
    return float(std::clamp(lod, double(-kMaxAbsLod), double(kMaxAbsLod)));
}

} // namespace sr
