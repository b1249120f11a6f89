// Tests of Color: arithmetic, and the exact float <-> 8-bit BGRX conversions (ties to even, round trips).
#include "TestFramework.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "Math/Color.hpp"
#include "MathTestUtil.hpp"

using namespace sr;

namespace {

// The reference the packing must equal: clamp, then std::nearbyint(c * 255.0f) in the default
// (round to nearest, ties to even) mode - Mesa llvmpipe's float -> unorm8.
unsigned referenceUnorm8(float c) {
    if (std::isnan(c)) return 0;
    const float clamped = c < 0.0f ? 0.0f : (c > 1.0f ? 1.0f : c);
    return static_cast<unsigned>(std::nearbyint(clamped * 255.0f));
}

} // namespace

TEST_CASE("Color arithmetic, lerp and clamp", "[math][color]") {
    const Color a{0.25f, 0.5f, 0.75f, 1.0f}, b{0.5f, 0.25f, 0.0f, 0.5f};
    CHECK(a + b == Color{0.75f, 0.75f, 0.75f, 1.5f});
    CHECK(a - b == Color{-0.25f, 0.25f, 0.75f, 0.5f});
    CHECK(a * 2.0f == Color{0.5f, 1.0f, 1.5f, 2.0f});
    CHECK(2.0f * a == a * 2.0f);
    CHECK(a * b == Color{0.125f, 0.125f, 0.0f, 0.5f});
    CHECK(a / 2.0f == Color{0.125f, 0.25f, 0.375f, 0.5f});
    CHECK(-a == Color{-0.25f, -0.5f, -0.75f, -1.0f});
    Color c = a;
    c += b;
    c -= b;
    c *= 4.0f;
    c /= 4.0f;
    CHECK(c == a);
    CHECK(Color{} == Color{0, 0, 0, 1}); // default: opaque black
    CHECK(Color{1, 0, 0}.a == 1.0f);

    CHECK(lerp(a, b, 0.0f) == a); // both ends exact
    CHECK(lerp(a, b, 1.0f) == b);
    CHECK(lerp(a, b, 0.5f) == Color{0.375f, 0.375f, 0.375f, 0.75f});

    CHECK(clamp(Color{-1.0f, 0.5f, 2.0f, HUGE_VALF}) == Color{0.0f, 0.5f, 1.0f, 1.0f});
    CHECK(clamp(Color{-1.0f, 0.5f, 2.0f, 3.0f}, 0.25f, 0.75f) == Color{0.25f, 0.5f, 0.75f, 0.75f});
    CHECK(std::isnan(clamp(Color{std::nanf(""), 0, 0, 0}).r)); // NaN stays NaN (documented)
    CHECK(toColor(toVec4(a)) == a);
    CHECK(toColor(Vec3(0.1f, 0.2f, 0.3f)) == Color{0.1f, 0.2f, 0.3f, 1.0f});
}

TEST_CASE("packBgra8 writes the 32-bpp DIB layout B, G, R, X=0xFF and ignores alpha", "[math][color]") {
    const std::uint32_t v = packBgra8(Color{1.0f, 0.0f, 128.0f / 255.0f, 0.0f});
    CHECK(v == 0xFFFF0080u);
    unsigned char bytes[4];
    std::memcpy(bytes, &v, 4);
    const std::uint32_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    if (first == 1) { // little-endian (x86, x64, ARM Windows): memory order B, G, R, X
        CHECK(bytes[0] == 0x80);
        CHECK(bytes[1] == 0x00);
        CHECK(bytes[2] == 0xFF);
        CHECK(bytes[3] == 0xFF);
    }
    CHECK(packBgra8(Color{0.2f, 0.4f, 0.6f, 0.0f}) == packBgra8(Color{0.2f, 0.4f, 0.6f, 1.0f}));
    CHECK(packBgra8(Color{0.2f, 0.4f, 0.6f, std::nanf("")}) == packBgra8(Color{0.2f, 0.4f, 0.6f, 1.0f}));
    CHECK(packBgra8(Color{0, 0, 0, 0}) == 0xFF000000u);
    CHECK(packBgra8(Color{1, 1, 1, 1}) == 0xFFFFFFFFu);
}

