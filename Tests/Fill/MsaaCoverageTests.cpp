// Multisampled coverage (Raster/Fill/MsaaFill.hpp): per sample equal to the reference rasterizer's edge
// functions at the sample points, shading once per covered pixel, and watertight per sample.
#include "TestFramework.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "Raster/Fill/MsaaFill.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "RasterTestUtil.hpp"
#include "ReferenceRasterizer.hpp"

using namespace sr;
using namespace sr::test;

namespace {

constexpr Pixel kClear = 0xFF000000u, kInk = 0xFFFFFFFFu;

// What fillTriangleMsaa did with one triangle (no depth test): the covered pixels of every sample
// (indices y * width + x, ascending), and how it shaded.
struct MsaaFillResult {
    std::vector<std::vector<int>> perSample;
    std::vector<int> centreShaded;   // pixels shaded at the centre (through the run shader)
    std::vector<int> centroidShaded; // pixels shaded at the centroid of their covered samples
    std::uint64_t shadedCount = 0;   // the fill's own counter
};

MsaaFillResult fillSamples(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, int samples,
                           int width, int height) {
    MsaaBuffer target;
    REQUIRE(target.resize(width, height, samples));
    target.clearRows(0, height, kClear, 0.0f);
    FrameBuffer shadeRows(width, height);
    MsaaFillResult r;
    TriangleSetup t;
    if (setupTriangleCulled(t, a, b, c, CullMode::None, 0, true, {}, true) == SetupOutcome::Ready) {
        MsaaScratch scratch;
        auto shadeRow = [&](int y) -> const Pixel* { return shadeRows.colorRow(y); };
        auto shadeRuns = [&](const SpanRun* runs, int count, const SampleWrite& write) {
            REQUIRE(write.target == &target); // an opaque draw: the samples offered
            for (int k = 0; k < count; ++k)
                for (int x = runs[k].x0, y = runs[k].y; x < runs[k].x1; ++x) {
                    shadeRows.colorRow(y)[x] = kInk;
                    const bool centre = runs[k].dx == 0.0 && runs[k].dy == 0.0;
                    (centre ? r.centreShaded : r.centroidShaded).push_back(y * width + x);
                    if (!centre) REQUIRE(runs[k].x1 == x + 1); // centroids one pixel at a time
                    REQUIRE(write.passed[runs[k].passedAt + std::uint32_t(x - runs[k].x0)] != 0); // a sample passed
                }
            return false; // written to the rows: the fill's write step stores the samples
        };
        fillTriangleMsaa<DepthMode::Off>(t, target, Scissor{0, 0, width, height}, scratch, shadeRow, shadeRuns,
                                         r.shadedCount);
    }
    r.perSample.resize(std::size_t(samples));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int s = 0; s < samples; ++s)
                if (target.colourRow(y)[std::size_t(x) * std::size_t(samples) + std::size_t(s)] == kInk)
                    r.perSample[std::size_t(s)].push_back(y * width + x);
    std::sort(r.centreShaded.begin(), r.centreShaded.end());
    std::sort(r.centroidShaded.begin(), r.centroidShaded.end());
    return r;
}

