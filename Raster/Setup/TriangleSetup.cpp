// Triangle setup: fixed-point snapping, exact area, y-sorted edges and attribute plane gradients.
#include "Raster/Setup/TriangleSetup.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define SR_SETUP_SSE2 1
#else
#define SR_SETUP_SSE2 0
#endif

namespace sr {

namespace {

using FixedPoint2 = SnappedVertex;


FixedEdge makeEdge(FixedPoint2 from, FixedPoint2 to) {
    assert(to.y >= from.y);
    return FixedEdge{from.x, from.y, to.x - from.x, to.y - from.y};
}

// First pixel row whose centre y is >= Y (fixed point): the smallest j with j*256 + 128 >= Y.
int firstRowAtOrBelow(Fixed y) { return int(firstCentreAtOrAfter(y, 1)); }

// Inlined into both callers even though there are two: out of line, `perf` put the call at 8.6%
// of the one-thread bunny frame (800x600, cull cw).
#if defined(__GNUC__) || defined(__clang__)
#define SR_SETUP_INLINE inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define SR_SETUP_INLINE __forceinline
#else
#define SR_SETUP_INLINE inline
#endif

// The decision from the snapped vertices (snapAndCull, screenSnapped): twice the exact signed
// area and the cull.
SR_SETUP_INLINE SetupOutcome cullSnapped(const FixedPoint2 (&p)[3], CullMode cull, std::int64_t& doubleArea) {
    // |coordinate| <= 2^22, so each difference is < 2^23 and each product < 2^46: exact in int64.
    const std::int64_t e1x = p[1].x - p[0].x, e1y = p[1].y - p[0].y;
    const std::int64_t e2x = p[2].x - p[0].x, e2y = p[2].y - p[0].y;
    doubleArea = e1x * e2y - e2x * e1y;
    // --- Cull on the snapped grid (Cull.hpp: y down, > 0 is clockwise) --------------------
    if (doubleArea == 0) return SetupOutcome::Culled; // collinear or coincident after snapping
    if ((cull == CullMode::CW && doubleArea > 0) || (cull == CullMode::CCW && doubleArea < 0))
        return SetupOutcome::Culled;
    return SetupOutcome::Ready;
}

// setupTriangleCulled's first steps: the vertices snapped (p) and the cull decided from twice
// the exact signed area. Ready when the triangle is to be set up.
SR_SETUP_INLINE SetupOutcome snapAndCull(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                                         CullMode cull, FixedPoint2 (&p)[3], std::int64_t& doubleArea) {
    // --- Preconditions: the clipper guarantees these; reject rather than overflow if not ---
    const bool valid = inGuardBand(v0) && inGuardBand(v1) && inGuardBand(v2);
    if (!valid) return isCulled(cull, v0, v1, v2) ? SetupOutcome::Culled : SetupOutcome::Empty;

    // --- Snap to 1/256 pixel -----------------------------------------------------------------
    p[0] = {snapToFixed(v0.x), snapToFixed(v0.y)};
    p[1] = {snapToFixed(v1.x), snapToFixed(v1.y)};
    p[2] = {snapToFixed(v2.x), snapToFixed(v2.y)};
    return cullSnapped(p, cull, doubleArea);
}

} // namespace

SetupOutcome screenSnapped(SnappedVertex p0, SnappedVertex p1, SnappedVertex p2, CullMode cull, bool keepRowless,
                           Fixed& minY, Fixed& maxY) {
    assert(p0.x != kUnsnapped && p1.x != kUnsnapped && p2.x != kUnsnapped);
    const FixedPoint2 p[3] = {p0, p1, p2};
    std::int64_t doubleArea = 0;
    const SetupOutcome outcome = cullSnapped(p, cull, doubleArea);
    if (outcome != SetupOutcome::Ready) return outcome;
    minY = std::min({p0.y, p1.y, p2.y});
    maxY = std::max({p0.y, p1.y, p2.y});
    if (!keepRowless && firstRowAtOrBelow(minY) >= firstRowAtOrBelow(maxY)) return SetupOutcome::Empty;
    return SetupOutcome::Ready;
}

SetupOutcome setupTriangleCulled(TriangleSetup& t, const ScreenVertex& v0, const ScreenVertex& v1,
                                 const ScreenVertex& v2, CullMode cull, int varyingCount, bool perspectiveCorrect,
                                 const VaryingRebase& rebase, bool keepRowless) {
    FixedPoint2 p[3];
    std::int64_t doubleArea = 0;
    const SetupOutcome culled = snapAndCull(v0, v1, v2, cull, p, doubleArea);
    if (culled != SetupOutcome::Ready) return culled;
    assert(varyingCount >= 0 && varyingCount <= kMaxVaryings);
    varyingCount = std::clamp(varyingCount, 0, kMaxVaryings);

    t.doubleArea = doubleArea;
    const std::int64_t e1x = p[1].x - p[0].x, e1y = p[1].y - p[0].y;
    const std::int64_t e2x = p[2].x - p[0].x, e2y = p[2].y - p[0].y;

    // --- Sort by y (top = smallest y, the screen is y-down) and build the three edges ------
    int top = 0, mid = 1, bot = 2;
    if (p[mid].y < p[top].y) std::swap(mid, top);
    if (p[bot].y < p[mid].y) std::swap(bot, mid);
    if (p[mid].y < p[top].y) std::swap(mid, top);
    const FixedPoint2 pt = p[top], pm = p[mid], pb = p[bot];

    // --- Rows: centre y in [yTop, yBottom), the lower part from the first centre >= yMid ----
    t.firstRow = firstRowAtOrBelow(pt.y);
    t.endRow = firstRowAtOrBelow(pb.y);
    // Thinner than one row of centres: nothing to fill, unless the caller samples elsewhere too.
    if (t.firstRow >= t.endRow && !keepRowless) return SetupOutcome::Empty;
    t.midRow = firstRowAtOrBelow(pm.y);

    t.longEdge = makeEdge(pt, pb);
    t.upperEdge = makeEdge(pt, pm);
    t.lowerEdge = makeEdge(pm, pb);
    // The middle vertex is right of the long edge when cross(bottom - top, mid - top) > 0
    // (y-down: the sign of (m.x*d.y - m.y*d.x) compares m.x with the long edge's x at m.y).
    const std::int64_t side = std::int64_t(pm.x - pt.x) * t.longEdge.dy -
                              std::int64_t(pm.y - pt.y) * t.longEdge.dx;
    assert(side != 0); // non-zero area
    t.longEdgeOnLeft = side > 0;
    const Fixed minX = std::min({pt.x, pm.x, pb.x}), maxX = std::max({pt.x, pm.x, pb.x});
    t.minX = int(floorDiv(minX, kSubPixelScale));
    t.maxX = int(floorDiv(maxX, kSubPixelScale));

    // --- Attribute planes from the snapped positions ---------------------------------------
    // For a plane a = a0 + A (x - x0) + B (y - y0) through the three vertices, Cramer's rule
    // gives A = (da1 e2y - da2 e1y) / area2 and B = (da2 e1x - da1 e2x) / area2 (e = edge
    // vectors from vertex 0, in pixels), in double; the origin stays at vertex 0.
    const double inv = double(kSubPixelScale) * double(kSubPixelScale) / double(doubleArea);
    const double ex1 = double(e1x) / kSubPixelScale, ey1 = double(e1y) / kSubPixelScale;
    const double ex2 = double(e2x) / kSubPixelScale, ey2 = double(e2y) / kSubPixelScale;
    t.originX = double(p[0].x) / kSubPixelScale;
    t.originY = double(p[0].y) / kSubPixelScale;
    t.varyingCount = varyingCount;
    auto plane = [&](int k, double a0, double a1, double a2) {
        const double da1 = a1 - a0, da2 = a2 - a0;
        t.value[k] = a0;
        t.ddx[k] = (da1 * ey2 - da2 * ey1) * inv;
        t.ddy[k] = (da2 * ex1 - da1 * ex2) * inv;
        t.ddxStep[k] = float(t.ddx[k]);
    };
    // Varying planes hold v/w (v * invW) or, for affine, v itself (v * 1.0 is exact).
    const double w0 = perspectiveCorrect ? double(v0.invW) : 1.0;
    const double w1 = perspectiveCorrect ? double(v1.invW) : 1.0;
    const double w2 = perspectiveCorrect ? double(v2.invW) : 1.0;
    // Rebased varyings: float inputs less a whole number of periods, exact in double.
    const int rebased = std::min(rebase.count, varyingCount);
    for (int k = 0; k < rebased; ++k) {
        const std::size_t i = std::size_t(k);
        double a0 = v0.varyings[i], a1 = v1.varyings[i], a2 = v2.varyings[i];
        const double offset = rebaseOffset(a0, a1, a2, rebase.period);
        a0 -= offset;
        a1 -= offset;
        a2 -= offset;
        plane(kPlaneVarying0 + k, a0 * w0, a1 * w1, a2 * w2);
    }
    int k = rebased;
#if SR_SETUP_SSE2
    // Two planes at a time: plane()'s double operations lane by lane (IEEE, no FMA), so the same
    // bits: depth and 1/w together, then the varyings (not rebased) in pairs.
    {
        const __m128d ex1v = _mm_set1_pd(ex1), ey1v = _mm_set1_pd(ey1), ex2v = _mm_set1_pd(ex2), ey2v = _mm_set1_pd(ey2),
                      invv = _mm_set1_pd(inv);
        auto planes = [&](int first, __m128d a0, __m128d a1, __m128d a2) {
            const __m128d da1 = _mm_sub_pd(a1, a0), da2 = _mm_sub_pd(a2, a0);
            const __m128d ddx = _mm_mul_pd(_mm_sub_pd(_mm_mul_pd(da1, ey2v), _mm_mul_pd(da2, ey1v)), invv);
            const __m128d ddy = _mm_mul_pd(_mm_sub_pd(_mm_mul_pd(da2, ex1v), _mm_mul_pd(da1, ex2v)), invv);
            _mm_storeu_pd(t.value + first, a0);
            _mm_storeu_pd(t.ddx + first, ddx);
            _mm_storeu_pd(t.ddy + first, ddy);
            const __m128 steps = _mm_cvtpd_ps(ddx); // two floats, rounded as float(ddx) is
            _mm_storel_epi64(reinterpret_cast<__m128i*>(t.ddxStep + first), _mm_castps_si128(steps));
        };
        static_assert(kPlaneInvW == kPlaneZ + 1, "depth and 1/w in adjacent planes");
        planes(kPlaneZ, _mm_setr_pd(double(v0.z), double(v0.invW)), _mm_setr_pd(double(v1.z), double(v1.invW)),
               _mm_setr_pd(double(v2.z), double(v2.invW)));
        auto pair = [](const Varyings& v, int at) { // v[at], v[at + 1] in double
            return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(v.data() + at))));
        };
        const __m128d w0v = _mm_set1_pd(w0), w1v = _mm_set1_pd(w1), w2v = _mm_set1_pd(w2);
        for (; k + 2 <= varyingCount; k += 2)
            planes(kPlaneVarying0 + k, _mm_mul_pd(pair(v0.varyings, k), w0v), _mm_mul_pd(pair(v1.varyings, k), w1v),
                   _mm_mul_pd(pair(v2.varyings, k), w2v));
    }
