// Watertightness: tilings (jittered grids, 64+ triangle fans, long thin strips) hit each pixel once.
#include "TestFramework.hpp"

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "Math/Conventions.hpp"
#include "RasterTestUtil.hpp"
#include "ReferenceRasterizer.hpp"

using namespace sr;
using namespace sr::test;

namespace {

constexpr int kW = 64, kH = 64;

struct FixedPt {
    std::int64_t x, y;
};

ScreenVertex toVertex(FixedPt p) { return vtxFixed(p.x, p.y); }

// Counts one triangle of a tiling into the hit map, in a random winding.
void addTriangle(std::vector<int>& counts, std::mt19937& rng, FixedPt a, FixedPt b, FixedPt c) {
    if (uniformInt(rng, 0, 1)) std::swap(b, c);
    countHits(counts, toVertex(a), toVertex(b), toVertex(c), kW, kH);
}

// Expected coverage of the axis-aligned rectangle [x0, x1) x [y0, y1) (fixed point) under the
// top-left rule: a centre on the left or top side is in, on the right or bottom side out.
std::vector<int> rectangleMask(FixedPt lo, FixedPt hi) {
    std::vector<int> m(kW * kH, 0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const std::int64_t cx = x * 256 + 128, cy = y * 256 + 128;
            m[std::size_t(y * kW + x)] = (cx >= lo.x && cx < hi.x && cy >= lo.y && cy < hi.y) ? 1 : 0;
        }
    return m;
}

// Reference coverage of a region given as a few big triangles (0/1 per pixel).
std::vector<int> referenceMask(const std::vector<std::array<FixedPt, 3>>& tris) {
    std::vector<int> m(kW * kH, 0);
    for (const auto& t : tris)
        for (int p : ref::coverage(toVertex(t[0]), toVertex(t[1]), toVertex(t[2]), kW, kH)) ++m[std::size_t(p)];
    return m;
}

// Pixels hit 0 times inside the region (holes), > 1 times (double hits), or at all outside.
struct TilingErrors {
    int holes = 0, doubles = 0, outside = 0, covered = 0;
};
TilingErrors compare(const std::vector<int>& counts, const std::vector<int>& mask) {
    TilingErrors e;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        if (mask[i]) {
            ++e.covered;
            if (counts[i] == 0) ++e.holes;
            if (counts[i] > 1) ++e.doubles;
        } else if (counts[i] != 0) {
            ++e.outside;
        }
    }
    return e;
}

#define CHECK_TILING(counts, mask)                       \
    do {                                                 \
        const TilingErrors e_ = compare(counts, mask);   \
        CHECK(e_.holes == 0);                            \
        CHECK(e_.doubles == 0);                          \
        CHECK(e_.outside == 0);                          \
        CHECK(e_.covered > 0);                           \
    } while (0)

} // namespace