// Checks one triangle in all six vertex orders against the reference, for every sample count.
void checkAgainstReference(const std::array<ScreenVertex, 3>& v, int width, int height) {
    for (int n : {2, 4, 8}) {
        const SampleOffset* pattern = msaaPattern(n);
        std::vector<std::vector<int>> expected;
        std::vector<int> any;
        for (int s = 0; s < n; ++s) {
            expected.push_back(ref::sampleCoverage(v[0], v[1], v[2], width, height, pattern[s].x, pattern[s].y));
            any.insert(any.end(), expected.back().begin(), expected.back().end());
        }
        std::sort(any.begin(), any.end());
        any.erase(std::unique(any.begin(), any.end()), any.end());
        const std::vector<int> centre = ref::coverage(v[0], v[1], v[2], width, height);
        std::vector<int> centreAndSample, sampleOnly;
        std::set_intersection(any.begin(), any.end(), centre.begin(), centre.end(), std::back_inserter(centreAndSample));
        std::set_difference(any.begin(), any.end(), centre.begin(), centre.end(), std::back_inserter(sampleOnly));

        std::array<int, 3> order{0, 1, 2};
        do {
            CAPTURE(n, order[0], order[1], order[2]);
            const MsaaFillResult r = fillSamples(v[std::size_t(order[0])], v[std::size_t(order[1])],
                                                 v[std::size_t(order[2])], n, width, height);
            for (int s = 0; s < n; ++s) {
                CAPTURE(s);
                REQUIRE(r.perSample[std::size_t(s)] == expected[std::size_t(s)]);
            }
            // Shaded once per pixel with a covered sample: at the centre where the centre is
            // covered, else at the centroid of the covered samples (which for a symmetric pair,
            // such as 4x samples 0 and 3, is the centre itself: such a pixel is a centre run).
            std::vector<int> all = r.centreShaded;
            all.insert(all.end(), r.centroidShaded.begin(), r.centroidShaded.end());
            std::sort(all.begin(), all.end());
            REQUIRE(all == any); // each once
            REQUIRE(std::includes(r.centreShaded.begin(), r.centreShaded.end(), centreAndSample.begin(),
                                  centreAndSample.end()));
            REQUIRE(std::includes(sampleOnly.begin(), sampleOnly.end(), r.centroidShaded.begin(),
                                  r.centroidShaded.end()));
            REQUIRE(r.shadedCount == any.size());
        } while (std::next_permutation(order.begin(), order.end()));
    }
}

} // namespace

TEST_CASE("MSAA: the standard Direct3D patterns, on the 1/256 grid, inside the pixel", "[msaa]") {
    CHECK(msaaPattern(3) == nullptr);
    CHECK(msaaPattern(16) == nullptr);
    CHECK(msaaPattern(1)[0].x == 0);
    CHECK(msaaPattern(1)[0].y == 0);
    // D3D11_STANDARD_MULTISAMPLE_PATTERN, 1/16 pixel: 2x (4,4) (-4,-4); 4x (-2,-6) (6,-2) (-6,2) (2,6).
    CHECK(msaaPattern(2)[0].x == 64);
    CHECK(msaaPattern(2)[1].y == -64);
    CHECK(msaaPattern(4)[0].x == -32);
    CHECK(msaaPattern(4)[0].y == -96);
    CHECK(msaaPattern(4)[3].x == 32);
    CHECK(msaaPattern(4)[3].y == 96);
    for (int n : {2, 4, 8}) {
        const SampleOffset* p = msaaPattern(n);
        int sumX = 0, sumY = 0;
        for (int s = 0; s < n; ++s) {
            CAPTURE(n, s);
            CHECK(p[s].x % 16 == 0);
            CHECK(p[s].y % 16 == 0);
            CHECK(p[s].x >= -128);
            CHECK(p[s].x < 128);
            CHECK(p[s].y >= -128);
            CHECK(p[s].y < 128);
            for (int o = 0; o < s; ++o) CHECK((p[o].x != p[s].x || p[o].y != p[s].y));
            sumX += p[s].x;
            sumY += p[s].y;
        }
        // Every standard pattern is centred on the pixel (no drift of the image).
        CHECK(sumX == 0);
        CHECK(sumY == 0);
    }
}

