// Perspective divide and viewport transform: clip-space vertex -> screen-space vertex.
#pragma once

#include "Raster/Geometry/Vertex.hpp"

namespace sr {

// Divides by w and maps to a width x height viewport (Math/Conventions.hpp):
//   x_s = (x/w + 1) * W/2,  y_s = (1 - y/w) * H/2 (y down),  z_s = z/w (reversed-Z depth),
//   invW = 1/w, varyings [0, varyingCount) copied raw (not divided by w; setup does that),
//   the others left 0.
// Precondition (asserted): finite position with w > 0 -- what Clipper guarantees for its output.
// x/w, y/w and z/w are true divisions, not products with invW, so a vertex on the near plane
// (z == w) gets depth exactly 1.
ScreenVertex toScreen(const ClipVertex& v, int width, int height, int varyingCount);

} // namespace sr
