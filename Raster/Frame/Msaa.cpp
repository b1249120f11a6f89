// Multisampling: the D3D sample patterns, the sample target and its box resolve (Msaa.hpp).
#include "Raster/Frame/Msaa.hpp"

#include <algorithm>
#include <cassert>

#include "Raster/Shade/ColorSpace.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define SR_RESOLVE_SSE2 1
#else
#define SR_RESOLVE_SSE2 0
#endif

namespace sr {
namespace {

constexpr Fixed kSixteenth = kSubPixelScale / 16;

constexpr SampleOffset at(int x16, int y16) { return {x16 * kSixteenth, y16 * kSixteenth}; }

constexpr SampleOffset kPattern1[] = {at(0, 0)};
constexpr SampleOffset kPattern2[] = {at(4, 4), at(-4, -4)};
constexpr SampleOffset kPattern4[] = {at(-2, -6), at(6, -2), at(-6, 2), at(2, 6)};
constexpr SampleOffset kPattern8[] = {at(1, -3), at(-1, 3), at(5, 1),  at(-3, -5),
                                      at(-5, 5), at(-7, -1), at(3, 7), at(7, -7)};

// One pixel's N samples: per channel the rounded mean (alpha 0xFF), depth the nearest (the
// samples folded in order with std::max). The rule every resolve path follows.
template <int N>
void resolvePixel(const Pixel* src, const float* depthSrc, Pixel* dst, float* depthDst) {
    constexpr std::uint32_t half = N / 2;
    float nearest = depthSrc[0];
    for (int s = 1; s < N; ++s) nearest = std::max(nearest, depthSrc[s]);
    *depthDst = nearest;
#if SR_RESOLVE_SSE2
    if constexpr (N == 4) {
        // The same sums and rounding four lanes at a time: (sum + 2) >> 2 is (sum + 2) / 4.
        const __m128i c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src));
        if (_mm_movemask_epi8(_mm_cmpeq_epi32(c, _mm_shuffle_epi32(c, 0))) == 0xFFFF) {
            *dst = src[0] | 0xFF000000u;
            return;
        }
        const __m128i zero = _mm_setzero_si128();
        __m128i sum = _mm_add_epi16(_mm_unpacklo_epi8(c, zero), _mm_unpackhi_epi8(c, zero));
        sum = _mm_add_epi16(sum, _mm_srli_si128(sum, 8));
        sum = _mm_srli_epi16(_mm_add_epi16(sum, _mm_set1_epi16(2)), 2);
        *dst = (Pixel(_mm_cvtsi128_si32(_mm_packus_epi16(sum, sum))) & 0x00FFFFFFu) | 0xFF000000u;
        return;
    }
#endif
    bool same = true; // every sample the same colour (a pixel inside one triangle): the mean is it
    for (int s = 1; s < N; ++s) same &= src[s] == src[0];
    if (same) {
        *dst = src[0] | 0xFF000000u;
        return;
    }
    // Red and blue side by side in one word, green (and the X byte) in another: N * 255 < 2^16.
    std::uint32_t rb = 0, gx = 0;
    for (int s = 0; s < N; ++s) {
        rb += src[s] & 0x00FF00FFu;
        gx += (src[s] >> 8) & 0x00FF00FFu;
    }
    const std::uint32_t r = rb >> 16, b = rb & 0xFFFFu, g = gx & 0xFFFFu;
    *dst = packBgra(std::uint8_t((r + half) / N), std::uint8_t((g + half) / N), std::uint8_t((b + half) / N));
}

