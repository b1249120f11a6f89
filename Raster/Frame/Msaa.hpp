// Multisampling (MSAA): the sample patterns, the per-sample colour and depth target, its resolve.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Setup/FixedPoint.hpp"

namespace sr {

// Samples per pixel MSAA offers: 1 (off), 2, 4 or 8.
inline constexpr int kMsaaSampleCounts[] = {1, 2, 4, 8};
constexpr bool validMsaa(int samples) { return samples == 1 || samples == 2 || samples == 4 || samples == 8; }

// Most samples a multisampled target may hold: as many as the largest supersampled one
// (FrameBuffer::kMaxDimension squared, 67M samples, 512 MiB of colour and depth).
inline constexpr std::int64_t kMaxMsaaSamples = std::int64_t(FrameBuffer::kMaxDimension) * FrameBuffer::kMaxDimension;
constexpr bool msaaFits(int width, int height, int samples) {
    return std::int64_t(width) * height * samples <= kMaxMsaaSamples;
}

// A sample's offset from its pixel centre in 1/256 pixel (the snapping grid), y down.
struct SampleOffset {
    Fixed x = 0, y = 0;
};

// The Direct3D standard sample patterns (D3D11_STANDARD_MULTISAMPLE_PATTERN; offsets in 1/16
// pixel, y down, as the D3D documentation lists them), scaled to the 1/256 grid: every sample
// lies exactly on it, so the per-sample coverage uses the same 8-bit fixed point as one sample.
// 1 sample: the pixel centre. Returns nullptr for a count validMsaa rejects.
const SampleOffset* msaaPattern(int samples);

// The per-sample target: `samples` colours and depths per pixel, pixel-major (the samples of
// one pixel are adjacent: sample s of pixel x on row y is element (y * width + x) * samples + s).
// Empty until resized; resize keeps the allocation when it fits, and the contents when the size
// and count are unchanged.
//
// Fast clear: clearRowsLazily marks blocks of kMsaaClearBlock pixels of a row as holding the
// clear values without writing them; a block is written (made real) only when something is
// drawn into it (prepareSpan), and the resolve turns a still-pending block into the clear colour
// without reading it. A frame that covers a fifth of the screen so moves a fifth of the sample
// memory instead of all of it twice (clear and resolve). colourRow / depthRow are the raw
// memory: whoever reads or writes samples calls prepareSpan for them first.
inline constexpr int kMsaaClearBlock = 16;

class MsaaBuffer {
public:
    // Returns false (and leaves the buffer as it was) for a size FrameBuffer would refuse, a
    // count validMsaa rejects, or more than kMaxMsaaSamples samples.
    [[nodiscard]] bool resize(int width, int height, int samples);
    void release(); // gives the memory back

    int width() const { return width_; }
    int height() const { return height_; }
    int samples() const { return samples_; }
    bool empty() const { return width_ == 0 || height_ == 0; }

    Pixel* colourRow(int y) { return colour_.data() + offset(y); }
    const Pixel* colourRow(int y) const { return colour_.data() + offset(y); }
    float* depthRow(int y) { return depth_.data() + offset(y); }
    const float* depthRow(int y) const { return depth_.data() + offset(y); }

    // Sets rows [rowBegin, rowEnd) of every sample to colour and depth (written now).
    void clearRows(int rowBegin, int rowEnd, Pixel colour, float depth);
    // The same, as pending blocks (fast clear): nothing is written until prepareSpan.
    void clearRowsLazily(int rowBegin, int rowEnd, Pixel colour, float depth);
    // Makes the samples of pixels [x0, x1) of row y real (writes the pending clear of the blocks
    // they lie in), so that colourRow / depthRow can be read and written there. Rows are
    // independent: lanes that own different rows may call it at once.
    void prepareSpan(int y, int x0, int x1) {
        std::uint8_t* pending = pending_.data() + std::size_t(y) * std::size_t(blocksPerRow_);
        for (int b = x0 / kMsaaClearBlock, last = (x1 - 1) / kMsaaClearBlock; b <= last; ++b)
            if (pending[b]) materialise(y, b);
    }
    // Whether block b (pixels [b * kMsaaClearBlock, ...)) of row y is a pending clear.
    bool pendingBlock(int y, int b) const {
        return pending_[std::size_t(y) * std::size_t(blocksPerRow_) + std::size_t(b)] != 0;
    }
    Pixel rowClearColour(int y) const { return rowClear_[std::size_t(y)].colour; }
    float rowClearDepth(int y) const { return rowClear_[std::size_t(y)].depth; }

    // Whether every sample is known to hold (colour, depth): set by markCleared once all rows are
    // cleared (by clearRows or a resolve that clears), reset by resize and markDrawn (any draw).
    bool isCleared(Pixel colour, float depth) const {
        return cleared_ && clearColour_ == colour && clearDepth_ == depth;
    }
    void markCleared(Pixel colour, float depth) {
        cleared_ = true;
        clearColour_ = colour;
        clearDepth_ = depth;
    }
    void markDrawn() { cleared_ = false; }

private:
    std::size_t offset(int y) const { return std::size_t(y) * std::size_t(width_) * std::size_t(samples_); }
    void materialise(int y, int block);
    struct RowClear {
        Pixel colour = 0;
        float depth = 0.0f;
    };
    int width_ = 0, height_ = 0, samples_ = 1, blocksPerRow_ = 0;
    bool cleared_ = false;
    Pixel clearColour_ = 0;
    float clearDepth_ = 0.0f;
    std::vector<Pixel> colour_;
    std::vector<float> depth_;
    std::vector<std::uint8_t> pending_; // per row, per block: 1 = holds its row's clear (not yet written)
    std::vector<RowClear> rowClear_;    // per row: the values of its pending blocks
};

// Box-filters rows [rowBegin, rowEnd) of `out` (the same size as `samples`, asserted) from the
// sample target, with the SSAA resolve's rule (Resolve.hpp): per channel the rounded mean
// (sum + n/2) / n of the stored 8-bit values (with `linear`: of the decoded values, encoded once),
// depth = the nearest (largest) sample.
void resolveMsaaRows(const MsaaBuffer& samples, FrameBuffer& out, int rowBegin, int rowEnd, bool linear = false);

// The same, then clearing each row of samples to (colour, depth) lazily (clearRowsLazily): the
// next frame's clear costs no pass over the memory (the caller marks the buffer cleared once
// every row is done). A pending block resolves to its clear without being read.
void resolveAndClearMsaaRows(MsaaBuffer& samples, FrameBuffer& out, int rowBegin, int rowEnd, Pixel colour,
                             float depth, bool linear = false);

} // namespace sr
