// Tests of the homogeneous clipper and the divide/viewport: near plane, w <= 0, guard band, NaN.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "PipelineTestUtil.hpp"
#include "Raster/Geometry/Clipper.hpp"
#include "Raster/Geometry/Viewport.hpp"
#include "Raster/Setup/RasterLimits.hpp"

using namespace sr;
using namespace srtest;

namespace {

constexpr int kW = 640;
constexpr int kH = 480;

ClipParams params(int varyings = 0, bool clipFar = false, int W = kW, int H = kH) {
    ClipParams p;
    p.viewportWidth = W;
    p.viewportHeight = H;
    p.clipFar = clipFar;
    p.varyingCount = varyings;
    return p;
}

// Every output vertex: finite, w > 0 (>= kClipMinW), in front of the near plane, inside the
// guard band once on screen.
void checkInvariants(const ClippedPolygon& poly, const ClipParams& p) {
    REQUIRE(poly.count >= 3);
    REQUIRE(poly.count <= kMaxClipVertices);
    for (int i = 0; i < poly.count; ++i) {
        const Vec4 q = poly.vertices[std::size_t(i)].position;
        INFO("vertex " << i << ": " << q.x << " " << q.y << " " << q.z << " " << q.w);
        REQUIRE(isFinite(q));
        CHECK(q.w >= kClipMinW);
        CHECK(q.w > 0.0f);
        CHECK(q.z <= q.w);
        if (p.clipFar)
            CHECK(q.z >= 0.0f);
        const ScreenVertex s = toScreen(poly.vertices[std::size_t(i)], p.viewportWidth, p.viewportHeight, 0);
        REQUIRE(std::isfinite(s.x));
        REQUIRE(std::isfinite(s.y));
        REQUIRE(std::isfinite(s.invW));
        CHECK(std::fabs(s.x) <= kGuardBand);
        CHECK(std::fabs(s.y) <= kGuardBand);
        CHECK(std::fabs(s.x) <= kClipGuardBand + 0.01f);
        CHECK(std::fabs(s.y) <= kClipGuardBand + 0.01f);
        CHECK(s.z <= 1.0f);
    }
}

// The winding every fan triangle must have: the orientation of the original triangle in the
// projective plane (screen area sign = -sign(det(x, y, w)) once every w > 0).
void checkWinding(const ClippedPolygon& poly, const ClipVertex& a, const ClipVertex& b, const ClipVertex& c,
                  const ClipParams& p) {
    const double det = homogeneousDet(a.position, b.position, c.position);
    REQUIRE(det != 0.0);
    for (int t = 0; t < poly.triangleCount(); ++t) {
        const auto idx = poly.triangle(t);
        const ScreenVertex s0 = toScreen(poly.vertices[std::size_t(idx[0])], p.viewportWidth, p.viewportHeight, 0);
        const ScreenVertex s1 = toScreen(poly.vertices[std::size_t(idx[1])], p.viewportWidth, p.viewportHeight, 0);
        const ScreenVertex s2 = toScreen(poly.vertices[std::size_t(idx[2])], p.viewportWidth, p.viewportHeight, 0);
        const double area = screenArea2(s0, s1, s2);
        if (std::fabs(area) < 1e-3)
            continue; // a sliver: its sign is at the mercy of rounding (and it covers nothing)
        INFO("triangle " << t << " area " << area << " det " << det);
        CHECK((area < 0.0) == (det > 0.0));
    }
}

// Varyings linear in clip space: f(p) = 2x - 3y + 0.5z + 7w, x + w, z - y/4.
void setLinearVaryings(ClipVertex& v) {
    const Vec4 p = v.position;
    v.varyings[0] = 2.0f * p.x - 3.0f * p.y + 0.5f * p.z + 7.0f * p.w;
    v.varyings[1] = p.x + p.w;
    v.varyings[2] = p.z - 0.25f * p.y;
}
struct VaryingScale {
    double s[3] = {0, 0, 0};
};
VaryingScale linearScale(const Vec4& p) {
    const double x = std::fabs(p.x), y = std::fabs(p.y), z = std::fabs(p.z), w = std::fabs(p.w);
    return {{2 * x + 3 * y + 0.5 * z + 7 * w, x + w, z + 0.25 * y}};
}
// The new vertex's varyings are the linear function of its own position, to within float
// rounding of the inputs: the input varyings were rounded at the inputs' magnitudes, so the
// tolerance scales with the largest input (`inputs` = the original triangle).
void checkLinearVaryings(const ClipVertex& v, const ClipVertex* inputs = nullptr) {
    const double x = v.position.x, y = v.position.y, z = v.position.z, w = v.position.w;
    const double expect[3] = {2 * x - 3 * y + 0.5 * z + 7 * w, x + w, z - 0.25 * y};
    VaryingScale scale = linearScale(v.position);
    if (inputs)
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i)
                scale.s[i] = std::max(scale.s[i], linearScale(inputs[k].position).s[i]);
    for (int i = 0; i < 3; ++i) {
        INFO("varying " << i);
        CHECK(std::fabs(double(v.varyings[std::size_t(i)]) - expect[i]) <= 2e-6 * scale.s[i] + 1e-6);
    }
}