#if SR_RESOLVE_SSE2
// Four adjacent pixels at once, with resolvePixel's exact results and no branch: every channel
// summed in 16 bits (8 * 255 fits) and rounded as (sum + N/2) >> log2(N), which is the shortcut's
// colour too when the samples are alike; the depths transposed so that row k holds sample k of
// the four pixels, then folded in sample order with _mm_max_ps(sample, nearest), which is
// std::max(nearest, sample) lane by lane (the nearest kept unless it is less: ties between signed
// zeros and NaN samples come out as the scalar fold's).
template <int N>
void resolveFour(const Pixel* src, const float* depthSrc, Pixel* dst, float* depthDst) {
    static_assert(N == 2 || N == 8, "the sample counts resolved four pixels at a time");
    constexpr int kVectors = N / 4; // colour or depth vectors per pixel (N = 8)
    const __m128i zero = _mm_setzero_si128();
    auto colours = [&](int i) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(src) + i); };
    auto depths = [&](int i) { return _mm_loadu_ps(depthSrc + 4 * i); };
    // The channel sums of pixels 0 and 1 (sum01: B, G, R, X of each) and of pixels 2 and 3.
    __m128i sum01, sum23;
    if constexpr (N == 2) {
        auto pairSums = [&](__m128i c) { // two pixels of two samples: [p s0, p s1] + [q s0, q s1]
            const __m128i lo = _mm_unpacklo_epi8(c, zero), hi = _mm_unpackhi_epi8(c, zero);
            return _mm_add_epi16(_mm_unpacklo_epi64(lo, hi), _mm_unpackhi_epi64(lo, hi));
        };
        sum01 = pairSums(colours(0));
        sum23 = pairSums(colours(1));
    } else {
        __m128i halves[4]; // per pixel: its even samples' sums, then its odd samples'
        for (int p = 0; p < 4; ++p) {
            halves[p] = zero;
            for (int v = 0; v < kVectors; ++v) {
                const __m128i c = colours(p * kVectors + v);
                halves[p] = _mm_add_epi16(halves[p], _mm_add_epi16(_mm_unpacklo_epi8(c, zero), _mm_unpackhi_epi8(c, zero)));
            }
        }
        sum01 = _mm_add_epi16(_mm_unpacklo_epi64(halves[0], halves[1]), _mm_unpackhi_epi64(halves[0], halves[1]));
        sum23 = _mm_add_epi16(_mm_unpacklo_epi64(halves[2], halves[3]), _mm_unpackhi_epi64(halves[2], halves[3]));
    }
    constexpr int kShift = N == 2 ? 1 : 3; // log2(N)
    const __m128i half = _mm_set1_epi16(N / 2);
    sum01 = _mm_srli_epi16(_mm_add_epi16(sum01, half), kShift);
    sum23 = _mm_srli_epi16(_mm_add_epi16(sum23, half), kShift);
    const __m128i opaque = _mm_set1_epi32(int(0xFF000000u));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), _mm_or_si128(_mm_packus_epi16(sum01, sum23), opaque));

    __m128 nearest = _mm_setzero_ps(); // sample 0's depths first below
    if constexpr (N == 2) {
        const __m128 a = depths(0), b = depths(1);
        const __m128 first = _mm_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0));
        const __m128 second = _mm_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1));
        nearest = _mm_max_ps(second, first);
    } else {
        for (int v = 0; v < kVectors; ++v) {
            __m128 r0 = depths(0 * kVectors + v), r1 = depths(1 * kVectors + v);
            __m128 r2 = depths(2 * kVectors + v), r3 = depths(3 * kVectors + v);
            _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
            nearest = v == 0 ? r0 : _mm_max_ps(r0, nearest);
            nearest = _mm_max_ps(r1, nearest);
            nearest = _mm_max_ps(r2, nearest);
            nearest = _mm_max_ps(r3, nearest);
        }
    }
    _mm_storeu_ps(depthDst, nearest);
}
#endif

// Two and eight samples: four pixels at a time (resolve stage 0.8-0.9x the pixel-by-pixel loop).
// Four samples: pixel by pixel, where the shortcut for a pixel inside one triangle is one vector
// compare (four at a time took 1.1-1.2x as long).
template <int N>
void resolvePixels(const Pixel* src, const float* depthSrc, Pixel* dst, float* depthDst, int x0, int x1) {
    int x = x0;
#if SR_RESOLVE_SSE2
    if constexpr (N != 4)
        for (; x + 4 <= x1; x += 4)
            resolveFour<N>(src + std::size_t(x) * N, depthSrc + std::size_t(x) * N, dst + x, depthDst + x);
#endif
    for (; x < x1; ++x) resolvePixel<N>(src + std::size_t(x) * N, depthSrc + std::size_t(x) * N, dst + x, depthDst + x);
}

// The resolve in linear light (Resolve.hpp's rule with `linear`): n samples per pixel decoded,
// their mean encoded once.
void resolvePixelsLinear(const Pixel* src, const float* depthSrc, Pixel* dst, float* depthDst, int x0, int x1, int n) {
    const auto& decode = srgbDecodeTable();
    const float inv = 1.0f / float(n);
    for (int x = x0; x < x1; ++x) {
        const Pixel* s = src + std::size_t(x) * std::size_t(n);
        const float* d = depthSrc + std::size_t(x) * std::size_t(n);
        float r = 0.0f, g = 0.0f, b = 0.0f, nearest = d[0];
        for (int k = 0; k < n; ++k) {
            r += decode[pixelR(s[k])];
            g += decode[pixelG(s[k])];
            b += decode[pixelB(s[k])];
            nearest = std::max(nearest, d[k]);
        }
        dst[x] = packBgra(encodeSrgb8(r * inv), encodeSrgb8(g * inv), encodeSrgb8(b * inv));
        depthDst[x] = nearest;
    }
}

