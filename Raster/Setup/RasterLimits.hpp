// The coordinate range triangle setup accepts (its fixed-point guard band) and the snapping grid.
#pragma once

#include "Raster/Frame/FrameBuffer.hpp"

namespace sr {

// Sub-pixel precision: positions are snapped to 1/256 pixel (Direct3D 10: 8 fractional bits).
inline constexpr int kSubPixelBits = 8;
inline constexpr int kSubPixelScale = 1 << kSubPixelBits;

// Guard band: triangle setup accepts screen coordinates x, y in [-kGuardBand, +kGuardBand]
// pixels (asserted). In fixed point that is |X| <= 2^22, so an edge's deltas fit in 24 bits and
// every edge-function product in 48 bits: int64 arithmetic can never overflow. The clipper
// clips against these planes only when a vertex would fall outside them.
inline constexpr float kGuardBand = 16384.0f;

static_assert(FrameBuffer::kMaxDimension <= kGuardBand / 2,
              "the guard band must reach at least one framebuffer size beyond every edge");

} // namespace sr
