// FXAA: the post-process edge filter of one-sample frames (Lottes' FXAA 3.11, quality variant).
#pragma once

#include <cstdint>
#include <vector>

#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Frame/FrameBuffer.hpp"

namespace sr {

// The filter reads the finished image (display values, as FXAA expects: after any sRGB encoding)
// and writes, at each pixel on an edge, the colour a bilinear tap would read a fraction of a pixel
// across the edge:
//  1. luma = 0.299 r + 0.587 g + 0.114 b of each pixel (channels / 255), into a copy with a
//     one-pixel border repeating the image's edge (clamp-to-edge, as the shader's texture);
//  2. a pixel whose 4-neighbourhood's luma range is below max(kFxaaEdgeThresholdMin,
//     kFxaaEdgeThreshold x its largest luma) is left as it is (most of a frame);
//  3. otherwise the edge's orientation comes from the 3x3 second differences, the neighbour
//     across it from the steeper of the two gradients, and both ends of the edge are searched
//     along it in kFxaaSearchSteps steps of kFxaaSteps pixels (each tap the mean of the two
//     rows' or columns' luma: a bilinear tap half way between them) until the luma leaves the
//     edge's mean by a quarter of the gradient;
//  4. the offset across the edge is 0.5 - (distance to the nearer end) / (edge length) where
//     that end's luma crosses on the right side, else 0; at least the sub-pixel term
//     kFxaaSubpix x f(contrast of the 3x3 low-pass to the pixel)^2, as FXAA 3.11 computes it;
//  5. the pixel becomes c + (c_across - c) x offset per channel, rounded to the nearest level.
// The thresholds are FXAA 3.11's high-quality settings, the search its default preset's (12:
// steps of 1, 1.5, 2, 4 and 12 pixels) with the 1.5 made 2, so that every tap lies on a pixel
// column or row and reads two pixels, not four. Depth is left alone.
inline constexpr float kFxaaEdgeThreshold = 0.125f;
inline constexpr float kFxaaEdgeThresholdMin = 0.0625f;
inline constexpr float kFxaaSubpix = 0.75f;
inline constexpr int kFxaaSearchSteps = 5;
inline constexpr int kFxaaSteps[kFxaaSearchSteps] = {1, 2, 2, 4, 12};
// The luma weights per 8-bit level (the products are rounded once each, in this order:
// (r wr + g wg) + b wb).
inline constexpr float kFxaaLumaR = 0.299f / 255.0f;
inline constexpr float kFxaaLumaG = 0.587f / 255.0f;
inline constexpr float kFxaaLumaB = 0.114f / 255.0f;

// A filtered pixel, waiting to be written: the filter reads the image while other threads
// filter it, so nothing is written until every band has been filtered.
struct FxaaWrite {
    std::uint32_t index; // y * width + x
    Pixel colour;
};

// The filter's scratch: the bordered luma image (kSlack floats of padding at its end, so that a
// vector group reading the last pixels stays inside) and each band's filtered pixels. Both keep
// their capacity between frames.
struct FxaaScratch {
    static constexpr int kSlack = 32;
    int width = 0, height = 0;
    std::vector<float> luma; // (width + 2) x (height + 2): pixel (x, y) at (y + 1) * (width + 2) + x + 1
    std::vector<std::vector<FxaaWrite>> writes; // per band (fxaaFilterRows' `band`)
    int lumaStride() const { return width + 2; }
    float lumaAt(int x, int y) const { return luma[std::size_t(y + 1) * std::size_t(width + 2) + std::size_t(x + 1)]; }
    void resize(int w, int h, int bands);
};

// Pass 1 over rows [y0, y1): their luma (with the border columns; row 0 also fills the top
// border, the last row the bottom one). `isa`: which kernels (Scalar: the reference); every ISA
// gives the same bits.
void fxaaPrepareRows(const FrameBuffer& image, FxaaScratch& scratch, int y0, int y1, Isa isa);
// Pass 2 over rows [y0, y1): the filter, reading `image` and keeping the pixels on an edge in
// scratch.writes[band] (cleared first). Needs pass 1 over every row first.
void fxaaFilterRows(FxaaScratch& scratch, const FrameBuffer& image, int band, int y0, int y1, Isa isa);
// Pass 3, once pass 2 is over everywhere: band `band`'s pixels written into `image`.
void fxaaWriteBand(const FxaaScratch& scratch, FrameBuffer& image, int band);

// The three passes over the whole image on the calling thread (tests, tools).
void applyFxaa(FrameBuffer& image, FxaaScratch& scratch, Isa isa);

// The vector kernels (FxaaLanes.inl, one copy per ISA); the dispatchers above call them.
#define SR_FXAA_KERNELS(ns)                                                                                   \
    namespace ns {                                                                                            \
    void fxaaPrepareRows(const FrameBuffer& image, FxaaScratch& scratch, int y0, int y1);                     \
    void fxaaFilterRows(const FxaaScratch& scratch, const FrameBuffer& image, int y0, int y1,                 \
                        std::vector<FxaaWrite>& writes);                                                      \
    }
SR_FXAA_KERNELS(kernels_sse2)
SR_FXAA_KERNELS(kernels_avx2)
SR_FXAA_KERNELS(kernels_avx512)
#undef SR_FXAA_KERNELS

} // namespace sr
