// Tests of Mat4: storage order, products, determinant, and the general / affine inverses at the extremes.
#include "TestFramework.hpp"

#include <cmath>
#include <limits>

#include "Math/Mat4.hpp"
#include "Math/Transform.hpp"
#include "MathTestUtil.hpp"

using namespace sr;
using srtest::kU;

namespace {

// Checks a * inv == I element by element, with the product taken in double so that only the
// error of `inv` is measured. Bound: inv is the exact inverse X with each element rounded to float
// (relative error <= u), so (a * inv - I)_ij = (a E)_ij with |E| <= u |X|, i.e.
// |(a * inv - I)_ij| <= u (|a| |inv|)_ij. We allow 2u (the double computation adds ~cond * 1e-16).
void checkInverseResidual(const Mat4& a, const Mat4& inv) {
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
            double p = 0.0, bound = 0.0;
            for (int k = 0; k < 4; ++k) {
                p += static_cast<double>(a(r, k)) * inv(k, c);
                bound += std::fabs(static_cast<double>(a(r, k)) * inv(k, c));
            }
            const double err = std::fabs(p - (r == c ? 1.0 : 0.0));
            INFO("element (" << r << ", " << c << "): error " << err << ", bound " << 2 * kU * bound);
            CHECK(err <= 2.0 * kU * bound);
        }
    }
}

Mat4 randomMatrix(srtest::Rng& rng) {
    Mat4 m;
    for (float& v : m.m) v = rng.uniform(-1.0f, 1.0f);
    for (int i = 0; i < 4; ++i) m(i, i) += 3.0f; // diagonally dominant: well conditioned
    return m;
}

} // namespace

TEST_CASE("Mat4 stores column-major: element (r, c) is m[c*4 + r]", "[math][mat4]") {
    const Mat4 a = Mat4::fromRows({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16});
    CHECK(a.m[0] == 1); // (0,0)
    CHECK(a.m[1] == 5); // (1,0): the first column is contiguous
    CHECK(a.m[4] == 2); // (0,1)
    CHECK(a(2, 3) == 12);
    CHECK(a.m[3 * 4 + 2] == 12);
    CHECK(a.row(1) == Vec4(5, 6, 7, 8));
    CHECK(a.column(1) == Vec4(2, 6, 10, 14));
    CHECK(Mat4::fromColumns(a.column(0), a.column(1), a.column(2), a.column(3)) == a);
    Mat4 b = a;
    b(3, 0) = -1;
    CHECK(b.m[3] == -1);
    CHECK(transpose(a)(2, 3) == 15);
    CHECK(transpose(transpose(a)) == a);

    // The translation of an affine matrix lives in m[12], m[13], m[14].
    const Mat4 t = translate({7, 8, 9});
    CHECK(t.m[12] == 7);
    CHECK(t.m[13] == 8);
    CHECK(t.m[14] == 9);
    CHECK(Mat4{}.m[15] == 0); // default is all zeros
    CHECK(Mat4::identity()(3, 3) == 1);
}

TEST_CASE("Mat4 products follow column-vector order (A * B applies B first)", "[math][mat4]") {
    const Mat4 a = Mat4::fromRows({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16});
    const Mat4 b = Mat4::fromRows({2, 0, 1, 0, 0, 1, 0, 3, 1, 0, 0, 0, 0, 2, 0, 1});
    // Computed by hand: row 0 of a times the columns of b.
    const Mat4 ab = a * b;
    CHECK(ab(0, 0) == 1 * 2 + 3 * 1);
    CHECK(ab(0, 1) == 2 * 1 + 4 * 2);
    CHECK(ab(0, 2) == 1 * 1);
    CHECK(ab(0, 3) == 2 * 3 + 4 * 1);
    CHECK(ab(3, 3) == 14 * 3 + 16);
    CHECK(a * Mat4::identity() == a);
    CHECK(Mat4::identity() * a == a);
    CHECK(a * Vec4(1, 0, 0, 0) == a.column(0));
    CHECK(a * Vec4(1, 1, 1, 1) == Vec4(10, 26, 42, 58));

    // translate * scale scales first, then translates.
    const Mat4 ts = translate({10, 0, 0}) * scale({2, 2, 2});
    CHECK(transformPoint(ts, {1, 1, 1}) == Vec3(12, 2, 2));
    CHECK(transformPoint(scale({2, 2, 2}) * translate({10, 0, 0}), {1, 1, 1}) == Vec3(22, 2, 2));
    CHECK(transformDirection(ts, {1, 1, 1}) == Vec3(2, 2, 2)); // no translation for directions
}

