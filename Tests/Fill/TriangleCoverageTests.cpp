// The scanline filler's coverage equals the per-pixel reference EXACTLY on >= 100,000 random triangles.
#include "TestFramework.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "RasterTestUtil.hpp"
#include "ReferenceRasterizer.hpp"

using namespace sr;
using namespace sr::test;

namespace {

struct Tri {
    ScreenVertex a, b, c;
};

// One random triangle of kind `kind` around a framebuffer of size w x h. The kinds cover: small
// to huge sizes, vertices on pixel centres / half pixels / the sub-pixel grid, the guard band,
// collinear and coincident vertices, and needle-thin slivers.
Tri randomTriangle(std::mt19937& rng, int kind, int w, int h) {
    auto centreNear = [&](float margin) {
        return vtx(uniform(rng, -margin, float(w) + margin), uniform(rng, -margin, float(h) + margin));
    };
    switch (kind) {
    case 0: { // free floats, log-uniform size from 1/256 px to 64 px
        const ScreenVertex c = centreNear(8.0f);
        const float s = std::exp2(uniform(rng, -8.0f, 6.0f));
        auto around = [&] { return vtx(c.x + s * uniform(rng, -1, 1), c.y + s * uniform(rng, -1, 1)); };
        return {around(), around(), around()};
    }
    case 1: { // pixel centres
        auto pc = [&] { return vtx(float(uniformInt(rng, -3, w + 3)) + 0.5f, float(uniformInt(rng, -3, h + 3)) + 0.5f); };
        return {pc(), pc(), pc()};
    }
    case 2: { // half-pixel lattice (corners and centres), small
        const int bx = uniformInt(rng, -4, 2 * w + 4), by = uniformInt(rng, -4, 2 * h + 4);
        auto hp = [&] { return vtx(float(bx + uniformInt(rng, -6, 6)) * 0.5f, float(by + uniformInt(rng, -6, 6)) * 0.5f); };
        return {hp(), hp(), hp()};
    }
    case 3: { // sub-pixel grid points, a few pixels across
        const int bx = uniformInt(rng, -1000, w * 256 + 1000), by = uniformInt(rng, -1000, h * 256 + 1000);
        auto g = [&] { return vtxFixed(bx + uniformInt(rng, -700, 700), by + uniformInt(rng, -700, 700)); };
        return {g(), g(), g()};
    }
    case 4: { // huge: anywhere in the guard band (limits included)
        auto any = [&] {
            const int pick = uniformInt(rng, 0, 9);
            if (pick == 0) return vtx(uniformInt(rng, 0, 1) ? kGuardBand : -kGuardBand, uniform(rng, -kGuardBand, kGuardBand));
            if (pick == 1) return vtx(uniform(rng, -kGuardBand, kGuardBand), uniformInt(rng, 0, 1) ? kGuardBand : -kGuardBand);
            return vtx(uniform(rng, -kGuardBand, kGuardBand), uniform(rng, -kGuardBand, kGuardBand));
        };
        return {any(), any(), centreNear(4.0f)};
    }
    case 5: { // degenerate: collinear on the grid, coincident pairs, all three equal
        const std::int64_t ax = uniformInt(rng, -500, w * 256 + 500), ay = uniformInt(rng, -500, h * 256 + 500);
        const std::int64_t dx = uniformInt(rng, -900, 900), dy = uniformInt(rng, -900, 900);
        const int k = uniformInt(rng, -2, 3);
        const ScreenVertex a = vtxFixed(ax, ay), b = vtxFixed(ax + dx, ay + dy);
        const ScreenVertex c = vtxFixed(ax + k * dx, ay + k * dy);
        switch (uniformInt(rng, 0, 2)) {
        case 0: return {a, b, c};
        case 1: return {a, a, b};
        default: return {a, a, a};
        }
    }
    case 6: { // slivers: two far vertices and a third within ~1 sub-pixel unit of their segment
        const ScreenVertex a = centreNear(40.0f), b = centreNear(40.0f);
        const float t = uniform(rng, -0.2f, 1.2f);
        const float off = float(uniformInt(rng, -3, 3)) / 256.0f;
        return {a, b, vtx(a.x + t * (b.x - a.x) + off, a.y + t * (b.y - a.y) - off)};
    }
    default: { // medium to large floats, partly off screen
        const ScreenVertex c = centreNear(32.0f);
        const float s = std::exp2(uniform(rng, 3.0f, 9.0f));
        auto around = [&] { return vtx(c.x + s * uniform(rng, -1, 1), c.y + s * uniform(rng, -1, 1)); };
        return {around(), around(), around()};
    }
    }
}

std::string describe(const Tri& t, int w, int h) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "fb %dx%d: (%.9g, %.9g) (%.9g, %.9g) (%.9g, %.9g)", w, h,
                  double(t.a.x), double(t.a.y), double(t.b.x), double(t.b.y), double(t.c.x), double(t.c.y));
    return buf;
}

} // namespace

