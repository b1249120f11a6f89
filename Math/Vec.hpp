// Vec2, Vec3, Vec4: float value types with operators and free functions (dot, cross, ...).
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "Conventions.hpp"

namespace sr {

struct Vec2 {
    float x = 0.0f, y = 0.0f;

    constexpr Vec2() = default;
    constexpr Vec2(float x_, float y_) : x(x_), y(y_) {}
    explicit constexpr Vec2(float s) : x(s), y(s) {}

    constexpr float operator[](int i) const { assert(i >= 0 && i < 2); return i == 0 ? x : y; }
    constexpr float& operator[](int i) { assert(i >= 0 && i < 2); return i == 0 ? x : y; }

    constexpr Vec2& operator+=(Vec2 b) { x += b.x; y += b.y; return *this; }
    constexpr Vec2& operator-=(Vec2 b) { x -= b.x; y -= b.y; return *this; }
    constexpr Vec2& operator*=(float s) { x *= s; y *= s; return *this; }
    constexpr Vec2& operator/=(float s) { x /= s; y /= s; return *this; }
};

struct Vec3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;

    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    explicit constexpr Vec3(float s) : x(s), y(s), z(s) {}

    constexpr float operator[](int i) const { assert(i >= 0 && i < 3); return i == 0 ? x : (i == 1 ? y : z); }
    constexpr float& operator[](int i) { assert(i >= 0 && i < 3); return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3& operator+=(Vec3 b) { x += b.x; y += b.y; z += b.z; return *this; }
    constexpr Vec3& operator-=(Vec3 b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
    constexpr Vec3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
    constexpr Vec3& operator/=(float s) { x /= s; y /= s; z /= s; return *this; }
};

struct Vec4 {
    float x = 0.0f, y = 0.0f, z = 0.0f, w = 0.0f;

    constexpr Vec4() = default;
    constexpr Vec4(float x_, float y_, float z_, float w_) : x(x_), y(y_), z(z_), w(w_) {}
    constexpr Vec4(Vec3 v, float w_) : x(v.x), y(v.y), z(v.z), w(w_) {}
    explicit constexpr Vec4(float s) : x(s), y(s), z(s), w(s) {}

    constexpr Vec3 xyz() const { return {x, y, z}; }

    constexpr float operator[](int i) const {
        assert(i >= 0 && i < 4);
        return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w));
    }
    constexpr float& operator[](int i) {
        assert(i >= 0 && i < 4);
        return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w));
    }

    constexpr Vec4& operator+=(Vec4 b) { x += b.x; y += b.y; z += b.z; w += b.w; return *this; }
    constexpr Vec4& operator-=(Vec4 b) { x -= b.x; y -= b.y; z -= b.z; w -= b.w; return *this; }
    constexpr Vec4& operator*=(float s) { x *= s; y *= s; z *= s; w *= s; return *this; }
    constexpr Vec4& operator/=(float s) { x /= s; y /= s; z /= s; w /= s; return *this; }
};