bool sameBits(const ClipVertex& a, const ClipVertex& b) {
    return a.position.x == b.position.x && a.position.y == b.position.y && a.position.z == b.position.z &&
           a.position.w == b.position.w;
}

ClipVertex viewVertex(float x, float y, float z) {
    ClipVertex v = makeVertex(projectInfinite(x, y, z));
    setLinearVaryings(v);
    return v;
}

} // namespace

TEST_CASE("a triangle inside the guard band is trivially accepted and copied through", "[pipeline][clip]") {
    Clipper clipper(params(3));
    const ClipVertex a = viewVertex(-1, -1, -5), b = viewVertex(1, -1, -5), c = viewVertex(0, 1, -5);
    CHECK(clipper.classify(a, b, c) == ClipClass::Accept);
    ClippedPolygon poly;
    REQUIRE(clipper.clip(a, b, c, poly) == 3);
    CHECK(sameBits(poly.vertices[0], a));
    CHECK(sameBits(poly.vertices[1], b));
    CHECK(sameBits(poly.vertices[2], c));
    CHECK(poly.vertices[2].varyings == c.varyings);
    CHECK(clipper.stats().trivialAccepted == 1);
    CHECK(clipper.stats().clipped == 0);

    // Partly off screen but inside the guard band: still no clipping (the scissor handles it).
    const ClipVertex d = fromScreen(-3000, 100, kW, kH), e = fromScreen(5000, 200, kW, kH),
                     f = fromScreen(300, 9000, kW, kH);
    CHECK(clipper.classify(d, e, f) == ClipClass::Accept);
}

TEST_CASE("0, 1, 2 and 3 vertices behind the near plane", "[pipeline][clip]") {
    struct Case {
        float z[3];
        int triangles;
    };
    // View-space z: negative is in front of the eye (near = 0.1), positive behind it.
    const Case cases[] = {{{-5, -5, -5}, 1}, {{-5, -5, 3}, 2}, {{-5, 2, 3}, 1}, {{1, 2, 3}, 0},
                          {{-5, 3, -5}, 2}, {{3, -5, 2}, 1}};
    for (const Case& k : cases) {
        for (int order = 0; order < 2; ++order) { // both windings
            INFO("z = " << k.z[0] << " " << k.z[1] << " " << k.z[2] << ", order " << order);
            ClipVertex v[3] = {viewVertex(-1, -1, k.z[0]), viewVertex(1, -1, k.z[1]), viewVertex(0, 1, k.z[2])};
            if (order == 1)
                std::swap(v[1], v[2]);
            const ClipParams p = params(3);
            ClippedPolygon poly;
            const int n = clipTriangle(v[0], v[1], v[2], p, poly);
            CHECK(poly.triangleCount() == k.triangles);
            if (k.triangles == 0) {
                CHECK(n == 0);
                continue;
            }
            checkInvariants(poly, p);
            checkWinding(poly, v[0], v[1], v[2], p);
            for (int i = 0; i < poly.count; ++i) {
                const ClipVertex& q = poly.vertices[std::size_t(i)];
                checkLinearVaryings(q);
                const bool original = sameBits(q, v[0]) || sameBits(q, v[1]) || sameBits(q, v[2]);
                if (!original)
                    CHECK(q.position.z == q.position.w); // new vertices lie exactly on the near plane
            }
        }
    }
}

