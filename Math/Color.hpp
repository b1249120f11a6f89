// Color: linear float RGBA with arithmetic, and the exact float <-> 8-bit BGRX (32-bpp DIB) packing.
#pragma once

#include <cstdint>

#include "Vec.hpp"

namespace sr {

// Four floats, nominally in [0, 1] but unclamped during shading (clamp when storing).
// A default Color is opaque black (0, 0, 0, 1); Color{r, g, b} is opaque too.
struct Color {
    float r = 0.0f, g = 0.0f, b = 0.0f, a = 1.0f;

    constexpr Color& operator+=(Color o) { r += o.r; g += o.g; b += o.b; a += o.a; return *this; }
    constexpr Color& operator-=(Color o) { r -= o.r; g -= o.g; b -= o.b; a -= o.a; return *this; }
    constexpr Color& operator*=(Color o) { r *= o.r; g *= o.g; b *= o.b; a *= o.a; return *this; }
    constexpr Color& operator*=(float s) { r *= s; g *= s; b *= s; a *= s; return *this; }
    constexpr Color& operator/=(float s) { r /= s; g /= s; b /= s; a /= s; return *this; }
};

// --- Arithmetic: all four channels, IEEE semantics (NaN/Inf propagate) ------------------------
constexpr Color operator+(Color x, Color y) { return {x.r + y.r, x.g + y.g, x.b + y.b, x.a + y.a}; }
constexpr Color operator-(Color x, Color y) { return {x.r - y.r, x.g - y.g, x.b - y.b, x.a - y.a}; }
constexpr Color operator-(Color x) { return {-x.r, -x.g, -x.b, -x.a}; }
constexpr Color operator*(Color x, Color y) { return {x.r * y.r, x.g * y.g, x.b * y.b, x.a * y.a}; }
constexpr Color operator*(Color x, float s) { return {x.r * s, x.g * s, x.b * s, x.a * s}; }
constexpr Color operator*(float s, Color x) { return {x.r * s, x.g * s, x.b * s, x.a * s}; }
constexpr Color operator/(Color x, float s) { return {x.r / s, x.g / s, x.b / s, x.a / s}; }
constexpr bool operator==(Color x, Color y) { return x.r == y.r && x.g == y.g && x.b == y.b && x.a == y.a; }
constexpr bool operator!=(Color x, Color y) { return !(x == y); }

// lerp(x, y, 0) == x and lerp(x, y, 1) == y exactly (same two-product form as Vec.hpp).
constexpr Color lerp(Color x, Color y, float t) { return x * (1.0f - t) + y * t; }
// Channel-wise clamp into [lo, hi]; a NaN channel stays NaN (see sr::clamp(float) in Vec.hpp).
constexpr Color clamp(Color c, float lo, float hi) {
    return {sr::clamp(c.r, lo, hi), sr::clamp(c.g, lo, hi), sr::clamp(c.b, lo, hi), sr::clamp(c.a, lo, hi)};
}
constexpr Color clamp(Color c) { return clamp(c, 0.0f, 1.0f); }

constexpr Vec4 toVec4(Color c) { return {c.r, c.g, c.b, c.a}; }
constexpr Color toColor(Vec4 v) { return {v.x, v.y, v.z, v.w}; }
constexpr Color toColor(Vec3 v, float alpha = 1.0f) { return {v.x, v.y, v.z, alpha}; }

// --- 8-bit conversions ------------------------------------------------------------------------
// One channel float -> unorm8: clamp to [0, 1], then c * 255 (in float) rounded to nearest with
// ties to EVEN - identical to std::nearbyint(c * 255.0f) in the default rounding mode and to Mesa
// llvmpipe's float -> unorm8 conversion (e.g. 0.3f * 255 == 76.5f -> 76, 0.5f -> 127.5f -> 128).
// NaN -> 0; +Inf -> 255, -Inf -> 0 (by the clamp). Implemented with the 2^23 trick (adding 2^23
// to a float in [0, 255] leaves no fraction bits, so the FPU's round-to-nearest-even does the
// rounding) instead of calling nearbyint, which saves and restores the FP environment per call.
// Inline: it runs per shaded pixel (three times).
inline std::uint8_t toUnorm8(float c) {
    if (!(c > 0.0f)) return 0; // NaN, zero, negatives and -Inf
    if (c >= 1.0f) return 255; // includes +Inf
    const float x = c * 255.0f; // in (0, 255): float product, as llvmpipe computes it
    // Round to nearest, ties to even: for 0 <= x < 2^23, x + 2^23 lies in [2^23, 2^24) where float's
    // spacing is exactly 1, so the addition itself rounds x to an integer in the current (default:
    // nearest-even) rounding mode, and subtracting 2^23 back is exact. Requires IEEE float
    // arithmetic without value-changing optimisations (no -ffast-math; SSE, not x87).
    constexpr float kTwo23 = 8388608.0f;
    const float rounded = (x + kTwo23) - kTwo23;
    return static_cast<std::uint8_t>(rounded);
}

// The 32-bpp DIB pixel: memory bytes B, G, R, X (little-endian value 0xXXRRGGBB), X always 0xFF;
// alpha is ignored. Each channel goes through toUnorm8.
inline std::uint32_t packBgra8(Color c) {
    return 0xFF000000u | (static_cast<std::uint32_t>(toUnorm8(c.r)) << 16) |
           (static_cast<std::uint32_t>(toUnorm8(c.g)) << 8) | static_cast<std::uint32_t>(toUnorm8(c.b));
}
// Inverse of packBgra8 for the colour channels: channel = byte / 255.0f; alpha = 1 (X ignored).
// packBgra8(unpackBgra8(v)) == (v | 0xFF000000) for every v.
Color unpackBgra8(std::uint32_t v);
// Bytes to floats: channel = byte / 255.0f (the same values unpackBgra8 produces).
Color fromRgba8(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255);

} // namespace sr
