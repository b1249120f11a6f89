// Double-precision Vec3d and Mat4d for the few computations kept in double (lookAt, rotate, the
// double view and projection lookAtD / perspectiveD, OBJ normals, analytic test references).
#pragma once

#include <cmath>

#include "Math/Vec.hpp"

namespace sr {

// A 3-vector of doubles. Operators evaluate component by component, left to right, so code moved
// onto it keeps its exact rounding (dot is (x x' + y y') + z z').
struct Vec3d {
    double x = 0.0, y = 0.0, z = 0.0;
    constexpr Vec3d() = default;
    constexpr Vec3d(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3d(Vec3 v) : x(v.x), y(v.y), z(v.z) {}
};

constexpr Vec3d operator+(Vec3d a, Vec3d b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3d operator*(Vec3d a, double s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3d operator/(Vec3d a, double s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3d cross(Vec3d a, Vec3d b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Float inputs squared cannot overflow or underflow double (|x| <= 3.4e38, >= 1.4e-45).
inline double length(Vec3d a) { return std::sqrt(dot(a, a)); }

// A 4x4 matrix of doubles, m[row][column] (column vectors, p' = M p, as Mat4).
struct Mat4d {
    double m[4][4] = {};
};

// a * b, each element summed over k = 0..3 in order.
inline Mat4d operator*(const Mat4d& a, const Mat4d& b) {
    Mat4d r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) r.m[i][j] += a.m[i][k] * b.m[k][j];
    return r;
}

} // namespace sr