TEST_CASE("vertices at w = 0, w < 0 and tiny w never reach the divide", "[pipeline][clip]") {
    const ClipParams p = params(3);
    const float ws[] = {0.0f, -0.0f, 1e-9f, -1e-9f, -2.0f, 1e-30f, std::numeric_limits<float>::denorm_min()};
    const float xs[] = {0.0f, 0.3f, -5.0f, 40.0f};
    for (float w : ws) {
        for (float x : xs) {
            INFO("w = " << w << ", x = " << x);
            // A projected vertex (z = near) at this w, plus two ordinary vertices in front.
            ClipVertex a = makeVertex({x, 0.2f, 0.1f, w});
            setLinearVaryings(a);
            const ClipVertex b = viewVertex(-1, -1, -5), c = viewVertex(1, -1, -4);
            ClippedPolygon poly;
            const int n = clipTriangle(a, b, c, p, poly);
            REQUIRE(n >= 3);
            checkInvariants(poly, p);
            if (w > 0.0f || x != 0.0f)
                checkWinding(poly, a, b, c, p);
            for (int i = 0; i < poly.count; ++i)
                checkLinearVaryings(poly.vertices[std::size_t(i)]);

            // Hand-made clip coordinates that are "in front of the near plane" (z <= w) with
            // w <= 0: only the w > 0 plane stops them.
            ClipVertex d = makeVertex({x, 0.2f, w - 1.0f, w});
            setLinearVaryings(d);
            if (clipTriangle(d, b, c, p, poly) > 0) {
                checkInvariants(poly, p);
                for (int i = 0; i < poly.count; ++i)
                    checkLinearVaryings(poly.vertices[std::size_t(i)]);
            }
        }
    }
}

TEST_CASE("an edge shared by two triangles is clipped bit-identically in both", "[pipeline][clip]") {
    Rng rng(12345);
    const ClipParams p = params(3);
    int sharedCuts = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        auto rnd = [&] {
            return viewVertex(float(rng.uniform(-30, 30)), float(rng.uniform(-30, 30)), float(rng.uniform(-10, 4)));
        };
        const ClipVertex A = rnd(), B = rnd(), C = rnd(), D = rnd();
        ClippedPolygon p1, p2;
        clipTriangle(A, B, C, p, p1);
        // The neighbour lists the edge reversed (a consistently wound mesh) or, for odd
        // iterations, in the same direction.
        if (iter % 2 == 0)
            clipTriangle(B, A, D, p, p2);
        else
            clipTriangle(A, B, D, p, p2);

        // The vertices of each output lying on segment AB (within rounding), away from A and B.
        auto onAB = [&](const ClippedPolygon& poly) {
            std::vector<ClipVertex> out;
            const double ab[4] = {double(B.position.x) - A.position.x, double(B.position.y) - A.position.y,
                                  double(B.position.z) - A.position.z, double(B.position.w) - A.position.w};
            const double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2] + ab[3] * ab[3];
            for (int i = 0; i < poly.count; ++i) {
                const Vec4 q = poly.vertices[std::size_t(i)].position;
                const double aq[4] = {double(q.x) - A.position.x, double(q.y) - A.position.y,
                                      double(q.z) - A.position.z, double(q.w) - A.position.w};
                const double s = (aq[0] * ab[0] + aq[1] * ab[1] + aq[2] * ab[2] + aq[3] * ab[3]) / len2;
                double r2 = 0;
                for (int k = 0; k < 4; ++k)
                    r2 += (aq[k] - s * ab[k]) * (aq[k] - s * ab[k]);
                if (s > 1e-3 && s < 1 - 1e-3 && r2 <= 1e-10 * len2)
                    out.push_back(poly.vertices[std::size_t(i)]);
            }
            return out;
        };
        // A triangle rejected whole (say, all three vertices above the screen) takes the
        // entire shared edge with it: that edge is invisible, so there is nothing to match.
        if (p1.count == 0 || p2.count == 0)
            continue;
        const std::vector<ClipVertex> cut1 = onAB(p1), cut2 = onAB(p2);
        INFO("iteration " << iter);
        REQUIRE(cut1.size() == cut2.size());
        for (const ClipVertex& v : cut1) {
            bool found = false;
            for (const ClipVertex& u : cut2)
                found = found || (sameBits(u, v) && u.varyings == v.varyings);
            CHECK(found);
        }
        sharedCuts += int(cut1.size());
    }
    CHECK(sharedCuts > 500); // the test really exercised cuts on the shared edge
}

