// Perspective-correct uvs on a tilted quad against the analytic ray/plane mapping, and the derived error bound of affine.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "Math/DoubleMath.hpp"
#include "Raster/Geometry/Viewport.hpp"
#include "Raster/Pipeline.hpp"
#include "Raster/Setup/FixedPoint.hpp"

using namespace sr;

namespace {

constexpr int kSize = 256;              // framebuffer kSize x kSize, and the texture is kSize texels wide
constexpr double kTexels = 256.0;       // uv error * kTexels = error in texels of a 256 x 256 texture
constexpr double kExactTolerance = 1.0 / 256.0; // texels

// The quad, in view space (camera at the origin looking down -Z). The projection is the plainest
// one: 90 degree field of view, aspect 1, so x_ndc = X / -Z, y_ndc = Y / -Z, w = -Z; clip z is a
// constant 0.5 (reversed-Z with near 0.5: z_ndc = 0.5 / w, inside (0, 1]).
// The corners are chosen so their screen positions are exact multiples of 1/256 pixel: the
// rasterizer's snapping (8 sub-pixel bits) then moves nothing and the triangles it draws are
// exactly the projection of the analytic plane (otherwise a snap of up to 1/512 pixel times a
// uv gradient of up to ~6 texels/pixel near the far edge would alone exceed 1/256 texel).
//   P0 = (-0.875, -0.75,   -1)  ndc (-0.875,   -0.75)     -> pixel (16, 224)    uv (0, 0)
//   P1 = ( 2,     -0.5,    -4)  ndc ( 0.5,     -0.125)    -> pixel (192, 144)   uv (1, 0)
//   P2 = ( 2.125,  1.0625, -4)  ndc ( 0.53125,  0.265625) -> pixel (196, 94)    uv (1, 1)
//   P3 = (-0.75,   0.8125, -1)  ndc (-0.75,     0.8125)   -> pixel (32, 24)     uv (0, 1)
// P2 - P1 = P3 - P0 = (0.125, 1.5625, 0): a planar parallelogram with an affine uv (u along
// E1 = P1 - P0, v along E2 = P3 - P0), tilted so that depth changes along every scanline (the
// near edge P0P3 at w = 1 is not horizontal on screen) with a depth ratio of 4.
const Vec3d kP[4] = {{-0.875, -0.75, -1.0}, {2.0, -0.5, -4.0}, {2.125, 1.0625, -4.0}, {-0.75, 0.8125, -1.0}};
const float kUv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
const double kPixel[4][2] = {{16, 224}, {192, 144}, {196, 94}, {32, 24}};
const std::uint32_t kIndices[6] = {0, 1, 2, 0, 2, 3};

// The analytic mapping: the ray through a pixel centre meets the quad's plane; uv = the affine
// coordinates of the hit point in the (E1, E2) frame, via the dual basis of (E1, E2).
struct Analytic {
    Vec3d e1 = kP[1] - kP[0], e2 = kP[3] - kP[0];
    Vec3d n = cross(e1, e2);
    Vec3d dual[2];
    Analytic() {
        const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2), det = g11 * g22 - g12 * g12;
        dual[0] = (e1 * g22 - e2 * g12) * (1.0 / det); // dual[0].e1 = 1, dual[0].e2 = 0
        dual[1] = (e2 * g11 - e1 * g12) * (1.0 / det); // dual[1].e1 = 0, dual[1].e2 = 1
    }
    // View direction through the screen point (px, py) (pixels, y down), with z = -1.
    static Vec3d dir(double px, double py) { return {px * (2.0 / kSize) - 1.0, 1.0 - py * (2.0 / kSize), -1.0}; }
    // Q = 1/w at the hit point: hit = dir * t with n.(hit - P0) = 0 -> t = n.P0 / n.dir, w = t.
    double invW(double px, double py) const { return dot(n, dir(px, py)) / dot(n, kP[0]); }
    // uv_k = dual_k . (hit - P0) = dual_k . dir / Q - dual_k . P0.
    double uv(int k, double px, double py) const {
        return dot(dual[k], dir(px, py)) / invW(px, py) - dot(dual[k], kP[0]);
    }
    // Along the row at height py, Q(x) = c + d x and U = uv_k * Q = a + b x are affine in the
    // pixel x (Hecker 1995), so uv_k(x) = (a + b x) / (c + d x) and
    //   uv' = (b c - a d) / (c + d x)^2,   uv'' = -2 d (b c - a d) / (c + d x)^3.
    double second(int k, double px, double py) const {
        const double np0 = dot(n, kP[0]), kp0 = dot(dual[k], kP[0]);
        const double c = dot(n, dir(0.0, py)) / np0, d = n.x * (2.0 / kSize) / np0;
        const double a = dot(dual[k], dir(0.0, py)) - kp0 * c, b = dual[k].x * (2.0 / kSize) - kp0 * d;
        const double q = c + d * px;
        return -2.0 * d * (b * c - a * d) / (q * q * q);
    }
};

struct Capture {
    std::vector<float> u, v;
    int covered = 0;
};

