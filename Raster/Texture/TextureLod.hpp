// Texture level of detail: screen-space uv derivatives from the triangle setup, and the GL mip level.
#pragma once

#include <cstdint>
#include <cstring>

#include "Math/Vec.hpp"
#include "Raster/Setup/TriangleSetup.hpp"
#include "Raster/Texture/Texture.hpp"

namespace sr {

// |lod| never exceeds this (2^32 texels per pixel, or 2^-32 pixels per texel, is beyond any texture).
inline constexpr float kMaxAbsLod = 32.0f;

// Partial derivatives of the texture coordinates with respect to screen x and y (per pixel).
struct UvDerivatives {
    float dudx = 0.0f, dvdx = 0.0f;
    float dudy = 0.0f, dvdy = 0.0f;
};

// Perspective-correct uv derivatives at one pixel. The setup's planes are linear in screen space:
// U = u/w (plane uPlane), V = v/w (vPlane) and Q = 1/w (kPlaneInvW), and u = U / Q, so by the
// quotient rule
//   du/dx = (dU/dx Q - U dQ/dx) / Q^2 = (dU/dx - u dQ/dx) / Q      (and likewise for v and y),
// with Q = invW and u, v the perspective-correct values at the pixel - exactly what the span loop
// hands a fragment (Fragment::invW and its varyings). The plane indices are kPlaneVarying0 + the
// varying's index (TriangleSetup.hpp). invW <= 0 or non-finite inputs give non-finite derivatives;
// mipLevel() accepts them.
// Evaluated in float, as a SIMD lane repeats it (Raster/Fill/Kernels): the gradients rounded to float
// once per triangle, then per pixel w = 1 / invW, a product, a difference and a product per
// derivative. The difference cancels only where u dQ/dx is close to dU/dx; setup rebases u per
// triangle (TriangleSetup.hpp, rebaseOffset), so |u| stays within the triangle's own uv extent and
// the lost bits are those of a uv difference across it, far below what the 8-bit level blend shows
// (TextureLodTests: against finite differences in double).
inline UvDerivatives uvDerivatives(const TriangleSetup& t, int uPlane, int vPlane, float invW, float u, float v) {
    const float w = 1.0f / invW;
    const float dqdx = float(t.ddx[kPlaneInvW]), dqdy = float(t.ddy[kPlaneInvW]);
    return {(float(t.ddx[uPlane]) - u * dqdx) * w, (float(t.ddx[vPlane]) - v * dqdx) * w,
            (float(t.ddy[uPlane]) - u * dqdy) * w, (float(t.ddy[vPlane]) - v * dqdy) * w};
}

// log2(x) for a normal positive finite float x, in float arithmetic that a SIMD lane repeats
// bit for bit (Raster/Fill/Kernels): x = 2^e m with m in [sqrt(1/2), sqrt(2)), then
//   log2(m) = (2 / ln 2) atanh(s) = (2 / ln 2) (s + s^3/3 + s^5/5 + s^7/7 + s^9/9 + ...),
// s = (m - 1) / (m + 1), |s| <= 0.1716, so the truncated series is off by < 2e-9; the float
// evaluation adds a few ulp. Exact (e) at powers of two. No library log2: its last bit differs
// between C libraries and no vector unit has it.
inline constexpr float kSqrt2f = 1.41421356f; // the float nearest sqrt(2)
inline constexpr float kLog2Series[5] = {2.88539008f, 0.961796694f, 0.577078016f, 0.412198583f, 0.320599087f};
inline float log2Positive(float x) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    float e = float(int(bits >> 23) - 127);
    const std::uint32_t mantissaBits = (bits & 0x007FFFFFu) | 0x3F800000u;
    float m;
    std::memcpy(&m, &mantissaBits, sizeof m); // [1, 2)
    if (m > kSqrt2f) {
        m = m * 0.5f; // exact
        e = e + 1.0f;
    }
    const float s = (m - 1.0f) / (m + 1.0f); // m - 1 exact (Sterbenz)
    const float s2 = s * s;
    const float* c = kLog2Series;
    return e + s * (c[0] + s2 * (c[1] + s2 * (c[2] + s2 * (c[3] + s2 * c[4]))));
}

// rho^2 is clamped to [2^-64, 2^64] before the logarithm: lambda stays within +-kMaxAbsLod.
inline constexpr float kMinRho2 = 0x1p-64f, kMaxRho2 = 0x1p64f;

// The mip level lambda = log2(rho) of OpenGL 4.5 core section 8.14.1 (scale factor and level of
// detail), without bias and before clamping to the texture's levels:
//   rho = max( sqrt((du/dx W)^2 + (dv/dx H)^2), sqrt((du/dy W)^2 + (dv/dy H)^2) ),
// the longer of the pixel's two screen-axis footprints, measured in texels of the W x H base
// level (the spec's exact form, not one of its allowed approximations), computed as
// log2(rho^2) / 2 in float with log2Positive (the SIMD kernels evaluate it per lane with the same
// operations). Defined for every input:
//  - any NaN argument -> 0 (the base level);
//  - rho^2 below 2^-64 (a constant uv, or one that underflows) -> -kMaxAbsLod (magnification);
//    above 2^64 (or infinite) -> +kMaxAbsLod;
//  - the result is always within [-kMaxAbsLod, kMaxAbsLod].
// width and height are the base level's size (>= 1, asserted; release builds use 1 for less).
float mipLevel(float dudx, float dvdx, float dudy, float dvdy, int width, int height);

inline float mipLevel(const UvDerivatives& d, int width, int height) {
    return mipLevel(d.dudx, d.dvdx, d.dudy, d.dvdy, width, height);
}

// Anisotropic filtering (the model of EXT_texture_filter_anisotropic, as GPUs and llvmpipe
// sample): the pixel's footprint in texels is Px = |(du/dx W, dv/dx H)| along screen x and Py
// along y; the longer, Pmax, is covered by N = min(ceil(Pmax / Pmin), maxAniso) trilinear taps
// spaced evenly along it, at level log2(Pmax / N) instead of log2(Pmax): the shorter axis sets the
// blur, not the longer. In float, as the vector kernels repeat it lane by lane:
//   N = 1 + #{k in [1, maxAniso) : k^2 < Pmax^2 / Pmin^2}   (NaN derivatives: N = 1, level 0),
//   lod = log2(clamp(Pmax^2 / N^2, kMinRho2, kMaxRho2)) / 2  (mipLevel's form: N = 1 is trilinear),
//   tap i at uv + (du, dv)_major ((i + 0.5) / N - 0.5), the taps' sum divided by N.
// taps is 1 for an isotropic footprint or maxAniso 1: exactly sampleTrilinear.
inline constexpr int kMaxAnisotropy = 16;
struct AnisoFootprint {
    int taps = 1;
    float lod = 0.0f;
    float du = 0.0f, dv = 0.0f; // the uv step of the major axis (one pixel along it)
};
AnisoFootprint anisoFootprint(const UvDerivatives& d, int width, int height, int maxAniso);
// The filtered colour (all four channels averaged); `decode`: sRGB-decoded texels (sampleSrgb).
Color sampleAnisotropic(const Texture& texture, Vec2 uv, const UvDerivatives& d, int maxAniso, WrapMode wrap, bool decode);
// The same with a wrap mode per axis (Texture::sample's WrapModes).
Color sampleAnisotropic(const Texture& texture, Vec2 uv, const UvDerivatives& d, int maxAniso, WrapModes wrap, bool decode);

} // namespace sr
