// World-space line and point primitives (glTF LINES / LINE_LOOP / LINE_STRIP / POINTS) through the view: homogeneous clipping, then the DDA line rule.
#pragma once

#include <cstdint>
#include <vector>

#include "Math/Vec.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Frame/RenderSettings.hpp"

namespace sr {

// Draws `indices` as segments (pairs) or, with `points`, as points into ctx's target (the
// multisampled one while multisampling), in the flat colour `colour` (lines carry no normal:
// unlit). Each end goes to clip space with view.viewProj (in float, as the triangles' vertices);
// a segment is clipped against the near plane (z <= w), w >= kClipMinW and, when the view has
// one, the far plane (z >= 0), by the parameters where it crosses them (Liang-Barsky, in
// double), then mapped to the screen and drawn by the DDA rule (Line.hpp; x and y are clipped
// exactly there), depth-tested (GREATER-OR-EQUAL, reversed-Z) and depth-written. A point is the
// one pixel containing it, drawn when it lies inside those planes. `width` k > 1 (supersampling
// k x k) draws k parallel lines (as the wireframe), and for a point the k x k pixels of the
// output pixel containing it, so the resolve keeps them 1 pixel wide. Non-finite positions draw nothing. Runs on the calling thread.
void drawWorldLines(RenderContext& ctx, const FrameView& view, const std::vector<Vec3>& positions,
                    const std::vector<std::uint32_t>& indices, bool points, Pixel colour, int width = 1);

} // namespace sr