Capture render(PerspectiveMode mode) {
    FrameBuffer fb(kSize, kSize);
    fb.clear(packBgra(0, 0, 0));
    RenderContext ctx(fb);
    DrawState state;
    state.perspective = mode;
    state.clipFar = false;
    Capture c;
    c.u.assign(std::size_t(kSize) * kSize, std::numeric_limits<float>::quiet_NaN());
    c.v = c.u;
    drawIndexed<2>(
        ctx, state, 4, kIndices, 6,
        [](std::size_t i, ClipVertex& out) {
            out.position = Vec4(float(kP[i].x), float(kP[i].y), 0.5f, float(-kP[i].z));
            out.varyings[0] = kUv[i][0];
            out.varyings[1] = kUv[i][1];
        },
        [&](const Fragment<2>& f) {
            const std::size_t at = std::size_t(f.y) * kSize + std::size_t(f.x);
            c.u[at] = f.varyings[0];
            c.v[at] = f.varyings[1];
            ++c.covered;
            return packBgra(255, 255, 255);
        });
    return c;
}

// Largest |uv - analytic| over the covered pixel centres, in texels (u and v).
double maxErrorTexels(const Capture& c, const Analytic& a) {
    double worst = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const std::size_t at = std::size_t(y) * kSize + std::size_t(x);
            if (std::isnan(c.u[at])) continue;
            const double px = x + 0.5, py = y + 0.5;
            worst = std::max(worst, std::fabs(double(c.u[at]) - a.uv(0, px, py)) * kTexels);
            worst = std::max(worst, std::fabs(double(c.v[at]) - a.uv(1, px, py)) * kTexels);
        }
    return worst;
}

} // namespace

TEST_CASE("the tilted quad's corners land exactly on the 1/256 sub-pixel grid", "[render][perspective]") {
    // The premise of the analytic comparison below: snapping moves no vertex.
    for (int i = 0; i < 4; ++i) {
        ClipVertex cv;
        cv.position = Vec4(float(kP[i].x), float(kP[i].y), 0.5f, float(-kP[i].z));
        const ScreenVertex s = toScreen(cv, kSize, kSize, 0);
        CHECK(double(s.x) == kPixel[i][0]);
        CHECK(double(s.y) == kPixel[i][1]);
        CHECK(snapToFixed(s.x) == Fixed(kPixel[i][0] * kSubPixelScale));
        CHECK(snapToFixed(s.y) == Fixed(kPixel[i][1] * kSubPixelScale));
    }
}

TEST_CASE("perspective modes: exact uvs within 1/256 texel, affine within its derived bound",
          "[render][perspective][texture]") {
    const Analytic a;

    // --- Exact: every covered pixel centre within 1/256 texel of the analytic uv -------------
    const Capture exact = render(PerspectiveMode::Exact);
    REQUIRE(exact.covered > 20000); // the quad covers ~26k of the 65k pixels
    const double exactErr = maxErrorTexels(exact, a);
    CHECK(exactErr <= kExactTolerance);

    const Capture affine = render(PerspectiveMode::Affine);
    CHECK(affine.covered == exact.covered);
    const double errAffine = maxErrorTexels(affine, a);

    // --- Affine: a bound from the depth ratio ------------------------------------------------
    // With screen barycentrics l_i and q_i = 1/w_i at the vertices, affine gives sum l_i u_i and
    // the true value is sum l_i q_i u_i / Q, Q = sum l_i q_i. Their difference is
    //   D = sum l_i (u_i - c)(1 - q_i / Q)   for any c   (since sum l_i (1 - q_i / Q) = 0).
    // With c the mid-range of the u_i, |u_i - c| <= R / 2 (R = u range over the triangle), and
    // sum l_i |q_i - Q| (a mean absolute deviation around the mean Q, q in [q0, q1]) is at most
    // 2 (Q - q0)(q1 - Q) / (q1 - q0) (the two-point distribution on the ends). So
    //   |D| <= R (Q - q0)(q1 - Q) / ((q1 - q0) Q) <= R (sqrt q1 - sqrt q0)^2 / (q1 - q0)
    //        = R (sqrt r - 1) / (sqrt r + 1),   r = q1 / q0 = w_max / w_min (the depth ratio),
    // the maximum being at Q = sqrt(q0 q1). Both triangles have R = 1 and r = 4: |D| <= 1/3 uv,
    // 85.3 texels. The bound is attained on the edge P0P1 (u 0 -> 1, w 1 -> 4) where Q = 1/2, so
    // the measured error must come close to it.
    const double r = 4.0;
    const double boundAffine = (std::sqrt(r) - 1.0) / (std::sqrt(r) + 1.0) * kTexels + kExactTolerance;

    INFO("max error (texels of a 256 texture): exact " << exactErr << ", affine " << errAffine << " (bound "
                                                       << boundAffine << ")");
    CHECK(errAffine <= boundAffine);

    // The other direction: affine really is as coarse as its name says - visibly worse than
    // exact (far above its tolerance, more than a texel) and within 25% of its bound (which the
    // geometry attains on the edge P0P1).
    CHECK(errAffine > 100.0 * kExactTolerance);
    CHECK(errAffine > 1.0);
    CHECK(errAffine > 0.75 * boundAffine);
}
