// Lines with any finite float endpoints (to +-3.4e38) against a slow exact reference of Line.hpp's rule.
#include "TestFramework.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <utility>

#include "Raster/Fill/Line.hpp"
#include "RasterTestUtil.hpp"
#include "ReferenceLine.hpp"

using namespace sr;
using namespace sr::test;

namespace {

using PixelSet = ref::PixelSet;

// --- What the drawer does ------------------------------------------------------------------------
constexpr Pixel kBlack = packBgra(0, 0, 0);

LineVertex lv(float x, float y) {
    LineVertex v;
    v.x = x;
    v.y = y;
    return v;
}

PixelSet drawn(int w, int h, float ax, float ay, float bx, float by) {
    FrameBuffer fb(w, h);
    fb.clear(kBlack);
    drawLine(fb, lv(ax, ay), lv(bx, by));
    PixelSet s;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (fb.pixel(x, y) != kBlack) s.insert({x, y});
    return s;
}

// The same through setupLine with any scissor (one around the origin sees lines through it).
PixelSet scissored(const Scissor& s, float ax, float ay, float bx, float by) {
    PixelSet p;
    if (const std::optional<LineSetup> l = setupLine(lv(ax, ay), lv(bx, by), s))
        forEachLinePixel(*l, s, [&](int x, int y, float) { p.insert({x, y}); });
    return p;
}

// Compares A->B and B->A with the reference on two framebuffers and two scissors; counts lines
// that differ anywhere and keeps the first one's endpoints (hex floats) for the failure message.
struct Checker {
    int lines = 0, mismatches = 0, drawnPixels = 0;
    std::string first;

    void operator()(float ax, float ay, float bx, float by) {
        ++lines;
        bool ok = true;
        const int sizes[2][2] = {{64, 48}, {5, 3}};
        for (const auto& sz : sizes) {
            const PixelSet want = ref::linePixels(Scissor{0, 0, sz[0], sz[1]}, ax, ay, bx, by);
            drawnPixels += int(want.size());
            ok = ok && drawn(sz[0], sz[1], ax, ay, bx, by) == want && drawn(sz[0], sz[1], bx, by, ax, ay) == want;
        }
        const Scissor scissors[2] = {{-32, -24, 32, 24}, {-70, 3, -20, 40}};
        for (const Scissor& s : scissors) {
            const PixelSet want = ref::linePixels(s, ax, ay, bx, by);
            drawnPixels += int(want.size());
            ok = ok && scissored(s, ax, ay, bx, by) == want && scissored(s, bx, by, ax, ay) == want;
        }
        if (!ok && mismatches++ == 0) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "(%a, %a) -> (%a, %a)", double(ax), double(ay), double(bx), double(by));
            first = buf;
        }
    }
};

float fromBits(std::uint32_t u) {
    float f = 0.0f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

// Any finite float, every binade (subnormals and zero included) equally likely, either sign.
float anyFinite(std::mt19937& rng) {
    for (;;)
        if (const float f = fromBits(std::uint32_t(rng())); std::isfinite(f)) return f;
}

// |v| in [2^14, 2^128), either sign: beyond (or on) the guard band, up to FLT_MAX.
float hugeFloat(std::mt19937& rng) {
    const std::uint32_t exponent = std::uint32_t(uniformInt(rng, 127 + 14, 254));
    return fromBits((std::uint32_t(rng()) & 0x807FFFFFu) | (exponent << 23));
}
float hugePositive(std::mt19937& rng) { return std::fabs(hugeFloat(rng)); }

// A coordinate near the viewport [lo, hi]: free, on the 1/512 grid, a pixel centre, or a
// snapping tie that decides the pixel (k - 1/512 snaps up to k, the first point of pixel k).
float nearView(std::mt19937& rng, int lo, int hi) {
    switch (uniformInt(rng, 0, 3)) {
    case 0: return uniform(rng, float(lo), float(hi));
    case 1: return float(uniformInt(rng, lo * 512, hi * 512)) / 512.0f;
    case 2: return float(uniformInt(rng, lo, hi)) + 0.5f;
    default: return float(uniformInt(rng, lo, hi)) - 1.0f / 512.0f;
    }
}

} // namespace

