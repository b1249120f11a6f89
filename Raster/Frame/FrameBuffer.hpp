// FrameBuffer: packed 32-bit colour laid out as a top-down BI_RGB 32-bpp DIB, plus float depth.
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sr {

// A colour pixel as a 32-bpp DIB stores it: bytes B, G, R, X in memory (little-endian
// 0xXXRRGGBB). The X byte is written as 0xFF so the same buffer also reads as opaque BGRA.
using Pixel = std::uint32_t;

constexpr Pixel packBgra(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    return 0xFF000000u | (Pixel(r) << 16) | (Pixel(g) << 8) | Pixel(b);
}
constexpr std::uint8_t pixelR(Pixel p) { return std::uint8_t(p >> 16); }
constexpr std::uint8_t pixelG(Pixel p) { return std::uint8_t(p >> 8); }
constexpr std::uint8_t pixelB(Pixel p) { return std::uint8_t(p); }

// Sets count 32-bit words from dst on to value (std::fill with 16-byte stores: a clear is bound
// by the number of stores, and -O2 does not vectorise std::fill).
void fillWords(std::uint32_t* dst, std::size_t count, std::uint32_t value);
void fillWords(float* dst, std::size_t count, float value);

class FrameBuffer {
public:
    // Largest accepted width or height. Keeps every framebuffer coordinate well inside the
    // rasterizer's fixed-point guard band and width*height*4 bytes far below 4 GiB.
    static constexpr int kMaxDimension = 8192;

    // Depth value of an empty pixel: reversed-Z, 0 = infinitely far (Math/Conventions.hpp).
    static constexpr float kFarDepth = 0.0f;

    FrameBuffer() = default;
    // For sizes known to be valid (tests, fixed offscreen targets); outside input goes
    // through resize() and its checked result.
    FrameBuffer(int width, int height) {
        [[maybe_unused]] const bool ok = resize(width, height);
        assert(ok && "FrameBuffer size out of range");
    }

    // Resizes to width x height (0 x 0 is valid: a minimised window). Returns false and leaves
    // the buffer unchanged when a dimension is negative or above kMaxDimension. Memory is
    // reused when the new size fits in the old allocation, so resizing back and forth does not
    // allocate. Contents are unspecified after a resize: clear() before drawing.
    [[nodiscard]] bool resize(int width, int height);

    void clear(Pixel colour, float depth = kFarDepth);
    void clearColor(Pixel colour);
    void clearDepth(float depth = kFarDepth);

    int width() const { return width_; }
    int height() const { return height_; }
    bool empty() const { return width_ == 0 || height_ == 0; }
    // Pixels from one row to the next (== width: rows are packed, as a 32-bpp DIB requires).
    int stride() const { return width_; }

    Pixel* colorData() { return color_.data(); }
    const Pixel* colorData() const { return color_.data(); }
    float* depthData() { return depth_.data(); }
    const float* depthData() const { return depth_.data(); }

    Pixel* colorRow(int y) { return color_.data() + std::size_t(y) * std::size_t(width_); }
    const Pixel* colorRow(int y) const { return color_.data() + std::size_t(y) * std::size_t(width_); }
    float* depthRow(int y) { return depth_.data() + std::size_t(y) * std::size_t(width_); }
    const float* depthRow(int y) const { return depth_.data() + std::size_t(y) * std::size_t(width_); }

    // The 8-bit stencil buffer (Raster/Fill/Stencil.hpp), one value per pixel in the colour's layout:
    // allocated only by enableStencil (a frame that uses it), sized by later resizes while it
    // exists, given back by releaseStencil. Contents unspecified until clearStencil.
    void enableStencil();
    void releaseStencil();
    bool hasStencil() const { return hasStencil_; }
    void clearStencil(std::uint8_t value);
    std::uint8_t* stencilRow(int y) { return stencil_.data() + std::size_t(y) * std::size_t(width_); }
    const std::uint8_t* stencilRow(int y) const { return stencil_.data() + std::size_t(y) * std::size_t(width_); }
    std::uint8_t stencil(int x, int y) const { return stencilRow(y)[x]; }

    Pixel pixel(int x, int y) const { return colorRow(y)[x]; }
    float depth(int x, int y) const { return depthRow(y)[x]; }
    void setPixel(int x, int y, Pixel p) { colorRow(y)[x] = p; }

private:
    int width_ = 0;
    int height_ = 0;
    std::vector<Pixel> color_;
    std::vector<float> depth_;
    std::vector<std::uint8_t> stencil_; // empty unless enableStencil
    bool hasStencil_ = false;
};

} // namespace sr
