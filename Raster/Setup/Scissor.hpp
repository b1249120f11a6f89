// Scissor: the pixel rectangle a fill may touch (a lane's band, or the whole target).
#pragma once

#include "Raster/Frame/FrameBuffer.hpp"

namespace sr {

// Pixel rectangle [x0, x1) x [y0, y1) the fill may touch. Clipping spans to it never changes
// which pixels inside it are covered.
struct Scissor {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
inline Scissor fullScissor(const FrameBuffer& fb) { return {0, 0, fb.width(), fb.height()}; }

} // namespace sr
