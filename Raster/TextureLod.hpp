// Texture level of detail: screen-space uv derivatives from the triangle setup, and the GL mip level.
#pragma once

#include "Raster/TriangleSetup.hpp"

namespace sr {

// |lod| never exceeds this (2^32 texels per pixel, or 2^-32 pixels per texel, is beyond any texture).
inline constexpr float kMaxAbsLod = 32.0f;

// Partial derivatives of the texture coordinates with respect to screen x and y (per pixel).
struct UvDerivatives {
    float dudx = 0.0f, dvdx = 0.0f;
    float dudy = 0.0f, dvdy = 0.0f;
};

// Perspective-correct uv derivatives at one pixel. The setup's planes are linear in screen space:
// U = u/w (plane uPlane), V = v/w (vPlane) and Q = 1/w (kPlaneInvW), and u = U / Q, so by the
// quotient rule
//   du/dx = (dU/dx Q - U dQ/dx) / Q^2 = (dU/dx - u dQ/dx) / Q      (and likewise for v and y),
// with Q = invW and u, v the perspective-correct values at the pixel - exactly what the span loop
// hands a fragment (Fragment::invW and its varyings). The plane indices are kPlaneVarying0 + the
// varying's index (TriangleSetup.hpp). invW <= 0 or non-finite inputs give non-finite derivatives;
// mipLevel() accepts them.
// Evaluated in double (the subtraction can cancel where u dQ/dx is close to dU/dx), rounded once.
inline UvDerivatives uvDerivatives(const TriangleSetup& t, int uPlane, int vPlane, float invW, float u, float v) {
    const double w = 1.0 / double(invW);
    const double dqdx = double(t.ddx[kPlaneInvW]), dqdy = double(t.ddy[kPlaneInvW]);
    const double du = double(u), dv = double(v);
    return {float((double(t.ddx[uPlane]) - du * dqdx) * w), float((double(t.ddx[vPlane]) - dv * dqdx) * w),
            float((double(t.ddy[uPlane]) - du * dqdy) * w), float((double(t.ddy[vPlane]) - dv * dqdy) * w)};
}

// The mip level lambda = log2(rho) of OpenGL 4.5 core section 8.14.1 (scale factor and level of
// detail), without bias and before clamping to the texture's levels:
//   rho = max( sqrt((du/dx W)^2 + (dv/dx H)^2), sqrt((du/dy W)^2 + (dv/dy H)^2) ),
// the longer of the pixel's two screen-axis footprints, measured in texels of the W x H base
// level (the spec's exact form, not one of its allowed approximations). Computed in double (no
// overflow for any float input). Defined for every input:
//  - any NaN argument -> 0 (the base level);
//  - rho == 0 (a constant uv) -> -kMaxAbsLod (magnification); rho infinite -> +kMaxAbsLod;
//  - the result is always within [-kMaxAbsLod, kMaxAbsLod].
// width and height are the base level's size (>= 1, asserted; release builds use 1 for less).
float mipLevel(float dudx, float dvdx, float dudy, float dvdy, int width, int height);

inline float mipLevel(const UvDerivatives& d, int width, int height) {
    return mipLevel(d.dudx, d.dvdx, d.dudy, d.dvdy, width, height);
}

} // namespace sr