TEST_CASE("MSAA coverage equals the per-sample reference, sample by sample (random, fixed seed)", "[msaa]") {
    constexpr int kW = 40, kH = 32;
    std::mt19937 rng(20261125);
    auto point = [&](float lo, float hi) { return vtx(uniform(rng, lo, hi), uniform(rng, lo, hi)); };
    SECTION("general triangles, partly off the target") {
        for (int i = 0; i < 150; ++i) checkAgainstReference({point(-6, 46), point(-6, 46), point(-6, 46)}, kW, kH);
    }
    SECTION("vertices on the 1/16 grid: edges through sample points, axis-aligned edges") {
        auto grid = [&] { return vtxFixed(16 * uniformInt(rng, -16, 16 * 36), 16 * uniformInt(rng, -16, 16 * 28)); };
        for (int i = 0; i < 150; ++i) {
            ScreenVertex a = grid(), b = grid(), c = grid();
            if (i % 3 == 0) b.y = a.y; // a horizontal edge
            if (i % 3 == 1) c.x = a.x; // a vertical edge
            checkAgainstReference({a, b, c}, kW, kH);
        }
    }
    SECTION("sub-pixel triangles (no pixel centre needed)") {
        for (int i = 0; i < 200; ++i) {
            const float x = uniform(rng, 2, 38), y = uniform(rng, 2, 30);
            checkAgainstReference({vtx(x, y), vtx(x + uniform(rng, -1.2f, 1.2f), y + uniform(rng, -1.2f, 1.2f)),
                                   vtx(x + uniform(rng, -1.2f, 1.2f), y + uniform(rng, -1.2f, 1.2f))},
                                  kW, kH);
        }
    }
    SECTION("slivers: the third vertex a few 1/256 off the line through the other two") {
        for (int i = 0; i < 150; ++i) {
            const ScreenVertex a = point(-4, 44), b = point(-4, 44);
            const float t = uniform(rng, 0.0f, 1.0f), off = float(uniformInt(rng, -4, 4)) / 256.0f;
            checkAgainstReference({a, b, vtx(a.x + t * (b.x - a.x) + off, a.y + t * (b.y - a.y) - off)}, kW, kH);
        }
    }
    SECTION("guard-band sizes: vertices up to 16384 pixels away") {
        for (int i = 0; i < 60; ++i) {
            const float g = kGuardBand;
            checkAgainstReference({point(-g, g), point(-g, g), vtx(uniform(rng, 0, 40), uniform(rng, 0, 32))}, kW, kH);
        }
    }
}

