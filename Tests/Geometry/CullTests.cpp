// Tests of back-face culling: the mode truth table, the snapped grid, parsing, near-plane splits.
#include "TestFramework.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "PipelineTestUtil.hpp"
#include "Raster/Geometry/Clipper.hpp"
#include "Raster/Geometry/Cull.hpp"
#include "Raster/Geometry/Viewport.hpp"
#include "Raster/Setup/FixedPoint.hpp"

using namespace sr;
using namespace srtest;

namespace {

ScreenVertex sv(float x, float y) {
    ScreenVertex v;
    v.x = x;
    v.y = y;
    return v;
}

} // namespace

TEST_CASE("cull modes: truth table for both windings", "[pipeline][cull]") {
    // y down: (0,0) -> (0,10) -> (10,0) goes down the left side then up-right: counter-clockwise
    // as seen on screen, negative signed area.
    const ScreenVertex a = sv(0, 0), b = sv(0, 10), c = sv(10, 0);
    REQUIRE(snappedArea2(a, b, c) < 0);
    CHECK(screenWinding(a, b, c) == Winding::CCW);
    CHECK(screenWinding(a, c, b) == Winding::CW);
    CHECK(snappedArea2(a, b, c) == -100 * kSubPixelScale * kSubPixelScale);

    CHECK_FALSE(isCulled(CullMode::None, a, b, c));
    CHECK_FALSE(isCulled(CullMode::None, a, c, b));
    CHECK_FALSE(isCulled(CullMode::CW, a, b, c));
    CHECK(isCulled(CullMode::CW, a, c, b));
    CHECK(isCulled(CullMode::CCW, a, b, c));
    CHECK_FALSE(isCulled(CullMode::CCW, a, c, b));

    // Cyclic rotations do not change the winding.
    CHECK(screenWinding(b, c, a) == Winding::CCW);
    CHECK(screenWinding(c, a, b) == Winding::CCW);
}

TEST_CASE("a CCW triangle in view space projects to a front face", "[pipeline][cull]") {
    // Counter-clockwise seen from the eye looking down -Z (x right, y up).
    const ClipVertex v0 = makeVertex(projectInfinite(-1, -1, -5)), v1 = makeVertex(projectInfinite(1, -1, -5)),
                     v2 = makeVertex(projectInfinite(0, 1, -5));
    const ScreenVertex s0 = toScreen(v0, 640, 480, 0), s1 = toScreen(v1, 640, 480, 0), s2 = toScreen(v2, 640, 480, 0);
    CHECK(screenWinding(s0, s1, s2) == Winding::CCW);
    CHECK_FALSE(isCulled(CullMode::CW, s0, s1, s2)); // back-face culling keeps front faces
}

TEST_CASE("zero-area triangles on the snapped grid are culled in every mode", "[pipeline][cull]") {
    const ScreenVertex a = sv(1, 1), b = sv(5, 5), c = sv(9, 9); // collinear
    const ScreenVertex t0 = sv(10.0f, 10.0f), t1 = sv(10.001f, 10.0f), t2 = sv(10.0f, 10.001f); // < 1/512 px
    const ScreenVertex p = sv(3, 3);
    for (CullMode m : {CullMode::None, CullMode::CW, CullMode::CCW}) {
        CHECK(isCulled(m, a, b, c));
        CHECK(isCulled(m, t0, t1, t2));
        CHECK(isCulled(m, p, p, p));
    }
    CHECK(screenWinding(t0, t1, t2) == Winding::Degenerate);
    // ... yet a tiny triangle that survives snapping keeps its winding.
    const ScreenVertex u0 = sv(10.0f, 10.0f), u1 = sv(10.0f, 10.0f + 1.0f / 256), u2 = sv(10.0f + 1.0f / 256, 10.0f);
    CHECK(screenWinding(u0, u1, u2) == Winding::CCW);
    CHECK(snappedArea2(u0, u1, u2) == -1);
}

