// Occlusion: whether a small triangle passes no depth test because the depths already stored in
// its box hide it. The fills skip such a triangle: no fragment or sample of it would pass
// `z > stored`, so the image, depths and counters are the same. With no back faces culled about
// half of a closed mesh's triangles are hidden so.
#pragma once

#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Setup/Scissor.hpp"
#include "Raster/Setup/TriangleSetup.hpp"

namespace sr {

// Whether the check is worth making for t: a triangle facing away (clockwise on screen, the
// convention's back face: Cull.hpp). With no culling nearly all of a closed mesh's hidden
// triangles face away, while a front face is rarely hidden whole; with back faces culled none is
// left, so visible triangles do not pay for a check that fails. (A mesh wound the other way only
// loses the shortcut.)
inline bool occlusionCandidate(const TriangleSetup& t) { return t.doubleArea > 0; }

// A float no depth of `t` can exceed at a point of the snapped triangle when its depth plane is
// evaluated over pixels [x0, x1) x [y0, y1) (plus sample offsets) as the fills evaluate it: the
// plane's largest value at the three vertices (inside the triangle a plane is at most that),
// plus a slack far above the rounding of value + ddx dx + ddy dy + ddx step in double, rounded to
// float (rounding is monotonic). The box is at most a small triangle's (32 pixels each way from
// its vertices). NaN for a plane that is not finite.
float nearestDepthBound(const TriangleSetup& t, int x0, int x1, int y0, int y1);

// One sample per pixel: whether t is small (its box at most 32 pixels each way) and every stored
// depth of its box inside `s` is at least nearestDepthBound (false for a NaN bound or depth).
// One stored depth is compared with the plane's value at the first vertex (which the bound is at
// least) before the bound is computed, so that most visible candidates cost little.
bool hiddenInFrame(const TriangleSetup& t, const FrameBuffer& fb, const Scissor& s);

} // namespace sr
