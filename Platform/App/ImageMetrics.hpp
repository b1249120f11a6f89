// Perceptual image error: the structural similarity index (SSIM) of two framebuffers.
#pragma once

#include "Raster/Frame/FrameBuffer.hpp"

namespace sr::app {

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

} // namespace sr::app
