// The fast paths against their references: per-vertex clip codes vs classify, cull-in-setup vs isCulled, binning's screen
// from snapped vertices vs the setup's, the inline normalize vs the robust one (the SIMD kernels: KernelIdentityTests.cpp).
#include "TestFramework.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "Math/Vec.hpp"
#include "Raster/Fill/ScanlineFill.hpp"
#include "Raster/Geometry/Clipper.hpp"
#include "Raster/Geometry/Cull.hpp"
#include "Raster/Geometry/Viewport.hpp"
#include "Raster/Setup/TriangleSetup.hpp"

using namespace sr;

namespace {

// Random clip-space positions: mostly in and around the view volume, some behind the eye,
// some far outside the guard band, some exactly on planes, a few non-finite.
Vec4 randomPosition(std::mt19937& rng) {
    std::uniform_int_distribution<int> kind(0, 19);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f), w(0.01f, 5.0f), big(-1e6f, 1e6f);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float ww = w(rng);
    switch (kind(rng)) {
    case 0: return {big(rng), big(rng), u(rng), w(rng)};              // past the guard band
    case 1: return {u(rng), u(rng), u(rng), -ww};                     // behind the eye
    case 2: return {ww, -ww, ww, ww};                                 // on x = w, y = -w, z = w
    case 3: return {u(rng), u(rng), 0.0f, 0.0f};                      // w = 0
    case 4: return {u(rng), nan, u(rng), ww};                         // NaN
    case 5: return {inf, u(rng), u(rng), ww};                         // Inf
    case 6: return {u(rng) * ww, u(rng) * ww, -0.1f * ww, ww};        // past the far plane
    case 7: return {u(rng) * ww, u(rng) * ww, 1.0f * ww, ww};         // on the near plane
    case 8: return {u(rng) * 1e-13f, u(rng) * 1e-13f, 0.0f, 1e-13f};  // below kClipMinW
    default: return {u(rng) * ww, u(rng) * ww, std::fabs(u(rng)) * 0.7f * ww, ww};
    }
}

} // namespace

TEST_CASE("per-vertex clip codes classify exactly like the per-triangle classify", "[threads][clip]") {
    std::mt19937 rng(42);
    const int sizes[][2] = {{800, 600}, {1920, 1080}, {1, 1}, {0, 600}, {800, 0}, {8192, 17}};
    for (const auto& size : sizes) {
        for (bool clipFar : {false, true}) {
            ClipParams params;
            params.viewportWidth = size[0];
            params.viewportHeight = size[1];
            params.clipFar = clipFar;
            const Clipper clipper(params);
            int counts[3] = {};
            for (int i = 0; i < 20000; ++i) {
                ClipVertex a, b, c;
                a.position = randomPosition(rng);
                b.position = randomPosition(rng);
                c.position = randomPosition(rng);
                const ClipClass expected = clipper.classify(a, b, c);
                const ClipClass actual = clipper.classifyCodes(clipper.vertexCode(a.position), clipper.vertexCode(b.position),
                                                               clipper.vertexCode(c.position));
                if (expected != actual) {
                    INFO(size[0] << "x" << size[1] << " far " << clipFar << " triangle " << i);
                    REQUIRE(int(expected) == int(actual));
                }
                ++counts[int(expected)];
                // An accepted triangle's vertices lie inside setup's guard band: binning screens
                // it from their snapped positions, which exist (snapVertex: not kUnsnapped).
                if (expected == ClipClass::Accept && size[0] > 0 && size[1] > 0)
                    for (const ClipVertex* cv : {&a, &b, &c})
                        REQUIRE(snapVertex(toScreen(*cv, size[0], size[1], 0)).x != kUnsnapped);
                // The non-finite bit is exactly "some component is NaN or Inf".
                CHECK(((clipper.vertexCode(a.position) & kCodeNonFinite) != 0) == !isFinite(a.position));
            }
            if (size[0] > 0 && size[1] > 0) {
                CHECK(counts[int(ClipClass::Accept)] > 100);
                CHECK(counts[int(ClipClass::Clip)] > 100);
            }
            CHECK(counts[int(ClipClass::Reject)] > 100);
        }
    }
}

