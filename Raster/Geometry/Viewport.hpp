// Perspective divide and viewport transform: clip-space vertex -> screen-space vertex.
#pragma once

#include <cassert>
#include <cstddef>

#include "Raster/Geometry/Vertex.hpp"

namespace sr {

// Divides by w and maps to a width x height viewport (Math/Conventions.hpp), into `s`:
//   x_s = (x/w + 1) * W/2,  y_s = (1 - y/w) * H/2 (y down),  z_s = z/w (reversed-Z depth),
//   invW = 1/w, varyings [0, varyingCount) copied raw (not divided by w; setup does that),
//   the others 0.
// Precondition (asserted): finite position with w > 0 -- what Clipper guarantees for its output.
// x/w, y/w and z/w are true divisions, not products with invW, so a vertex on the near plane
// (z == w) gets depth exactly 1.
// The vertex stage writes its array in place with it: a record returned by value was built on
// the stack with narrow stores and copied with wide loads that store forwarding cannot serve (a
// stall per vertex that `perf` put at most of the vertex stage's time).
inline void writeScreenVertex(const ClipVertex& v, int width, int height, int varyingCount, ScreenVertex& s) {
    assert(isFinite(v.position) && v.position.w > 0.0f && "clip before the divide");
    assert(varyingCount >= 0 && varyingCount <= kMaxVaryings);
    const Vec4& p = v.position;
    const float halfW = 0.5f * float(width);
    const float halfH = 0.5f * float(height);
    s.x = (p.x / p.w + 1.0f) * halfW;
    s.y = (1.0f - p.y / p.w) * halfH;
    s.z = p.z / p.w;
    s.invW = 1.0f / p.w;
    for (int i = 0; i < kMaxVaryings; ++i)
        s.varyings[std::size_t(i)] = i < varyingCount ? v.varyings[std::size_t(i)] : 0.0f;
}
// The same, returned.
inline ScreenVertex toScreen(const ClipVertex& v, int width, int height, int varyingCount) {
    ScreenVertex s;
    writeScreenVertex(v, width, height, varyingCount, s);
    return s;
}

} // namespace sr
