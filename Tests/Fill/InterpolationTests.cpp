// Interpolation: perspective-correct varyings match an analytic world-space value; affine does not.
#include "TestFramework.hpp"

#include <cmath>
#include <random>
#include <vector>

#include "RasterTestUtil.hpp"
#include "ReferenceRasterizer.hpp"

using namespace sr;
using namespace sr::test;

namespace {

constexpr int kW = 64, kH = 64;

// The tiny projection of this test: camera at the origin looking down -Z (identity view), 90
// degree vertical field of view (f = 1), square viewport, reversed-Z with an infinite far plane:
// clip = (x, y, near, -z), so z_ndc = near / d for a point at distance d = -z.
constexpr double kNear = 0.1;

struct P3 {
    double x, y, z;
};

// Screen pixel (sx, sy) and distance d -> view-space point (inverse of the projection above).
P3 unproject(double sx, double sy, double d) {
    const double ndcX = 2.0 * sx / kW - 1.0, ndcY = 1.0 - 2.0 * sy / kH;
    return {ndcX * d, ndcY * d, -d};
}

// The attribute under test: linear in world space and >= 10 + 0.55 d > 0 everywhere in view
// (|x|, |y| <= 2.25 d for the screens used here), so a relative error is meaningful; it grows
// with distance, so screen-linear interpolation visibly fails on steep triangles.
double attribute(const P3& p) { return 10.0 + 0.1 * p.x - 0.1 * p.y - p.z; }

struct Scene {
    ScreenVertex v[3];
    P3 world[3];
};

// A triangle whose screen vertices lie exactly on the 1/256 grid (so snapping changes nothing)
// at the given distances: the world triangle is then exactly the one the fill sees.
Scene makeScene(const double sx[3], const double sy[3], const double d[3]) {
    Scene s;
    for (int i = 0; i < 3; ++i) {
        s.world[i] = unproject(sx[i], sy[i], d[i]);
        ScreenVertex& v = s.v[i];
        v = vtx(float(sx[i]), float(sy[i]), float(kNear / d[i]), float(1.0 / d[i]));
        v.varyings[0] = float(attribute(s.world[i]));
        v.varyings[1] = float(s.world[i].z);
    }
    return s;
}

// Analytic attribute at a pixel centre: intersect the eye ray with the triangle's plane.
double analytic(const Scene& s, double sx, double sy, double* depthOut) {
    const P3 dir = unproject(sx, sy, 1.0); // point at distance 1 along the pixel's ray
    const P3 a = s.world[0], b = s.world[1], c = s.world[2];
    const P3 u{b.x - a.x, b.y - a.y, b.z - a.z}, v{c.x - a.x, c.y - a.y, c.z - a.z};
    const P3 n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    const double t = (n.x * a.x + n.y * a.y + n.z * a.z) / (n.x * dir.x + n.y * dir.y + n.z * dir.z);
    *depthOut = kNear / t;
    return attribute({dir.x * t, dir.y * t, dir.z * t});
}

struct Errors {
    double perspective = 0.0, affine = 0.0, depth = 0.0;
    int pixels = 0;
};

Errors measure(const Scene& s) {
    Errors e;
    FrameBuffer fb(kW, kH);
    fb.clear(0);
    const auto t = setupTriangle(s.v[0], s.v[1], s.v[2], 2);
    REQUIRE(t);
    fillTriangle<DepthMode::Off, 2>(*t, fb, [&](const Fragment<2>& f) {
        double z = 0.0;
        const double want = analytic(s, f.x + 0.5, f.y + 0.5, &z);
        e.perspective = std::max(e.perspective, std::fabs(f.varyings[0] - want) / std::fabs(want));
        e.depth = std::max(e.depth, std::fabs(f.z - z) / z);
        ++e.pixels;
        return Pixel(0);
    });
    // Affine (screen-linear) interpolation: the same fill with every 1/w set to 1.
    ScreenVertex flat[3] = {s.v[0], s.v[1], s.v[2]};
    for (auto& v : flat) v.invW = 1.0f;
    const auto ta = setupTriangle(flat[0], flat[1], flat[2], 1);
    REQUIRE(ta);
    fillTriangle<DepthMode::Off, 1>(*ta, fb, [&](const Fragment<1>& f) {
        double z = 0.0;
        const double want = analytic(s, f.x + 0.5, f.y + 0.5, &z);
        e.affine = std::max(e.affine, std::fabs(f.varyings[0] - want) / std::fabs(want));
        return Pixel(0);
    });
    return e;
}

} // namespace

