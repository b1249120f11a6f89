// Texture level of detail: lambda = log2(rho) of OpenGL 4.5 core section 8.14.1, NaN/0/Inf safe.
#include "TextureLod.hpp"

#include <algorithm>
#include <cassert>

namespace sr {

namespace {

// The squared footprints along screen x and y in texels of the width x height base level. An
// overflow to +Inf or an underflow to 0 lands beyond the clamps anyway (rho^2 >= 2^128 or
// < 2^-126 is far outside [2^-64, 2^64]); log2(rho) = log2(rho^2) / 2 saves the square roots.
void squaredFootprints(float dudx, float dvdx, float dudy, float dvdy, int width, int height, float& rx, float& ry) {
    assert(width >= 1 && height >= 1);
    const float w = width >= 1 ? float(width) : 1.0f;
    const float h = height >= 1 ? float(height) : 1.0f;
    const float ax = dudx * w, bx = dvdx * h;
    const float ay = dudy * w, by = dvdy * h;
    rx = ax * ax + bx * bx;
    ry = ay * ay + by * by;
}

} // namespace

float mipLevel(float dudx, float dvdx, float dudy, float dvdy, int width, int height) {
    float rx, ry;
    squaredFootprints(dudx, dvdx, dudy, dvdy, width, height, rx, ry);
    if (!(rx >= 0.0f) || !(ry >= 0.0f)) return 0.0f; // a NaN derivative (sums of squares are >= 0 else)
    const float rho2 = std::min(std::max(std::max(rx, ry), kMinRho2), kMaxRho2);
    return 0.5f * log2Positive(rho2);
}

AnisoFootprint anisoFootprint(const UvDerivatives& d, int width, int height, int maxAniso) {
    float rx, ry;
    squaredFootprints(d.dudx, d.dvdx, d.dudy, d.dvdy, width, height, rx, ry);
    if (!(rx >= 0.0f) || !(ry >= 0.0f)) return {}; // a NaN derivative: one tap at the base level
    const bool xMajor = rx >= ry;
    const float pMax2 = xMajor ? rx : ry, pMin2 = xMajor ? ry : rx;
    const float ratio2 = pMax2 / pMin2; // Pmin 0: infinite; both 0: NaN, one tap
    AnisoFootprint f;
    for (int k = 1; k < std::min(maxAniso, kMaxAnisotropy); ++k) f.taps += float(k * k) < ratio2 ? 1 : 0;
    const float n = float(f.taps);
    const float rho2 = std::min(std::max(pMax2 / (n * n), kMinRho2), kMaxRho2);
    f.lod = 0.5f * log2Positive(rho2);
    f.du = xMajor ? d.dudx : d.dudy;
    f.dv = xMajor ? d.dvdx : d.dvdy;
    return f;
}

Color sampleAnisotropic(const Texture& texture, Vec2 uv, const UvDerivatives& d, int maxAniso, WrapMode wrap, bool decode) {
    return sampleAnisotropic(texture, uv, d, maxAniso, WrapModes{wrap, wrap}, decode);
}

Color sampleAnisotropic(const Texture& texture, Vec2 uv, const UvDerivatives& d, int maxAniso, WrapModes wrap, bool decode) {
    const AnisoFootprint f = anisoFootprint(d, texture.width(), texture.height(), maxAniso);
    auto tap = [&](Vec2 at) {
        return decode ? texture.sampleSrgb(at, f.lod, TextureFilter::Trilinear, wrap)
                      : texture.sample(at, f.lod, TextureFilter::Trilinear, wrap);
    };
    if (f.taps == 1) return tap(uv);
    const float n = float(f.taps);
    Color sum{0.0f, 0.0f, 0.0f, 0.0f};
    for (int i = 0; i < f.taps; ++i) {
        const float t = (float(i) + 0.5f) / n - 0.5f;
        const Color c = tap({uv.x + f.du * t, uv.y + f.dv * t});
        sum = {sum.r + c.r, sum.g + c.g, sum.b + c.b, sum.a + c.a};
    }
    return {sum.r / n, sum.g / n, sum.b / n, sum.a / n};
}

} // namespace sr