TEST_CASE("MSAA is watertight per sample: a jittered grid and a fan cover every sample once", "[msaa]") {
    constexpr int kW = 48, kH = 40;
    std::mt19937 rng(7);
    for (int n : {2, 4, 8}) {
        CAPTURE(n);
        const SampleOffset* pattern = msaaPattern(n);
        // A 6 x 5 grid of cells over [4, 44) x [4, 36) with jittered inner vertices (1/256 grid,
        // some on the 1/16 sample grid), each cell split along a random diagonal.
        constexpr int kCols = 6, kRows = 5;
        std::vector<std::vector<std::pair<std::int64_t, std::int64_t>>> grid(kRows + 1);
        for (int j = 0; j <= kRows; ++j)
            for (int i = 0; i <= kCols; ++i) {
                std::int64_t x = (4 + i * 40 / kCols) * 256, y = (4 + j * 32 / kRows) * 256;
                if (i > 0 && i < kCols) x += (j % 2 ? 16 : 1) * uniformInt(rng, -100 / (j % 2 ? 16 : 1), 100 / (j % 2 ? 16 : 1));
                if (j > 0 && j < kRows) y += uniformInt(rng, -100, 100);
                grid[std::size_t(j)].push_back({x, y});
            }
        std::vector<int> hits(std::size_t(kW * kH * n), 0);
        auto add = [&](std::pair<std::int64_t, std::int64_t> a, std::pair<std::int64_t, std::int64_t> b,
                       std::pair<std::int64_t, std::int64_t> c) {
            if (uniformInt(rng, 0, 1)) std::swap(b, c);
            const MsaaFillResult r = fillSamples(vtxFixed(a.first, a.second), vtxFixed(b.first, b.second),
                                                 vtxFixed(c.first, c.second), n, kW, kH);
            for (int s = 0; s < n; ++s)
                for (int p : r.perSample[std::size_t(s)]) ++hits[std::size_t(p * n + s)];
        };
        for (int j = 0; j < kRows; ++j)
            for (int i = 0; i < kCols; ++i) {
                const auto p00 = grid[std::size_t(j)][std::size_t(i)], p10 = grid[std::size_t(j)][std::size_t(i + 1)];
                const auto p01 = grid[std::size_t(j + 1)][std::size_t(i)], p11 = grid[std::size_t(j + 1)][std::size_t(i + 1)];
                if (uniformInt(rng, 0, 1)) {
                    add(p00, p10, p11);
                    add(p00, p11, p01);
                } else {
                    add(p00, p10, p01);
                    add(p10, p11, p01);
                }
            }
        int inside = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int s = 0; s < n; ++s) {
                    const std::int64_t sx = x * 256 + 128 + pattern[s].x, sy = y * 256 + 128 + pattern[s].y;
                    // The rectangle [4, 44) x [4, 36): left and top sides in, right and bottom out.
                    const int expect = sx >= 4 * 256 && sx < 44 * 256 && sy >= 4 * 256 && sy < 36 * 256 ? 1 : 0;
                    inside += expect;
                    CAPTURE(x, y, s);
                    REQUIRE(hits[std::size_t((y * kW + x) * n + s)] == expect);
                }
        CHECK(inside == 40 * 32 * n);

        // A fan of 64 triangles around an off-grid centre: every sample inside the polygon once.
        std::fill(hits.begin(), hits.end(), 0);
        std::vector<int> expected(hits.size(), 0);
        const std::pair<std::int64_t, std::int64_t> centre{24 * 256 + 37, 20 * 256 + 101};
        std::vector<std::pair<std::int64_t, std::int64_t>> ring;
        for (int k = 0; k < 64; ++k) {
            const double a = 2.0 * 3.14159265358979 * k / 64.0;
            ring.push_back({centre.first + std::int64_t(std::cos(a) * 17.3 * 256), centre.second + std::int64_t(std::sin(a) * 15.1 * 256)});
        }
        for (int k = 0; k < 64; ++k) {
            const auto a = ring[std::size_t(k)], b = ring[std::size_t((k + 1) % 64)];
            add(centre, a, b);
            for (int s = 0; s < n; ++s)
                for (int p : ref::sampleCoverage(vtxFixed(centre.first, centre.second), vtxFixed(a.first, a.second),
                                                 vtxFixed(b.first, b.second), kW, kH, pattern[s].x, pattern[s].y))
                    ++expected[std::size_t(p * n + s)];
        }
        CHECK(*std::max_element(expected.begin(), expected.end()) == 1);
        CHECK(std::count(expected.begin(), expected.end(), 1) > 700 * n);
        CHECK(hits == expected);
    }
}