TEST_CASE("lines with endpoints up to 3.4e38 draw exactly the pixels of the exact rule", "[raster][line]") {
    std::mt19937 rng(20240614);
    Checker check;

    // Through the origin from near-float-max endpoints: a clip that loses precision here puts y near
    // 3.8e22, beyond int's range (an undefined conversion).
    check(-9.572489e37f, 2.138198e38f, 9.572489e37f, -2.138198e38f);
    CHECK(scissored({-32, -24, 32, 24}, -9.572489e37f, 2.138198e38f, 9.572489e37f, -2.138198e38f).size() == 48);
    CHECK(scissored({-32, -24, 32, 24}, 9.572489e37f, -2.138198e38f, -9.572489e37f, 2.138198e38f).size() == 48);
    // Extremes, and lines touching the grown box [-1, 65] x [-1, 49] only at its corner (-1, -1).
    const float fmax = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min();
    check(-fmax, -fmax, fmax, fmax);
    check(-fmax, fmax, fmax, -fmax);
    check(-fmax, tiny, fmax, -tiny);
    check(tiny, -fmax, -tiny, fmax);
    check(-1048577.0f, 1048575.0f, 1048575.0f, -1048577.0f);
    check(-1048577.0f, 1048575.0f, -1.0f, -1.0f);

    // Any finite floats (nearly all of these lines miss every scissor).
    for (int i = 0; i < 400; ++i) check(anyFinite(rng), anyFinite(rng), anyFinite(rng), anyFinite(rng));
    // One endpoint near the viewport, the other anywhere (mostly far outside).
    for (int i = 0; i < 500; ++i) {
        const float ax = nearView(rng, -72, 68), ay = nearView(rng, -26, 52);
        const float bx = i % 2 ? anyFinite(rng) : hugeFloat(rng), by = i % 3 ? hugeFloat(rng) : anyFinite(rng);
        if (i % 2) check(ax, ay, bx, by);
        else check(bx, by, ax, ay);
    }
    // Through the origin: a = -2^j b is exact. Small integer directions put the clip points on
    // snapping ties and on box corners.
    for (int i = 0; i < 500; ++i) {
        float bx, by;
        if (i % 2) {
            bx = hugeFloat(rng);
            by = i % 4 == 1 ? hugeFloat(rng) : anyFinite(rng);
        } else {
            const float scale = std::ldexp(1.0f, uniformInt(rng, 14, 100));
            const int pow2 = 1 << uniformInt(rng, 0, 9);
            bx = float(i % 4 == 0 ? pow2 : uniformInt(rng, -600, 600)) * scale;
            by = float(uniformInt(rng, -600, 600)) * scale;
        }
        if (i % 8 == 0) std::swap(bx, by);
        const float k = -std::ldexp(1.0f, uniformInt(rng, 0, 40));
        const float ax = bx * k, ay = by * k;
        if (std::isfinite(ax) && std::isfinite(ay)) check(ax, ay, bx, by);
    }
    // Through the origin and, on a vertical side of a grown scissor, through a snapping tie
    // k - 1/512 (or a horizontal side: transposed): b = (512 side, 512 k - 1) 2^e.
    for (int i = 0; i < 400; ++i) {
        const int sides[] = {-1, 65, 6, -33, 33, -71, -19, 49, 4, -25, 25, 2, 41};
        const int side = sides[uniformInt(rng, 0, 12)], k = uniformInt(rng, -40, 70);
        const float scale = std::ldexp(1.0f, uniformInt(rng, -40, 100));
        float bx = float(512 * side) * scale, by = float(512 * k - 1) * scale;
        if (i % 2) std::swap(bx, by);
        const float f = -std::ldexp(1.0f, uniformInt(rng, 0, 20));
        if (std::isfinite(bx * f) && std::isfinite(by * f)) check(bx * f, by * f, bx, by);
    }
    // Horizontal, vertical and diagonal lines, far outside on both sides or on one side only.
    for (int i = 0; i < 300; ++i) {
        const float x0 = -hugePositive(rng), x1 = i % 3 == 2 ? nearView(rng, -72, 68) : hugePositive(rng);
        const float y = nearView(rng, -26, 52), x = nearView(rng, -72, 68);
        check(x0, y, x1, y);    // horizontal
        check(x, -x1, x, -x0);  // vertical
        check(x0, x0, x1, x1);  // y = x
        check(x0, -x0, x1, -x1); // y = -x
    }
    // Nearly horizontal or vertical, crossing the viewport somewhere between the two ends.
    for (int i = 0; i < 300; ++i) {
        const float h0 = -hugePositive(rng), h1 = hugePositive(rng);
        const float n0 = nearView(rng, -300, 300), n1 = nearView(rng, -300, 300);
        if (i % 2) check(h0, n0, h1, n1);
        else check(n0, h1, n1, h0);
    }
    // Lines that miss: both ends beyond the same side of every scissor.
    for (int i = 0; i < 200; ++i) {
        const float f0 = hugePositive(rng) + 100.0f, f1 = hugePositive(rng) + 100.0f;
        const float o0 = anyFinite(rng), o1 = anyFinite(rng);
        check(-f0, o0, -f1, o1);
        check(o0, f0, o1, f1);
    }
    // At the guard band: +-16384 (inside, snapped whole) and the next float out (clipped).
    for (int i = 0; i < 200; ++i) {
        const float edge = i % 2 ? 16384.0f : std::nextafter(16384.0f, 1e9f);
        const float sx = i % 4 < 2 ? edge : -edge;
        check(sx, nearView(rng, -300, 300), nearView(rng, -72, 68), nearView(rng, -26, 52));
        check(nearView(rng, -300, 300), sx, nearView(rng, -72, 68), nearView(rng, -26, 52));
    }

    INFO("first mismatching line: " << check.first);
    CHECK(check.mismatches == 0);
    CHECK(check.lines > 3000);
    CHECK(check.drawnPixels > 100000); // most lines cross a scissor: the pixels are really compared
}

