// Mat4 products, transpose, determinant and the double-precision general and affine inverses.
#include "Mat4.hpp"

#include <cfloat>
#include <cmath>
#include <limits>

namespace sr {
namespace {

// Unit roundoff of float (half an ULP of 1.0): the largest relative error of rounding to float.
constexpr double kFloatUnitRoundoff = 1.0 / 16777216.0; // 2^-24

// The element (r, c) of a, widened to double. Products of two such values are exact in double
// (24 + 24 significant bits < 53), which is why the 2x2 minors below lose almost nothing.
inline double el(const Mat4& a, int r, int c) { return static_cast<double>(a.m[c * 4 + r]); }

// Rounds a double to float, refusing values beyond FLT_MAX (converting those is undefined
// behaviour in C++, and an Inf element would poison every later use of the matrix).
inline bool toFloatChecked(double v, float& out) {
    if (!(std::fabs(v) <= static_cast<double>(FLT_MAX))) return false; // also rejects NaN
    out = static_cast<float>(v);
    return true;
}

// Determinant and adjugate of a 4x4 matrix via the Laplace expansion theorem by complementary
// 2x2 minors (Eberly 2008, section 2): s_i are the six 2x2 minors of rows 0-1, c_i those of
// rows 2-3, det = s0 c5 - s1 c4 + s2 c3 + s3 c2 - s4 c1 + s5 c0. The same expansion with
// absolute values and + everywhere gives the permanent of |a| (the permanent obeys the same
// Laplace expansion, without signs), used as the scale of the singularity test.
struct Expansion4 {
    double det = 0.0;
    double perm = 0.0;   // permanent of |a|, >= |det|
    double adj[4][4]{};  // adj[r][c]: the adjugate, so inverse = adj / det
};

Expansion4 expand4(const Mat4& m) {
    double a[4][4];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) a[r][c] = el(m, r, c);

    const double s0 = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    const double s1 = a[0][0] * a[1][2] - a[0][2] * a[1][0];
    const double s2 = a[0][0] * a[1][3] - a[0][3] * a[1][0];
    const double s3 = a[0][1] * a[1][2] - a[0][2] * a[1][1];
    const double s4 = a[0][1] * a[1][3] - a[0][3] * a[1][1];
    const double s5 = a[0][2] * a[1][3] - a[0][3] * a[1][2];
    const double c5 = a[2][2] * a[3][3] - a[2][3] * a[3][2];
    const double c4 = a[2][1] * a[3][3] - a[2][3] * a[3][1];
    const double c3 = a[2][1] * a[3][2] - a[2][2] * a[3][1];
    const double c2 = a[2][0] * a[3][3] - a[2][3] * a[3][0];
    const double c1 = a[2][0] * a[3][2] - a[2][2] * a[3][0];
    const double c0 = a[2][0] * a[3][1] - a[2][1] * a[3][0];

    Expansion4 e;
    e.det = s0 * c5 - s1 * c4 + s2 * c3 + s3 * c2 - s4 * c1 + s5 * c0;

    // Permanent of |a| by the same expansion.
    double b[4][4];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) b[r][c] = std::fabs(a[r][c]);
    const double p0 = b[0][0] * b[1][1] + b[0][1] * b[1][0];
    const double p1 = b[0][0] * b[1][2] + b[0][2] * b[1][0];
    const double p2 = b[0][0] * b[1][3] + b[0][3] * b[1][0];
    const double p3 = b[0][1] * b[1][2] + b[0][2] * b[1][1];
    const double p4 = b[0][1] * b[1][3] + b[0][3] * b[1][1];
    const double p5 = b[0][2] * b[1][3] + b[0][3] * b[1][2];
    const double q5 = b[2][2] * b[3][3] + b[2][3] * b[3][2];
    const double q4 = b[2][1] * b[3][3] + b[2][3] * b[3][1];
    const double q3 = b[2][1] * b[3][2] + b[2][2] * b[3][1];
    const double q2 = b[2][0] * b[3][3] + b[2][3] * b[3][0];
    const double q1 = b[2][0] * b[3][2] + b[2][2] * b[3][0];
    const double q0 = b[2][0] * b[3][1] + b[2][1] * b[3][0];
    e.perm = p0 * q5 + p1 * q4 + p2 * q3 + p3 * q2 + p4 * q1 + p5 * q0;

