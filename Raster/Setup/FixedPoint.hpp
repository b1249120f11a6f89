// Sub-pixel snapping, exact integer floor/ceil division and bit scans shared by triangle setup,
// fill and lines.
#pragma once

#include <cassert>
#include <cmath>
#include <cstdint>

#include "Raster/Setup/RasterLimits.hpp"

namespace sr {

// A coordinate in 1/kSubPixelScale pixel units (24.8 fixed point for the guard band's range).
using Fixed = std::int32_t;

// Fixed-point coordinate of a pixel centre: pixel i spans [i, i + 1), its centre is i + 0.5.
constexpr std::int64_t pixelCentreFixed(std::int64_t i) {
    return i * kSubPixelScale + kSubPixelScale / 2;
}

// Snaps a screen coordinate (pixels) to the 1/256 grid, rounding to nearest with ties towards
// +infinity: floor(v * 256 + 0.5). v * 256 and the + 0.5 are exact in double for |v| <= 2^30,
// so the result is the exactly rounded value. Ties up (not "away from zero") keep the rule
// translation-invariant: shifting a triangle by whole pixels shifts its coverage exactly.
// Precondition: |v| <= kGuardBand (callers check), so the result fits 24 bits.
// The floor is done with a truncating conversion and a one-step correction (exactly floor()
// for |s| < 2^31) because without SSE4.1 std::floor is a library call, and this runs six
// times per triangle.
inline Fixed snapToFixed(float v) {
    assert(std::fabs(v) <= kGuardBand);
    const double s = double(v) * double(kSubPixelScale) + 0.5;
    const Fixed t = Fixed(s); // truncates towards zero
    return t - Fixed(double(t) > s);
}

constexpr float fixedToFloat(std::int64_t f) { return float(f) / float(kSubPixelScale); }

// floor(a / b) and ceil(a / b) for b > 0, exact for every int64 a (C++ division truncates
// towards zero, so negative quotients with a remainder need one step of correction).
constexpr std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
    assert(b > 0);
    const std::int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}
constexpr std::int64_t ceilDiv(std::int64_t a, std::int64_t b) {
    assert(b > 0);
    const std::int64_t q = a / b;
    return (a % b != 0 && a > 0) ? q + 1 : q;
}

// Index of the first pixel whose centre coordinate is >= the rational position n / d
// (in fixed-point units, d > 0): the smallest i with i*256 + 128 >= n/d, i.e.
// ceil((n/d - 128) / 256) = ceil((n - 128 d) / (256 d)). Exact: no rounding anywhere.
constexpr std::int64_t firstCentreAtOrAfter(std::int64_t n, std::int64_t d) {
    return ceilDiv(n - std::int64_t(kSubPixelScale / 2) * d, std::int64_t(kSubPixelScale) * d);
}

// Index of the lowest / highest set bit of a non-zero word (masks of pixels, samples and lanes).
inline int lowestSetBit(std::uint64_t v) {
    assert(v != 0);
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctzll(v);
#else
    int i = 0;
    for (; !(v & 1u); v >>= 1) ++i;
    return i;
#endif
}
inline int highestSetBit(std::uint64_t v) {
    assert(v != 0);
#if defined(__GNUC__) || defined(__clang__)
    return 63 - __builtin_clzll(v);
#else
    int i = 63;
    for (; !(v >> 63); v <<= 1) --i;
    return i;
#endif
}

} // namespace sr
