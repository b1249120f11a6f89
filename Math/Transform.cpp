// Transform builders (model, view, reversed-Z projection, viewport), computed in double where it matters.
#include "Transform.hpp"

#include <cassert>
#include <cfloat>
#include <cmath>
#include <limits>

#include "Math/Conventions.hpp"
#include "Math/DoubleMath.hpp"

namespace sr {
namespace {

// lookAt and rotate compute in double (Math/DoubleMath.hpp's Vec3d).
double norm(Vec3d a) { return length(a); }

// double -> float, with values beyond the float range becoming +-Inf explicitly (the plain
// conversion is undefined behaviour there) and NaN staying NaN.
float roundToFloat(double v) {
    if (std::isnan(v)) return std::numeric_limits<float>::quiet_NaN();
    if (v > static_cast<double>(FLT_MAX)) return HUGE_VALF;
    if (v < -static_cast<double>(FLT_MAX)) return -HUGE_VALF;
    return static_cast<float>(v);
}

// double -> float clamped into [-FLT_MAX, FLT_MAX]: for projection coefficients, which must stay
// finite whatever the arguments (the caller has already replaced NaN arguments).
float saturateToFloat(double v) {
    const double lim = static_cast<double>(FLT_MAX);
    return static_cast<float>(v > lim ? lim : (v < -lim ? -lim : v));
}

bool allFinite(Vec3 a, Vec3 b, Vec3 c) { return isFinite(a) && isFinite(b) && isFinite(c); }

// Projection arguments after the release-build substitutions documented in Transform.hpp.
struct PerspectiveArgs {
    double xScale, yScale, n, f; // f = +Inf means infinite far
};

PerspectiveArgs sanitizePerspective(float fovY, float aspect, float nearZ, float farZ) {
    PerspectiveArgs p{};
    double fov = std::isnan(fovY) ? kPiD / 2.0 : static_cast<double>(fovY);
    fov = fov < 1e-6 ? 1e-6 : (fov > kPiD - 1e-6 ? kPiD - 1e-6 : fov);
    const double asp = (std::isfinite(aspect) && aspect > 0.0f) ? static_cast<double>(aspect) : 1.0;
    p.n = (std::isfinite(nearZ) && nearZ > 0.0f) ? static_cast<double>(nearZ) : static_cast<double>(0.1f);
    p.f = (farZ > p.n) ? static_cast<double>(farZ) : HUGE_VAL; // NaN compares false -> infinite
    p.yScale = 1.0 / std::tan(fov / 2.0);                       // cot(fovY / 2), in [5e-7, 2e6]
    p.xScale = p.yScale / asp;
    return p;
}

// The shared layout of both perspective matrices: rows (sx 0 0 0), (0 sy 0 0), (0 0 A B), (0 0 -1 0).
Mat4 perspectiveMatrix(const PerspectiveArgs& p) {
    double a = 0.0, b = p.n; // the infinite-far limit of A = n/(f-n), B = f n/(f-n)
    if (std::isfinite(p.f)) {
        const double range = p.f - p.n; // > 0: exact difference of two floats with f > n
        a = p.n / range;
        b = p.f * p.n / range;
    }
    Mat4 m;
    m(0, 0) = saturateToFloat(p.xScale);
    m(1, 1) = saturateToFloat(p.yScale);
    m(2, 2) = saturateToFloat(a);
    m(2, 3) = saturateToFloat(b);
    m(3, 2) = -1.0f;
    return m;
}

void assertPerspectiveArgs(float fovY, float aspect, float nearZ) {
    assert(std::isfinite(fovY) && fovY > 0.0f && fovY < kPi && "perspective: fovY must be in (0, pi)");
    assert(std::isfinite(aspect) && aspect > 0.0f && "perspective: aspect must be > 0");
    assert(std::isfinite(nearZ) && nearZ > 0.0f && "perspective: near must be > 0");
    (void)fovY, (void)aspect, (void)nearZ;
}

// Scale and offset mapping [lo, hi] to [-1, 1]: 2 / (hi - lo), -(hi + lo) / (hi - lo). An invalid
// pair (equal or non-finite) maps as (-1, 1), the identity.
void orthoAxis(float lo, float hi, float& scaleOut, float& offsetOut) {
    const double l = lo, h = hi;
    if (!(std::isfinite(l) && std::isfinite(h) && h != l)) {
        scaleOut = 1.0f;
        offsetOut = 0.0f;
        return;
    }
    scaleOut = saturateToFloat(2.0 / (h - l));
    offsetOut = saturateToFloat(-(h + l) / (h - l));
}

} // namespace

// --- Model transforms -------------------------------------------------------------------------
Mat4 translate(Vec3 t) {
    Mat4 m = Mat4::identity();
    m(0, 3) = t.x;
    m(1, 3) = t.y;
    m(2, 3) = t.z;
    return m;
}

Mat4 scale(Vec3 s) {
    Mat4 m;
    m(0, 0) = s.x;
    m(1, 1) = s.y;
    m(2, 2) = s.z;
    m(3, 3) = 1.0f;
    return m;
}

Mat4 rotate(float radians, Vec3 axis) {
    const Vec3d a = Vec3d(axis);
    const double len = norm(a);
    if (len == 0.0) return Mat4::identity();
    const Vec3d k = a * (1.0 / len); // NaN for a non-finite axis: propagates into the matrix
    const double theta = radians;
    const double c = std::cos(theta), s = std::sin(theta);
    const double h = std::sin(theta / 2.0);
    const double t = 2.0 * h * h; // 1 - cos(theta) without the cancellation for small angles

    Mat4 m = Mat4::identity();
    m(0, 0) = roundToFloat(c + t * k.x * k.x);
    m(0, 1) = roundToFloat(t * k.x * k.y - s * k.z);
    m(0, 2) = roundToFloat(t * k.x * k.z + s * k.y);
    m(1, 0) = roundToFloat(t * k.x * k.y + s * k.z);
    m(1, 1) = roundToFloat(c + t * k.y * k.y);
    m(1, 2) = roundToFloat(t * k.y * k.z - s * k.x);
    m(2, 0) = roundToFloat(t * k.x * k.z - s * k.y);
    m(2, 1) = roundToFloat(t * k.y * k.z + s * k.x);
    m(2, 2) = roundToFloat(c + t * k.z * k.z);
    return m;
}

// --- View transform ---------------------------------------------------------------------------
Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up) {
    if (!allFinite(eye, target, up)) {
        Mat4 nan;
        for (float& v : nan.m) v = std::numeric_limits<float>::quiet_NaN();
        return nan;
    }
    constexpr double kParallelSine = 1e-6; // |f x up| / |up| at or below this: up is unusable

    // Forward direction; eye == target falls back to the default -Z.
    const Vec3d e = Vec3d(eye);
    Vec3d f = Vec3d(target) - e;
    const double fLen = norm(f);
    f = fLen > 0.0 ? f * (1.0 / fLen) : Vec3d{0.0, 0.0, -1.0};

    // Side = forward x up, with the documented fallbacks for a zero or parallel up.
    Vec3d u0 = Vec3d(up);
    Vec3d s = cross(f, u0);
    const double upLen = norm(u0);
    if (!(upLen > 0.0) || norm(s) <= kParallelSine * upLen) {
        u0 = {0.0, 1.0, 0.0};
        s = cross(f, u0);
        if (norm(s) <= kParallelSine) {
            u0 = {0.0, 0.0, f.y > 0.0 ? 1.0 : -1.0};
            s = cross(f, u0);
        }
    }
    // With sin(f, up) > 1e-6 the double cross product is orthogonal to f to ~1e-16 / 1e-6 = 1e-10,
    // far below float's rounding, so no Gram-Schmidt pass is needed.
    s = s * (1.0 / norm(s));
    const Vec3d u = cross(s, f); // unit and orthogonal to both, up to double rounding

    Mat4 m = Mat4::identity();
    const Vec3d rows[3] = {s, u, f * -1.0};
    for (int r = 0; r < 3; ++r) {
        m(r, 0) = roundToFloat(rows[r].x);
        m(r, 1) = roundToFloat(rows[r].y);
        m(r, 2) = roundToFloat(rows[r].z);
        m(r, 3) = roundToFloat(-dot(rows[r], e));
    }
    return m;
}