TEST_CASE("MSAA coverage and depth (edge functions, vector depth test) equal the reference walks",
          "[msaa]") {
    // coverTriangleSamples' two methods on the same random triangles and random stored depths:
    // the rows, covered and passed masks, the pixels to shade (and where) and the depth buffer
    // after the test must be the same, for every sample count and depth mode, scissored or not,
    // and for every ISA the draw may have (Avx2 and Avx512 test small triangles' boxes eight
    // pixels at a time).
    constexpr int kW = 48, kH = 40;
    std::mt19937 rng(20261126);
    int small = 0, large = 0, hidden = 0;
    for (Isa isa : kAllIsas) {
        if (!isaAvailable(isa)) continue;
        CAPTURE(isaName(isa));
        for (int n : {2, 4, 8}) {
            for (DepthMode depth : {DepthMode::Off, DepthMode::Test, DepthMode::TestWrite}) {
                CAPTURE(n, int(depth));
                MsaaBuffer walked, edged;
                REQUIRE(walked.resize(kW, kH, n));
                REQUIRE(edged.resize(kW, kH, n));
                for (int y = 0; y < kH; ++y)
                    for (int i = 0; i < kW * n; ++i)
                        walked.depthRow(y)[i] = edged.depthRow(y)[i] = uniform(rng, 0.0f, 1.0f);
                MsaaScratch a, b;
                for (int i = 0; i < 300; ++i) {
                    CAPTURE(i);
                    // Sizes from sub-pixel to larger than the edge-function box (kMsaaSmallSide).
                    const float size = i % 3 == 0 ? 1.5f : i % 3 == 1 ? 12.0f : 45.0f;
                    const float cx = uniform(rng, -4, kW + 4), cy = uniform(rng, -4, kH + 4);
                    // Every other triangle on the patterns' 1/16-pixel grid: vertices on pixel edges
                    // and on sample points, where the edge-function box (msaaColumnRange) is tightest.
                    const bool onGrid = i % 2 == 1;
                    auto coordinate = [&](float c) { return onGrid ? std::round(c * 16.0f) / 16.0f : c; };
                    auto around = [&] {
                        return vtx(coordinate(cx + uniform(rng, -size, size)), coordinate(cy + uniform(rng, -size, size)),
                                   uniform(rng, 0.0f, 1.0f));
                    };
                    const ScreenVertex v0 = around(), v1 = around(), v2 = around();
                    TriangleSetup t;
                    if (setupTriangleCulled(t, v0, v1, v2, CullMode::None, 0, true, {}, true) != SetupOutcome::Ready)
                        continue;
                    (msaaSmallTriangle(t) ? small : large) += 1;
                    Scissor s{0, 0, kW, kH};
                    if (i % 4 == 3)
                        s = {uniformInt(rng, 0, 20), uniformInt(rng, 0, 15), uniformInt(rng, 24, kW), uniformInt(rng, 20, kH)};
                    coverTriangleSamples(t, edged, s, depth, a, MsaaCoverageMethod::Auto, isa);
                    coverTriangleSamples(t, walked, s, depth, b, MsaaCoverageMethod::Reference);
                    if (a.rows.empty() && !b.rows.empty()) {
                        // A small triangle behind every stored depth of its box lists no rows
                        // (hiddenBehind): then no sample passes in the reference either.
                        REQUIRE(depth != DepthMode::Off);
                        REQUIRE(msaaSmallTriangle(t));
                        for (const MsaaScratch::Row& rb : b.rows)
                            for (int x = 0; x < rb.hi - rb.lo; ++x) REQUIRE(b.passed[rb.offset + std::size_t(x)] == 0);
                        ++hidden;
                    }
                    REQUIRE((a.rows.size() == b.rows.size() || a.rows.empty()));
                    for (std::size_t r = 0; r < a.rows.size(); ++r) {
                        const MsaaScratch::Row &ra = a.rows[r], &rb = b.rows[r];
                        REQUIRE((ra.y == rb.y && ra.lo == rb.lo && ra.hi == rb.hi));
                        for (int x = 0; x < ra.hi - ra.lo; ++x) {
                            REQUIRE(a.covered[ra.offset + std::size_t(x)] == b.covered[rb.offset + std::size_t(x)]);
                            REQUIRE(a.passed[ra.offset + std::size_t(x)] == b.passed[rb.offset + std::size_t(x)]);
                        }
                    }
                    REQUIRE(a.runs.size() == b.runs.size());
                    std::size_t row = 0; // the record of the runs' row (runs are listed row by row)
                    for (std::size_t r = 0; r < a.runs.size(); ++r) {
                        const SpanRun &ra = a.runs[r], &rb = b.runs[r];
                        REQUIRE((ra.y == rb.y && ra.x0 == rb.x0 && ra.x1 == rb.x1 && ra.dx == rb.dx && ra.dy == rb.dy));
                        // Each run's masks are its pixels' passing samples in the row records.
                        while (a.rows[row].y != ra.y) ++row;
                        const MsaaScratch::Row &rowA = a.rows[row], &rowB = b.rows[row];
                        for (int x = ra.x0; x < ra.x1; ++x) {
                            const std::uint8_t pass = a.passed[rowA.offset + std::size_t(x - rowA.lo)];
                            REQUIRE(pass != 0);
                            REQUIRE(a.passed[ra.passedAt + std::size_t(x - ra.x0)] == pass);
                            REQUIRE(b.passed[rb.passedAt + std::size_t(x - rb.x0)] ==
                                    b.passed[rowB.offset + std::size_t(x - rowB.lo)]);
                        }
                    }
                    for (int y = 0; y < kH; ++y)
                        REQUIRE(std::equal(edged.depthRow(y), edged.depthRow(y) + kW * n, walked.depthRow(y)));
                }
            }
        }
    }
    // Both methods were exercised (the large triangles go to the walks under Auto as well), and
    // so was the hidden triangles' shortcut.
    CHECK(small > 1000);
    CHECK(large > 200);
    CHECK(hidden > 100);
}

