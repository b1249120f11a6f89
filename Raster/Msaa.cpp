// Multisampling: the D3D sample patterns, the sample target and its box resolve (Msaa.hpp).
#include "Raster/Msaa.hpp"

#include <algorithm>
#include <cassert>

namespace sr {
namespace {

constexpr Fixed kSixteenth = kSubPixelScale / 16;

constexpr SampleOffset at(int x16, int y16) { return {x16 * kSixteenth, y16 * kSixteenth}; }

constexpr SampleOffset kPattern1[] = {at(0, 0)};
constexpr SampleOffset kPattern2[] = {at(4, 4), at(-4, -4)};
constexpr SampleOffset kPattern4[] = {at(-2, -6), at(6, -2), at(-6, 2), at(2, 6)};
constexpr SampleOffset kPattern8[] = {at(1, -3), at(-1, 3), at(5, 1),  at(-3, -5),
                                      at(-5, 5), at(-7, -1), at(3, 7), at(7, -7)};

template <int N>
void resolveRow(const MsaaBuffer& samples, FrameBuffer& out, int y) {
    constexpr std::uint32_t half = N / 2;
    const Pixel* src = samples.colourRow(y);
    const float* depthSrc = samples.depthRow(y);
    Pixel* dst = out.colorRow(y);
    float* depthDst = out.depthRow(y);
    for (int x = 0, w = out.width(); x < w; ++x, src += N, depthSrc += N) {
        float nearest = depthSrc[0];
        bool same = true; // every sample the same colour (a pixel inside one triangle): the mean is it
        for (int s = 1; s < N; ++s) {
            nearest = std::max(nearest, depthSrc[s]);
            same &= src[s] == src[0];
        }
        depthDst[x] = nearest;
        if (same) {
            dst[x] = src[0] | 0xFF000000u;
            continue;
        }
        // Red and blue side by side in one word, green (and the X byte) in another: N * 255 < 2^16.
        std::uint32_t rb = 0, gx = 0;
        for (int s = 0; s < N; ++s) {
            rb += src[s] & 0x00FF00FFu;
            gx += (src[s] >> 8) & 0x00FF00FFu;
        }
        const std::uint32_t r = rb >> 16, b = rb & 0xFFFFu, g = gx & 0xFFFFu;
        dst[x] = packBgra(std::uint8_t((r + half) / N), std::uint8_t((g + half) / N), std::uint8_t((b + half) / N));
    }
}

} // namespace

const SampleOffset* msaaPattern(int samples) {
    switch (samples) {
    case 1: return kPattern1;
    case 2: return kPattern2;
    case 4: return kPattern4;
    case 8: return kPattern8;
    default: return nullptr;
    }
}

bool MsaaBuffer::resize(int width, int height, int samples) {
    if (width < 0 || height < 0 || width > FrameBuffer::kMaxDimension || height > FrameBuffer::kMaxDimension ||
        !validMsaa(samples) || !msaaFits(width, height, samples))
        return false;
    const std::size_t n = std::size_t(width) * std::size_t(height) * std::size_t(samples);
    if (width == width_ && height == height_ && samples == samples_) return true; // contents kept
    colour_.resize(n);
    depth_.resize(n);
    cleared_ = false;
    width_ = width;
    height_ = height;
    samples_ = samples;
    return true;
}

void MsaaBuffer::release() {
    colour_ = {};
    depth_ = {};
    cleared_ = false;
    width_ = height_ = 0;
    samples_ = 1;
}

void MsaaBuffer::clearRows(int rowBegin, int rowEnd, Pixel colour, float depth) {
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, height_);
    if (rowBegin >= rowEnd) return;
    const std::size_t count = offset(rowEnd) - offset(rowBegin);
    fillWords(colourRow(rowBegin), count, colour);
    fillWords(depthRow(rowBegin), count, depth);
}

void resolveMsaaRows(const MsaaBuffer& samples, FrameBuffer& out, int rowBegin, int rowEnd) {
    assert(samples.width() == out.width() && samples.height() == out.height());
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, out.height());
    for (int y = rowBegin; y < rowEnd; ++y) {
        switch (samples.samples()) {
        case 1:
            std::copy_n(samples.colourRow(y), out.width(), out.colorRow(y));
            std::copy_n(samples.depthRow(y), out.width(), out.depthRow(y));
            break;
        case 2: resolveRow<2>(samples, out, y); break;
        case 4: resolveRow<4>(samples, out, y); break;
        case 8: resolveRow<8>(samples, out, y); break;
        default: assert(false && "MSAA sample count must be 1, 2, 4 or 8"); return;
        }
    }
}

void resolveAndClearMsaaRows(MsaaBuffer& samples, FrameBuffer& out, int rowBegin, int rowEnd, Pixel colour,
                             float depth) {
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, out.height());
    for (int y = rowBegin; y < rowEnd; ++y) {
        resolveMsaaRows(samples, out, y, y + 1);
        samples.clearRows(y, y + 1, colour, depth);
    }
}

} // namespace sr
