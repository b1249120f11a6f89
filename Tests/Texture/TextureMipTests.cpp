// Mip chain construction (sizes, box-filter values by hand, odd sizes) and trilinear level blending.
#include "TestFramework.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "TextureReference.hpp"
#include "TextureTestUtil.hpp"

using namespace sr;
using namespace sr::test;

namespace {

std::uint8_t channel(std::uint32_t texel, int c) { return std::uint8_t(texel >> (8 * c)); }

} // namespace

TEST_CASE("mip chain sizes halve with floor down to 1x1, as glGenerateMipmap's", "[texture][mip]") {
    struct Case {
        int w, h, levels;
    };
    for (const Case& c : {Case{1, 1, 1}, Case{2, 2, 2}, Case{4, 4, 3}, Case{3, 5, 3}, Case{5, 3, 3},
                          Case{1024, 1, 11}, Case{1, 7, 3}, Case{640, 480, 10}, Case{257, 255, 9}}) {
        const Texture t = makeTexture(c.w, c.h, [](int, int) { return Rgba8{1, 2, 3, 4}; });
        INFO(c.w << "x" << c.h);
        REQUIRE(t.levelCount() == c.levels);
        for (int k = 0; k < t.levelCount(); ++k) {
            REQUIRE(t.levelWidth(k) == std::max(1, c.w >> k));
            REQUIRE(t.levelHeight(k) == std::max(1, c.h >> k));
        }
        REQUIRE(t.levelWidth(t.levelCount() - 1) == 1);
        REQUIRE(t.levelHeight(t.levelCount() - 1) == 1);
        // A constant texture stays constant at every level.
        for (int k = 0; k < t.levelCount(); ++k) REQUIRE(t.texel(k, 0, 0) == 0x04030201u);
    }
}

TEST_CASE("every level's rows end with a copy of their first texel (the SIMD samplers' texel pairs)", "[texture][mip]") {
    // The kernels fetch texel x and its GL_REPEAT right neighbour with one 64-bit load from
    // LevelView::texels + y * stride + x; for the last x the neighbour is the row's copy of texel 0.
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{2, 3}, std::pair{13, 7}, std::pair{32, 16}, std::pair{5, 1}}) {
        const Texture t = makeTexture(w, h, [](int x, int y) {
            return Rgba8{std::uint8_t(17 * x + 3 * y), std::uint8_t(5 * x + 29 * y), std::uint8_t(x * y), std::uint8_t(255 - x)};
        });
        for (int k = 0; k < t.levelCount(); ++k) {
            const Texture::LevelView l = t.levelView(k);
            INFO(w << "x" << h << " level " << k);
            REQUIRE(l.width == t.levelWidth(k));
            REQUIRE(l.height == t.levelHeight(k));
            REQUIRE(l.stride == l.width + 1);
            for (int y = 0; y < l.height; ++y) {
                for (int x = 0; x < l.width; ++x)
                    REQUIRE(l.texels[std::size_t(y) * std::size_t(l.stride) + std::size_t(x)] == t.texel(k, x, y));
                REQUIRE(l.texels[std::size_t(y) * std::size_t(l.stride) + std::size_t(l.width)] == t.texel(k, 0, y));
            }
        }
    }
}

TEST_CASE("halvingLevels: the leading levels whose axes are the base size / 2^k exactly, or 1", "[texture][mip]") {
    struct Case {
        int w, h, halving;
    };
    // 480 = 15 * 2^5: 480 .. 15 halve, 15 -> 7 does not; 13 -> 6 does not; 12 -> 6 -> 3 -> 1 (size 1
    // counts); 2x8 -> 1x4 -> 1x2 -> 1x1 (a width of 1 from level 1 on); 6x4 -> 3x2 -> 1x1.
    for (const Case& c : {Case{1, 1, 1}, Case{256, 256, 9}, Case{640, 480, 6}, Case{13, 7, 1}, Case{12, 12, 4},
                          Case{2, 8, 4}, Case{6, 4, 3}, Case{7, 8, 1}, Case{1024, 1, 11}}) {
        const Texture t = makeTexture(c.w, c.h, [](int, int) { return Rgba8{1, 2, 3, 4}; });
        INFO(c.w << "x" << c.h);
        REQUIRE(t.halvingLevels() == c.halving);
        // The definition, level by level.
        for (int k = 0; k < t.halvingLevels(); ++k) {
            REQUIRE((t.levelWidth(k) == 1 || t.levelWidth(k) << k == c.w));
            REQUIRE((t.levelHeight(k) == 1 || t.levelHeight(k) << k == c.h));
        }
    }
}