TEST_CASE("unorm8 rounds to nearest with ties to even, like llvmpipe", "[math][color]") {
    // 0.3f * 255 == 76.5f exactly: the tie goes to the even 76, not 77 (round-half-up would give 77).
    REQUIRE(0.3f * 255.0f == 76.5f);
    CHECK(toUnorm8(0.3f) == 76);
    // 0.5f * 255 == 127.5f: the tie goes to the even 128.
    REQUIRE(0.5f * 255.0f == 127.5f);
    CHECK(toUnorm8(0.5f) == 128);
    CHECK(packBgra8(Color{0.3f, 0.5f, 0.3f, 1.0f}) == 0xFF4C804Cu);

    // Every float c in [0, 1] near a tie (k + 0.5) / 255 whose product c * 255.0f is exactly a
    // tie: each must round to the even neighbour. Count them so the search cannot come up empty.
    int ties = 0, tiesUp = 0, tiesDown = 0;
    for (int k = 0; k < 255; ++k) {
        float c = (k + 0.5f) / 255.0f;
        for (int i = 0; i < 8; ++i) c = std::nextafter(c, 0.0f);
        for (int i = 0; i < 17; ++i, c = std::nextafter(c, 1.0f)) {
            const float x = c * 255.0f;
            if (x != std::floor(x) + 0.5f) continue;
            ++ties;
            const unsigned got = toUnorm8(c);
            const unsigned even = (static_cast<unsigned>(std::floor(x)) % 2 == 0) ? static_cast<unsigned>(std::floor(x))
                                                                                 : static_cast<unsigned>(std::ceil(x));
            INFO("c = " << c << ", c * 255 = " << x);
            CHECK(got == even);
            (got > x ? tiesUp : tiesDown) += 1;
        }
    }
    CHECK(ties >= 100);
    CHECK(tiesUp > 0); // both directions occur: this is not floor or ceil in disguise
    CHECK(tiesDown > 0);
}

TEST_CASE("unorm8 equals clamp + std::nearbyint on a million floats and all near-ties", "[math][color]") {
    int mismatches = 0;
    // Every float within 64 ULPs of each boundary k / 255 and each tie (k + 0.5) / 255.
    for (int k = 0; k <= 510; ++k) {
        float c = (k * 0.5f) / 255.0f;
        for (int i = 0; i < 64; ++i) c = std::nextafter(c, -1.0f);
        for (int i = 0; i < 129; ++i, c = std::nextafter(c, 2.0f)) mismatches += toUnorm8(c) != referenceUnorm8(c);
    }
    // A million pseudo-random floats in [-0.5, 1.5] (covering both clamps).
    srtest::Rng rng(4242);
    for (int i = 0; i < 1000000; ++i) {
        const float c = rng.uniform(-0.5f, 1.5f);
        mismatches += toUnorm8(c) != referenceUnorm8(c);
    }
    CHECK(mismatches == 0);
}

TEST_CASE("unorm8 of non-finite and out-of-range values", "[math][color][nonfinite]") {
    CHECK(toUnorm8(std::nanf("")) == 0);
    CHECK(toUnorm8(-std::nanf("")) == 0);
    CHECK(toUnorm8(HUGE_VALF) == 255);
    CHECK(toUnorm8(-HUGE_VALF) == 0);
    CHECK(toUnorm8(-0.0f) == 0);
    CHECK(toUnorm8(-1e-30f) == 0);
    CHECK(toUnorm8(1.0000001f) == 255);
    CHECK(toUnorm8(std::numeric_limits<float>::denorm_min()) == 0);
    CHECK(packBgra8(Color{std::nanf(""), HUGE_VALF, -HUGE_VALF, 1.0f}) == 0xFF00FF00u);
}

TEST_CASE("unpack -> pack round-trips every 8-bit value exactly", "[math][color]") {
    // All 2^24 colours (the X byte is forced to 0xFF on the way back).
    std::uint32_t failures = 0;
    for (std::uint32_t v = 0; v < (1u << 24); ++v) {
        const Color c = unpackBgra8(v | 0x5A000000u); // any X byte on input
        failures += packBgra8(c) != (v | 0xFF000000u);
    }
    CHECK(failures == 0);
    for (int k = 0; k < 256; ++k) {
        const auto b = static_cast<std::uint8_t>(k);
        const Color c = fromRgba8(b, b, b, b);
        INFO("byte " << k);
        CHECK(c.r == static_cast<float>(k) / 255.0f);
        CHECK(c.a == c.r);
        CHECK(toUnorm8(c.r) == k);
    }
    CHECK(unpackBgra8(0x00112233u) == fromRgba8(0x11, 0x22, 0x33, 0xFF));
    CHECK(unpackBgra8(0x00112233u).a == 1.0f);
    CHECK(unpackBgra8(0xFFFFFFFFu) == Color{1, 1, 1, 1});
}
