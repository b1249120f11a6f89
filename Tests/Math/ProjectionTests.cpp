// Tests of the reversed-Z projections, aspectRatio and viewport: known values and depth precision at extreme ranges.
#include "TestFramework.hpp"

#include <cmath>
#include <vector>

#include "Math/Transform.hpp"
#include "MathTestUtil.hpp"

using namespace sr;
using srtest::kU;

namespace {

// NDC depth of the view-space point (0, 0, -d): clip z / clip w, in float, as the pipeline does.
float depthAt(const Mat4& p, float d) {
    const Vec4 c = p * Vec4(0.0f, 0.0f, -d, 1.0f);
    return c.z / c.w;
}

// Exact reversed-Z depth for the float arguments, in double: n (f - d) / (d (f - n)).
double exactDepth(double n, double f, double d) { return n * (f - d) / (d * (f - n)); }

// Distances from lo to hi (inclusive) in geometric steps of `ratio`.
std::vector<float> geometric(float lo, float hi, double ratio) {
    std::vector<float> v;
    for (double d = lo; d < hi; d *= ratio) v.push_back(static_cast<float>(d));
    v.push_back(hi);
    return v;
}

} // namespace

TEST_CASE("perspective: known values, near -> exactly 1, far -> exactly 0", "[math][projection]") {
    // n = 1, f = 3: A = n/(f-n) = 0.5, B = f n/(f-n) = 1.5, all exact in float.
    const Mat4 p = perspective(radians(60.0f), 2.0f, 1.0f, 3.0f);
    CHECK(p(2, 2) == 0.5f);
    CHECK(p(2, 3) == 1.5f);
    CHECK(p(3, 2) == -1.0f); // w = -z_view
    CHECK(p(3, 3) == 0.0f);
    CHECK(depthAt(p, 1.0f) == 1.0f);
    CHECK(depthAt(p, 3.0f) == 0.0f);
    CHECK(depthAt(p, 2.0f) == 0.25f); // n (f - d) / (d (f - n)) = 1 * 1 / (2 * 2)
    CHECK((p * Vec4(0, 0, -2, 1)).w == 2.0f);
    // x and y: cot(30 deg) = sqrt(3); x is divided by the aspect ratio. Rounding 60 degrees to float
    // moves cot by 0.6u and the result is rounded once more (u): within 2u.
    CHECK(p(1, 1) == Approx(std::sqrt(3.0)).epsilon(2 * kU));
    CHECK(p(0, 0) == Approx(std::sqrt(3.0) / 2.0).epsilon(2 * kU));
    // The top-right corner of the frustum at distance 5 maps to NDC (1, 1).
    // Four roundings of <= u each (t, the scale, the product, the divide): error < 5u.
    const float t = static_cast<float>(5.0 * std::tan(double(radians(30.0f))));
    const Vec4 corner = p * Vec4(2.0f * t, t, -5.0f, 1.0f);
    CHECK(corner.x / corner.w == Approx(1.0).epsilon(5 * kU));
    CHECK(corner.y / corner.w == Approx(1.0).epsilon(5 * kU));
    // Points in front of the near plane (closer) get depth > 1; behind the far plane < 0.
    CHECK(depthAt(p, 0.5f) > 1.0f);
    CHECK(depthAt(p, 4.0f) < 0.0f);
}

TEST_CASE("perspective coefficients are the double values rounded once to float", "[math][projection]") {
    // Over random near/far pairs spanning 1e-6 .. 1e9, every coefficient equals the double-precision
    // formula rounded once. (Computing f n / (f - n) in float rounds three times and misses this
    // for a large share of the pairs.)
    srtest::Rng rng(31337);
    int wrong = 0;
    for (int i = 0; i < 2000; ++i) {
        const float n = std::pow(10.0f, rng.uniform(-6.0f, 3.0f));
        const float f = n * std::pow(10.0f, rng.uniform(0.001f, 6.0f));
        const float fov = rng.uniform(0.01f, 3.1f), aspect = rng.uniform(0.2f, 5.0f);
        if (!(f > n)) continue;
        const Mat4 p = perspective(fov, aspect, n, f);
        const double range = double(f) - double(n);
        const double cot = 1.0 / std::tan(double(fov) / 2.0);
        wrong += p(2, 2) != static_cast<float>(double(n) / range);
        wrong += p(2, 3) != static_cast<float>(double(f) * double(n) / range);
        wrong += p(1, 1) != static_cast<float>(cot);
        wrong += p(0, 0) != static_cast<float>(cot / double(aspect));
    }
    CHECK(wrong == 0);
}

