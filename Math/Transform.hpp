// Transform builders: translate/scale/rotate, the lookAt view matrix, reversed-Z projections, viewport.
// The view matrix and the perspective projection also come in double (lookAtD, perspectiveD).
#pragma once

#include "DoubleMath.hpp"
#include "Mat4.hpp"

namespace sr {

// --- Model transforms -------------------------------------------------------------------------
// Non-finite arguments propagate into the matrix (IEEE semantics, see Conventions.hpp).
Mat4 translate(Vec3 t);
Mat4 scale(Vec3 s);

// Rotation by `radians` about `axis` (counter-clockwise when the axis points at the viewer,
// right-hand rule), by Rodrigues' formula R = cos(a) I + sin(a) [k]x + (1 - cos(a)) k k^T with
// k = axis / |axis| (Rodrigues 1840; e.g. Murray, Li, Sastry, "A Mathematical Introduction to
// Robotic Manipulation", eq. 2.14). The axis need not be unit length. Computed in double, rounded
// to float. A zero axis (no direction) returns the identity. rotate(pi/2, X) maps +Y to +Z.
Mat4 rotate(float radians, Vec3 axis);

// --- View transform ---------------------------------------------------------------------------
// Right-handed view matrix (the gluLookAt construction): the camera at `eye` looks at `target`
// down its -Z axis, +Y of the view is the component of `up` orthogonal to the view direction,
// +X = forward x up. With f = forward, s = side, u = up (all unit), the rows are
//   [ s  -s.eye ]   [ u  -u.eye ]   [ -f  f.eye ]   [ 0 0 0 1 ]
// Computed in double and rounded once, so the rotation rows are orthonormal to within one float
// rounding per element. Degenerate inputs get a deterministic fallback:
//  - eye == target: forward is -Z (the default camera orientation);
//  - up is zero or parallel to forward (sine of their angle <= 1e-6): up becomes +Y, or, when
//    forward is itself along +-Y, up = (0, 0, sign(forward.y)) - the orientation of the default
//    camera pitched by +-90 degrees (looking down -Y keeps +X to the right and -Z up the screen);
//  - any non-finite component of eye, target or up: every element of the result is NaN (so
//    isFinite() of the result reports it).
Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up);

// The same view matrix kept in double (not rounded to float), for a view-projection that is
// multiplied in double and rounded once (the front end's frame view, as the reference renderer
// builds it). Each direction is divided by its length. No fallbacks: for eye == target or an up
// parallel to the view direction, the rows that have no direction are zero.
Mat4d lookAtD(Vec3 eye, Vec3 target, Vec3 up);

// --- Projections (reversed-Z, D3D clip range 0 <= z <= w; see Conventions.hpp) ----------------
// Perspective projection with clip w = -z_view and z_clip = A z_view + B, where
//   A = n / (f - n), B = f n / (f - n)  so view z = -n -> z_ndc = 1 and z = -f -> z_ndc = 0,
// (solve -A n + B = n and -A f + B = 0; Reed, "Depth Precision Visualized", NVIDIA 2015;
// Microsoft's D3DXMatrixPerspectiveFovRH with near and far exchanged), and
//   x_clip = (cot(fovY / 2) / aspect) x_view, y_clip = cot(fovY / 2) y_view.
// Coefficients are computed in double and rounded once to float (precise for near = 1e-6 with
// far = 1e9). far = +infinity is accepted and equals perspectiveInfinite().
// Invalid arguments are programming errors (assert); release builds substitute, so the matrix is
// always finite: fovY NaN -> pi/2, otherwise clamped into [1e-6, pi - 1e-6]; aspect <= 0 or not
// finite -> 1; near <= 0 or not finite -> 0.1f; far NaN or far <= near -> infinite far.
// Coefficients that would overflow float saturate at +-FLT_MAX.
Mat4 perspective(float fovYRadians, float aspect, float nearZ, float farZ);

// The limit far -> infinity: A = 0, B = n, so z_ndc = n / distance: exactly 1 at the near plane,
// positive and strictly decreasing towards 0 for any finite distance. Same argument policy.
Mat4 perspectiveInfinite(float fovYRadians, float aspect, float nearZ);

// perspective()'s matrix in double, not rounded; far = +infinity gives perspectiveInfinite's.
// No argument substitutions: the caller passes fovY in (0, pi), aspect > 0 and 0 < near < far.
Mat4d perspectiveD(double fovYRadians, double aspect, double nearZ, double farZ);

// Orthographic projection, reversed-Z: x in [l, r] -> [-1, 1], y in [b, t] -> [-1, 1], view
// z = -near -> z_ndc 1 and z = -far -> 0: z_ndc = (z_view + far) / (far - near); w = 1.
// (The D3D orthographic matrix, D3DXMatrixOrthoOffCenterRH, with near and far exchanged.)
// near may be negative or 0. A zero-width range (l == r, b == t, near == far) or a non-finite
// argument is a programming error (assert); release builds replace that pair by (-1, 1) for x/y
// and (near, far) = (0, 1) for depth, so the matrix is always finite.
Mat4 orthographic(float left, float right, float bottom, float top, float nearZ, float farZ);

// width / height of a window or image, for perspective(). A minimised window reports 0x0: when
// either size is <= 0 the ratio is 1 (any finite positive value keeps the matrix finite; nothing
// is visible anyway).
float aspectRatio(int width, int height);

// NDC -> screen pixels per Conventions.hpp: x_s = (x + 1) W / 2, y_s = (1 - y) H / 2, z and w
// unchanged. Its last row is (0, 0, 0, 1), so it can equally be applied to clip coordinates before
// the perspective divide. Negative sizes are treated as 0 (a 0x0 viewport maps everything to the
// pixel corner (0, 0)).
Mat4 viewport(int width, int height);

} // namespace sr
