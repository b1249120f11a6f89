// The specialised samplers (sample / sampleNearest / sampleBilinear / sampleTrilinear) against sampleReference, bit for bit.
#include "TestFramework.hpp"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "TextureReference.hpp"
#include "TextureTestUtil.hpp"

using namespace sr;
using namespace sr::test;

namespace {

// A texture of random bytes.
Texture randomTexture(int w, int h, std::mt19937& rng) {
    std::vector<std::uint8_t> bytes(std::size_t(w) * std::size_t(h) * 4);
    for (auto& b : bytes) b = std::uint8_t(rng() & 0xFFu);
    return Texture::fromRgba8(w, h, bytes.data());
}

// Coordinates from several populations: ordinary [-3, 3], texel-grid points (centres and edges,
// where weights are exactly 0 or 0.5), far away (|u| up to 1e7 and any float magnitude), and
// the special values.
float randomCoordinate(std::mt19937& rng, int size) {
    static const float kSpecial[] = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, -2.0f, 0.5f, 1e-30f, -1e-30f, 1e-45f,
                                     FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, std::nanf(""), 1e6f + 0.25f,
                                     -1e6f + 0.375f, 16777215.0f, 16777216.0f, 0.99999994f, -0.99999994f};
    switch (rng() % 6) {
    case 0:
    case 1: return std::uniform_real_distribution<float>(-3.0f, 3.0f)(rng);
    case 2: { // texel centre or edge, possibly a few periods away
        const int i = int(rng() % std::uint32_t(4 * size + 1)) - 2 * size;
        return (float(i) + ((rng() & 1u) ? 0.5f : 0.0f)) / float(size);
    }
    case 3: return std::uniform_real_distribution<float>(-1e7f, 1e7f)(rng);
    case 4: { // any magnitude: random sign, exponent and mantissa (finite)
        const float m = std::uniform_real_distribution<float>(1.0f, 2.0f)(rng);
        const int e = int(rng() % 250u) - 125;
        return ((rng() & 1u) ? -1.0f : 1.0f) * std::ldexp(m, e);
    }
    default: return kSpecial[rng() % (sizeof(kSpecial) / sizeof(kSpecial[0]))];
    }
}

} // namespace

TEST_CASE("fast samplers are bit-identical to the reference on random uvs, lods, sizes and wraps",
          "[texture][fastpath]") {
    std::mt19937 rng(20240611u);
    const int sizes[][2] = {{1, 1}, {1, 7}, {3, 5}, {4, 4}, {16, 8}, {33, 17}, {64, 64}, {5, 128}};
    const WrapMode wraps[] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};
    const TextureFilter filters[] = {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear};
    long compared = 0;
    for (const auto& s : sizes) {
        const Texture t = randomTexture(s[0], s[1], rng);
        for (int i = 0; i < 6000; ++i) {
            const Vec2 uv{randomCoordinate(rng, s[0]), randomCoordinate(rng, s[1])};
            float lod = std::uniform_real_distribution<float>(-1.0f, float(t.levelCount()) + 1.0f)(rng);
            if (rng() % 16u == 0) lod = std::floor(lod); // exact levels
            if (rng() % 64u == 0) lod = std::nanf("");
            for (WrapMode w : wraps) {
                for (TextureFilter f : filters) {
                    const Color ref = sampleReference(t, uv, lod, f, w);
                    const Color fast = t.sample(uv, lod, f, w);
                    if (!bitEqual(ref, fast)) {
                        INFO(s[0] << "x" << s[1] << " uv (" << uv.x << ", " << uv.y << ") lod " << lod << " "
                                  << filterName(f) << " " << wrapName(w));
                        REQUIRE(fast == ref);
                    }
                    REQUIRE(std::isfinite(ref.r + ref.g + ref.b + ref.a));
                    REQUIRE((ref.r >= 0.0f && ref.r <= 1.0f && ref.a >= 0.0f && ref.a <= 1.0f));
                    ++compared;
                }
                REQUIRE(bitEqual(t.sampleNearest(uv, w), sampleReference(t, uv, lod, TextureFilter::Nearest, w)));
                REQUIRE(bitEqual(t.sampleBilinear(uv, w), sampleReference(t, uv, lod, TextureFilter::Bilinear, w)));
                REQUIRE(bitEqual(t.sampleTrilinear(uv, lod, w),
                                 sampleReference(t, uv, lod, TextureFilter::Trilinear, w)));
            }
        }
    }
    REQUIRE(compared == 8L * 6000 * 9);
}