TEST_CASE("perspective near 1e-6, far 1e9: depth finite, monotonic, within the stated error", "[math][projection]") {
    const float n = 1e-6f, f = 1e9f;
    const Mat4 p = perspective(radians(60.0f), 16.0f / 9.0f, n, f);
    REQUIRE(isFinite(p));
    // Coefficients: the double value rounded once to float.
    const double A = double(n) / (double(f) - n), B = double(f) * n / (double(f) - n);
    CHECK(p(2, 2) == static_cast<float>(A));
    CHECK(p(2, 3) == static_cast<float>(B));
    CHECK(depthAt(p, n) == 1.0f);
    // Error bound: z_clip = fl(fl(A' z) + B') with A', B' the rounded coefficients and |A d| <= B
    // for d in [n, f], so |z_clip - exact| <= u (|B| + 2 |A d| + |B - A d|) <= 4u B; dividing by
    // w = d (exact) adds one more rounding: |z_ndc - exact| <= 4u B / d + u |exact|.
    // At the far plane that is |z_ndc| <= 4u n / (f - n): a relative distance error of <= 4u.
    CHECK(std::fabs(depthAt(p, f)) <= 4 * kU * B / f);
    // Over 34,000 distances from near to far in steps of 0.1%: the worst error / bound ratio and
    // the first distance where depth fails to decrease strictly (reported, not asserted per step).
    float prev = 2.0f, firstNonMonotonic = 0.0f, worstAt = 0.0f;
    double worst = 0.0;
    int checked = 0, nonFinite = 0;
    for (float d : geometric(n, f, 1.001)) {
        const float z = depthAt(p, d);
        if (!std::isfinite(z)) ++nonFinite;
        const double exact = exactDepth(n, f, d);
        const double ratio = std::fabs(z - exact) / (4 * kU * B / d + kU * std::fabs(exact));
        if (ratio > worst) worst = ratio, worstAt = d;
        if (!(z < prev) && firstNonMonotonic == 0.0f) firstNonMonotonic = d;
        prev = z;
        ++checked;
    }
    INFO("worst error / bound " << worst << " at d = " << worstAt);
    CHECK(checked > 30000);
    CHECK(nonFinite == 0);
    CHECK(worst <= 1.0);
    CHECK(firstNonMonotonic == 0.0f);
}

TEST_CASE("reversed-Z keeps a relative distance resolution of 1e-5 across 15 decades", "[math][projection]") {
    // Two points whose distances differ by a factor 1 + 1e-5 never share a depth value, from the
    // near plane (1e-6) to the far plane (1e9): the property that makes float reversed-Z the most
    // precise choice (Reed 2015). A standard [0,1] depth with far -> 1 fails this badly.
    const float n = 1e-6f;
    const Mat4 finite = perspective(1.0f, 1.0f, n, 1e9f), infinite = perspectiveInfinite(1.0f, 1.0f, n);
    int ties = 0, pairs = 0;
    for (int decade = -6; decade < 9; ++decade) {
        double d = std::pow(10.0, decade);
        float prevF = depthAt(finite, static_cast<float>(d)), prevI = depthAt(infinite, static_cast<float>(d));
        for (int i = 0; i < 1000; ++i) {
            d *= 1.0 + 1e-5;
            const float zf = depthAt(finite, static_cast<float>(d)), zi = depthAt(infinite, static_cast<float>(d));
            ties += !(zf < prevF) + !(zi < prevI);
            pairs += 2;
            prevF = zf;
            prevI = zi;
        }
    }
    CHECK(pairs == 30000);
    CHECK(ties == 0);
}