TEST_CASE("the cull area uses the rasterizer's snapping", "[pipeline][cull]") {
    Rng rng(99);
    for (int i = 0; i < 2000; ++i) {
        ScreenVertex v[3];
        for (auto& s : v) {
            s.x = float(rng.uniform(-kGuardBand, kGuardBand));
            s.y = float(rng.uniform(-kGuardBand, kGuardBand));
            if (i % 2) { // land some coordinates on exact half-steps (rounding ties)
                s.x = std::round(s.x * 512.0f) / 512.0f;
                s.y = std::round(s.y * 512.0f) / 512.0f;
            }
        }
        const std::int64_t X0 = snapToFixed(v[0].x), Y0 = snapToFixed(v[0].y), X1 = snapToFixed(v[1].x),
                           Y1 = snapToFixed(v[1].y), X2 = snapToFixed(v[2].x), Y2 = snapToFixed(v[2].y);
        CHECK(snappedArea2(v[0], v[1], v[2]) == (X1 - X0) * (Y2 - Y0) - (X2 - X0) * (Y1 - Y0));
    }
}

TEST_CASE("non-finite or out-of-band screen positions do not break culling", "[pipeline][cull]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(isCulled(CullMode::None, sv(nan, 0), sv(1, 0), sv(0, 1)));
    CHECK(snappedArea2(sv(0, 0), sv(1e30f, 0), sv(0, 1e30f)) == 1);
    CHECK(screenWinding(sv(0, 0), sv(0, 1e30f), sv(1e30f, 0)) == Winding::CCW);
}

TEST_CASE("cull mode names parse and print", "[pipeline][cull]") {
    for (CullMode m : {CullMode::None, CullMode::CW, CullMode::CCW}) {
        const auto parsed = parseCullMode(cullModeName(m));
        REQUIRE(parsed.has_value());
        CHECK(*parsed == m);
    }
    CHECK(std::string(cullModeName(CullMode::CCW)) == "ccw");
    CHECK(parseCullMode("CW") == CullMode::CW);
    CHECK(parseCullMode("None") == CullMode::None);
    CHECK_FALSE(parseCullMode("").has_value());
    CHECK_FALSE(parseCullMode("back").has_value());
    CHECK_FALSE(parseCullMode("cw ").has_value());
    CHECK_FALSE(parseCullMode("ccww").has_value());
}

TEST_CASE("every sub-triangle of a near-split triangle gets the same cull decision", "[pipeline][cull]") {
    Rng rng(4242);
    const ClipParams p{640, 480, false, 0};
    int split = 0;
    for (int iter = 0; iter < 5000; ++iter) {
        ClipVertex v[3];
        for (auto& c : v)
            c = makeVertex(projectInfinite(float(rng.uniform(-10, 10)), float(rng.uniform(-10, 10)),
                                           float(rng.uniform(-8, 3))));
        ClippedPolygon poly;
        if (clipTriangle(v[0], v[1], v[2], p, poly) == 0 || poly.triangleCount() < 2)
            continue;
        ++split;
        const double det = homogeneousDet(v[0].position, v[1].position, v[2].position);
        const Winding expected = det > 0 ? Winding::CCW : Winding::CW;
        for (int t = 0; t < poly.triangleCount(); ++t) {
            const auto idx = poly.triangle(t);
            const ScreenVertex s0 = toScreen(poly.vertices[std::size_t(idx[0])], 640, 480, 0);
            const ScreenVertex s1 = toScreen(poly.vertices[std::size_t(idx[1])], 640, 480, 0);
            const ScreenVertex s2 = toScreen(poly.vertices[std::size_t(idx[2])], 640, 480, 0);
            const Winding w = screenWinding(s0, s1, s2);
            if (w == Winding::Degenerate)
                continue; // a sliver that covers no sample: dropped in every mode
            INFO("iteration " << iter << ", sub-triangle " << t);
            CHECK(w == expected);
            for (CullMode m : {CullMode::None, CullMode::CW, CullMode::CCW}) {
                const bool culledExpected = (m == CullMode::CW && expected == Winding::CW) ||
                                            (m == CullMode::CCW && expected == Winding::CCW);
                CHECK(isCulled(m, s0, s1, s2) == culledExpected);
            }
        }
    }
    CHECK(split > 500);
}
