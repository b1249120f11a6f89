// Texture level of detail: lambda = log2(rho) of OpenGL 4.5 core section 8.14.1, NaN/0/Inf safe.
#include "TextureLod.hpp"

#include <algorithm>
#include <cassert>

namespace sr {

float mipLevel(float dudx, float dvdx, float dudy, float dvdy, int width, int height) {
    assert(width >= 1 && height >= 1);
    const float w = width >= 1 ? float(width) : 1.0f;
    const float h = height >= 1 ? float(height) : 1.0f;
    // Squared footprints; an overflow to +Inf or an underflow to 0 lands beyond the clamp anyway
    // (rho^2 >= 2^128 or < 2^-126 is far outside [2^-64, 2^64]). log2(rho) = log2(rho^2) / 2
    // saves the square roots.
    const float ax = dudx * w, bx = dvdx * h;
    const float ay = dudy * w, by = dvdy * h;
    const float rx = ax * ax + bx * bx, ry = ay * ay + by * by;
    if (!(rx >= 0.0f) || !(ry >= 0.0f)) return 0.0f; // a NaN derivative (sums of squares are >= 0 else)
    const float rho2 = std::min(std::max(std::max(rx, ry), kMinRho2), kMaxRho2);
    return 0.5f * log2Positive(rho2);
}

} // namespace sr
