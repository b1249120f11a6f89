// The depth view: the reversed-Z depth buffer shown as grey (near = white, far = dark,
// background = black), and the screenshot helpers of the demo.
#pragma once

#include <ctime>
#include <string>

#include "Raster/Frame/FrameBuffer.hpp"
#include "Resources/Result.hpp"

namespace sr::app {

// Overwrites fb's colour with a grey picture of its depth buffer. Reversed-Z stores d in (0, 1]
// with d = 0 the cleared background (infinitely far); with a perspective projection d is
// proportional to 1/distance, so log(d) = -log(distance) + const. The grey level is log(d)
// stretched over the frame's own [min, max] of the covered pixels: linear in log-distance, which
// keeps both the near objects and the far floor readable at any near/far ratio.
//   covered pixel: 40 + 215 * (log d - log dmin) / (log dmax - log dmin)  (nearest = 255)
//   background (d <= 0, NaN): 0
// A frame with one depth value only is drawn 255 wherever covered.
void depthToGrey(FrameBuffer& fb);

// "SoftRaster-YYYYMMDD-HHMMSS-N.png" for local time `when` and a per-run counter N.
std::string screenshotName(const std::tm& when, int counter);

// Writes fb's colour as an image (format by the extension: .png, .bmp, .ppm) to a UTF-8 path.
Status saveScreenshot(const FrameBuffer& fb, const std::string& utf8Path);

} // namespace sr::app