TEST_CASE("huge triangles are clipped to the guard band without changing what is on screen", "[pipeline][clip]") {
    struct Case {
        double x[3], y[3];
    };
    const Case cases[] = {
        {{-1e6, 1e6, 0}, {-1e6, 0, 1e6}},
        {{-1e9, 1e9, 320}, {240, -1e9, 1e9}},
        {{-1e9, 1e9, 0}, {-1e9, -1e9, 1e9}},
        {{100, 1e9, 100}, {100, 100, 1e9}},       // one corner on screen, two far away
        {{-1e6, 2e6, 500}, {-2e6, 700, 3e6}},
        {{1e9, -1e9, 1e9}, {-1e9, 200, 1e9}},     // covers the whole screen, thin at the far end
        {{-5e8, 6e8, 320}, {300, 310, -4e8}},     // a long sliver across the screen
    };
    const double ws[] = {1.0, 0.01, 250.0};
    const ClipParams p = params();
    for (const Case& k : cases) {
        for (double w : ws) {
            for (int order = 0; order < 2; ++order) {
                ClipVertex v[3];
                for (int i = 0; i < 3; ++i)
                    v[i] = fromScreen(k.x[i], k.y[i], kW, kH, w);
                if (order == 1)
                    std::swap(v[1], v[2]);
                INFO("case " << (&k - cases) << ", w " << w << ", order " << order);
                ClippedPolygon poly;
                REQUIRE(clipTriangle(v[0], v[1], v[2], p, poly) >= 3);
                checkInvariants(poly, p);
                checkWinding(poly, v[0], v[1], v[2], p);

                // Screen polygons in double: the original (from its float clip coordinates)
                // and the clipped one.
                std::vector<P2> orig, clipped;
                for (int i = 0; i < 3; ++i) {
                    const Vec4 q = v[i].position;
                    orig.push_back({(double(q.x) / q.w + 1) * kW / 2, (1 - double(q.y) / q.w) * kH / 2});
                }
                for (int i = 0; i < poly.count; ++i) {
                    const ScreenVertex s = toScreen(poly.vertices[std::size_t(i)], kW, kH, 0);
                    clipped.push_back({s.x, s.y});
                }
                // Convex, with one consistent turning direction.
                const double sign = polygonArea(clipped) > 0 ? 1.0 : -1.0;
                for (std::size_t i = 0; i < clipped.size(); ++i) {
                    const P2 a = clipped[i], b = clipped[(i + 1) % clipped.size()],
                             c = clipped[(i + 2) % clipped.size()];
                    const double turn = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
                    CHECK(sign * turn >= -1e-3 * kClipGuardBand);
                }
                const double areaOrig = std::fabs(polygonArea(clipToRect(orig, kW, kH)));
                const double areaClip = std::fabs(polygonArea(clipToRect(clipped, kW, kH)));
                CHECK(areaOrig > 0.0);
                CHECK(std::fabs(areaOrig - areaClip) <= 1.0 + 1e-5 * areaOrig);
            }
        }
    }
}