Mat4d lookAtD(Vec3 eye, Vec3 target, Vec3 up) {
    auto unit = [](Vec3d v) {
        const double l = length(v);
        return l > 0 ? v / l : v;
    };
    const Vec3d e(eye);
    const Vec3d f = unit(Vec3d(target) - e);
    const Vec3d s = unit(cross(f, Vec3d(up)));
    const Vec3d u = cross(s, f);
    Mat4d v;
    const Vec3d rows[3] = {s, u, f * -1.0};
    for (int r = 0; r < 3; ++r) {
        v.m[r][0] = rows[r].x;
        v.m[r][1] = rows[r].y;
        v.m[r][2] = rows[r].z;
    }
    v.m[0][3] = -dot(s, e);
    v.m[1][3] = -dot(u, e);
    v.m[2][3] = dot(f, e);
    v.m[3][3] = 1.0;
    return v;
}

// --- Projections ------------------------------------------------------------------------------
Mat4 perspective(float fovYRadians, float aspect, float nearZ, float farZ) {
    assertPerspectiveArgs(fovYRadians, aspect, nearZ);
    assert(farZ > nearZ && "perspective: far must be > near (or +infinity)");
    return perspectiveMatrix(sanitizePerspective(fovYRadians, aspect, nearZ, farZ));
}