TEST_CASE("perspectiveInfinite: z = n / d correctly rounded, positive up to FLT_MAX", "[math][projection]") {
    const float n = 1e-6f;
    const Mat4 p = perspectiveInfinite(radians(75.0f), 1.25f, n);
    CHECK(p(2, 2) == 0.0f);
    CHECK(p(2, 3) == n);
    CHECK(depthAt(p, n) == 1.0f);
    // far = +infinity is the same matrix.
    CHECK(perspective(radians(75.0f), 1.25f, n, HUGE_VALF) == p);
    float prev = 2.0f;
    int outOfBound = 0, nonMonotonic = 0, count = 0;
    for (float d : geometric(n, 1e30f, 1.001)) {
        const float z = depthAt(p, d);
        const double exact = double(n) / d;
        outOfBound += !(std::fabs(z - exact) <= kU * exact); // one rounding (the division)
        nonMonotonic += !(z < prev);
        prev = z;
        ++count;
    }
    CHECK(count > 80000);
    CHECK(outOfBound == 0);
    CHECK(nonMonotonic == 0);
    const float zMax = depthAt(p, FLT_MAX);
    CHECK(zMax > 0.0f); // denormal, but not 0: still nearer than the cleared depth buffer
    CHECK(std::isfinite(zMax));
}

TEST_CASE("perspective at fov 1e-3 and 179.9 degrees: finite, correct scale and aspect ratio", "[math][projection]") {
    for (float deg : {1e-3f, 179.9f}) {
        const float fov = radians(deg);
        const float aspect = 4.0f / 3.0f;
        const Mat4 p = perspective(fov, aspect, 0.1f, 100.0f);
        INFO("fov " << deg << " degrees");
        REQUIRE(isFinite(p));
        const double cot = 1.0 / std::tan(double(fov) / 2.0);
        CHECK(srtest::relErr(p(1, 1), cot) <= kU);
        CHECK(srtest::relErr(p(0, 0), cot / double(aspect)) <= kU);
        CHECK(srtest::relErr(double(p(1, 1)) / p(0, 0), double(aspect)) <= 2 * kU);
        // A point on the top edge of the frustum maps to y_ndc = 1.
        const float d = 10.0f;
        const float y = static_cast<float>(d * std::tan(double(fov) / 2.0));
        const Vec4 c = p * Vec4(0.0f, y, -d, 1.0f);
        CHECK(srtest::relErr(c.y / c.w, 1.0) <= 5 * kU); // 4 roundings, as above
    }
}

TEST_CASE("aspectRatio of a minimised 0x0 window is 1", "[math][projection]") {
    CHECK(aspectRatio(1920, 1080) == static_cast<float>(1920.0 / 1080.0));
    CHECK(aspectRatio(3, 1) == 3.0f);
    CHECK(aspectRatio(0, 0) == 1.0f);
    CHECK(aspectRatio(0, 1080) == 1.0f);
    CHECK(aspectRatio(1920, 0) == 1.0f);
    CHECK(aspectRatio(-4, 3) == 1.0f);
    const Mat4 p = perspective(1.0f, aspectRatio(0, 0), 0.1f, 10.0f);
    CHECK(isFinite(p));
    CHECK(p(0, 0) == p(1, 1));
}

#if defined(NDEBUG)
// Invalid arguments assert in debug builds; release builds substitute the documented values.
TEST_CASE("perspective with invalid arguments stays finite (release substitutions)", "[math][projection][nonfinite]") {
    const float nan = std::nanf("");
    const Mat4 ref = perspective(1.0f, 1.5f, 0.1f, 100.0f);
    const Mat4 nanFov = perspective(nan, 1.5f, 0.1f, 100.0f); // fov -> pi/2: cot(pi/4) = 1
    CHECK(nanFov(1, 1) == 1.0f);
    CHECK(nanFov(0, 0) == static_cast<float>(1.0 / 1.5));
    CHECK(nanFov(2, 3) == ref(2, 3));
    CHECK(perspective(0.0f, 1.5f, 0.1f, 100.0f)(1, 1) == static_cast<float>(1.0 / std::tan(0.5e-6)));
    CHECK(perspective(-1.0f, 1.5f, 0.1f, 100.0f) == perspective(0.0f, 1.5f, 0.1f, 100.0f));
    const Mat4 wide = perspective(4.0f, 1.5f, 0.1f, 100.0f); // > pi: clamped to pi - 1e-6
    CHECK(wide(1, 1) > 0.0f);                               // not a mirrored image
    CHECK(wide(1, 1) < 1e-6f);
    CHECK(perspective(1.0f, 0.0f, 0.1f, 100.0f) == perspective(1.0f, 1.0f, 0.1f, 100.0f));
    CHECK(perspective(1.0f, nan, 0.1f, 100.0f) == perspective(1.0f, 1.0f, 0.1f, 100.0f));
    CHECK(perspective(1.0f, 1.5f, 0.0f, 100.0f) == ref);
    CHECK(perspective(1.0f, 1.5f, -5.0f, 100.0f) == ref);
    CHECK(perspective(1.0f, 1.5f, nan, 100.0f) == ref);
    CHECK(perspective(1.0f, 1.5f, 0.1f, 0.05f) == perspectiveInfinite(1.0f, 1.5f, 0.1f)); // far <= near
    CHECK(perspective(1.0f, 1.5f, 0.1f, nan) == perspectiveInfinite(1.0f, 1.5f, 0.1f));
    CHECK(isFinite(perspective(nan, nan, nan, nan)));
    CHECK(isFinite(perspective(HUGE_VALF, 1e-38f, FLT_MAX, HUGE_VALF)));
    CHECK(isFinite(perspectiveInfinite(-HUGE_VALF, HUGE_VALF, HUGE_VALF)));
    CHECK(isFinite(orthographic(1, 1, 2, 2, 3, 3)));
    CHECK(orthographic(1, 1, -1, 1, 0, 1) == orthographic(-1, 1, -1, 1, 0, 1));
    CHECK(isFinite(orthographic(nan, 1, 0, HUGE_VALF, nan, nan)));
}
#endif

