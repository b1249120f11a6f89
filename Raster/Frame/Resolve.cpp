// Box-filter resolve of a supersampled target (see Resolve.hpp for the rule).
#include "Raster/Frame/Resolve.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>

#include "Raster/Shade/ColorSpace.hpp"

namespace sr {
namespace {

// One output row for a grid of Factor x Factor samples (a compile-time side lets the inner
// loops unroll; factors 2 and 4 are the only ones used).
template <int Factor, bool kLinear>
void resolveRow(const FrameBuffer& samples, FrameBuffer& out, int y) {
    const auto& decode = srgbDecodeTable();
    constexpr std::uint32_t n = Factor * Factor, half = n / 2;
    Pixel* dst = out.colorRow(y);
    float* depthDst = out.depthRow(y);
    const Pixel* rows[Factor];
    const float* depthRows[Factor];
    for (int j = 0; j < Factor; ++j) {
        rows[j] = samples.colorRow(y * Factor + j);
        depthRows[j] = samples.depthRow(y * Factor + j);
    }
    for (int x = 0, w = out.width(); x < w; ++x) {
        std::uint32_t r = 0, g = 0, b = 0;
        float lr = 0.0f, lg = 0.0f, lb = 0.0f;
        float nearest = depthRows[0][x * Factor];
        for (int j = 0; j < Factor; ++j)
            for (int i = 0; i < Factor; ++i) {
                const Pixel p = rows[j][x * Factor + i];
                if constexpr (kLinear) {
                    lr += decode[pixelR(p)];
                    lg += decode[pixelG(p)];
                    lb += decode[pixelB(p)];
                } else {
                    r += pixelR(p);
                    g += pixelG(p);
                    b += pixelB(p);
                }
                nearest = std::max(nearest, depthRows[j][x * Factor + i]);
            }
        if constexpr (kLinear) {
            constexpr float inv = 1.0f / float(n);
            dst[x] = packBgra(encodeSrgb8(lr * inv), encodeSrgb8(lg * inv), encodeSrgb8(lb * inv));
        } else {
            dst[x] = packBgra(std::uint8_t((r + half) / n), std::uint8_t((g + half) / n), std::uint8_t((b + half) / n));
        }
        depthDst[x] = nearest;
    }
}

} // namespace

void resolveBoxRows(const FrameBuffer& samples, int factor, FrameBuffer& out, int rowBegin, int rowEnd, bool linear) {
    assert(samples.width() == out.width() * factor && samples.height() == out.height() * factor);
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, out.height());
    for (int y = rowBegin; y < rowEnd; ++y) {
        switch (factor) {
        case 1:
            std::copy_n(samples.colorRow(y), out.width(), out.colorRow(y));
            std::copy_n(samples.depthRow(y), out.width(), out.depthRow(y));
            break;
        case 2: linear ? resolveRow<2, true>(samples, out, y) : resolveRow<2, false>(samples, out, y); break;
        case 4: linear ? resolveRow<4, true>(samples, out, y) : resolveRow<4, false>(samples, out, y); break;
        default: assert(false && "SSAA factor must be 1, 2 or 4"); return;
        }
    }
}

} // namespace sr