TEST_CASE("cull in setup decides exactly like isCulled and builds the same record", "[threads][cull]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-40.0f, 840.0f), small(-2.0f, 2.0f), attr(0.0f, 1.0f);
    std::uniform_int_distribution<int> kind(0, 9);
    auto vertex = [&](float x, float y) {
        ScreenVertex v;
        v.x = x;
        v.y = y;
        v.z = attr(rng);
        v.invW = 0.5f + attr(rng);
        for (int k = 0; k < 4; ++k) v.varyings[std::size_t(k)] = attr(rng);
        return v;
    };
    int outcomes[3] = {};
    for (int i = 0; i < 60000; ++i) {
        ScreenVertex v[3];
        const int k = kind(rng);
        const float bx = coord(rng), by = coord(rng);
        for (auto& p : v) {
            if (k < 4) p = vertex(bx + small(rng), by + small(rng));               // tiny: often empty or degenerate
            else if (k == 4) p = vertex(std::round(bx), std::round(by) + small(rng)); // near-collinear
            else p = vertex(coord(rng), coord(rng));
        }
        if (k == 5) v[2] = v[1];                                                 // coincident
        if (k == 6) v[2].x = v[0].x + (v[1].x - v[0].x) * 2.0f, v[2].y = v[0].y + (v[1].y - v[0].y) * 2.0f;
        for (CullMode mode : {CullMode::None, CullMode::CW, CullMode::CCW}) {
            for (bool persp : {true, false}) {
                TriangleSetup record;
                const SetupOutcome outcome = setupTriangleCulled(record, v[0], v[1], v[2], mode, 4, persp);
                ++outcomes[int(outcome)];
                const bool culled = isCulled(mode, v[0], v[1], v[2]);
                REQUIRE((outcome == SetupOutcome::Culled) == culled);
                if (culled) continue;
                const auto reference = setupTriangle(v[0], v[1], v[2], 4, persp);
                REQUIRE(reference.has_value() == (outcome == SetupOutcome::Ready));
                if (!reference) continue;
                CHECK(record.doubleArea == reference->doubleArea);
                CHECK(record.firstRow == reference->firstRow);
                CHECK(record.midRow == reference->midRow);
                CHECK(record.endRow == reference->endRow);
                CHECK(record.minX == reference->minX);
                CHECK(record.maxX == reference->maxX);
                CHECK(record.longEdgeOnLeft == reference->longEdgeOnLeft);
                CHECK(std::memcmp(&record.longEdge, &reference->longEdge, sizeof(FixedEdge)) == 0);
                CHECK(std::memcmp(record.ddx, reference->ddx, sizeof record.ddx) == 0);
                CHECK(std::memcmp(record.ddy, reference->ddy, sizeof record.ddy) == 0);
                CHECK(std::memcmp(record.value, reference->value, sizeof record.value) == 0);
            }
        }
    }
    CHECK(outcomes[int(SetupOutcome::Ready)] > 1000);
    CHECK(outcomes[int(SetupOutcome::Culled)] > 1000);
    CHECK(outcomes[int(SetupOutcome::Empty)] > 100);
}

TEST_CASE("binning's screen from once-snapped vertices decides exactly like the triangle's setup", "[threads][cull]") {
    std::mt19937 rng(11); // sampled: 40,000 triangles x 3 cull modes x 2 row rules, fixed seed
    std::uniform_real_distribution<float> coord(-40.0f, 840.0f), small(-2.0f, 2.0f);
    std::uniform_int_distribution<int> kind(0, 11);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    int outcomes[3] = {}, unsnapped = 0;
    for (int i = 0; i < 40000; ++i) {
        ScreenVertex v[3];
        const int k = kind(rng);
        const float bx = coord(rng), by = coord(rng);
        for (auto& p : v) {
            if (k < 4) p.x = bx + small(rng), p.y = by + small(rng); // tiny: often empty or rowless
            else p.x = coord(rng), p.y = coord(rng);
        }
        if (k == 4) v[1] = v[0];                         // coincident
        if (k == 5) v[2].x = kGuardBand * 1.5f;          // outside the guard band
        if (k == 6) v[0].y = nan;
        if (k == 7) v[1].x = -kGuardBand, v[1].y = kGuardBand; // exactly on its corner: snapped
        SnappedVertex p[3];
        for (int j = 0; j < 3; ++j) {
            p[j] = snapVertex(v[j]);
            REQUIRE((p[j].x == kUnsnapped) == !inGuardBand(v[j]));
            if (p[j].x != kUnsnapped) {
                CHECK(p[j].x == snapToFixed(v[j].x));
                CHECK(p[j].y == snapToFixed(v[j].y));
            }
        }
        if (p[0].x == kUnsnapped || p[1].x == kUnsnapped || p[2].x == kUnsnapped) {
            ++unsnapped; // never an accepted triangle's (the clip-code test above): never binned
            continue;
        }
        for (CullMode mode : {CullMode::None, CullMode::CW, CullMode::CCW}) {
            for (bool keepRowless : {false, true}) {
                Fixed minY = -1, maxY = -1;
                const SetupOutcome outcome = screenSnapped(p[0], p[1], p[2], mode, keepRowless, minY, maxY);
                TriangleSetup record;
                const SetupOutcome setup = setupTriangleCulled(record, v[0], v[1], v[2], mode, 0, true, {}, keepRowless);
                ++outcomes[int(outcome)];
                REQUIRE(outcome == setup);
                REQUIRE((outcome == SetupOutcome::Culled) == isCulled(mode, v[0], v[1], v[2]));
                if (outcome != SetupOutcome::Ready) continue;
                CHECK(minY == record.longEdge.y0); // the long edge runs from the top vertex to the bottom one
                CHECK(maxY == record.longEdge.y0 + record.longEdge.dy);
            }
        }
    }
    CHECK(outcomes[int(SetupOutcome::Ready)] > 10000);
    CHECK(outcomes[int(SetupOutcome::Culled)] > 10000);
    CHECK(outcomes[int(SetupOutcome::Empty)] > 100);
    CHECK(unsnapped > 5000);
}

TEST_CASE("normalize's inline fast path is bit-identical to the robust path", "[threads][math]") {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_int_distribution<int> e(-60, 60);
    for (int i = 0; i < 200000; ++i) {
        const float s = std::ldexp(1.0f, e(rng));
        const Vec3 v{u(rng) * s, u(rng) * s, (i % 5 == 0) ? 0.0f : u(rng) * s};
        const Vec3 a = normalize(v), b = normalizeRobust(v);
        REQUIRE(std::memcmp(&a, &b, sizeof a) == 0);
    }
    const float inf = std::numeric_limits<float>::infinity();
    for (const Vec3 v : {Vec3{0, 0, 0}, Vec3{inf, 1, 0}, Vec3{3e38f, 3e38f, 3e38f}, Vec3{1e-45f, 0, 0}}) {
        const Vec3 a = normalize(v), b = normalizeRobust(v);
        CHECK(std::memcmp(&a, &b, sizeof a) == 0);
    }
}