TEST_CASE("non-finite vertex positions drop the triangle", "[pipeline][clip]") {
    const float bad[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                         -std::numeric_limits<float>::infinity()};
    Clipper clipper(params());
    int dropped = 0;
    for (float b : bad) {
        for (int vertex = 0; vertex < 3; ++vertex) {
            for (int comp = 0; comp < 4; ++comp) {
                ClipVertex v[3] = {viewVertex(-1, -1, -5), viewVertex(1, -1, -5), viewVertex(0, 1, -5)};
                v[vertex].position[comp] = b;
                ClippedPolygon poly;
                CHECK(clipper.classify(v[0], v[1], v[2]) == ClipClass::Reject);
                CHECK(clipper.clip(v[0], v[1], v[2], poly) == 0);
                CHECK(poly.count == 0);
                CHECK(poly.triangleCount() == 0);
                ++dropped;
            }
        }
    }
    CHECK(clipper.stats().nonFinite == std::uint64_t(dropped));
    CHECK(clipper.stats().trivialAccepted == 0);
}

TEST_CASE("trivial reject by any single plane of the view volume", "[pipeline][clip]") {
    Clipper clipper(params());
    ClippedPolygon poly;
    // Left of the screen (x < -w) but inside the guard band: rejected, not clipped.
    const ClipVertex l0 = fromScreen(-100, 10, kW, kH), l1 = fromScreen(-5, 300, kW, kH),
                     l2 = fromScreen(-3000, 400, kW, kH);
    CHECK(clipper.classify(l0, l1, l2) == ClipClass::Reject);
    // Below the screen.
    const ClipVertex b0 = fromScreen(10, 500, kW, kH), b1 = fromScreen(600, 481, kW, kH),
                     b2 = fromScreen(300, 1e7, kW, kH);
    CHECK(clipper.classify(b0, b1, b2) == ClipClass::Reject);
    // Behind the eye.
    const ClipVertex n0 = viewVertex(-1, -1, 5), n1 = viewVertex(1, -1, 0.01f), n2 = viewVertex(0, 1, 1);
    CHECK(clipper.classify(n0, n1, n2) == ClipClass::Reject);
    CHECK(clipper.clip(n0, n1, n2, poly) == 0);
    CHECK(clipper.stats().trivialRejected == 1);
    // Each vertex outside a different plane: not trivially rejected.
    CHECK(clipper.classify(l0, b2, n0) == ClipClass::Clip);

    // An empty (minimised) viewport rejects everything.
    Clipper empty(params(0, false, 0, 0));
    CHECK(empty.clip(viewVertex(-1, -1, -5), viewVertex(1, -1, -5), viewVertex(0, 1, -5), poly) == 0);
}

TEST_CASE("the far plane is clipped only when the projection has one", "[pipeline][clip]") {
    // z < 0 is beyond a finite far plane (reversed-Z: far is z = 0).
    const ClipVertex a = makeVertex({-0.5f, -0.5f, -0.2f, 1.0f}), b = makeVertex({0.5f, -0.5f, 0.5f, 1.0f}),
                     c = makeVertex({0.0f, 0.5f, 0.5f, 1.0f});
    ClippedPolygon poly;
    CHECK(clipTriangle(a, b, c, params(0, false), poly) == 3); // infinite: kept whole

    const ClipParams pf = params(0, true);
    REQUIRE(clipTriangle(a, b, c, pf, poly) == 4);
    checkInvariants(poly, pf);
    checkWinding(poly, a, b, c, pf);
    int onFar = 0;
    for (int i = 0; i < poly.count; ++i)
        onFar += poly.vertices[std::size_t(i)].position.z == 0.0f;
    CHECK(onFar == 2);

    // Entirely beyond the far plane: rejected with the flag, kept without it.
    const ClipVertex d = makeVertex({0, 0, -0.1f, 1}), e = makeVertex({0.5f, 0, -0.1f, 1}),
                     f = makeVertex({0, 0.5f, -0.3f, 1});
    CHECK(clipTriangle(d, e, f, pf, poly) == 0);
    CHECK(clipTriangle(d, e, f, params(0, false), poly) == 3);
}