TEST_CASE("jittered grids tile a rectangle exactly once", "[raster][watertight]") {
    std::mt19937 rng(2024);
    for (int iter = 0; iter < 300; ++iter) {
        // Rectangle corners anywhere on the sub-pixel grid, partly off screen at times; cells
        // from 1/3 px to 12 px; every third grid on exact pixel centres without jitter (ties).
        const bool onCentres = iter % 3 == 0;
        const int nx = uniformInt(rng, 1, 14), ny = uniformInt(rng, 1, 14);
        const std::int64_t cell = onCentres ? 256 * uniformInt(rng, 1, 5) : uniformInt(rng, 85, 3072);
        const FixedPt lo = onCentres ? FixedPt{256 * uniformInt(rng, -4, 30) + 128, 256 * uniformInt(rng, -4, 30) + 128}
                                     : FixedPt{uniformInt(rng, -2000, 9000), uniformInt(rng, -2000, 9000)};
        const FixedPt hi{lo.x + nx * cell, lo.y + ny * cell};
        // Grid points: interior ones jittered by up to 0.2 cell (cells stay convex), boundary ones
        // only along their side so the region stays exactly the rectangle.
        const std::int64_t j = onCentres ? 0 : cell / 5;
        std::vector<FixedPt> g(std::size_t((nx + 1) * (ny + 1)));
        for (int y = 0; y <= ny; ++y)
            for (int x = 0; x <= nx; ++x) {
                FixedPt p{lo.x + x * cell, lo.y + y * cell};
                if (x > 0 && x < nx) p.x += uniformInt(rng, int(-j), int(j));
                if (y > 0 && y < ny) p.y += uniformInt(rng, int(-j), int(j));
                g[std::size_t(y * (nx + 1) + x)] = p;
            }
        std::vector<int> counts(kW * kH, 0);
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                const FixedPt p00 = g[std::size_t(y * (nx + 1) + x)], p10 = g[std::size_t(y * (nx + 1) + x + 1)];
                const FixedPt p01 = g[std::size_t((y + 1) * (nx + 1) + x)], p11 = g[std::size_t((y + 1) * (nx + 1) + x + 1)];
                if (uniformInt(rng, 0, 1)) { // either diagonal
                    addTriangle(counts, rng, p00, p10, p11);
                    addTriangle(counts, rng, p00, p11, p01);
                } else {
                    addTriangle(counts, rng, p00, p10, p01);
                    addTriangle(counts, rng, p10, p11, p01);
                }
            }
        const std::vector<int> mask = rectangleMask(lo, hi);
        if (std::count(mask.begin(), mask.end(), 1) == 0) continue; // entirely off screen
        INFO("grid " << iter);
        CHECK_TILING(counts, mask);
        // The hand-derived rectangle rule and the reference agree on the region.
        CHECK(referenceMask({{lo, {hi.x, lo.y}, hi}, {lo, hi, {lo.x, hi.y}}}) == mask);
    }
}

TEST_CASE("fans of 64+ triangles around one vertex tile their rectangle exactly once", "[raster][watertight]") {
    std::mt19937 rng(99);
    for (int iter = 0; iter < 200; ++iter) {
        // Rectangle boundary (corners included) carries >= 64 points; the fan's centre is inside,
        // exactly on a pixel centre every other time.
        const FixedPt lo{uniformInt(rng, -1500, 3000), uniformInt(rng, -1500, 3000)};
        const FixedPt hi{lo.x + uniformInt(rng, 2000, 14000), lo.y + uniformInt(rng, 2000, 14000)};
        FixedPt c{uniformInt(rng, int(lo.x) + 1, int(hi.x) - 1), uniformInt(rng, int(lo.y) + 1, int(hi.y) - 1)};
        if (iter % 2 == 0) { // snap the centre to the nearest pixel centre inside
            c.x = std::clamp<std::int64_t>((c.x / 256) * 256 + 128, lo.x + 1, hi.x - 1);
            c.y = std::clamp<std::int64_t>((c.y / 256) * 256 + 128, lo.y + 1, hi.y - 1);
        }
        // Walk the boundary clockwise (y down): top, right, bottom, left; 16-40 points per side.
        std::vector<FixedPt> ring;
        auto side = [&](FixedPt from, FixedPt to) {
            const int n = uniformInt(rng, 16, 40);
            std::vector<std::int64_t> ts{0};
            for (int k = 1; k < n; ++k) ts.push_back(uniformInt(rng, 1, 4095));
            std::sort(ts.begin(), ts.end());
            ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
            for (std::int64_t t : ts) // points on the side, exact in fixed point
                ring.push_back({from.x + (to.x - from.x) * t / 4096, from.y + (to.y - from.y) * t / 4096});
        };
        side(lo, {hi.x, lo.y});
        side({hi.x, lo.y}, hi);
        side(hi, {lo.x, hi.y});
        side({lo.x, hi.y}, lo);
        REQUIRE(ring.size() >= 64);
        std::vector<int> counts(kW * kH, 0);
        for (std::size_t k = 0; k < ring.size(); ++k) addTriangle(counts, rng, c, ring[k], ring[(k + 1) % ring.size()]);
        INFO("fan " << iter);
        CHECK_TILING(counts, rectangleMask(lo, hi));
    }
}