TEST_CASE("a 4x4 mip chain: the 2x2 and 1x1 averages by hand, ties rounded to even", "[texture][mip]") {
    // Texel rows bottom first (y = 0 is the bottom row). Red, green and alpha; blue is constant 77.
    const int red[4][4] = {{10, 20, 30, 40}, {30, 40, 50, 60}, {200, 200, 0, 0}, {100, 100, 4, 8}};
    const int green[4][4] = {{1, 2, 0, 1}, {3, 4, 2, 4}, {3, 4, 0, 0}, {3, 4, 0, 1}};
    const Texture t = makeTexture(4, 4, [&](int x, int y) {
        return Rgba8{std::uint8_t(red[y][x]), std::uint8_t(green[y][x]), 77, std::uint8_t(x == 0 && y == 0 ? 251 : 255)};
    });
    REQUIRE(t.levelCount() == 3);
    // Level 1 (2x2), each texel the 2x2 block (2x..2x+1, 2y..2y+1):
    //   red   (0,0) = (10+20+30+40)/4 = 25      (1,0) = (30+40+50+60)/4 = 45
    //         (0,1) = (200+200+100+100)/4 = 150 (1,1) = (0+0+4+8)/4 = 3
    //   green (0,0) = 10/4 = 2.5 -> 2 (even)    (1,0) = 7/4 = 1.75 -> 2
    //         (0,1) = 14/4 = 3.5 -> 4 (even)    (1,1) = 1/4 = 0.25 -> 0
    //   alpha (0,0) = (251+3*255)/4 = 254, elsewhere 255
    const int red1[2][2] = {{25, 45}, {150, 3}}, green1[2][2] = {{2, 2}, {4, 0}}, alpha1[2][2] = {{254, 255}, {255, 255}};
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            const std::uint32_t v = t.texel(1, x, y);
            INFO("level 1 texel " << x << "," << y);
            REQUIRE(int(channel(v, 0)) == red1[y][x]);
            REQUIRE(int(channel(v, 1)) == green1[y][x]);
            REQUIRE(int(channel(v, 2)) == 77);
            REQUIRE(int(channel(v, 3)) == alpha1[y][x]);
        }
    // Level 2 (1x1), from the STORED level 1: red (25+45+150+3)/4 = 55.75 -> 56; green 8/4 = 2;
    // alpha (254+3*255)/4 = 254.75 -> 255.
    const std::uint32_t top = t.texel(2, 0, 0);
    REQUIRE(int(channel(top, 0)) == 56);
    REQUIRE(int(channel(top, 1)) == 2);
    REQUIRE(int(channel(top, 2)) == 77);
    REQUIRE(int(channel(top, 3)) == 255);
}

TEST_CASE("odd sizes fold the edge texel into the last destination texel (3x5 -> 1x2 -> 1x1)", "[texture][mip]") {
    // red = 10 y + x: rows (bottom first) 0 1 2 / 10 11 12 / 20 21 22 / 30 31 32 / 40 41 42.
    const Texture t = makeTexture(3, 5, [](int x, int y) { return Rgba8{std::uint8_t(10 * y + x), 0, 0, 255}; });
    REQUIRE(t.levelCount() == 3);
    REQUIRE(t.levelWidth(1) == 1);
    REQUIRE(t.levelHeight(1) == 2);
    // Level 1, x: the single column takes all 3 source columns (odd width 3).
    //   (0,0): rows 0-1: (0+1+2+10+11+12)/6 = 6;  (0,1): rows 2-4 (odd height 5): 279/9 = 31.
    REQUIRE(int(channel(t.texel(1, 0, 0), 0)) == 6);
    REQUIRE(int(channel(t.texel(1, 0, 1), 0)) == 31);
    // Level 2: (6 + 31) / 2 = 18.5 -> 18 (ties to even).
    REQUIRE(int(channel(t.texel(2, 0, 0), 0)) == 18);

    // 5x1: a height of 1 is not filtered; width 5 -> 2: (a0+a1)/2 and (a2+a3+a4)/3.
    const Texture row = makeTexture(5, 1, [](int x, int) { return Rgba8{std::uint8_t(std::array<int, 5>{0, 10, 20, 31, 60}[std::size_t(x)]), 0, 0, 255}; });
    REQUIRE(row.levelCount() == 3);
    REQUIRE(int(channel(row.texel(1, 0, 0), 0)) == 5);  // 10 / 2
    REQUIRE(int(channel(row.texel(1, 1, 0), 0)) == 37); // 111 / 3 = 37
    REQUIRE(int(channel(row.texel(2, 0, 0), 0)) == 21); // 42 / 2
}

TEST_CASE("trilinear: lod clamps to the chain and blends the two nearest levels by frac(lod)", "[texture][mip]") {
    const Texture t = makeTexture(8, 8, distinctTexel);
    REQUIRE(t.levelCount() == 4);
    for (WrapMode w : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
        const Vec2 uv{0.3f, 0.8f};
        const Color base = t.sampleBilinear(uv, w);
        // lod <= 0 (magnification) and NaN: the base level exactly, as GL_LINEAR.
        for (float lod : {0.0f, -0.5f, -100.0f, std::nanf("")}) REQUIRE(bitEqual(t.sampleTrilinear(uv, lod, w), base));
        // lod >= last level: the 1x1 level, i.e. its texel for every uv.
        const Color top = t.texelColor(3, 0, 0);
        for (float lod : {3.0f, 3.5f, 1000.0f, INFINITY}) REQUIRE(bitEqual(t.sampleTrilinear(uv, lod, w), top));
        // Integer lods: that level alone. The 2x2 level (lod 2) at its texel centres returns texels.
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x)
                REQUIRE(bitEqual(t.sampleTrilinear({0.25f + 0.5f * float(x), 0.25f + 0.5f * float(y)}, 2.0f, w),
                                 t.texelColor(2, x, y)));
        // lod 2.25 at a level-2 texel centre: (3 level-2 texel + level-3 texel) / 4, rounded once.
        const Rgba8 l2 = unpackTexel(t.texel(2, 1, 0)), l3 = unpackTexel(t.texel(3, 0, 0));
        REQUIRE(bitEqual(t.sampleTrilinear({0.75f, 0.25f}, 2.25f, w), blend3to1(l2, l3)));
        // lod 2.5 likewise: the correctly rounded average of the two levels.
        REQUIRE(bitEqual(t.sampleTrilinear({0.75f, 0.25f}, 2.5f, w), average(l2, l3)));
        // lod 1.5 anywhere: the mean of the two levels' bilinear samples equals the reference.
        REQUIRE(bitEqual(t.sampleTrilinear(uv, 1.5f, w), sampleReference(t, uv, 1.5f, TextureFilter::Trilinear, w)));
    }
}
