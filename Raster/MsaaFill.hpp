// The multisampled fill: coverage and depth per sample, shading once per pixel.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <vector>

#include "Raster/Blend.hpp"
#include "Raster/Msaa.hpp"
#include "Raster/PipelineModes.hpp" // DepthMode, PerspectiveMode
#include "Raster/ScanlineFill.hpp"

namespace sr {

// Pixels [x0, x1) of row y, to be shaded at their centres moved by (dx, dy) pixels: (0, 0) for
// runs of pixels whose centre the triangle covers, the centroid's offset for a single pixel whose
// centre it does not. A moved point is evaluated as the plane with its origin moved the other
// way (moveOrigin), so the span loops and kernels need no other change.
struct SpanRun {
    int y = 0, x0 = 0, x1 = 0;
    double dx = 0.0, dy = 0.0;
};

// Makes `moved` (a copy of `t`) evaluate its planes at (x + run.dx, y + run.dy) when asked for
// (x, y): the plane origin moves the other way (rounded once, the same in every path).
inline void moveOrigin(const TriangleSetup& t, const SpanRun& run, TriangleSetup& moved) {
    moved.originX = t.originX - run.dx;
    moved.originY = t.originY - run.dy;
}

// Per-lane memory of the multisampled fill, kept from triangle to triangle.
struct MsaaScratch {
    std::vector<int> spans;             // per row of the triangle, per sample and the centre: [x0, x1)
    struct Row {
        int y = 0, lo = 0, hi = 0; // pixels [lo, hi) of row y have a covered sample
        std::size_t offset = 0;    // where the row's masks start in `covered` and `passed`
    };
    std::vector<Row> rows;
    std::vector<std::uint8_t> covered;  // per pixel of those rows: the covered samples (bit s = sample s)
    std::vector<std::uint8_t> passed;   // ... the covered samples that passed the depth test
    std::vector<SpanRun> runs;          // the triangle's pixels to shade (SpanRun)
};

// Pixel rows a triangle's samples can fall in: every row the snapped triangle's y extent
// touches (a sample lies inside its pixel), a superset of every sample's covered rows. From the
// setup's long edge, which spans the triangle from top to bottom.
inline void msaaRowRange(const TriangleSetup& t, int& rowBegin, int& rowEnd) {
    rowBegin = int(floorDiv(t.longEdge.y0, kSubPixelScale));
    rowEnd = int(floorDiv(std::int64_t(t.longEdge.y0) + t.longEdge.dy, kSubPixelScale)) + 1;
}

namespace detail {

// A hint that the cache line holding `p` is about to be read and written (no effect where the
// compiler has no such hint).
inline void prefetchForWrite(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 1, 3);
#else
    (void)p;
#endif
}

// The centroid of the samples in a coverage mask, as an offset from the pixel centre in pixels
// (the mean of their pattern offsets; (0, 0) for an empty mask).
struct Centroid {
    double dx = 0.0, dy = 0.0;
};
template <int kN>
const Centroid* centroidTable() {
    static const auto table = [] {
        std::vector<Centroid> t(std::size_t(1) << kN);
        const SampleOffset* pattern = msaaPattern(kN);
        for (unsigned mask = 1; mask < t.size(); ++mask) {
            double sx = 0.0, sy = 0.0;
            int count = 0;
            for (int k = 0; k < kN; ++k) {
                if (!(mask & (1u << k))) continue;
                sx += pattern[k].x;
                sy += pattern[k].y;
                ++count;
            }
            t[mask] = {sx / (count * double(kSubPixelScale)), sy / (count * double(kSubPixelScale))};
        }
        return t;
    }();
    return table.data();
}

} // namespace detail

// A multisampled draw with texel alpha (Blend.hpp) shades once per pixel like any other, and its
// alpha travels with the colour in the shading row's X byte (the top byte, 0xFF otherwise) to
// the per-sample write: Mask: 0xFF kept, 0 discarded (the float test a >= cutoff is made here,
// exactly as the one-sample fill makes it); Blend: toUnorm8(a), the opacity the samples are
// blended with (so, multisampled, a transparent texel's alpha is rounded to 8 bits first).
inline Pixel withMsaaAlpha(Pixel colour, const TexelAlpha& texelAlpha, float a) {
    std::uint32_t x = 0;
    if (texelAlpha.mode == AlphaMode::Mask) x = a >= texelAlpha.cutoff ? 0xFFu : 0u;
    else x = toUnorm8(a);
    return (colour & 0x00FFFFFFu) | (x << 24);
}