TEST_CASE("a 360-degree fan of 96 triangles around a pixel centre has no holes or double hits", "[raster][watertight]") {
    const int n = 96;
    const double cx = 32.5, cy = 32.5, r = 25.0, pi = kPiD;
    std::vector<ScreenVertex> ring;
    for (int k = 0; k < n; ++k)
        ring.push_back(vtx(float(cx + r * std::cos(2 * pi * k / n)), float(cy + r * std::sin(2 * pi * k / n))));
    std::vector<int> counts(kW * kH, 0);
    for (int k = 0; k < n; ++k) countHits(counts, vtx(float(cx), float(cy)), ring[std::size_t(k)], ring[std::size_t((k + 1) % n)], kW, kH);
    int inner = 0, bad = 0;
    const double rIn = r * std::cos(pi / n) - 0.05, rOut = r + 0.05;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const int hits = counts[std::size_t(y * kW + x)];
            const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
            if (hits > 1) ++bad;                 // never a double hit
            if (d < rIn && hits != 1) ++bad;     // no hole inside the inscribed circle
            if (d > rOut && hits != 0) ++bad;    // nothing outside the circumscribed one
            inner += d < rIn ? 1 : 0;
        }
    CHECK(bad == 0);
    CHECK(inner > 1800); // ~ pi * 25^2
    CHECK(counts[32 * kW + 32] == 1); // the shared vertex's own pixel: exactly one owner
}

TEST_CASE("long thin strips tile their parallelogram exactly once", "[raster][watertight]") {
    std::mt19937 rng(7);
    for (int iter = 0; iter < 300; ++iter) {
        // Strip between the parallel lines T0 + i D and B0 + i D; the step D is an integer
        // fixed-point vector, so every strip vertex is exactly on its line.
        const int n = uniformInt(rng, 8, 60);
        const FixedPt d{uniformInt(rng, -600, 600), uniformInt(rng, -600, 600)};
        if (d.x == 0 && d.y == 0) continue;
        const FixedPt t0{uniformInt(rng, -2000, 18000) - n * d.x / 2, uniformInt(rng, -2000, 18000) - n * d.y / 2};
        // Width from ~0.05 px to 3 px, across the strip direction (plus a random shear).
        const double len = std::hypot(double(d.x), double(d.y));
        const double wpx = std::exp2(uniform(rng, -4.5f, 1.6f)) * 256.0;
        const FixedPt off{std::int64_t(std::llround(-d.y / len * wpx)) + uniformInt(rng, -20, 20),
                          std::int64_t(std::llround(d.x / len * wpx)) + uniformInt(rng, -20, 20)};
        const FixedPt b0{t0.x + off.x, t0.y + off.y};
        auto T = [&](int i) { return FixedPt{t0.x + i * d.x, t0.y + i * d.y}; };
        auto B = [&](int i) { return FixedPt{b0.x + i * d.x, b0.y + i * d.y}; };
        if (off.x * d.y - off.y * d.x == 0) continue; // degenerate strip
        std::vector<int> counts(kW * kH, 0);
        for (int i = 0; i < n; ++i) {
            addTriangle(counts, rng, T(i), T(i + 1), B(i));
            addTriangle(counts, rng, T(i + 1), B(i + 1), B(i));
        }
        const std::vector<int> mask = referenceMask({{T(0), T(n), B(n)}, {T(0), B(n), B(0)}});
        if (std::count(mask.begin(), mask.end(), 1) == 0) continue;
        INFO("strip " << iter);
        REQUIRE(*std::max_element(mask.begin(), mask.end()) <= 1); // the reference tiles too
        CHECK_TILING(counts, mask);
    }
}
