// The first-light picture: an animated four-corner colour gradient drawn into a FrameBuffer.
#pragma once

#include "Math/Color.hpp"
#include "Raster/FrameBuffer.hpp"

namespace sr::demo {

// The four corner colours at time t (seconds): each corner cycles through hues, a quarter turn
// apart, with a period of kGradientPeriodSeconds. Alpha is 1.
struct GradientCorners {
    Color topLeft, topRight, bottomLeft, bottomRight;
};
inline constexpr double kGradientPeriodSeconds = 6.0;
GradientCorners gradientCorners(double timeSeconds);

// Colour at normalised image position (u, v) in [0, 1]^2 ((0, 0) = top-left corner):
// bilinear blend of the corners.
Color gradientColor(const GradientCorners& corners, float u, float v);

// Fills every pixel (x, y) with gradientColor at its centre ((x + 0.5) / W, (y + 0.5) / H).
// A 0 x 0 framebuffer is left alone.
void renderGradient(FrameBuffer& fb, double timeSeconds);

} // namespace sr::demo
