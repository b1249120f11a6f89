// Error metrics between two framebuffers (mean abs error, PSNR, max abs error, share of differing pixels).
#pragma once

#include <cstdint>

#include "Raster/Frame/FrameBuffer.hpp"

namespace sr::headless {

struct ImageError {
    double meanAbs = 0.0;       // mean absolute difference per R, G, B channel, in levels (0..255)
    double psnrDb = 0.0;        // over the R, G, B channels; +infinity when identical
    int maxAbs = 0;             // largest per-channel difference (0..255)
    double differingShare = 0;  // share of pixels where any channel differs (0..1)
    std::int64_t differing = 0; // number of such pixels
};

// Compares the colour buffers of two framebuffers of the same size (asserted).
ImageError compareImages(const FrameBuffer& reference, const FrameBuffer& test);

} // namespace sr::headless