namespace detail {

template <int kN, DepthMode kDepth, class ShadeRow, class ShadeRuns>
void fillTriangleSamples(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch,
                         ShadeRow& shadeRow, ShadeRuns& shadeRuns, std::uint64_t& shaded, float alpha,
                         AlphaMode texelAlpha) {
    constexpr int n = kN;
    const SampleOffset* pattern = msaaPattern(n);
    const Centroid* centroids = centroidTable<kN>();
    int rowBegin = 0, rowEnd = 0;
    msaaRowRange(t, rowBegin, rowEnd);
    rowBegin = std::max(rowBegin, s.y0);
    rowEnd = std::min(rowEnd, s.y1);
    if (rowBegin >= rowEnd || t.maxX + 1 < s.x0 || t.minX - 1 >= s.x1) return;

    // 0. A small triangle's samples are a few short pieces of rows far apart in memory (a row of
    //    samples is width * n * 4 bytes): ask for all of its depth and colour lines now, so that
    //    their cache misses overlap with each other and with the walks below instead of stalling
    //    the depth test one line at a time (a large triangle's rows stream well on their own).
    const int boxX0 = std::max(t.minX - 1, s.x0), boxX1 = std::min(t.maxX + 2, s.x1);
    if (boxX1 - boxX0 <= 64 && rowEnd - rowBegin <= 64) {
        constexpr std::size_t kLine = 64 / sizeof(float); // samples per 64-byte cache line
        for (int y = rowBegin; y < rowEnd; ++y) {
            const std::size_t from = std::size_t(boxX0) * n, to = std::size_t(boxX1) * n;
            for (std::size_t i = from; i < to; i += kLine) {
                prefetchForWrite(target.depthRow(y) + i);
                prefetchForWrite(target.colourRow(y) + i);
            }
            prefetchForWrite(target.depthRow(y) + to - 1);
            prefetchForWrite(target.colourRow(y) + to - 1);
        }
    }

    // 1. The span of every sample (and of the centre, entry n) on every row: n + 1 exact walks.
    const int stride = 2 * (n + 1);
    scratch.spans.assign(std::size_t(rowEnd - rowBegin) * std::size_t(stride), 0); // [0, 0): empty
    for (int k = 0; k <= n; ++k) {
        const SpanCoverage c = k < n ? sampleCoverage(t, pattern[k].x, pattern[k].y) : sampleCoverage(t, 0, 0);
        const Scissor rows{s.x0, rowBegin, s.x1, rowEnd};
        forEachSpan(c, rows, [&](int y, int x0, int x1) {
            int* span = scratch.spans.data() + std::size_t(y - rowBegin) * std::size_t(stride) + 2 * k;
            span[0] = x0;
            span[1] = x1;
        });
    }

    // 2. Per row: coverage and the depth test, pixel by pixel, its N samples together (adjacent
    //    in memory); the masks are kept (per row from its first pixel `lo`) for step 4, and the
    //    pixels to shade are listed: runs of pixels whose centre is covered, shaded at the
    //    centre, and every other pixel with a sample that passed on its own, at the centroid of
    //    its covered samples. Depth of sample k: the plane at the sample point of pixel `lo` in
    //    double, then + (x - lo) ddx in double, rounded once.
    scratch.rows.clear();
    scratch.runs.clear();
    std::size_t used = 0;
    const double ddx = t.ddx[kPlaneZ];
    for (int y = rowBegin; y < rowEnd; ++y) {
        const int* spans = scratch.spans.data() + std::size_t(y - rowBegin) * std::size_t(stride);
        int lo = s.x1, hi = s.x0;
        for (int k = 0; k < n; ++k) {
            if (spans[2 * k] >= spans[2 * k + 1]) continue;
            lo = std::min(lo, spans[2 * k]);
            hi = std::max(hi, spans[2 * k + 1]);
        }
        if (lo >= hi) continue;
        const std::size_t width = std::size_t(hi - lo);
        if (scratch.covered.size() < used + width) {
            scratch.covered.resize(2 * (used + width));
            scratch.passed.resize(2 * (used + width));
        }
        std::uint8_t* covered = scratch.covered.data() + used;
        std::uint8_t* passed = scratch.passed.data() + used;
        scratch.rows.push_back({y, lo, hi, used});
        used += width;

        float* depth = target.depthRow(y);
        double zStart[kN];
        int x0s[kN], x1s[kN];
        for (int k = 0; k < kN; ++k) {
            x0s[k] = spans[2 * k];
            x1s[k] = spans[2 * k + 1];
            zStart[k] = t.planeAt(kPlaneZ, lo + 0.5 + double(pattern[k].x) / kSubPixelScale,
                                  y + 0.5 + double(pattern[k].y) / kSubPixelScale);
        }
        for (int x = lo; x < hi; ++x) {
            float* stored = depth + std::size_t(x) * kN;
            const double step = double(x - lo);
            unsigned cover = 0, pass = 0;
            for (int k = 0; k < kN; ++k) {
                const bool in = x >= x0s[k] && x < x1s[k];
                const float z = float(zStart[k] + ddx * step);
                bool ok = in;
                if constexpr (kDepth != DepthMode::Off) ok = ok && z > stored[k];
                if constexpr (kDepth == DepthMode::TestWrite) stored[k] = ok ? z : stored[k];
                cover |= unsigned(in) << k;
                pass |= unsigned(ok) << k;
            }
            covered[x - lo] = std::uint8_t(cover);
            passed[x - lo] = std::uint8_t(pass);
        }

        const int c0 = std::max(spans[2 * n], lo), c1 = std::min(spans[2 * n + 1], hi);
        for (int x = lo; x < hi;) {
            if (passed[x - lo] == 0) {
                ++x;
            } else if (x >= c0 && x < c1) {
                const int from = x;
                while (x < c1 && passed[x - lo] != 0) ++x;
                scratch.runs.push_back({y, from, x, 0.0, 0.0});
            } else {
                const Centroid& m = centroids[covered[x - lo]];
                scratch.runs.push_back({y, x, x + 1, m.dx, m.dy});
                ++x;
            }
        }
    }
    if (scratch.runs.empty()) return;

    // 3. Shade once per listed pixel, all rows in one call; the colours land in the pixel-sized
    //    shading rows.
    shadeRuns(static_cast<const SpanRun*>(scratch.runs.data()), int(scratch.runs.size()));

    // 4. Write each shaded colour to the samples that passed.
    for (const MsaaScratch::Row& row : scratch.rows) {
        const Pixel* shadedRow = shadeRow(row.y);
        const std::uint8_t* passed = scratch.passed.data() + row.offset;
        Pixel* colour = target.colourRow(row.y);
        double zStart[kN] = {};
        if (texelAlpha == AlphaMode::Mask)
            for (int k = 0; k < kN; ++k)
                zStart[k] = t.planeAt(kPlaneZ, row.lo + 0.5 + double(pattern[k].x) / kSubPixelScale,
                                      row.y + 0.5 + double(pattern[k].y) / kSubPixelScale);
        for (int x = row.lo; x < row.hi; ++x) {
            const unsigned pass = passed[x - row.lo];
            if (pass == 0) continue;
            ++shaded;
            Pixel c = shadedRow[x];
            Pixel* samples = colour + std::size_t(x) * std::size_t(n);
            if (texelAlpha == AlphaMode::Blend) { // per pixel: the opacity in c's X byte
                const float a = float(c >> 24) / 255.0f;
                for (int k = 0; k < n; ++k)
                    if (pass & (1u << k)) samples[k] = blendOver(c, samples[k], a);
                continue;
            }
            if (texelAlpha == AlphaMode::Mask) { // kept (X 0xFF) or discarded (X 0)
                if ((c >> 24) == 0) {
                    --shaded;
                    continue;
                }
                c |= 0xFF000000u;
                // The depth write the test left to this step (kDepth is Test): step 2's floats.
                float* depth = target.depthRow(row.y) + std::size_t(x) * std::size_t(n);
                for (int k = 0; k < n; ++k)
                    if (pass & (1u << k)) depth[k] = float(zStart[k] + ddx * double(x - row.lo));
            }
            if (alpha < 1.0f) { // a transparent draw: over each passing sample's own colour
                for (int k = 0; k < n; ++k)
                    if (pass & (1u << k)) samples[k] = blendOver(c, samples[k], alpha);
                continue;
            }
            for (int k = 0; k < n; ++k)
                if (pass & (1u << k)) samples[k] = c;
        }
    }
}

} // namespace detail

