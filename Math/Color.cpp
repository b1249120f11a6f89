// Color <-> 8-bit conversions: clamp, round-to-nearest-even unorm8, and the BGRX DIB packing.
#include "Color.hpp"

namespace sr {

std::uint8_t toUnorm8(float c) {
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

std::uint32_t packBgra8(Color c) {
    return 0xFF000000u | (static_cast<std::uint32_t>(toUnorm8(c.r)) << 16) |
           (static_cast<std::uint32_t>(toUnorm8(c.g)) << 8) | static_cast<std::uint32_t>(toUnorm8(c.b));
}

Color unpackBgra8(std::uint32_t v) {
    return fromRgba8(static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
                     static_cast<std::uint8_t>(v), 255);
}

Color fromRgba8(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
    return {static_cast<float>(r) / 255.0f, static_cast<float>(g) / 255.0f, static_cast<float>(b) / 255.0f,
            static_cast<float>(a) / 255.0f};
}

} // namespace sr
