// Tests of the model and view transforms: translate, scale, rotate (Rodrigues) and lookAt.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>

#include "Math/Transform.hpp"
#include "MathTestUtil.hpp"

using namespace sr;
using srtest::kU;

namespace {

// cos(float(pi/2)) = -4.37e-8: a rotation by radians(90) differs from the exact quarter turn by
// that much in the entries that should be 0. One ULP of 1.0 (1.19e-7) bounds it.
constexpr float kQuarterTurnTol = FLT_EPSILON;

bool near3(Vec3 a, Vec3 b, float tol) {
    return std::fabs(a.x - b.x) <= tol && std::fabs(a.y - b.y) <= tol && std::fabs(a.z - b.z) <= tol;
}

// The 3x3 rotation part of m has orthonormal rows: |r_i . r_j - delta_ij| <= tol, computed in
// double from the float elements.
void checkOrthonormalRows(const Mat4& m, double tol) {
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            double d = 0.0;
            for (int k = 0; k < 3; ++k) d += static_cast<double>(m(i, k)) * m(j, k);
            INFO("rows " << i << ", " << j << ": dot " << d);
            CHECK(std::fabs(d - (i == j ? 1.0 : 0.0)) <= tol);
        }
    }
}

} // namespace

TEST_CASE("translate and scale: known values", "[math][transform]") {
    CHECK(transformPoint(translate({1, -2, 3}), {10, 20, 30}) == Vec3(11, 18, 33));
    CHECK(transformDirection(translate({1, -2, 3}), {10, 20, 30}) == Vec3(10, 20, 30));
    CHECK(transformPoint(scale({2, -3, 0.5f}), {1, 1, 4}) == Vec3(2, -3, 2));
    CHECK(scale({2, 3, 4})(3, 3) == 1.0f);
    CHECK(translate({0, 0, 0}) == Mat4::identity());
}

TEST_CASE("rotate by 90 degrees about each axis (right-hand rule), by hand", "[math][transform]") {
    const float q = radians(90.0f);
    // About +X: Y -> Z, Z -> -Y.
    CHECK(near3(transformDirection(rotate(q, {1, 0, 0}), {0, 1, 0}), {0, 0, 1}, kQuarterTurnTol));
    CHECK(near3(transformDirection(rotate(q, {1, 0, 0}), {0, 0, 1}), {0, -1, 0}, kQuarterTurnTol));
    CHECK(near3(transformDirection(rotate(q, {1, 0, 0}), {1, 0, 0}), {1, 0, 0}, 0.0f));
    // About +Y: Z -> X, X -> -Z.
    CHECK(near3(transformDirection(rotate(q, {0, 1, 0}), {0, 0, 1}), {1, 0, 0}, kQuarterTurnTol));
    CHECK(near3(transformDirection(rotate(q, {0, 1, 0}), {1, 0, 0}), {0, 0, -1}, kQuarterTurnTol));
    // About +Z: X -> Y, Y -> -X.
    CHECK(near3(transformDirection(rotate(q, {0, 0, 1}), {1, 0, 0}), {0, 1, 0}, kQuarterTurnTol));
    CHECK(near3(transformDirection(rotate(q, {0, 0, 1}), {0, 1, 0}), {-1, 0, 0}, kQuarterTurnTol));
    // The full matrix about +Z: rows (0,-1,0), (1,0,0), (0,0,1).
    const Mat4 rz = rotate(q, {0, 0, 1});
    CHECK(rz(0, 1) == -1.0f);
    CHECK(rz(1, 0) == 1.0f);
    CHECK(std::fabs(rz(0, 0)) <= kQuarterTurnTol);
    CHECK(rz(2, 2) == 1.0f);
    CHECK(rz.row(3) == Vec4(0, 0, 0, 1));
    CHECK(rz.column(3) == Vec4(0, 0, 0, 1));
}