TEST_CASE("random triangles: every clipped output keeps the invariants", "[pipeline][clip]") {
    Rng rng(777);
    ClipStats stats;
    int maxCount = 0;
    for (int iter = 0; iter < 20000; ++iter) {
        const bool clipFar = (iter % 3) == 0;
        const int W = 1 + int(rng.next() % 4000), H = 1 + int(rng.next() % 3000);
        const ClipParams p = params(3, clipFar, W, H);
        const double range = (iter % 4 == 0) ? 1e7 : 50.0;
        ClipVertex v[3];
        for (int i = 0; i < 3; ++i) {
            v[i] = makeVertex({float(rng.uniform(-range, range)), float(rng.uniform(-range, range)),
                               float(rng.uniform(-2, 2)), float(rng.uniform(-2, 2))});
            setLinearVaryings(v[i]);
        }
        ClippedPolygon poly;
        const int n = clipTriangle(v[0], v[1], v[2], p, poly, &stats);
        INFO("iteration " << iter);
        if (n == 0)
            continue;
        maxCount = std::max(maxCount, n);
        checkInvariants(poly, p);
        if (std::fabs(homogeneousDet(v[0].position, v[1].position, v[2].position)) > 1e-3)
            checkWinding(poly, v[0], v[1], v[2], p);
        for (int i = 0; i < poly.count; ++i)
            checkLinearVaryings(poly.vertices[std::size_t(i)], v);
    }
    CHECK(stats.clipped > 1000);
    CHECK(stats.trivialRejected > 1000);
    CHECK(stats.trivialAccepted > 10);
    CHECK(maxCount >= 7); // polygons cut by several planes at once were exercised
}

TEST_CASE("toScreen follows the viewport conventions", "[pipeline][viewport]") {
    ClipVertex v = makeVertex({0.5f, 0.5f, 0.25f, 1.0f});
    v.varyings[0] = 3.0f;
    v.varyings[1] = 4.0f;
    const ScreenVertex s = toScreen(v, 200, 100, 1);
    CHECK(s.x == 150.0f); // (0.5 + 1) * 100
    CHECK(s.y == 25.0f);  // (1 - 0.5) * 50: NDC up is screen down
    CHECK(s.z == 0.25f);
    CHECK(s.invW == 1.0f);
    CHECK(s.varyings[0] == 3.0f);
    CHECK(s.varyings[1] == 0.0f); // not live: not copied

    // Divided by w; a vertex on the near plane (z == w) gets depth exactly 1.
    const float w = 0.1f;
    const ScreenVertex n = toScreen(makeVertex({-w, w, w, w}), 640, 480, 0);
    CHECK(n.x == 0.0f);
    CHECK(n.y == 0.0f);
    CHECK(n.z == 1.0f);
    CHECK(n.invW == Approx(10.0f));
}

TEST_CASE("a triangle cut by many planes at once fits the polygon buffer", "[pipeline][clip]") {
    // Found by a random search: near, far and guard-band planes all cut this one, leaving a
    // 9-gon (kMaxClipVertices = 10 is the bound for 7 planes).
    const ClipVertex a = makeVertex({121.256638f, -268.075989f, 2.05789876f, -0.398781508f});
    const ClipVertex b = makeVertex({-2.83029509f, 155.191238f, -2.18403411f, 3.17873192f});
    const ClipVertex c = makeVertex({-217.537064f, 270.530212f, 1.99066031f, 3.44468451f});
    const ClipParams p = params(0, true);
    ClippedPolygon poly;
    CHECK(clipTriangle(a, b, c, p, poly) == 9);
    CHECK(poly.triangleCount() == 7);
    checkInvariants(poly, p);
    checkWinding(poly, a, b, c, p);
}