TEST_CASE("MSAA: a small triangle behind every stored depth of its box lists nothing; one barely in front is found",
          "[msaa]") {
    // Stored depth 0.3 everywhere. A small triangle whose vertices are all at most 0.3 deep (larger
    // is nearer) passes no sample and is skipped before its coverage (no rows); raising its third
    // vertex to 0.31 brings the samples near that vertex in front, which the shortcut must not
    // hide: Auto lists the reference walks' runs and depths. Every ISA and sample count.
    constexpr int kW = 24, kH = 20;
    for (Isa isa : kAllIsas) {
        if (!isaAvailable(isa)) continue;
        for (int n : {2, 4, 8})
            for (DepthMode depth : {DepthMode::Test, DepthMode::TestWrite}) {
                CAPTURE(isaName(isa), n, int(depth));
                MsaaBuffer edged, walked;
                REQUIRE(edged.resize(kW, kH, n));
                REQUIRE(walked.resize(kW, kH, n));
                edged.clearRows(0, kH, 0, 0.3f);
                walked.clearRows(0, kH, 0, 0.3f);
                MsaaScratch a, b;
                TriangleSetup behind, front;
                REQUIRE(setupTriangleCulled(behind, vtx(3.2f, 2.7f, 0.29f), vtx(13.6f, 5.1f, 0.295f), vtx(6.3f, 14.4f, 0.3f),
                                            CullMode::None, 0, true, {}, true) == SetupOutcome::Ready);
                REQUIRE(setupTriangleCulled(front, vtx(3.2f, 2.7f, 0.29f), vtx(13.6f, 5.1f, 0.295f), vtx(6.3f, 14.4f, 0.31f),
                                            CullMode::None, 0, true, {}, true) == SetupOutcome::Ready);
                REQUIRE(msaaSmallTriangle(behind));
                coverTriangleSamples(behind, edged, Scissor{0, 0, kW, kH}, depth, a, MsaaCoverageMethod::Auto, isa);
                coverTriangleSamples(behind, walked, Scissor{0, 0, kW, kH}, depth, b, MsaaCoverageMethod::Reference);
                CHECK(a.rows.empty()); // skipped
                CHECK(a.runs.empty());
                CHECK_FALSE(b.rows.empty()); // the walks cover its samples, none passes
                CHECK(b.runs.empty());
                coverTriangleSamples(front, edged, Scissor{0, 0, kW, kH}, depth, a, MsaaCoverageMethod::Auto, isa);
                coverTriangleSamples(front, walked, Scissor{0, 0, kW, kH}, depth, b, MsaaCoverageMethod::Reference);
                REQUIRE(b.runs.size() > 3);
                REQUIRE(a.runs.size() == b.runs.size());
                for (std::size_t r = 0; r < a.runs.size(); ++r)
                    CHECK((a.runs[r].y == b.runs[r].y && a.runs[r].x0 == b.runs[r].x0 && a.runs[r].x1 == b.runs[r].x1));
                for (int y = 0; y < kH; ++y)
                    CHECK(std::equal(edged.depthRow(y), edged.depthRow(y) + kW * n, walked.depthRow(y)));
            }
    }
}

