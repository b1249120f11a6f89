// Helpers for the texture tests: textures built from a texel function, and exact colour checks.
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "TestFramework.hpp"

#include "Math/Color.hpp"
#include "Raster/Texture/Texture.hpp"

namespace sr::test {

struct Rgba8 {
    std::uint8_t r = 0, g = 0, b = 0, a = 255;
};

// A texture whose base texel (x, y) - y = 0 the BOTTOM row, as the sampler sees it - is f(x, y).
// The bytes handed to fromRgba8 are top row first, as a decoder produces them.
inline Texture makeTexture(int w, int h, const std::function<Rgba8(int x, int y)>& f) {
    std::vector<std::uint8_t> bytes(std::size_t(w) * std::size_t(h) * 4);
    for (int row = 0; row < h; ++row) {         // image row, top first
        for (int x = 0; x < w; ++x) {
            const Rgba8 c = f(x, h - 1 - row);  // texel row counted from the bottom
            std::uint8_t* p = &bytes[(std::size_t(row) * std::size_t(w) + std::size_t(x)) * 4];
            p[0] = c.r;
            p[1] = c.g;
            p[2] = c.b;
            p[3] = c.a;
        }
    }
    return Texture::fromRgba8(w, h, bytes.data());
}

// Distinct bytes per texel and channel (for textures up to 16 x 16).
inline Rgba8 distinctTexel(int x, int y) {
    return {std::uint8_t(20 + 13 * x), std::uint8_t(30 + 11 * y), std::uint8_t(3 + 7 * (x + 2 * y)),
            std::uint8_t(255 - 5 * (x + y))};
}

inline Color toColor(Rgba8 c) { return fromRgba8(c.r, c.g, c.b, c.a); }

// Bitwise equality of all four channels (distinguishes -0 from +0; NaN equals the same NaN).
inline bool bitEqual(Color a, Color b) { return std::memcmp(&a, &b, sizeof(Color)) == 0; }

// GL_LINEAR halfway between two texels: the correctly rounded (a + b) / 510 per channel; between
// four: (a + b + c + d) / 1020; weights 3/4 and 1/4: (3 a + b) / 1020.
inline Color average(Rgba8 a, Rgba8 b) {
    auto ch = [](int x, int y) { return float(x + y) / 510.0f; };
    return {ch(a.r, b.r), ch(a.g, b.g), ch(a.b, b.b), ch(a.a, b.a)};
}
inline Color average(Rgba8 a, Rgba8 b, Rgba8 c, Rgba8 d) {
    auto ch = [](int x, int y, int z, int w) { return float(x + y + z + w) / 1020.0f; };
    return {ch(a.r, b.r, c.r, d.r), ch(a.g, b.g, c.g, d.g), ch(a.b, b.b, c.b, d.b), ch(a.a, b.a, c.a, d.a)};
}
inline Color blend3to1(Rgba8 a, Rgba8 b) {
    auto ch = [](int x, int y) { return float(3 * x + y) / 1020.0f; };
    return {ch(a.r, b.r), ch(a.g, b.g), ch(a.b, b.b), ch(a.a, b.a)};
}
inline Rgba8 unpackTexel(std::uint32_t t) {
    return {std::uint8_t(t), std::uint8_t(t >> 8), std::uint8_t(t >> 16), std::uint8_t(t >> 24)};
}

} // namespace sr::test

// Readable failure messages: Catch prints colours instead of "{?}".
namespace Catch {
template <>
struct StringMaker<sr::Color> {
    static std::string convert(sr::Color c) {
        std::ostringstream o;
        o.precision(9);
        o << "Color(" << c.r << ", " << c.g << ", " << c.b << ", " << c.a << ")";
        return o.str();
    }
};
} // namespace Catch
