// Error metrics between two framebuffers (mean abs error, PSNR, max abs error, share of differing pixels, SSIM) and the error heat map.
#pragma once

#include <cstdint>

#include "Raster/Frame/FrameBuffer.hpp"
#include "Platform/App/ImageMetrics.hpp" // structuralSimilarity
#include "Resources/Image.hpp"

namespace sr::headless {

struct ImageError {
    double meanAbs = 0.0;       // mean absolute difference per R, G, B channel, in levels (0..255)
    double psnrDb = 0.0;        // over the R, G, B channels; +infinity when identical
    int maxAbs = 0;             // largest per-channel difference (0..255)
    double differingShare = 0;  // share of pixels where any channel differs (0..1)
    std::int64_t differing = 0; // number of such pixels
    double ssim = 1.0;          // structuralSimilarity (1: identical); only when asked for
};

// Compares the colour buffers of two framebuffers of the same size (asserted); with `withSsim`
// also the structural similarity (the costly one: about 10 ns a pixel).
ImageError compareImages(const FrameBuffer& reference, const FrameBuffer& test, bool withSsim = false);

// The error heat map of two images of the same size: per pixel the largest channel difference d
// (0..255) as a colour from black (d = 0) through blue, magenta, red and orange to white, at
// t = min(1, sqrt(d / 64)): a difference of one level is already visible, 64 or more is white.
Image errorHeatMap(const FrameBuffer& reference, const FrameBuffer& test);

// The framebuffer of an image (RGBA8, top row first), for comparing files.
FrameBuffer frameOf(const Image& image);

} // namespace sr::headless