TEST_CASE("msaaStages: one choice per sample count and depth mode, made once per draw", "[msaa]") {
    // The stages a draw chooses carry its sample count and depth mode: every combination is its
    // own cover function; each one's depth mode shows in what it does to the stored depths (Off:
    // untouched and every covered sample passes; Test: untouched; TestWrite: the passing samples
    // hold the triangle's depth), and its write stores exactly the passing samples.
    constexpr int kW = 24, kH = 20;
    std::vector<void (*)(const TriangleSetup&, MsaaBuffer&, const Scissor&, MsaaScratch&)> covers;
    TriangleSetup t;
    REQUIRE(setupTriangleCulled(t, vtx(2.3f, 1.7f, 0.6f), vtx(21.4f, 6.2f, 0.6f), vtx(7.9f, 18.6f, 0.6f), CullMode::None, 0,
                                true, {}, true) == SetupOutcome::Ready);
    for (int n : {1, 2, 4, 8}) {
        for (DepthMode depth : {DepthMode::Off, DepthMode::Test, DepthMode::TestWrite}) {
            CAPTURE(n, int(depth));
            const MsaaStages stages = msaaStages(n, depth);
            REQUIRE(stages.samples == n);
            REQUIRE(std::find(covers.begin(), covers.end(), stages.cover) == covers.end());
            covers.push_back(stages.cover);
            MsaaBuffer target;
            REQUIRE(target.resize(kW, kH, n));
            target.clearRows(0, kH, 0u, 0.0f);
            for (int y = 10; y < kH; ++y) std::fill(target.depthRow(y), target.depthRow(y) + kW * n, 0.9f); // nearer: hides
            MsaaScratch scratch;
            stages.cover(t, target, Scissor{0, 0, kW, kH}, scratch);
            int covered = 0, passed = 0, written = 0;
            for (const MsaaScratch::Row& row : scratch.rows) {
                std::vector<Pixel> shaded(std::size_t(kW), 0u);
                for (int x = row.lo; x < row.hi; ++x) shaded[std::size_t(x)] = Pixel(1000 * row.y + x);
                std::vector<Pixel> before(target.colourRow(row.y), target.colourRow(row.y) + kW * n);
                stages.write(target.colourRow(row.y), shaded.data(), scratch.passed.data() + row.offset, row.lo, row.hi);
                for (int x = row.lo; x < row.hi; ++x) {
                    const unsigned cover = scratch.covered[row.offset + std::size_t(x - row.lo)];
                    const unsigned pass = scratch.passed[row.offset + std::size_t(x - row.lo)];
                    REQUIRE((pass & ~cover) == 0u);
                    if (depth == DepthMode::Off) REQUIRE(pass == cover);
                    for (int k = 0; k < n; ++k) {
                        const std::size_t i = std::size_t(x) * std::size_t(n) + std::size_t(k);
                        covered += cover >> k & 1u;
                        passed += pass >> k & 1u;
                        const float z = target.depthRow(row.y)[i];
                        const float stored = row.y >= 10 ? 0.9f : 0.0f;
                        if (depth == DepthMode::TestWrite && (pass >> k & 1u)) REQUIRE(z == 0.6f);
                        else REQUIRE(z == stored);
                        const Pixel c = target.colourRow(row.y)[i];
                        REQUIRE(c == ((pass >> k & 1u) ? Pixel(1000 * row.y + x) : before[i]));
                        written += (pass >> k & 1u) ? 1 : 0;
                    }
                }
            }
            CHECK(covered > 100 * n);
            if (depth == DepthMode::Off) CHECK(passed == covered);
            else CHECK((passed > 20 * n && passed < covered)); // the rows below 10 hide it
            CHECK(written == passed);
        }
    }
}