// Row y, block by block: a pending block (fast clear) is its row's clear, as the resolve of N
// equal samples would give (the colour with X = 0xFF, the depth itself), without reading it.
void resolveRow(const MsaaBuffer& samples, FrameBuffer& out, int y, bool linear) {
    const Pixel* src = samples.colourRow(y);
    const float* depthSrc = samples.depthRow(y);
    Pixel* dst = out.colorRow(y);
    float* depthDst = out.depthRow(y);
    const int width = out.width();
    for (int x0 = 0, b = 0; x0 < width; x0 += kMsaaClearBlock, ++b) {
        int x1 = std::min(x0 + kMsaaClearBlock, width);
        if (samples.pendingBlock(y, b)) { // this and the pending blocks after it, in one fill
            while (x1 < width && samples.pendingBlock(y, b + 1)) {
                ++b;
                x1 = std::min(x1 + kMsaaClearBlock, width);
            }
            fillWords(dst + x0, std::size_t(x1 - x0), samples.rowClearColour(y) | 0xFF000000u);
            fillWords(depthDst + x0, std::size_t(x1 - x0), samples.rowClearDepth(y));
            x0 = x1 - kMsaaClearBlock; // the loop's step lands on x1
            continue;
        }
        if (linear && samples.samples() > 1) {
            resolvePixelsLinear(src, depthSrc, dst, depthDst, x0, x1, samples.samples());
            continue;
        }
        switch (samples.samples()) {
        case 1:
            std::copy(src + x0, src + x1, dst + x0);
            std::copy(depthSrc + x0, depthSrc + x1, depthDst + x0);
            break;
        case 2: resolvePixels<2>(src, depthSrc, dst, depthDst, x0, x1); break;
        case 4: resolvePixels<4>(src, depthSrc, dst, depthDst, x0, x1); break;
        case 8: resolvePixels<8>(src, depthSrc, dst, depthDst, x0, x1); break;
        default: assert(false && "MSAA sample count must be 1, 2, 4 or 8"); return;
        }
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
    blocksPerRow_ = (width + kMsaaClearBlock - 1) / kMsaaClearBlock;
    pending_.assign(std::size_t(height) * std::size_t(blocksPerRow_), 0);
    rowClear_.assign(std::size_t(height), RowClear{});
    return true;
}

void MsaaBuffer::release() {
    colour_ = {};
    depth_ = {};
    pending_ = {};
    rowClear_ = {};
    cleared_ = false;
    width_ = height_ = blocksPerRow_ = 0;
    samples_ = 1;
}

void MsaaBuffer::clearRows(int rowBegin, int rowEnd, Pixel colour, float depth) {
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, height_);
    if (rowBegin >= rowEnd) return;
    const std::size_t count = offset(rowEnd) - offset(rowBegin);
    fillWords(colourRow(rowBegin), count, colour);
    fillWords(depthRow(rowBegin), count, depth);
    std::fill(pending_.begin() + std::ptrdiff_t(rowBegin) * blocksPerRow_,
              pending_.begin() + std::ptrdiff_t(rowEnd) * blocksPerRow_, std::uint8_t(0));
}

void MsaaBuffer::clearRowsLazily(int rowBegin, int rowEnd, Pixel colour, float depth) {
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, height_);
    if (rowBegin >= rowEnd) return;
    std::fill(pending_.begin() + std::ptrdiff_t(rowBegin) * blocksPerRow_,
              pending_.begin() + std::ptrdiff_t(rowEnd) * blocksPerRow_, std::uint8_t(1));
    std::fill(rowClear_.begin() + rowBegin, rowClear_.begin() + rowEnd, RowClear{colour, depth});
}

void MsaaBuffer::materialise(int y, int block) {
    const int x0 = block * kMsaaClearBlock, x1 = std::min(x0 + kMsaaClearBlock, width_);
    const std::size_t from = offset(y) + std::size_t(x0) * std::size_t(samples_);
    const std::size_t count = std::size_t(x1 - x0) * std::size_t(samples_);
    fillWords(colour_.data() + from, count, rowClear_[std::size_t(y)].colour);
    fillWords(depth_.data() + from, count, rowClear_[std::size_t(y)].depth);
    pending_[std::size_t(y) * std::size_t(blocksPerRow_) + std::size_t(block)] = 0;
}

void resolveMsaaRows(const MsaaBuffer& samples, FrameBuffer& out, int rowBegin, int rowEnd, bool linear) {
    assert(samples.width() == out.width() && samples.height() == out.height());
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, out.height());
    for (int y = rowBegin; y < rowEnd; ++y) resolveRow(samples, out, y, linear);
}

void resolveAndClearMsaaRows(MsaaBuffer& samples, FrameBuffer& out, int rowBegin, int rowEnd, Pixel colour,
                             float depth, bool linear) {
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, out.height());
    resolveMsaaRows(samples, out, rowBegin, rowEnd, linear);
    samples.clearRowsLazily(rowBegin, rowEnd, colour, depth);
}

} // namespace sr
