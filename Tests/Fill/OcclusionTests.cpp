// Occlusion: the depth bound a small triangle cannot exceed, and the one-sample test that skips a
// triangle every stored depth of its box hides.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "RasterTestUtil.hpp"
#include "Raster/Fill/Occlusion.hpp"

using namespace sr;
using namespace sr::test;

TEST_CASE("nearestDepthBound: no depth the fill writes exceeds it, and it is the largest vertex depth to a few ulps",
          "[raster][occlusion]") {
    // Sampled with a fixed seed: 3000 small triangles anywhere on a 2048-pixel-wide target (far
    // from the plane's origin the double evaluation rounds most), with depth slopes from flat to
    // 1 per pixel. Each is filled alone (TestWrite over the far depth) by the scalar loop, whose
    // depths the kernels reproduce bit for bit; every written depth must be at most the bound.
    constexpr int kW = 2048, kH = 48;
    FrameBuffer fb(kW, kH);
    std::mt19937 rng(20261129);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int filled = 0;
    for (int i = 0; i < 3000; ++i) {
        const float cx = 16.0f + unit(rng) * (kW - 32), cy = 16.0f + unit(rng) * (kH - 32);
        const float reach = 1.0f + unit(rng) * 14.0f, slope = i % 3 == 0 ? 0.0f : std::pow(10.0f, -6.0f * unit(rng));
        const float base = unit(rng);
        ScreenVertex v[3];
        for (ScreenVertex& p : v) {
            p = vtx(cx + (unit(rng) * 2 - 1) * reach, cy + (unit(rng) * 2 - 1) * reach);
            p.z = std::clamp(base + (unit(rng) * 2 - 1) * slope * reach, 0.0f, 1.0f);
        }
        const std::optional<TriangleSetup> t = setupTriangle(v[0], v[1], v[2], 0);
        if (!t) continue;
        fb.clear(0, FrameBuffer::kFarDepth);
        fillTriangle<DepthMode::TestWrite, 0>(*t, fb, [](const Fragment<0>&) { return Pixel(1); });
        const float bound = nearestDepthBound(*t, t->minX, t->maxX + 1, t->firstRow, t->endRow);
        const float zMax = std::max({v[0].z, v[1].z, v[2].z});
        CAPTURE(i, v[0].x, v[0].y, v[0].z, v[1].x, v[1].y, v[1].z, v[2].x, v[2].y, v[2].z, bound);
        for (int y = t->firstRow; y < t->endRow; ++y)
            for (int x = t->minX; x <= t->maxX; ++x)
                if (fb.pixel(x, y) == 1) REQUIRE(fb.depth(x, y) <= bound);
        // Tight: within a few float steps of the largest vertex depth (the vertices are snapped
        // to the 1/256 grid, which moves the plane's values there by at most a rounding).
        REQUIRE(bound >= zMax - 1e-6f);
        REQUIRE(bound <= zMax + 4 * std::numeric_limits<float>::epsilon() * std::max(1.0f, zMax));
        ++filled;
    }
    CHECK(filled > 2500);
}

TEST_CASE("hiddenInFrame: a small triangle behind every stored depth of its box is hidden; one barely in front is not",
          "[raster][occlusion]") {
    constexpr int kW = 40, kH = 40;
    FrameBuffer fb(kW, kH);
    fb.clear(0, 0.3f);
    const Scissor all{0, 0, kW, kH};
    // Clockwise on screen (y down): a back face by the convention, the check's candidates.
    const auto behind = setupTriangle(vtx(3.2f, 2.7f, 0.29f), vtx(13.6f, 5.1f, 0.295f), vtx(6.3f, 14.4f, 0.3f), 0);
    const auto front = setupTriangle(vtx(3.2f, 2.7f, 0.29f), vtx(13.6f, 5.1f, 0.295f), vtx(6.3f, 14.4f, 0.31f), 0);
    REQUIRE((behind && front));
    CHECK(occlusionCandidate(*behind));
    CHECK(hiddenInFrame(*behind, fb, all));
    CHECK_FALSE(hiddenInFrame(*front, fb, all)); // the pixels near its third vertex pass
    {
        // What the fill does with them: `behind` writes nothing, `front` writes some pixels.
        FrameBuffer a(kW, kH);
        a.clear(0, 0.3f);
        fillTriangle<DepthMode::TestWrite, 0>(*behind, a, [](const Fragment<0>&) { return Pixel(1); });
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) REQUIRE(a.pixel(x, y) == 0);
        fillTriangle<DepthMode::TestWrite, 0>(*front, a, [](const Fragment<0>&) { return Pixel(1); });
        int written = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) written += a.pixel(x, y) == 1 ? 1 : 0;
        CHECK(written > 0);
    }
    // One stored depth of the box below the bound (here a pixel the triangle does not cover, the
    // box's corner): not hidden, the check is over the box. Inside the scissor only.
    const int cornerX = behind->minX, cornerY = behind->firstRow;
    float& corner = fb.depthRow(cornerY)[cornerX];
    corner = 0.2f;
    CHECK_FALSE(hiddenInFrame(*behind, fb, all));
    CHECK(hiddenInFrame(*behind, fb, Scissor{cornerX + 1, 0, kW, kH}));
    corner = std::numeric_limits<float>::quiet_NaN();
    CHECK_FALSE(hiddenInFrame(*behind, fb, all)); // NaN keeps the triangle
    corner = 0.3f;
    CHECK(hiddenInFrame(*behind, fb, all));
    float& last = fb.depthRow(behind->endRow - 1)[behind->maxX]; // past the first-depth shortcut
    last = std::numeric_limits<float>::quiet_NaN();
    CHECK_FALSE(hiddenInFrame(*behind, fb, all));
    last = 0.29f;
    CHECK_FALSE(hiddenInFrame(*behind, fb, all));
    last = 0.3f;
    CHECK(hiddenInFrame(*behind, fb, all));
    // Wholly outside the scissor: nothing to test, kept (the fill clips it).
    CHECK_FALSE(hiddenInFrame(*behind, fb, Scissor{20, 20, kW, kH}));
    // Counter-clockwise (front facing): not a candidate, though hidden the same way.
    const auto ccw = setupTriangle(vtx(3.2f, 2.7f, 0.29f), vtx(6.3f, 14.4f, 0.3f), vtx(13.6f, 5.1f, 0.295f), 0);
    REQUIRE(ccw);
    CHECK_FALSE(occlusionCandidate(*ccw));
    CHECK(hiddenInFrame(*ccw, fb, all));
    // More than 32 pixels across: not small, never tested.
    const auto large = setupTriangle(vtx(1.0f, 1.0f, 0.1f), vtx(38.0f, 2.0f, 0.1f), vtx(2.0f, 38.0f, 0.1f), 0);
    REQUIRE(large);
    CHECK_FALSE(hiddenInFrame(*large, fb, all));
}
