// RenderContext: the explicit render state (target, per-draw scratch memory, statistics).
#pragma once

#include <cstdint>
#include <vector>

#include "Raster/Clipper.hpp"
#include "Raster/FrameBuffer.hpp"
#include "Raster/Vertex.hpp"

namespace sr {

// Counters of one or more draws (reset by the owner, e.g. once per frame).
struct RenderStats {
    std::uint64_t trianglesIn = 0;      // triangles submitted
    std::uint64_t trivialRejected = 0;  // outside one clip plane (or non-finite): never set up
    std::uint64_t clipped = 0;          // went through the clipper
    std::uint64_t culled = 0;           // back/front-face culled or zero-area on the snapped grid
    std::uint64_t rasterized = 0;       // triangle setups handed to the fill
    std::uint64_t nonFinite = 0;        // dropped for a NaN/Inf position (part of trivialRejected)
    std::uint64_t fragmentsShaded = 0;  // pixels that passed the depth test and were shaded

    RenderStats& operator+=(const RenderStats& o) {
        trianglesIn += o.trianglesIn;
        trivialRejected += o.trivialRejected;
        clipped += o.clipped;
        culled += o.culled;
        rasterized += o.rasterized;
        nonFinite += o.nonFinite;
        fragmentsShaded += o.fragmentsShaded;
        return *this;
    }
};

// Passed explicitly to every draw (no global state). Owns scratch buffers whose capacity is
// kept from draw to draw, so a steady frame loop allocates nothing.
class RenderContext {
public:
    explicit RenderContext(FrameBuffer& target) : target_(&target) {}

    FrameBuffer& target() { return *target_; }
    void setTarget(FrameBuffer& target) { target_ = &target; }

    RenderStats stats;

    // Post-transform vertex cache of the current draw: clip-space vertex, and the screen-space
    // vertex where the clip-space one is finite with w > 0 (usable[i] != 0).
    std::vector<ClipVertex> clipVertices;
    std::vector<ScreenVertex> screenVertices;
    std::vector<std::uint8_t> usable;

private:
    FrameBuffer* target_;
};

} // namespace sr
