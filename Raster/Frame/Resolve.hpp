// Supersampling (SSAA): the per-pixel sample grid and the box-filter resolve of a sample target.
#pragma once

#include "Raster/Frame/FrameBuffer.hpp"

namespace sr {

// Supersampling renders the frame at factor x factor times the output size and box-filters it
// down: an ordered grid of factor^2 samples per output pixel, each shaded on its own, at
// (x + (i + 0.5) / factor, y + (j + 0.5) / factor) for i, j in [0, factor) - the sample-target
// pixel centres, so every rasterization rule (8 sub-pixel bits, top-left fill) holds per sample.
// Samples per pixel: 1 (off), 4 (2x2) or 16 (4x4).
inline constexpr int kSsaaSampleCounts[] = {1, 4, 16};

// The grid side for a sample count (1 -> 1, 4 -> 2, 16 -> 4), 0 for any other count.
constexpr int ssaaFactor(int samples) {
    return samples == 1 ? 1 : samples == 4 ? 2 : samples == 16 ? 4 : 0;
}

// Box-filters rows [rowBegin, rowEnd) of `out` from `samples` (asserted: samples is exactly
// factor times out's size in each dimension). Colour: each channel is the mean of the factor^2
// stored 8-bit values, rounded to nearest (ties up): (sum + n/2) / n, in the stored (display)
// encoding as a UNORM8 multisample resolve does. With `linear` (ColorMode::Linear), as an sRGB
// multisample resolve does: each sample decoded, the mean in linear light encoded once
// (encodeSrgb8). Depth (reversed-Z): the nearest sample, the largest value, so a pixel counts as
// covered when any of its samples is.
void resolveBoxRows(const FrameBuffer& samples, int factor, FrameBuffer& out, int rowBegin, int rowEnd,
                    bool linear = false);

// The whole image.
inline void resolveBox(const FrameBuffer& samples, int factor, FrameBuffer& out, bool linear = false) {
    resolveBoxRows(samples, factor, out, 0, out.height(), linear);
}

} // namespace sr