// Fills triangle `t` into the sample target inside the scissor, multisampled:
//  - coverage per sample: sample s of pixel (x, y) sits at the pixel centre plus the pattern's
//    offset (Msaa.hpp) and is covered by the top-left rule exactly as a pixel centre is
//    (sampleCoverage: the same fixed-point walk, moved);
//  - depth per sample: the depth plane at the sample point, tested (and written, TestWrite)
//    against that sample's depth;
//  - shading ONCE per pixel with at least one covered sample that passed: at the pixel centre
//    when the centre is inside the triangle, otherwise at the centroid of the covered samples (no
//    attribute is extrapolated outside the triangle), by one call shadeRuns(runs, count) per
//    triangle (SpanRun), which writes the colours to shadeRow(y)[x] (pixel-sized scratch rows);
//  - the colour goes to every covered sample that passed (alpha < 1: blended over each, Blend.hpp);
//  - texelAlpha (Mask or Blend; kDepth is then Test): the shaded colour carries its alpha in the
//    X byte (withMsaaAlpha): Blend blends it over each passing sample, Mask writes a kept pixel's
//    colour and depth to its passing samples and leaves a discarded pixel's samples alone.
// `shaded` counts the pixels shaded (and kept).
template <DepthMode kDepth, class ShadeRow, class ShadeRuns>
void fillTriangleMsaa(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch,
                      ShadeRow&& shadeRow, ShadeRuns&& shadeRuns, std::uint64_t& shaded, float alpha = 1.0f,
                      AlphaMode texelAlpha = AlphaMode::Off) {
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= target.width() && s.y1 <= target.height());
    switch (target.samples()) {
    case 2: detail::fillTriangleSamples<2, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shaded, alpha, texelAlpha); break;
    case 4: detail::fillTriangleSamples<4, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shaded, alpha, texelAlpha); break;
    case 8: detail::fillTriangleSamples<8, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shaded, alpha, texelAlpha); break;
    default: detail::fillTriangleSamples<1, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shaded, alpha, texelAlpha); break;
    }
}

} // namespace sr