#else
    plane(kPlaneZ, double(v0.z), double(v1.z), double(v2.z));
    plane(kPlaneInvW, double(v0.invW), double(v1.invW), double(v2.invW));
#endif
    for (; k < varyingCount; ++k) {
        const std::size_t i = std::size_t(k);
        plane(kPlaneVarying0 + k, double(v0.varyings[i]) * w0, double(v1.varyings[i]) * w1, double(v2.varyings[i]) * w2);
    }
    return SetupOutcome::Ready;
}

std::optional<TriangleSetup> setupTriangle(const ScreenVertex& v0, const ScreenVertex& v1,
                                           const ScreenVertex& v2, int varyingCount, bool perspectiveCorrect,
                                           const VaryingRebase& rebase) {
    [[maybe_unused]] const bool valid = inGuardBand(v0) && inGuardBand(v1) && inGuardBand(v2);
    assert(valid && "triangle setup: vertex outside the guard band or not finite");
    // Built in place in the returned optional (one named return value: no copy of the record).
    std::optional<TriangleSetup> result(std::in_place);
    if (setupTriangleCulled(*result, v0, v1, v2, CullMode::None, varyingCount, perspectiveCorrect, rebase, false) !=
        SetupOutcome::Ready)
        result.reset();
    return result;
}

} // namespace sr