TEST_CASE("perspective-correct varyings match the analytic value on a steep floor; affine fails", "[raster][interpolation]") {
    // A floor-like triangle from 1 to 400 units away (near/far ratio 400 across the triangle).
    const double sx[3] = {2.5, 61.25, 31.0}, sy[3] = {62.0, 60.5, 6.125}, d[3] = {1.0, 1.5, 400.0};
    const Errors e = measure(makeScene(sx, sy, d));
    INFO("perspective " << e.perspective << " affine " << e.affine << " depth " << e.depth);
    CHECK(e.pixels > 1000);
    CHECK(e.perspective < 1e-4);
    CHECK(e.depth < 1e-4);
    CHECK(e.affine > 1e-4);  // the bound can fail...
    CHECK(e.affine > 0.1);   // ...and screen-linear interpolation misses it by far
}

TEST_CASE("perspective-correct varyings on random tilted triangles", "[raster][interpolation]") {
    std::mt19937 rng(31337);
    double worst = 0.0, worstAffine = 1e30;
    for (int i = 0; i < 200; ++i) {
        double sx[3], sy[3], d[3];
        for (int k = 0; k < 3; ++k) {
            sx[k] = std::floor(uniform(rng, -40.0f, 104.0f) * 256.0) / 256.0; // on the grid
            sy[k] = std::floor(uniform(rng, -40.0f, 104.0f) * 256.0) / 256.0;
            d[k] = std::exp2(uniform(rng, 0.0f, 10.0f)); // 1 .. 1024
        }
        const Scene s = makeScene(sx, sy, d);
        if (!setupTriangle(s.v[0], s.v[1], s.v[2], 2)) continue;
        const Errors e = measure(s);
        if (e.pixels < 50) continue;
        worst = std::max(worst, e.perspective);
        if (std::max({d[0], d[1], d[2]}) > 20 * std::min({d[0], d[1], d[2]})) worstAffine = std::min(worstAffine, e.affine);
    }
    INFO("worst perspective error " << worst << ", smallest affine error on steep ones " << worstAffine);
    CHECK(worst < 1e-4);
    CHECK(worstAffine > 1e-4);
}

TEST_CASE("fill varyings agree with the reference rasterizer's double-precision barycentrics", "[raster][interpolation]") {
    std::mt19937 rng(4);
    double worst = 0.0;
    int pixels = 0, positionMismatches = 0;
    for (int i = 0; i < 300; ++i) {
        ScreenVertex v[3];
        for (auto& x : v) {
            x = vtx(uniform(rng, -30, 94), uniform(rng, -30, 94), uniform(rng, 0, 1), uniform(rng, 0.01f, 1.0f));
            for (int k = 0; k < 4; ++k) x.varyings[std::size_t(k)] = uniform(rng, 1.0f, 2.0f);
        }
        const auto t = setupTriangle(v[0], v[1], v[2], 4);
        if (!t) continue;
        std::vector<Fragment<4>> got;
        FrameBuffer fb(kW, kH);
        fillTriangle<DepthMode::Off, 4>(*t, fb, [&](const Fragment<4>& f) { got.push_back(f); return Pixel(0); });
        const std::vector<ref::Fragment> want = ref::rasterize(v[0], v[1], v[2], 4, kW, kH);
        REQUIRE(got.size() == want.size());
        for (std::size_t p = 0; p < got.size(); ++p) {
            positionMismatches += (got[p].x != want[p].x || got[p].y != want[p].y) ? 1 : 0;
            for (int k = 0; k < 4; ++k) {
                const double w = want[p].varyings[std::size_t(k)];
                worst = std::max(worst, std::fabs(got[p].varyings[std::size_t(k)] - w) / w);
            }
        }
        pixels += int(got.size());
    }
    CHECK(pixels > 10000);
    CHECK(positionMismatches == 0);
    // float stepping along a span with 1/w from 1 down to 0.01 costs ~range/value * 2^-24 in
    // each of v/w and 1/w (measured ~2e-6); the double reference has none of it.
    INFO("worst relative error " << worst);
    CHECK(worst < 1e-5);
}
