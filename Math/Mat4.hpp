// Mat4: a 4x4 float matrix in COLUMN-MAJOR storage (m[c * 4 + r]) acting on column vectors.
#pragma once

#include <cassert>
#include <optional>

#include "Vec.hpp"

namespace sr {

// Element (row r, column c) is m[c * 4 + r] (see Conventions.hpp): the four columns are the
// contiguous runs m[0..3], m[4..7], m[8..11], m[12..15]; an affine matrix keeps its translation
// in m[12], m[13], m[14]. A default-constructed Mat4 is all zeros; use identity() for I.
struct Mat4 {
    float m[16] = {};

    static constexpr Mat4 identity() {
        Mat4 r;
        r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
        return r;
    }
    // Built from 16 values written in reading order (row by row), as matrices appear on paper.
    static constexpr Mat4 fromRows(const float (&rowMajor)[16]) {
        Mat4 r;
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) r.m[col * 4 + row] = rowMajor[row * 4 + col];
        return r;
    }
    static constexpr Mat4 fromColumns(Vec4 c0, Vec4 c1, Vec4 c2, Vec4 c3) {
        Mat4 r;
        const Vec4 cols[4] = {c0, c1, c2, c3};
        for (int col = 0; col < 4; ++col)
            for (int row = 0; row < 4; ++row) r.m[col * 4 + row] = cols[col][row];
        return r;
    }

    constexpr float operator()(int r, int c) const {
        assert(r >= 0 && r < 4 && c >= 0 && c < 4);
        return m[c * 4 + r];
    }
    constexpr float& operator()(int r, int c) {
        assert(r >= 0 && r < 4 && c >= 0 && c < 4);
        return m[c * 4 + r];
    }

    constexpr Vec4 column(int c) const {
        assert(c >= 0 && c < 4);
        return {m[c * 4 + 0], m[c * 4 + 1], m[c * 4 + 2], m[c * 4 + 3]};
    }
    constexpr Vec4 row(int r) const {
        assert(r >= 0 && r < 4);
        return {m[r], m[4 + r], m[8 + r], m[12 + r]};
    }
};

// --- Products ---------------------------------------------------------------------------------
// (A * B)(r, c) = sum_k A(r, k) B(k, c); with column vectors, (A * B) * v applies B first.
Mat4 operator*(const Mat4& a, const Mat4& b);
// M * v for a column vector v, in float (each component is a 4-term dot product of a row and v,
// summed left to right). Inline: the vertex stage calls it per vertex, and out of line the call
// and the reloaded matrix cost the bunny's frame about 5%.
inline Vec4 operator*(const Mat4& a, Vec4 v) {
    const float* m = a.m;
    return {m[0] * v.x + m[4] * v.y + m[8] * v.z + m[12] * v.w,
            m[1] * v.x + m[5] * v.y + m[9] * v.z + m[13] * v.w,
            m[2] * v.x + m[6] * v.y + m[10] * v.z + m[14] * v.w,
            m[3] * v.x + m[7] * v.y + m[11] * v.z + m[15] * v.w};
}

bool operator==(const Mat4& a, const Mat4& b); // exact, element by element (NaN != NaN)
inline bool operator!=(const Mat4& a, const Mat4& b) { return !(a == b); }

Mat4 transpose(const Mat4& a);
bool isFinite(const Mat4& a); // true when all 16 elements are finite

// Determinant, computed in double from the float elements (Laplace expansion in 2x2 minors,
// see inverse()) and rounded to float: +-Inf when it exceeds FLT_MAX, NaN for NaN input.
// A negative determinant means the matrix mirrors: it turns CCW triangles into CW ones.
float determinant(const Mat4& a);

// --- Inverses ---------------------------------------------------------------------------------
// inverse(a): the general 4x4 inverse, computed in double as adjugate / determinant (the
// Laplace expansion by complementary 2x2 minors of rows 0-1 and 2-3, as in Eberly, "The
// Laplace Expansion Theorem: Computing the Determinants and Inverses of Matrices", 2008), then
// rounded to float. It is EMPTY when:
//  - any element of a is NaN or +-Inf;
//  - a is singular within the rounding of its own float elements: |det| <= 4u * perm(|a|),
//    with u = 2^-24 and perm(|a|) the permanent of the element-wise absolute values. To first
//    order, rounding every element by a relative u moves det by at most n*u*perm(|a|) (expand
//    d(det) = sum_ij C_ij da_ij with |C_ij| <= perm of the minor), so a smaller |det| is
//    indistinguishable from 0 given float input. The test is relative (invariant to scaling any
//    row or column, so scale(1e-30) and scale(1e30) both invert) and, unlike |det| / ||a||^4, it
//    does not reject affine matrices with large translations (perm = det for those);
//  - some element of the inverse overflows float (e.g. scale(1e-39), whose inverse 1e39 > FLT_MAX).
// The test only knows the rounding of the elements themselves: a matrix whose elements carry larger
// errors from how they were computed (e.g. a projection onto a plane, I - n n^T, built in float)
// can pass it and come back with a finite but huge inverse. Do not invert such matrices.
// Precision: each element of the result is the correctly computed double value rounded to float,
// so a * inverse(a) = I within about 2u * (|a| |inverse(a)|)_ij per element (the tests check it).
std::optional<Mat4> inverse(const Mat4& a);

// affineInverse(a) for a = [L t; 0 0 0 1] (rotation, scale, shear + translation): returns
// [L^-1, -L^-1 t; 0 0 0 1], with L^-1 computed in double by the 3x3 adjugate. EMPTY when the
// bottom row is not exactly (0, 0, 0, 1) (not affine: use inverse()), when any element is not
// finite, when L is singular by the 3x3 version of the test above (|det L| <= 3u * perm(|L|)), or
// when the result overflows float. The bottom row of the result is exactly (0, 0, 0, 1).
std::optional<Mat4> affineInverse(const Mat4& a);

// The matrix that transforms normals of geometry transformed by the affine matrix a: the
// inverse transpose of its linear part L (no translation; bottom row and last column (0,0,0,1)).
// Apply it with transformDirection() and renormalise. Empty when affineInverse(a) is empty.
std::optional<Mat4> normalMatrix(const Mat4& a);

// --- Applying a matrix to points and directions -----------------------------------------------
// transformPoint: p' = M * (p, 1). If the resulting w is exactly 1 (every affine matrix), p' is its
// xyz; otherwise xyz / w (the projective point, as pbrt's Transform::operator()(Point3) does),
// which is +-Inf or NaN when w == 0 (IEEE semantics, see Conventions.hpp).
Vec3 transformPoint(const Mat4& a, Vec3 p);
// transformDirection: d' = upper-left 3x3 of M times d (w = 0: translation does not apply).
Vec3 transformDirection(const Mat4& a, Vec3 d);

} // namespace sr