// --- Component-wise operators --------------------------------------------------------------
constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(Vec2 a, Vec2 b) { return {a.x * b.x, a.y * b.y}; }
constexpr Vec2 operator*(Vec2 a, float s) { return {a.x * s, a.y * s}; }
constexpr Vec2 operator*(float s, Vec2 a) { return {a.x * s, a.y * s}; }
constexpr Vec2 operator/(Vec2 a, float s) { return {a.x / s, a.y / s}; }
constexpr bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
constexpr bool operator!=(Vec2 a, Vec2 b) { return !(a == b); }

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(float s, Vec3 a) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator/(Vec3 a, float s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
constexpr bool operator!=(Vec3 a, Vec3 b) { return !(a == b); }

constexpr Vec4 operator+(Vec4 a, Vec4 b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
constexpr Vec4 operator-(Vec4 a, Vec4 b) { return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
constexpr Vec4 operator-(Vec4 a) { return {-a.x, -a.y, -a.z, -a.w}; }
constexpr Vec4 operator*(Vec4 a, Vec4 b) { return {a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w}; }
constexpr Vec4 operator*(Vec4 a, float s) { return {a.x * s, a.y * s, a.z * s, a.w * s}; }
constexpr Vec4 operator*(float s, Vec4 a) { return {a.x * s, a.y * s, a.z * s, a.w * s}; }
constexpr Vec4 operator/(Vec4 a, float s) { return {a.x / s, a.y / s, a.z / s, a.w / s}; }
constexpr bool operator==(Vec4 a, Vec4 b) { return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w; }
constexpr bool operator!=(Vec4 a, Vec4 b) { return !(a == b); }

// --- Products ------------------------------------------------------------------------------
constexpr float dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr float dot(Vec4 a, Vec4 b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }

// 2D cross product (z of the 3D cross product): twice the signed area of (0, a, b).
constexpr float cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// --- Component-wise min / max / clamp / lerp / abs -------------------------------------------
constexpr Vec2 min(Vec2 a, Vec2 b) { return {std::min(a.x, b.x), std::min(a.y, b.y)}; }
constexpr Vec2 max(Vec2 a, Vec2 b) { return {std::max(a.x, b.x), std::max(a.y, b.y)}; }
constexpr Vec3 min(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
constexpr Vec3 max(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
constexpr Vec4 min(Vec4 a, Vec4 b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z), std::min(a.w, b.w)};
}
constexpr Vec4 max(Vec4 a, Vec4 b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z), std::max(a.w, b.w)};
}

constexpr float clamp(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }
constexpr Vec2 clamp(Vec2 v, Vec2 lo, Vec2 hi) { return min(max(v, lo), hi); }
constexpr Vec3 clamp(Vec3 v, Vec3 lo, Vec3 hi) { return min(max(v, lo), hi); }
constexpr Vec4 clamp(Vec4 v, Vec4 lo, Vec4 hi) { return min(max(v, lo), hi); }

// lerp(a, b, 0) == a and lerp(a, b, 1) == b exactly (the two-product form keeps both ends exact).
constexpr float lerp(float a, float b, float t) { return a * (1.0f - t) + b * t; }
constexpr Vec2 lerp(Vec2 a, Vec2 b, float t) { return a * (1.0f - t) + b * t; }
constexpr Vec3 lerp(Vec3 a, Vec3 b, float t) { return a * (1.0f - t) + b * t; }
constexpr Vec4 lerp(Vec4 a, Vec4 b, float t) { return a * (1.0f - t) + b * t; }

inline Vec3 abs(Vec3 v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }

inline bool isFinite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
inline bool isFinite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool isFinite(Vec4 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// --- Length and normalisation ---------------------------------------------------------------
// length() scales by the largest component first, so it neither overflows for 1e30 components
// nor underflows to 0 for denormal ones (x*x of 1e-30 is 0 in float).
float length(Vec2 v);
float length(Vec3 v);
float length(Vec4 v);
inline float lengthSquared(Vec3 v) { return dot(v, v); }

// normalize(v): v / length(v), computed with the same scaling, so denormal and huge vectors come
// back with unit length. Defined results for the edge cases:
//  - a zero-length vector returns the zero vector (callers that need a direction check for it);
//  - a vector with an infinite component (and no NaN) returns the unit vector along the signs
//    of the infinite components (e.g. (inf, 1, 0) -> (1, 0, 0));
//  - a vector with a NaN component returns all-NaN (NaN propagates, see Conventions.hpp).
Vec2 normalize(Vec2 v);
Vec4 normalize(Vec4 v);
Vec3 normalizeRobust(Vec3 v); // the general case of normalize(Vec3), out of line

// Inline fast path for the common case (finite, non-zero components whose sum does not
// overflow): the very same operations as the general case (divide by the largest |component|,
// sum of squares, one reciprocal square root, three products), so the result is bit-identical;
// it only skips the NaN/Inf loop and the call. Everything else goes to normalizeRobust.
inline Vec3 normalize(Vec3 v) {
    const float ax = std::fabs(v.x), ay = std::fabs(v.y), az = std::fabs(v.z);
    const float m = std::max(std::max(ax, ay), az);
    if (!(m > 0.0f) || !(ax + ay + az <= std::numeric_limits<float>::max())) return normalizeRobust(v);
    const float x = v.x / m, y = v.y / m, z = v.z / m;
    float sum = x * x;
    sum += y * y;
    sum += z * z;
    const float inv = 1.0f / std::sqrt(sum);
    return {x * inv, y * inv, z * inv};
}

} // namespace sr