TEST_CASE("transformPoint divides by w only for projective matrices", "[math][mat4]") {
    Mat4 p = Mat4::identity();
    p(3, 2) = -1.0f; // w = -z
    p(3, 3) = 0.0f;
    CHECK(transformPoint(p, {2, 4, -2}) == Vec3(1, 2, -1));
    const Vec3 atW0 = transformPoint(p, {1, 1, 0}); // w == 0: IEEE division, documented
    CHECK(std::isinf(atW0.x));
}

TEST_CASE("determinant: known values, mirrors are negative, computed in double", "[math][mat4]") {
    CHECK(determinant(Mat4::identity()) == 1.0f);
    CHECK(determinant(scale({2, 3, 4})) == 24.0f);
    CHECK(determinant(scale({-1, 1, 1})) == -1.0f);
    CHECK(determinant(Mat4::fromRows({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16})) == 0.0f);
    // 1e-30^3 underflows float products but not the double computation: rounds to 0 only at the end.
    CHECK(determinant(scale({1e-12f, 1e-12f, 1e-12f})) == Approx(1e-36).epsilon(1e-6));
    CHECK(determinant(scale({1e20f, 1e20f, 1e20f})) == HUGE_VALF); // 1e60 > FLT_MAX
}

TEST_CASE("inverse: M * inverse(M) = I within 2u (|M| |inverse(M)|) per element", "[math][mat4]") {
    srtest::Rng rng(12345);
    for (int i = 0; i < 200; ++i) {
        const Mat4 m = randomMatrix(rng);
        const std::optional<Mat4> inv = inverse(m);
        REQUIRE(inv.has_value());
        checkInverseResidual(m, *inv);
    }
    // A hand-computed inverse: [[2,0,0,1],[0,4,0,2],[0,0,8,3],[0,0,0,1]].
    const Mat4 m = Mat4::fromRows({2, 0, 0, 1, 0, 4, 0, 2, 0, 0, 8, 3, 0, 0, 0, 1});
    const Mat4 expected = Mat4::fromRows({0.5f, 0, 0, -0.5f, 0, 0.25f, 0, -0.5f, 0, 0, 0.125f, -0.375f, 0, 0, 0, 1});
    CHECK(inverse(m) == expected);
    CHECK(affineInverse(m) == expected);
    // A projective matrix: the reversed-Z perspective inverts (unprojection), both directions.
    const Mat4 p = perspective(1.0f, 1.5f, 0.1f, 100.0f);
    REQUIRE(inverse(p).has_value());
    checkInverseResidual(p, *inverse(p));
    checkInverseResidual(*inverse(p), p);
}

TEST_CASE("inverse: singular matrices give an empty optional", "[math][mat4]") {
    CHECK_FALSE(inverse(Mat4{}).has_value()); // zero matrix
    CHECK_FALSE(inverse(scale({1, 0, 1})).has_value());
    // Rank 2 in exact arithmetic; the double-precision determinant need not come out as exactly 0.
    CHECK_FALSE(inverse(Mat4::fromRows({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16})).has_value());
    // Row 3 = 2 * row 0 exactly (random floats): singular in exact arithmetic, although the
    // double-precision expansion of such a matrix need not produce a determinant of exactly 0.
    srtest::Rng rng(7);
    for (int i = 0; i < 50; ++i) {
        Mat4 r = randomMatrix(rng);
        for (int c = 0; c < 4; ++c) r(3, c) = 2.0f * r(0, c);
        CHECK_FALSE(inverse(r).has_value());
    }
    // One ULP away from exact singularity is still singular at float precision...
    Mat4 s = scale({1, 1, 1});
    s(0, 1) = 1.0f; // rows 0 and 1 now (1,1,0,0) and (0,1,0,0): fine
    s(1, 0) = 1.0f; // (1,1,0,0) twice: singular
    CHECK_FALSE(inverse(s).has_value());
    s(1, 0) = std::nextafter(1.0f, 2.0f); // det = -1.19e-7, |det| / perm = 6e-8 < 4u
    CHECK_FALSE(inverse(s).has_value());
    CHECK_FALSE(affineInverse(s).has_value());
    // ...while a relative perturbation of 1e-3 is invertible, with the stated accuracy.
    s(1, 0) = 1.001f;
    REQUIRE(inverse(s).has_value());
    checkInverseResidual(s, *inverse(s));
}

