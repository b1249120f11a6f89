// FrameBuffer: resize (including to 0x0) without per-frame allocation, and clears.
#include "Raster/FrameBuffer.hpp"

#include <algorithm>

namespace sr {

bool FrameBuffer::resize(int width, int height) {
    if (width < 0 || height < 0 || width > kMaxDimension || height > kMaxDimension) return false;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    // std::vector::resize never shrinks capacity, so going back to a size seen before is free.
    color_.resize(count);
    depth_.resize(count);
    width_ = width;
    height_ = height;
    return true;
}

void FrameBuffer::clear(Pixel colour, float depth) {
    clearColor(colour);
    clearDepth(depth);
}

void FrameBuffer::clearColor(Pixel colour) { std::fill(color_.begin(), color_.end(), colour); }

void FrameBuffer::clearDepth(float depth) { std::fill(depth_.begin(), depth_.end(), depth); }

} // namespace sr