    // Adjugate (transposed cofactors), Eberly 2008, equation (7).
    e.adj[0][0] = a[1][1] * c5 - a[1][2] * c4 + a[1][3] * c3;
    e.adj[0][1] = -a[0][1] * c5 + a[0][2] * c4 - a[0][3] * c3;
    e.adj[0][2] = a[3][1] * s5 - a[3][2] * s4 + a[3][3] * s3;
    e.adj[0][3] = -a[2][1] * s5 + a[2][2] * s4 - a[2][3] * s3;
    e.adj[1][0] = -a[1][0] * c5 + a[1][2] * c2 - a[1][3] * c1;
    e.adj[1][1] = a[0][0] * c5 - a[0][2] * c2 + a[0][3] * c1;
    e.adj[1][2] = -a[3][0] * s5 + a[3][2] * s2 - a[3][3] * s1;
    e.adj[1][3] = a[2][0] * s5 - a[2][2] * s2 + a[2][3] * s1;
    e.adj[2][0] = a[1][0] * c4 - a[1][1] * c2 + a[1][3] * c0;
    e.adj[2][1] = -a[0][0] * c4 + a[0][1] * c2 - a[0][3] * c0;
    e.adj[2][2] = a[3][0] * s4 - a[3][1] * s2 + a[3][3] * s0;
    e.adj[2][3] = -a[2][0] * s4 + a[2][1] * s2 - a[2][3] * s0;
    e.adj[3][0] = -a[1][0] * c3 + a[1][1] * c1 - a[1][2] * c0;
    e.adj[3][1] = a[0][0] * c3 - a[0][1] * c1 + a[0][2] * c0;
    e.adj[3][2] = -a[3][0] * s3 + a[3][1] * s1 - a[3][2] * s0;
    e.adj[3][3] = a[2][0] * s3 - a[2][1] * s1 + a[2][2] * s0;
    return e;
}

} // namespace

// --- Products ---------------------------------------------------------------------------------
Mat4 operator*(const Mat4& a, const Mat4& b) {
    Mat4 r;
    for (int c = 0; c < 4; ++c) {
        for (int row = 0; row < 4; ++row) {
            r.m[c * 4 + row] = a.m[0 * 4 + row] * b.m[c * 4 + 0] + a.m[1 * 4 + row] * b.m[c * 4 + 1] +
                               a.m[2 * 4 + row] * b.m[c * 4 + 2] + a.m[3 * 4 + row] * b.m[c * 4 + 3];
        }
    }
    return r;
}

bool operator==(const Mat4& a, const Mat4& b) {
    for (int i = 0; i < 16; ++i)
        if (!(a.m[i] == b.m[i])) return false;
    return true;
}

Mat4 transpose(const Mat4& a) {
    Mat4 r;
    for (int row = 0; row < 4; ++row)
        for (int c = 0; c < 4; ++c) r.m[row * 4 + c] = a.m[c * 4 + row];
    return r;
}

bool isFinite(const Mat4& a) {
    for (float v : a.m)
        if (!std::isfinite(v)) return false;
    return true;
}

float determinant(const Mat4& a) {
    const double det = expand4(a).det;
    if (std::isnan(det)) return std::numeric_limits<float>::quiet_NaN();
    float out = 0.0f;
    if (!toFloatChecked(det, out)) return det > 0.0 ? HUGE_VALF : -HUGE_VALF;
    return out;
}