TEST_CASE("rotate: a third of a turn about (1,1,1) cycles the axes; axis length is irrelevant", "[math][transform]") {
    const Mat4 r = rotate(radians(120.0f), {1, 1, 1});
    CHECK(near3(transformDirection(r, {1, 0, 0}), {0, 1, 0}, 2 * FLT_EPSILON));
    CHECK(near3(transformDirection(r, {0, 1, 0}), {0, 0, 1}, 2 * FLT_EPSILON));
    CHECK(near3(transformDirection(r, {0, 0, 1}), {1, 0, 0}, 2 * FLT_EPSILON));
    CHECK(rotate(0.7f, {0, 0, 5}) == rotate(0.7f, {0, 0, 1}));
    CHECK(srtest::maxAbsDiff(rotate(0.7f, {2e-30f, 4e-30f, 0}), rotate(0.7f, {1, 2, 0})) <= kU);
    CHECK(srtest::maxAbsDiff(rotate(0.7f, {2e30f, 4e30f, 0}), rotate(0.7f, {1, 2, 0})) <= kU);
}

TEST_CASE("rotate: orthonormal, determinant 1, composes and inverts", "[math][transform]") {
    srtest::Rng rng(2024);
    for (int i = 0; i < 100; ++i) {
        const Vec3 axis{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        const float a = rng.uniform(-6.3f, 6.3f), b = rng.uniform(-3, 3);
        const Mat4 r = rotate(a, axis);
        // Each element is the double value rounded once, so dot products are off by <= 3 * 2u.
        checkOrthonormalRows(r, 6 * kU);
        CHECK(determinant(r) == Approx(1.0).epsilon(4 * kU));
        CHECK(srtest::maxAbsDiff(rotate(a, axis) * rotate(b, axis), rotate(a + b, axis)) <= 1e-6);
        CHECK(srtest::maxAbsDiff(rotate(a, axis) * rotate(-a, axis), Mat4::identity()) <= 1e-6);
        // The axis itself is fixed.
        const Vec3 k = normalize(axis);
        CHECK(near3(transformDirection(r, k), k, 4 * FLT_EPSILON));
    }
}

TEST_CASE("rotate: every element within 1 ULP of Rodrigues in long double, small angles included", "[math][transform]") {
    // The reference evaluates R = cos I + sin [k]x + (1 - cos) k k^T directly in long double (at
    // least double precision). Elements that are O(angle) and the (1 - cos) term of size angle^2
    // must stay accurate for angles down to 1e-6 rad: a float cos would lose them entirely.
    srtest::Rng rng(8);
    int worst = 0;
    for (int i = 0; i < 300; ++i) {
        const float angle = (i % 2 ? 1.0f : -1.0f) * std::pow(10.0f, rng.uniform(-6.0f, 0.5f));
        const Vec3 axis{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        const Mat4 r = rotate(angle, axis);
        const long double len = std::sqrt((long double)axis.x * axis.x + (long double)axis.y * axis.y +
                                          (long double)axis.z * axis.z);
        const long double k[3] = {axis.x / len, axis.y / len, axis.z / len};
        const long double c = std::cos((long double)angle), s = std::sin((long double)angle);
        for (int row = 0; row < 3; ++row) {
            for (int col = 0; col < 3; ++col) {
                long double ref = (1 - c) * k[row] * k[col] + (row == col ? c : 0.0L);
                const int e = 3 - row - col; // index of the third axis for the [k]x term
                if (row != col) ref += ((col - row + 3) % 3 == 1 ? -1 : 1) * s * k[e];
                worst = std::max(worst, static_cast<int>(srtest::ulpDistance(r(row, col), static_cast<float>(ref))));
            }
        }
    }
    CHECK(worst <= 1);
}

TEST_CASE("rotate: zero axis is the identity; non-finite input propagates", "[math][transform][nonfinite]") {
    CHECK(rotate(1.0f, {0, 0, 0}) == Mat4::identity());
    CHECK(rotate(0.0f, {1, 2, 3}) == Mat4::identity());
    CHECK_FALSE(isFinite(rotate(std::nanf(""), {0, 1, 0})));
    CHECK_FALSE(isFinite(rotate(HUGE_VALF, {0, 1, 0})));
    CHECK_FALSE(isFinite(rotate(1.0f, {std::nanf(""), 1, 0})));
    CHECK_FALSE(isFinite(rotate(1.0f, {HUGE_VALF, 1, 0})));
}

TEST_CASE("lookAt at known poses, computed by hand", "[math][transform][lookat]") {
    // From +Z towards the origin: the view is a translation by -5 along Z.
    const Mat4 v = lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    CHECK(v == translate({0, 0, -5}));
    CHECK(transformPoint(v, {0, 0, 0}) == Vec3(0, 0, -5)); // in front: negative view z

    // From (1,2,3) looking along +X, up +Y: side = +X x +Y = +Z, rows (0,0,1), (0,1,0), (-1,0,0).
    const Mat4 w = lookAt({1, 2, 3}, {4, 2, 3}, {0, 1, 0});
    CHECK(w.row(0) == Vec4(0, 0, 1, -3));
    CHECK(w.row(1) == Vec4(0, 1, 0, -2));
    CHECK(w.row(2) == Vec4(-1, 0, 0, 1));
    CHECK(w.row(3) == Vec4(0, 0, 0, 1));
    CHECK(transformPoint(w, {3, 2, 3}) == Vec3(0, 0, -2)); // 2 units ahead
    CHECK(transformPoint(w, {1, 2, 4}) == Vec3(1, 0, 0));  // +Z world is to the right
    CHECK(transformPoint(w, {1, 3, 3}) == Vec3(0, 1, 0));  // up stays up

    // Only the part of up orthogonal to the view matters: up = (1, 1, 0) acts as (0, 1, 0) here.
    CHECK(lookAt({1, 2, 3}, {4, 2, 3}, {1, 1, 0}) == w);
    // A camera at 45 degrees: eye (1,0,1) looking at the origin.
    const Mat4 d = lookAt({1, 0, 1}, {0, 0, 0}, {0, 1, 0});
    const float h = std::sqrt(0.5f);
    CHECK(srtest::maxAbsDiff(d, Mat4::fromRows({h, 0, -h, 0, 0, 1, 0, 0, h, 0, h, -std::sqrt(2.0f), 0, 0, 0, 1})) <=
          FLT_EPSILON);
}

TEST_CASE("lookAt rows are orthonormal within 2 ULPs of 1 and the eye maps to the origin", "[math][transform][lookat]") {
    srtest::Rng rng(77);
    for (int i = 0; i < 500; ++i) {
        const Vec3 eye{rng.uniform(-1e3f, 1e3f), rng.uniform(-1e3f, 1e3f), rng.uniform(-1e3f, 1e3f)};
        const Vec3 target{rng.uniform(-1e3f, 1e3f), rng.uniform(-1e3f, 1e3f), rng.uniform(-1e3f, 1e3f)};
        const Vec3 up{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        const Mat4 v = lookAt(eye, target, up);
        REQUIRE(isFinite(v));
        // Each element is its double value rounded once (relative error <= u): 2u = 1 ULP of 1.0
        // per dot product, plus double-precision noise.
        checkOrthonormalRows(v, 2 * FLT_EPSILON);
        CHECK(determinant(v) == Approx(1.0).epsilon(4 * FLT_EPSILON)); // right-handed, no mirror
        // The eye maps to the origin up to the float rounding of the translation column and of
        // the float matrix-vector product: a few u per term of |eye|, bounded by 6u sum|eye_k|.
        const Vec3 e = transformPoint(v, eye);
        CHECK(length(e) <= 6.0f * FLT_EPSILON * (std::fabs(eye.x) + std::fabs(eye.y) + std::fabs(eye.z)));
        const Vec3 t = transformPoint(v, target);
        CHECK(t.z < 0.0f); // the target is in front (-Z)
        CHECK(std::fabs(t.x) <= 1e-3f);
        CHECK(std::fabs(t.y) <= 1e-3f);
        // The up vector projects to the upper half of the view (+Y), never below.
        CHECK(transformDirection(v, up).y >= 0.0f);
    }
}

TEST_CASE("lookAt fallbacks: up parallel to the view, zero up, eye == target", "[math][transform][lookat]") {
    // Looking straight down with up = +Y: up falls back to -Z (default camera pitched down).
    const Mat4 down = lookAt({0, 10, 0}, {0, 0, 0}, {0, 1, 0});
    CHECK(down.row(0) == Vec4(1, 0, 0, 0));
    CHECK(down.row(1) == Vec4(0, 0, -1, 0));
    CHECK(down.row(2) == Vec4(0, 1, 0, -10));
    // Looking straight up: up falls back to +Z.
    const Mat4 upward = lookAt({0, 0, 0}, {0, 5, 0}, {0, -3, 0});
    CHECK(upward.row(0) == Vec4(1, 0, 0, 0));
    CHECK(upward.row(1) == Vec4(0, 0, 1, 0));
    CHECK(upward.row(2) == Vec4(0, -1, 0, 0));
    // Up parallel to a horizontal view direction: +Y is used.
    CHECK(lookAt({1, 2, 3}, {4, 2, 3}, {7, 0, 0}) == lookAt({1, 2, 3}, {4, 2, 3}, {0, 1, 0}));
    // Zero up: same fallback.
    CHECK(lookAt({1, 2, 3}, {4, 2, 3}, {0, 0, 0}) == lookAt({1, 2, 3}, {4, 2, 3}, {0, 1, 0}));
    // Nearly parallel (sine 1e-7 <= 1e-6): fallback; clearly not (sine 1e-4): the given up rules.
    CHECK(lookAt({0, 10, 0}, {0, 0, 0}, {0, 1, 1e-7f}) == down);
    const Mat4 tilted = lookAt({0, 10, 0}, {0, 0, 0}, {1e-4f, 1, 0});
    checkOrthonormalRows(tilted, 2 * FLT_EPSILON);
    CHECK(tilted.row(1).x > 0.99f); // screen-up follows the given up's +X component
    // eye == target: forward is -Z; with up +Y the rotation is the identity.
    const Mat4 same = lookAt({1, 2, 3}, {1, 2, 3}, {0, 1, 0});
    CHECK(same == translate({-1, -2, -3}));
    // eye == target and up along Z: both fallbacks at once, still orthonormal and finite.
    const Mat4 both = lookAt({1, 2, 3}, {1, 2, 3}, {0, 0, 1});
    REQUIRE(isFinite(both));
    checkOrthonormalRows(both, 2 * FLT_EPSILON);
    // Huge and tiny distances are fine: computed in double.
    checkOrthonormalRows(lookAt({1e30f, 0, 0}, {-1e30f, 1e25f, 0}, {0, 1, 0}), 2 * FLT_EPSILON);
    checkOrthonormalRows(lookAt({1e-30f, 0, 0}, {0, 1e-38f, 0}, {0, 0, 1}), 2 * FLT_EPSILON);
}

TEST_CASE("lookAt with non-finite input returns an all-NaN matrix", "[math][transform][lookat][nonfinite]") {
    const float nan = std::nanf("");
    for (const Mat4& m : {lookAt({nan, 0, 0}, {0, 0, -1}, {0, 1, 0}), lookAt({0, 0, 0}, {0, HUGE_VALF, -1}, {0, 1, 0}),
                          lookAt({0, 0, 0}, {0, 0, -1}, {0, -HUGE_VALF, 0})}) {
        for (float v : m.m) CHECK(std::isnan(v));
    }
}