TEST_CASE("scanline coverage equals the reference on 120,000 random triangles", "[raster][coverage]") {
    std::mt19937 rng(0x5EED1234u);
    const int sizes[][2] = {{64, 64}, {64, 64}, {37, 23}, {1, 1}, {5, 64}, {64, 3}};
    constexpr int kTriangles = 120000;
    int mismatches = 0, nonEmpty = 0, pixels = 0;
    std::string firstFailure;
    for (int i = 0; i < kTriangles; ++i) {
        const auto& size = sizes[uniformInt(rng, 0, 5)];
        const int w = size[0], h = size[1];
        const Tri t = randomTriangle(rng, uniformInt(rng, 0, 7), w, h);
        const std::vector<int> expected = ref::coverage(t.a, t.b, t.c, w, h);
        // The same triangle in three vertex orders: as given, opposite winding, rotated.
        const std::vector<int> got[3] = {scanCoverage(t.a, t.b, t.c, w, h),
                                         scanCoverage(t.b, t.a, t.c, w, h),
                                         scanCoverage(t.c, t.a, t.b, w, h)};
        for (const auto& g : got) {
            if (g != expected) {
                if (mismatches++ == 0) firstFailure = describe(t, w, h);
            }
        }
        nonEmpty += expected.empty() ? 0 : 1;
        pixels += int(expected.size());
    }
    INFO("first mismatch: " << firstFailure);
    CHECK(mismatches == 0);
    // The generator must actually exercise coverage, not only empty triangles.
    CHECK(nonEmpty > kTriangles / 3);
    CHECK(pixels > 10 * kTriangles);
}

TEST_CASE("scissored coverage is the full coverage restricted to the scissor", "[raster][coverage]") {
    std::mt19937 rng(77);
    for (int i = 0; i < 2000; ++i) {
        const Tri t = randomTriangle(rng, uniformInt(rng, 0, 7), 64, 64);
        const std::vector<int> full = ref::coverage(t.a, t.b, t.c, 64, 64);
        const Scissor s{uniformInt(rng, 0, 40), uniformInt(rng, 0, 40), uniformInt(rng, 24, 64), uniformInt(rng, 24, 64)};
        std::vector<int> expected;
        for (int p : full) {
            const int x = p % 64, y = p / 64;
            if (x >= s.x0 && x < s.x1 && y >= s.y0 && y < s.y1) expected.push_back(p);
        }
        std::vector<int> got;
        if (const auto setup = setupTriangle(t.a, t.b, t.c, 0)) {
            forEachSpan(*setup, s, [&](int y, int x0, int x1) {
                for (int x = x0; x < x1; ++x) got.push_back(y * 64 + x);
            });
        }
        REQUIRE(got == expected);
    }
}

TEST_CASE("zero-area and out-of-row triangles are rejected by setup", "[raster][coverage]") {
    CHECK_FALSE(setupTriangle(vtx(1, 1), vtx(1, 1), vtx(5, 5), 0));     // coincident
    CHECK_FALSE(setupTriangle(vtx(1, 1), vtx(3, 3), vtx(5, 5), 0));     // collinear
    CHECK_FALSE(setupTriangle(vtx(1, 1), vtx(1, 1), vtx(1, 1), 0));     // a point
    // Distinct floats that snap to one grid point (< 1/512 apart) collapse to zero area.
    CHECK_FALSE(setupTriangle(vtx(1, 1), vtx(1.001f, 1), vtx(1, 1.001f), 0));
    // Between two rows of centres: non-zero area but no row to cover.
    CHECK_FALSE(setupTriangle(vtx(0, 0.6f), vtx(10, 0.6f), vtx(5, 1.4f), 0));
    // A real triangle reports its signed area in input order (> 0 clockwise on screen).
    const auto cw = setupTriangle(vtx(0, 0), vtx(4, 0), vtx(0, 4), 0);
    REQUIRE(cw);
    CHECK(cw->doubleArea == 16 * 256 * 256);
    const auto ccw = setupTriangle(vtx(0, 0), vtx(0, 4), vtx(4, 0), 0);
    REQUIRE(ccw);
    CHECK(ccw->doubleArea == -16 * 256 * 256);
}