TEST_CASE("ordinary lines (inside the guard band) draw exactly the rule's pixels", "[raster][line]") {
    std::mt19937 rng(77);
    Checker check;
    for (int i = 0; i < 6000; ++i) {
        float c[4];
        const float range = i % 3 == 0 ? 80.0f : i % 3 == 1 ? 1000.0f : 16384.0f;
        for (float& v : c) v = i % 2 ? uniform(rng, -range, range) : float(uniformInt(rng, -512 * 80, 512 * 80)) / 512.0f;
        if (i % 20 == 0) c[2] = c[0];                 // vertical
        if (i % 20 == 1) c[3] = c[1];                 // horizontal
        if (i % 20 == 2) c[3] = c[1] + (c[2] - c[0]); // 45 degrees
        if (i % 20 == 3) c[0] = i % 40 == 3 ? 16384.0f : -16384.0f; // on the guard band
        check(c[0], c[1], c[2], c[3]);
    }
    INFO("first mismatching line: " << check.first);
    CHECK(check.mismatches == 0);
    CHECK(check.drawnPixels > 50000);
}

TEST_CASE("ordinary lines: a whole-pixel translation translates the pixels", "[raster][line]") {
    // Copy-free check of the unchanged rule: endpoints on the 1/1024 grid below 2^9 translate
    // exactly, and snapping (ties up) commutes with whole-pixel shifts, so where both windows
    // overlap the translated line's pixels are the original's, shifted.
    std::mt19937 rng(5);
    const int n = 96;
    int mismatches = 0, compared = 0;
    for (int i = 0; i < 3000; ++i) {
        float c[4];
        for (float& v : c) v = float(uniformInt(rng, -20 * 1024, (n + 20) * 1024)) / 1024.0f;
        const int tx = uniformInt(rng, -40, 40), ty = uniformInt(rng, -40, 40);
        const PixelSet p = drawn(n, n, c[0], c[1], c[2], c[3]);
        const PixelSet q = drawn(n, n, c[0] + float(tx), c[1] + float(ty), c[2] + float(tx), c[3] + float(ty));
        auto inBoth = [&](int x, int y) { return x >= 0 && x < n && y >= 0 && y < n && x + tx >= 0 && x + tx < n && y + ty >= 0 && y + ty < n; };
        PixelSet pp, qq;
        for (const auto& [x, y] : p)
            if (inBoth(x, y)) pp.insert({x, y});
        for (const auto& [x, y] : q)
            if (inBoth(x - tx, y - ty)) qq.insert({x - tx, y - ty});
        mismatches += pp != qq ? 1 : 0;
        compared += int(pp.size());
    }
    CHECK(mismatches == 0);
    CHECK(compared > 20000);
}