TEST_CASE("orthographic: reversed-Z, near -> 1, far -> 0, known values", "[math][projection]") {
    const Mat4 o = orthographic(-2, 2, -1, 1, 1, 5);
    CHECK(o * Vec4(2, 1, -1, 1) == Vec4(1, 1, 1, 1));
    CHECK(o * Vec4(-2, -1, -5, 1) == Vec4(-1, -1, 0, 1));
    CHECK((o * Vec4(0, 0, -3, 1)).z == 0.5f);
    CHECK(o.row(3) == Vec4(0, 0, 0, 1));
    const Mat4 screen = orthographic(0, 640, 480, 0, -1, 1); // y down, near behind the eye
    CHECK(screen * Vec4(0, 0, 1, 1) == Vec4(-1, 1, 1, 1));
    CHECK(screen * Vec4(640, 480, -1, 1) == Vec4(1, -1, 0, 1));
    CHECK(screen * Vec4(320, 240, 0, 1) == Vec4(0, 0, 0.5f, 1));
}

TEST_CASE("viewport maps NDC to y-down pixels; 0x0 stays finite", "[math][projection]") {
    const Mat4 v = viewport(640, 480);
    CHECK(v * Vec4(-1, 1, 0.25f, 1) == Vec4(0, 0, 0.25f, 1));     // top-left corner
    CHECK(v * Vec4(1, -1, 0.75f, 1) == Vec4(640, 480, 0.75f, 1)); // bottom-right corner
    CHECK(v * Vec4(0, 0, 1, 1) == Vec4(320, 240, 1, 1));
    // The centre of pixel (0, 0) is at (0.5, 0.5) (a 512x256 viewport keeps the NDC exact).
    CHECK(viewport(512, 256) * Vec4(1.0f / 512 - 1, 1 - 1.0f / 256, 0, 1) == Vec4(0.5f, 0.5f, 0, 1));
    // Applied to clip coordinates before the divide, the result divides to the same pixel.
    const Vec4 clip(0.5f * 4, -0.25f * 4, 0.5f * 4, 4);
    const Vec4 s = v * clip;
    CHECK(s.x / s.w == 480.0f);
    CHECK(s.y / s.w == 300.0f);
    CHECK(s.z / s.w == 0.5f);
    // A view-space point on the optical axis lands in the centre of the screen at any depth.
    const Mat4 chain = viewport(800, 600) * perspective(1.0f, aspectRatio(800, 600), 0.1f, 100.0f);
    for (float d : {0.1f, 1.0f, 50.0f}) {
        const Vec4 c = chain * Vec4(0, 0, -d, 1);
        CHECK(c.x / c.w == 400.0f);
        CHECK(c.y / c.w == 300.0f);
    }
    // Minimised window: everything maps to pixel corner (0, 0), no NaN.
    const Mat4 z = viewport(0, 0);
    REQUIRE(isFinite(z));
    CHECK(z * Vec4(0.3f, -0.7f, 0.5f, 1) == Vec4(0, 0, 0.5f, 1));
    CHECK(viewport(-10, -5) == z);
}
