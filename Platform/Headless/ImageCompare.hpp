// Error metrics between two framebuffers (mean abs error, PSNR, max abs error, share of differing pixels, SSIM) and the error heat map.
#pragma once

#include <cstdint>

#include "Raster/Frame/FrameBuffer.hpp"
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

// The structural similarity index (Wang, Bovik, Sheikh and Simoncelli, "Image Quality Assessment:
// From Error Visibility to Structural Similarity", IEEE Trans. Image Processing 13(4), 2004) with
// the paper's constants, as its authors' reference code and scikit-image (gaussian_weights=True,
// use_sample_covariance=False) compute it: local means, variances and covariance under an 11 x 11
// Gaussian window of sigma 1.5 (normalised), K1 = 0.01, K2 = 0.03, L = 255,
//   SSIM = (2 mx my + C1)(2 sxy + C2) / ((mx^2 + my^2 + C1)(sx^2 + sy^2 + C2)),
// averaged over every pixel whose window lies inside the image, per R, G, B channel, and the
// three channels averaged. An image under 11 pixels on a side gets the largest odd window that
// fits (the Gaussian cut there and normalised again). 1 for identical images; lower is worse.
double structuralSimilarity(const FrameBuffer& reference, const FrameBuffer& test);

// The error heat map of two images of the same size: per pixel the largest channel difference d
// (0..255) as a colour from black (d = 0) through blue, magenta, red and orange to white, at
// t = min(1, sqrt(d / 64)): a difference of one level is already visible, 64 or more is white.
Image errorHeatMap(const FrameBuffer& reference, const FrameBuffer& test);

// The framebuffer of an image (RGBA8, top row first), for comparing files.
FrameBuffer frameOf(const Image& image);

} // namespace sr::headless
