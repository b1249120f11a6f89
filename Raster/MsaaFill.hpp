// The multisampled fill: coverage and depth per sample, shading once per pixel.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <vector>

#include "Raster/Msaa.hpp"
#include "Raster/PipelineModes.hpp" // DepthMode, PerspectiveMode
#include "Raster/ScanlineFill.hpp"

namespace sr {

// Pixels [x0, x1) of one row.
struct SpanRun {
    int x0 = 0, x1 = 0;
};

// Per-lane memory of the multisampled fill, kept from triangle to triangle.
struct MsaaScratch {
    std::vector<int> spans;             // per row of the triangle, per sample and the centre: [x0, x1)
    std::vector<std::uint8_t> covered;  // per pixel of a row: the covered samples (bit s = sample s)
    std::vector<std::uint8_t> passed;   // ... the covered samples that passed the depth test
    std::vector<SpanRun> runs;          // the row's runs of centre-covered pixels to shade
};

// The fragment at screen point (px, py) of pixel (x, y): the planes evaluated there in double
// and rounded once, the varyings perspective-correct as kPersp says (fillSpan's formulas, at an
// arbitrary point instead of a pixel centre).
template <int kVaryings, PerspectiveMode kPersp>
Fragment<kVaryings> fragmentAt(const TriangleSetup& t, int x, int y, double px, double py) {
    Fragment<kVaryings> f;
    f.x = x;
    f.y = y;
    f.z = float(t.planeAt(kPlaneZ, px, py));
    if constexpr (kVaryings > 0) {
        f.invW = float(t.planeAt(kPlaneInvW, px, py));
        const float w = kPersp == PerspectiveMode::Exact ? 1.0f / f.invW : 1.0f;
        for (int k = 0; k < kVaryings; ++k) {
            const float v = float(t.planeAt(kPlaneVarying0 + k, px, py));
            f.varyings[std::size_t(k)] = kPersp == PerspectiveMode::Exact ? v * w : v;
        }
    }
    return f;
}

// Pixel rows a triangle's samples can fall in: every row the snapped triangle's y extent
// touches (a sample lies inside its pixel), a superset of every sample's covered rows. From the
// setup's long edge, which spans the triangle from top to bottom.
inline void msaaRowRange(const TriangleSetup& t, int& rowBegin, int& rowEnd) {
    rowBegin = int(floorDiv(t.longEdge.y0, kSubPixelScale));
    rowEnd = int(floorDiv(std::int64_t(t.longEdge.y0) + t.longEdge.dy, kSubPixelScale)) + 1;
}

namespace detail {

template <int kN, DepthMode kDepth, class ShadeRow, class ShadeRuns, class ShadeAt>
void fillTriangleSamples(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch,
                         ShadeRow& shadeRow, ShadeRuns& shadeRuns, ShadeAt& shadeAt, std::uint64_t& shaded) {
    constexpr int n = kN;
    const SampleOffset* pattern = msaaPattern(n);
    int rowBegin = 0, rowEnd = 0;
    msaaRowRange(t, rowBegin, rowEnd);
    rowBegin = std::max(rowBegin, s.y0);
    rowEnd = std::min(rowEnd, s.y1);
    if (rowBegin >= rowEnd || t.maxX + 1 < s.x0 || t.minX - 1 >= s.x1) return;

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
        if (scratch.covered.size() < width) {
            scratch.covered.resize(width);
            scratch.passed.resize(width);
        }
        std::uint8_t* covered = scratch.covered.data();
        std::uint8_t* passed = scratch.passed.data();

        // 2. Coverage and the depth test, pixel by pixel, its N samples together (adjacent in
        //    memory). Depth of sample k: the plane at the sample point of the row's first pixel
        //    `lo`, in double, then + (x - lo) ddx in double, rounded once.
        float* depth = target.depthRow(y);
        double zStart[kN];
        int x0s[kN], x1s[kN];
        for (int k = 0; k < kN; ++k) {
            x0s[k] = spans[2 * k];
            x1s[k] = spans[2 * k + 1];
            zStart[k] = t.planeAt(kPlaneZ, lo + 0.5 + double(pattern[k].x) / kSubPixelScale,
                                  y + 0.5 + double(pattern[k].y) / kSubPixelScale);
        }
        const double ddx = t.ddx[kPlaneZ];
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

        // 3. Shade: the pixels whose centre is covered in runs (at the centre), the others one
        //    by one at the centroid of their covered samples.
        const int c0 = std::max(spans[2 * n], lo), c1 = std::min(spans[2 * n + 1], hi);
        scratch.runs.clear();
        for (int x = c0; x < c1;) {
            if (passed[x - lo] == 0) {
                ++x;
                continue;
            }
            const int from = x;
            while (x < c1 && passed[x - lo] != 0) ++x;
            scratch.runs.push_back({from, x});
        }
        if (!scratch.runs.empty()) shadeRuns(y, scratch.runs.data(), int(scratch.runs.size()));
        const Pixel* centreColours = shadeRow(y);

        // 4. Write each shaded colour to the samples that passed.
        Pixel* colour = target.colourRow(y);
        for (int x = lo; x < hi; ++x) {
            const unsigned pass = passed[x - lo];
            if (pass == 0) continue;
            ++shaded;
            Pixel c;
            if (x >= c0 && x < c1) {
                c = centreColours[x];
            } else {
                const unsigned cover = covered[x - lo];
                double sx = 0.0, sy = 0.0;
                int count = 0;
                for (int k = 0; k < n; ++k) {
                    if (!(cover & (1u << k))) continue;
                    sx += pattern[k].x;
                    sy += pattern[k].y;
                    ++count;
                }
                c = shadeAt(x, y, x + 0.5 + sx / (count * double(kSubPixelScale)),
                            y + 0.5 + sy / (count * double(kSubPixelScale)));
            }
            Pixel* samples = colour + std::size_t(x) * std::size_t(n);
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
//    when the centre is inside the triangle, with shadeRuns(y, runs, count) over the row's runs
//    of such pixels, which writes their colours to shadeRow(y)[x] (a pixel-sized scratch row);
//    otherwise at the centroid of the covered samples, with shadeAt(x, y, px, py) -> Pixel
//    (no attribute is extrapolated outside the triangle);
//  - the colour goes to every covered sample that passed.
// `shaded` counts the pixels shaded.
template <DepthMode kDepth, class ShadeRow, class ShadeRuns, class ShadeAt>
void fillTriangleMsaa(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch,
                      ShadeRow&& shadeRow, ShadeRuns&& shadeRuns, ShadeAt&& shadeAt, std::uint64_t& shaded) {
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= target.width() && s.y1 <= target.height());
    switch (target.samples()) {
    case 2: detail::fillTriangleSamples<2, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shadeAt, shaded); break;
    case 4: detail::fillTriangleSamples<4, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shadeAt, shaded); break;
    case 8: detail::fillTriangleSamples<8, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shadeAt, shaded); break;
    default: detail::fillTriangleSamples<1, kDepth>(t, target, s, scratch, shadeRow, shadeRuns, shadeAt, shaded); break;
    }
}

} // namespace sr
