// Tests of Vec2/3/4: operators, products, and length/normalize at the extremes.
#include "TestFramework.hpp"

#include <cfloat>
#include <cmath>
#include <limits>

#include "Math/Vec.hpp"
#include "MathTestUtil.hpp"

using namespace sr;

TEST_CASE("cross product follows the right-hand rule", "[math][vec]") {
    CHECK(cross(Vec3(1, 0, 0), Vec3(0, 1, 0)) == Vec3(0, 0, 1));
    CHECK(cross(Vec3(0, 1, 0), Vec3(0, 0, 1)) == Vec3(1, 0, 0));
    CHECK(cross(Vec3(2, 3, 4), Vec3(5, 6, 7)) == Vec3(3 * 7 - 4 * 6, 4 * 5 - 2 * 7, 2 * 6 - 3 * 5));
}

TEST_CASE("normalize of zero, denormal and huge vectors", "[math][vec]") {
    CHECK(normalize(Vec3(0, 0, 0)) == Vec3(0, 0, 0));
    const float denorm = std::numeric_limits<float>::denorm_min() * 8.0f;
    const Vec3 d = normalize(Vec3(denorm, 0, denorm));
    CHECK(d.x == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(d.z == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    const Vec3 h = normalize(Vec3(1e30f, -1e30f, 0));
    CHECK(h.x == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(h.y == Approx(-std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(length(Vec3(3e30f, 4e30f, 0)) == Approx(5e30f).epsilon(1e-6));
}

TEST_CASE("normalize and length at the extremes of float, all vector sizes", "[math][vec]") {
    const float dmin = std::numeric_limits<float>::denorm_min();
    // The smallest denormal: x * x would be 0 in float, the scaled computation is exact.
    CHECK(length(Vec3(dmin, 0, 0)) == dmin);
    CHECK(normalize(Vec3(0, -dmin, 0)) == Vec3(0, -1, 0));
    CHECK(normalize(Vec2(dmin, dmin)).x == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    // Components near FLT_MAX: x * x would overflow to Inf.
    const float big = std::numeric_limits<float>::max();
    const Vec3 n = normalize(Vec3(big, big, big));
    CHECK(n.x == Approx(1.0 / std::sqrt(3.0)).epsilon(1e-6));
    CHECK(length(n) == Approx(1.0).epsilon(1e-6));
    CHECK(length(Vec3(big, 0, 0)) == big);
    CHECK(std::isinf(length(Vec3(big, big, 0)))); // the true length exceeds FLT_MAX: Inf, not NaN
    // 1e30 in every component of a Vec4.
    const Vec4 h = normalize(Vec4(1e30f, 1e30f, 1e30f, 1e30f));
    CHECK(h.w == Approx(0.5).epsilon(1e-6));
    CHECK(length(Vec4(1e30f, 1e30f, 1e30f, 1e30f)) == Approx(2e30).epsilon(1e-6));
    // Zero stays zero for every size (the documented policy: callers check for it).
    CHECK(normalize(Vec2(0, 0)) == Vec2(0, 0));
    CHECK(normalize(Vec4(0, 0, 0, 0)) == Vec4(0, 0, 0, 0));
    CHECK(length(Vec3(0, 0, 0)) == 0.0f);
    // A random sample: unit length within 2 ULPs of 1 across 60 orders of magnitude.
    srtest::Rng rng(5);
    int bad = 0;
    for (int i = 0; i < 10000; ++i) {
        const float s = std::pow(10.0f, rng.uniform(-30.0f, 30.0f));
        const Vec3 v{rng.uniform(-1, 1) * s, rng.uniform(-1, 1) * s, rng.uniform(-1, 1) * s};
        if (v == Vec3(0, 0, 0)) continue;
        const Vec3 u = normalize(v);
        const double len = std::sqrt(double(u.x) * u.x + double(u.y) * u.y + double(u.z) * u.z);
        bad += !(std::fabs(len - 1.0) <= 2 * FLT_EPSILON);
    }
    CHECK(bad == 0);
}

TEST_CASE("normalize and length with Inf and NaN components", "[math][vec][nonfinite]") {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(normalize(Vec3(inf, 1, 0)) == Vec3(1, 0, 0));
    CHECK(normalize(Vec3(-inf, 5, 0)) == Vec3(-1, 0, 0));
    const Vec3 two = normalize(Vec3(inf, -inf, 3));
    CHECK(two.x == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(two.y == Approx(-std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(two.z == 0.0f);
    CHECK(std::isinf(length(Vec3(0, -inf, 0))));
    const Vec3 q = normalize(Vec3(nan, 1, 0));
    CHECK((std::isnan(q.x) && std::isnan(q.y) && std::isnan(q.z)));
    CHECK(std::isnan(normalize(Vec3(inf, nan, 0)).z)); // NaN wins over Inf
    CHECK(std::isnan(length(Vec3(1, nan, 0))));
    CHECK_FALSE(isFinite(Vec3(1, inf, 0)));
    CHECK(isFinite(Vec4(1, 2, 3, 4)));
    // Arithmetic propagates (IEEE): the pipeline, not the math, drops such vertices.
    CHECK(std::isnan(dot(Vec3(nan, 0, 0), Vec3(1, 1, 1))));
    CHECK(std::isnan(cross(Vec3(inf, 0, 0), Vec3(0, 0, 0)).y)); // inf * 0
}

TEST_CASE("lerp, clamp, min and max", "[math][vec]") {
    const Vec3 a(1, 2, 3), b(-4, 0.1f, 7);
    CHECK(lerp(a, b, 0.0f) == a); // both ends exact, even for inexact differences
    CHECK(lerp(a, b, 1.0f) == b);
    CHECK(lerp(a, b, 0.5f) == Vec3(-1.5f, 1.05f, 5.0f));
    CHECK(min(a, b) == Vec3(-4, 0.1f, 3));
    CHECK(max(a, b) == Vec3(1, 2, 7));
    CHECK(clamp(Vec3(-1, 0.5f, 9), Vec3(0), Vec3(1)) == Vec3(0, 0.5f, 1));
    CHECK(std::isnan(clamp(std::nanf(""), 0.0f, 1.0f))); // NaN is not clamped (documented)
    CHECK(dot(Vec4(1, 2, 3, 4), Vec4(5, 6, 7, 8)) == 70.0f);
    CHECK(cross(Vec2(1, 0), Vec2(0, 1)) == 1.0f);
}