TEST_CASE("a wrap mode per axis: each axis wrapped by its own mode, bit-identical to the reference (sampled, fixed seed)",
          "[texture][fastpath]") {
    std::mt19937 rng(20261205u);
    const int sizes[][2] = {{1, 7}, {3, 5}, {4, 4}, {16, 8}, {33, 17}};
    const WrapMode wraps[] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};
    const TextureFilter filters[] = {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear};
    long compared = 0, unlike = 0;
    for (const auto& s : sizes) {
        const Texture t = randomTexture(s[0], s[1], rng);
        for (int i = 0; i < 1500; ++i) {
            const Vec2 uv{randomCoordinate(rng, s[0]), randomCoordinate(rng, s[1])};
            const float lod = std::uniform_real_distribution<float>(-1.0f, float(t.levelCount()) + 1.0f)(rng);
            for (WrapMode wu : wraps)
                for (WrapMode wv : wraps)
                    for (TextureFilter f : filters) {
                        const Color ref = sampleReference(t, uv, lod, f, WrapModes{wu, wv});
                        const Color fast = t.sample(uv, lod, f, WrapModes{wu, wv});
                        if (!bitEqual(ref, fast)) {
                            INFO(s[0] << "x" << s[1] << " uv (" << uv.x << ", " << uv.y << ") lod " << lod << " " << filterName(f)
                                      << " " << wrapName(wu) << "/" << wrapName(wv));
                            REQUIRE(fast == ref);
                        }
                        if (wu == wv) REQUIRE(bitEqual(fast, t.sample(uv, lod, f, wu)));
                        else if (!bitEqual(fast, t.sample(uv, lod, f, wu))) ++unlike;
                        ++compared;
                    }
        }
    }
    REQUIRE(compared == 5L * 1500 * 27);
    CHECK(unlike > compared / 10); // the second axis's mode matters (a wrong one would change nothing)
}

TEST_CASE("a wrap mode per axis on decoded texels: u's mode decides the columns, v's the rows", "[texture][fastpath][srgb]") {
    // Red varies with the column only, green with the row only: under modes (a, b) red is what a
    // alone gives and green what b alone gives, in every filter (to float rounding: the other
    // axis's weights multiply equal rows; a wrong tap is off by at least one 16-bit step).
    const Texture t = makeTexture(5, 3, [](int x, int y) { return Rgba8{std::uint8_t(40 * x + 7), std::uint8_t(90 * y + 11), 0, 255}; });
    std::mt19937 rng(99u);
    const WrapMode wraps[] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};
    for (int i = 0; i < 3000; ++i) {
        const Vec2 uv{std::uniform_real_distribution<float>(-2.5f, 2.5f)(rng), std::uniform_real_distribution<float>(-2.5f, 2.5f)(rng)};
        const float lod = std::uniform_real_distribution<float>(0.0f, 2.0f)(rng);
        for (WrapMode a : wraps)
            for (WrapMode b : wraps)
                for (TextureFilter f : {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear}) {
                    const Color both = t.sampleSrgb(uv, lod, f, WrapModes{a, b});
                    REQUIRE(both.r == Approx(t.sampleSrgb(uv, lod, f, a).r).margin(1e-6));
                    REQUIRE(both.g == Approx(t.sampleSrgb(uv, lod, f, b).g).margin(1e-6));
                }
    }
}

TEST_CASE("a region of equal texels samples to exactly that texel at any uv and lod", "[texture][fastpath]") {
    std::mt19937 rng(7u);
    const Texture t = makeTexture(6, 10, [](int, int) { return Rgba8{201, 3, 77, 128}; });
    const Color c = fromRgba8(201, 3, 77, 128);
    for (int i = 0; i < 20000; ++i) {
        const Vec2 uv{randomCoordinate(rng, 6), randomCoordinate(rng, 10)};
        const float lod = std::uniform_real_distribution<float>(-1.0f, 5.0f)(rng);
        for (WrapMode w : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
            REQUIRE(bitEqual(t.sampleBilinear(uv, w), c));
            REQUIRE(bitEqual(t.sampleTrilinear(uv, lod, w), c));
            REQUIRE(bitEqual(sampleReference(t, uv, lod, TextureFilter::Trilinear, w), c));
        }
    }
}