// --- Inverses ---------------------------------------------------------------------------------
std::optional<Mat4> inverse(const Mat4& a) {
    if (!isFinite(a)) return std::nullopt;
    const Expansion4 e = expand4(a);
    // Singular within the rounding of the float elements (see the header): n u perm(|a|), n = 4.
    if (!(std::fabs(e.det) > 4.0 * kFloatUnitRoundoff * e.perm)) return std::nullopt;
    const double invDet = 1.0 / e.det;
    Mat4 r;
    for (int row = 0; row < 4; ++row)
        for (int c = 0; c < 4; ++c)
            if (!toFloatChecked(e.adj[row][c] * invDet, r.m[c * 4 + row])) return std::nullopt;
    return r;
}

std::optional<Mat4> affineInverse(const Mat4& a) {
    if (!(a(3, 0) == 0.0f && a(3, 1) == 0.0f && a(3, 2) == 0.0f && a(3, 3) == 1.0f)) return std::nullopt;
    if (!isFinite(a)) return std::nullopt;

    // 3x3 cofactors of the linear part L (rule of Sarrus / cofactor expansion along row 0).
    double l[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) l[r][c] = el(a, r, c);
    double adj[3][3]; // adj[r][c] = cofactor C(c, r)
    adj[0][0] = l[1][1] * l[2][2] - l[1][2] * l[2][1];
    adj[1][0] = l[1][2] * l[2][0] - l[1][0] * l[2][2];
    adj[2][0] = l[1][0] * l[2][1] - l[1][1] * l[2][0];
    adj[0][1] = l[0][2] * l[2][1] - l[0][1] * l[2][2];
    adj[1][1] = l[0][0] * l[2][2] - l[0][2] * l[2][0];
    adj[2][1] = l[0][1] * l[2][0] - l[0][0] * l[2][1];
    adj[0][2] = l[0][1] * l[1][2] - l[0][2] * l[1][1];
    adj[1][2] = l[0][2] * l[1][0] - l[0][0] * l[1][2];
    adj[2][2] = l[0][0] * l[1][1] - l[0][1] * l[1][0];
    const double det = l[0][0] * adj[0][0] + l[0][1] * adj[1][0] + l[0][2] * adj[2][0];

    // Permanent of |L|, expanded along row 0.
    double b[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) b[r][c] = std::fabs(l[r][c]);
    const double perm = b[0][0] * (b[1][1] * b[2][2] + b[1][2] * b[2][1]) +
                        b[0][1] * (b[1][0] * b[2][2] + b[1][2] * b[2][0]) +
                        b[0][2] * (b[1][0] * b[2][1] + b[1][1] * b[2][0]);
    if (!(std::fabs(det) > 3.0 * kFloatUnitRoundoff * perm)) return std::nullopt;

    const double invDet = 1.0 / det;
    double inv[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) inv[r][c] = adj[r][c] * invDet;
    const double t[3] = {el(a, 0, 3), el(a, 1, 3), el(a, 2, 3)};

    Mat4 res = Mat4::identity();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c)
            if (!toFloatChecked(inv[r][c], res(r, c))) return std::nullopt;
        const double tr = -(inv[r][0] * t[0] + inv[r][1] * t[1] + inv[r][2] * t[2]);
        if (!toFloatChecked(tr, res(r, 3))) return std::nullopt;
    }
    return res;
}

std::optional<Mat4> normalMatrix(const Mat4& a) {
    const std::optional<Mat4> inv = affineInverse(a);
    if (!inv) return std::nullopt;
    Mat4 n = transpose(*inv);
    n(3, 0) = n(3, 1) = n(3, 2) = 0.0f; // the transposed translation must not leak into w
    return n;
}

// --- Applying a matrix to points and directions -----------------------------------------------
Vec3 transformPoint(const Mat4& a, Vec3 p) {
    const Vec4 q = a * Vec4(p, 1.0f);
    if (q.w == 1.0f) return q.xyz();
    return q.xyz() / q.w;
}

Vec3 transformDirection(const Mat4& a, Vec3 d) {
    const float* m = a.m;
    return {m[0] * d.x + m[4] * d.y + m[8] * d.z,
            m[1] * d.x + m[5] * d.y + m[9] * d.z,
            m[2] * d.x + m[6] * d.y + m[10] * d.z};
}

} // namespace sr
