// FrameBuffer: resize (including to 0x0) without per-frame allocation, and clears.
#include "Raster/Frame/FrameBuffer.hpp"

#include <algorithm>
#include <cstring>

#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#include <emmintrin.h>
#define SR_FILL_SSE2 1
#else
#define SR_FILL_SSE2 0
#endif

namespace sr {

bool FrameBuffer::resize(int width, int height) {
    if (width < 0 || height < 0 || width > kMaxDimension || height > kMaxDimension) return false;
    const std::size_t count = std::size_t(width) * std::size_t(height);
    // std::vector::resize never shrinks capacity, so going back to a size seen before is free.
    color_.resize(count);
    depth_.resize(count);
    if (hasStencil_) stencil_.resize(count);
    width_ = width;
    height_ = height;
    return true;
}

namespace {

// Single words up to a 16-byte boundary, then aligned 16-byte stores (__m128i may alias any
// type), then the tail; `bits` is value's object representation.
template <class Word>
void fillWordsImpl(Word* dst, std::size_t count, Word value, [[maybe_unused]] std::uint32_t bits) {
    static_assert(sizeof(Word) == 4, "32-bit words");
#if SR_FILL_SSE2
    while (count > 0 && (reinterpret_cast<std::uintptr_t>(dst) & 15u) != 0) {
        *dst++ = value;
        --count;
    }
    const __m128i v = _mm_set1_epi32(int(bits));
    for (; count >= 16; count -= 16, dst += 16) {
        _mm_store_si128(reinterpret_cast<__m128i*>(dst), v);
        _mm_store_si128(reinterpret_cast<__m128i*>(dst + 4), v);
        _mm_store_si128(reinterpret_cast<__m128i*>(dst + 8), v);
        _mm_store_si128(reinterpret_cast<__m128i*>(dst + 12), v);
    }
    for (; count >= 4; count -= 4, dst += 4) _mm_store_si128(reinterpret_cast<__m128i*>(dst), v);
#endif
    std::fill(dst, dst + count, value);
}

} // namespace

void fillWords(std::uint32_t* dst, std::size_t count, std::uint32_t value) { fillWordsImpl(dst, count, value, value); }

void fillWords(float* dst, std::size_t count, float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    fillWordsImpl(dst, count, value, bits);
}

void FrameBuffer::clear(Pixel colour, float depth) {
    clearColor(colour);
    clearDepth(depth);
}

void FrameBuffer::enableStencil() {
    hasStencil_ = true;
    stencil_.resize(color_.size());
}

void FrameBuffer::releaseStencil() {
    hasStencil_ = false;
    std::vector<std::uint8_t>().swap(stencil_);
}

void FrameBuffer::clearStencil(std::uint8_t value) { std::fill(stencil_.begin(), stencil_.end(), value); }

void FrameBuffer::clearColor(Pixel colour) { fillWords(color_.data(), color_.size(), colour); }

void FrameBuffer::clearDepth(float depth) { fillWords(depth_.data(), depth_.size(), depth); }

} // namespace sr
