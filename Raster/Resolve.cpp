// Box-filter resolve of a supersampled target (see Resolve.hpp for the rule).
#include "Raster/Resolve.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>

namespace sr {
namespace {

// One output row for a grid of Factor x Factor samples (a compile-time side lets the inner
// loops unroll; factors 2 and 4 are the only ones used).
template <int Factor>
void resolveRow(const FrameBuffer& samples, FrameBuffer& out, int y) {
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
        float nearest = depthRows[0][x * Factor];
        for (int j = 0; j < Factor; ++j)
            for (int i = 0; i < Factor; ++i) {
                const Pixel p = rows[j][x * Factor + i];
                r += pixelR(p);
                g += pixelG(p);
                b += pixelB(p);
                nearest = std::max(nearest, depthRows[j][x * Factor + i]);
            }
        dst[x] = packBgra(std::uint8_t((r + half) / n), std::uint8_t((g + half) / n), std::uint8_t((b + half) / n));
        depthDst[x] = nearest;
    }
}

} // namespace

void resolveBoxRows(const FrameBuffer& samples, int factor, FrameBuffer& out, int rowBegin, int rowEnd) {
    assert(samples.width() == out.width() * factor && samples.height() == out.height() * factor);
    rowBegin = std::max(rowBegin, 0);
    rowEnd = std::min(rowEnd, out.height());
    for (int y = rowBegin; y < rowEnd; ++y) {
        switch (factor) {
        case 1:
            std::copy_n(samples.colorRow(y), out.width(), out.colorRow(y));
            std::copy_n(samples.depthRow(y), out.width(), out.depthRow(y));
            break;
        case 2: resolveRow<2>(samples, out, y); break;
        case 4: resolveRow<4>(samples, out, y); break;
        default: assert(false && "SSAA factor must be 1, 2 or 4"); return;
        }
    }
}

} // namespace sr