TEST_CASE("inverse: the singularity test is relative, not an absolute epsilon", "[math][mat4]") {
    // scale(1e-30): det = 1e-90, far below any absolute epsilon, yet exactly invertible.
    const std::optional<Mat4> tiny = inverse(scale({1e-30f, 1e-30f, 1e-30f}));
    REQUIRE(tiny.has_value());
    CHECK(srtest::ulpDistance((*tiny)(0, 0), 1e30f) <= 1);
    CHECK(srtest::ulpDistance((*tiny)(2, 2), 1e30f) <= 1);
    CHECK((*tiny)(3, 3) == 1.0f);
    // A single tiny axis: the matrix is not near-singular relative to its own columns.
    const std::optional<Mat4> oneAxis = affineInverse(scale({1e-30f, 1, 1}));
    REQUIRE(oneAxis.has_value());
    CHECK(srtest::ulpDistance((*oneAxis)(0, 0), 1e30f) <= 1);
    // Huge scales invert to tiny ones, still finite and normal.
    const std::optional<Mat4> huge = inverse(scale({1e30f, 1e30f, 1e30f}));
    REQUIRE(huge.has_value());
    CHECK(srtest::ulpDistance((*huge)(1, 1), 1e-30f) <= 1);
    // Large translations do not make a matrix "nearly singular" (an |det| / ||M||^4 test would
    // reject this one: det = 1, ||M||^4 = 1e28).
    const Mat4 far = translate({1e7f, -3e6f, 2.5e6f}) * rotate(0.5f, {0, 1, 0});
    const std::optional<Mat4> farInv = inverse(far);
    REQUIRE(farInv.has_value());
    checkInverseResidual(far, *farInv);
    // scale(1e-39): denormal input, its inverse 1e39 exceeds FLT_MAX -> empty, not Inf elements.
    CHECK_FALSE(inverse(scale({1e-39f, 1e-39f, 1e-39f})).has_value());
    CHECK_FALSE(affineInverse(scale({1e-39f, 1, 1})).has_value());
}

TEST_CASE("affineInverse matches inverse on affine matrices and rejects the rest", "[math][mat4]") {
    srtest::Rng rng(99);
    for (int i = 0; i < 100; ++i) {
        const Mat4 m = translate({rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100)}) *
                       rotate(rng.uniform(-3, 3), {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}) *
                       scale({rng.uniform(0.1f, 10), rng.uniform(0.1f, 10), rng.uniform(0.1f, 10)});
        const std::optional<Mat4> a = affineInverse(m), g = inverse(m);
        REQUIRE(a.has_value());
        REQUIRE(g.has_value());
        checkInverseResidual(m, *a);
        CHECK((*a).row(3) == Vec4(0, 0, 0, 1)); // exactly affine
        CHECK(srtest::maxAbsDiff(*a, *g) <= 1e-4);
    }
    CHECK_FALSE(affineInverse(perspective(1.0f, 1.0f, 0.1f, 10.0f)).has_value()); // not affine
    Mat4 almost = Mat4::identity();
    almost(3, 3) = 2.0f;
    CHECK_FALSE(affineInverse(almost).has_value());
    CHECK(inverse(almost).has_value());
}

TEST_CASE("normalMatrix keeps transformed normals perpendicular to transformed surfaces", "[math][mat4]") {
    const Mat4 m = translate({5, 6, 7}) * rotate(0.3f, {1, 2, 3}) * scale({1, 4, 0.25f});
    const std::optional<Mat4> n = normalMatrix(m);
    REQUIRE(n.has_value());
    CHECK((*n).row(3) == Vec4(0, 0, 0, 1));
    CHECK((*n).column(3) == Vec4(0, 0, 0, 1));
    // The plane x + y + z = 0 has tangents (1,-1,0), (0,1,-1) and normal (1,1,1).
    const Vec3 t1 = transformDirection(m, {1, -1, 0}), t2 = transformDirection(m, {0, 1, -1});
    const Vec3 nn = normalize(transformDirection(*n, {1, 1, 1}));
    CHECK(std::fabs(dot(nn, normalize(t1))) <= 1e-6);
    CHECK(std::fabs(dot(nn, normalize(t2))) <= 1e-6);
    CHECK_FALSE(normalMatrix(scale({1, 0, 1})).has_value());
}