Mat4 perspectiveInfinite(float fovYRadians, float aspect, float nearZ) {
    assertPerspectiveArgs(fovYRadians, aspect, nearZ);
    return perspectiveMatrix(sanitizePerspective(fovYRadians, aspect, nearZ, HUGE_VALF));
}

Mat4d perspectiveD(double fovYRadians, double aspect, double nearZ, double farZ) {
    const double cot = 1.0 / std::tan(fovYRadians / 2.0);
    const bool infinite = std::isinf(farZ);
    Mat4d p;
    p.m[0][0] = cot / aspect;
    p.m[1][1] = cot;
    p.m[2][2] = infinite ? 0.0 : nearZ / (farZ - nearZ);
    p.m[2][3] = infinite ? nearZ : farZ * nearZ / (farZ - nearZ);
    p.m[3][2] = -1.0;
    return p;
}

Mat4 orthographic(float left, float right, float bottom, float top, float nearZ, float farZ) {
    assert(std::isfinite(left) && std::isfinite(right) && left != right && "orthographic: bad x range");
    assert(std::isfinite(bottom) && std::isfinite(top) && bottom != top && "orthographic: bad y range");
    assert(std::isfinite(nearZ) && std::isfinite(farZ) && nearZ != farZ && "orthographic: bad z range");
    Mat4 m;
    orthoAxis(left, right, m(0, 0), m(0, 3));
    orthoAxis(bottom, top, m(1, 1), m(1, 3));
    // Depth: z_ndc = (z + f) / (f - n), i.e. scale 1 / (f - n) and offset f / (f - n).
    double n = nearZ, f = farZ;
    if (!(std::isfinite(n) && std::isfinite(f) && f != n)) n = 0.0, f = 1.0;
    m(2, 2) = saturateToFloat(1.0 / (f - n));
    m(2, 3) = saturateToFloat(f / (f - n));
    m(3, 3) = 1.0f;
    return m;
}

float aspectRatio(int width, int height) {
    if (width <= 0 || height <= 0) return 1.0f;
    return static_cast<float>(static_cast<double>(width) / static_cast<double>(height));
}

Mat4 viewport(int width, int height) {
    const float halfW = static_cast<float>(width > 0 ? width : 0) * 0.5f;
    const float halfH = static_cast<float>(height > 0 ? height : 0) * 0.5f;
    Mat4 m;
    m(0, 0) = halfW;
    m(0, 3) = halfW;
    m(1, 1) = -halfH;
    m(1, 3) = halfH;
    m(2, 2) = 1.0f;
    m(3, 3) = 1.0f;
    return m;
}

} // namespace sr
