// The multisampled fill: coverage and depth per sample, shading once per pixel.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <vector>

#include "Raster/Fill/Blend.hpp"
#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Fill/ScanlineFill.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "Raster/Setup/PipelineModes.hpp" // DepthMode, PerspectiveMode

namespace sr {

// Pixels [x0, x1) of row y, to be shaded at their centres moved by (dx, dy) pixels: (0, 0) for
// runs of pixels whose centre the triangle covers, the centroid's offset for a single pixel whose
// centre it does not. A moved point is evaluated as the plane with its origin moved the other
// way (moveOrigin), so the span loops and kernels need no other change. The run's pixels' masks
// of passing samples start at MsaaScratch::passed[passedAt] (one per pixel, x0 first).
struct SpanRun {
    int y = 0, x0 = 0, x1 = 0;
    std::uint32_t passedAt = 0;
    double dx = 0.0, dy = 0.0;
};

// Where a run shader may write its colours itself (kernels whose shading reads nothing of the
// triangle: Kernels.inl, shadeRunSpans): the target's samples whose bits are set in the runs'
// masks, passed[run.passedAt + (x - run.x0)]. Null target: the draw blends or discards per
// sample (transparent, texel alpha), so the colours go to the shading rows.
struct SampleWrite {
    MsaaBuffer* target = nullptr;
    const std::uint8_t* passed = nullptr;
};

// What a program's run shader did with a triangle's runs: nothing (no kernel for this draw: the
// scalar loop shades), shaded them into the shading rows, or wrote them to the samples
// (SampleWrite).
enum class RunShading { NotDone, IntoRows, IntoSamples };

// The plane origin that makes `t`'s planes evaluate at (x + run.dx, y + run.dy) when asked for
// (x, y): moved the other way, rounded once (the same in every path).
struct PlaneOrigin {
    double x = 0.0, y = 0.0;
};
inline PlaneOrigin movedOrigin(const TriangleSetup& t, const SpanRun& run) {
    return {t.originX - run.dx, t.originY - run.dy};
}

// Makes `moved` (a copy of `t`) evaluate its planes there (movedOrigin).
inline void moveOrigin(const TriangleSetup& t, const SpanRun& run, TriangleSetup& moved) {
    const PlaneOrigin origin = movedOrigin(t, run);
    moved.originX = origin.x;
    moved.originY = origin.y;
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

// How coverTriangleSamples finds the covered samples and tests their depth (both give the same
// result: tested).
enum class MsaaCoverageMethod {
    Auto,      // edge functions for a small triangle, else the walks; the depth test 4 samples at a
               // time, the pixels to shade listed in the same pass over the row
    Reference, // n + 1 exact edge walks (forEachSpan), one per sample and one for the centre, and
               // the depth test sample by sample: the readable twin
};

// Pixel columns [x0, x1) a triangle's samples can fall in: the columns of its snapped extent
// (t.minX, t.maxX: the columns of its leftmost and rightmost vertex). Every sample lies strictly
// inside its own pixel (each pattern offset is below half a pixel each way: tested), and a
// covered sample lies inside the closed triangle, so within its extent: no column outside it
// has a covered sample. The analogue of msaaRowRange.
inline void msaaColumnRange(const TriangleSetup& t, int& x0, int& x1) {
    x0 = t.minX;
    x1 = t.maxX + 1;
}

// Whether coverTriangleSamples tests triangle `t` with edge functions (Auto): its columns and
// rows (msaaColumnRange, msaaRowRange) fit in kMsaaSmallSide pixels each way, so that every
// vertex and sample point of that box lies within 32 * 256 of every other each way, and every
// edge value over the box is at most 2 * (32 * 256)^2 = 2^27 in magnitude: exact in int32.
inline constexpr int kMsaaSmallSide = 32;
inline bool msaaSmallTriangle(const TriangleSetup& t) {
    int rowBegin = 0, rowEnd = 0, x0 = 0, x1 = 0;
    msaaRowRange(t, rowBegin, rowEnd);
    msaaColumnRange(t, x0, x1);
    return x1 - x0 <= kMsaaSmallSide && rowEnd - rowBegin <= kMsaaSmallSide;
}

// The multisampled fill's out-of-line stages for one sample count, depth mode and coverage
// method (MsaaCoverage.cpp), chosen once per draw (msaaStages; LaneState::msaaStages): no switch
// on the sample count or the depth mode per triangle.
struct MsaaStages {
    int samples = 0; // 0: not chosen
    // coverTriangleSamples' work for this choice (the target holds `samples` samples per pixel).
    void (*cover)(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch) = nullptr;
    // Writes shaded[x] to the samples of pixels [lo, hi) of a sample row whose bits are set in
    // passed[x - lo] (the others keep theirs); returns how many pixels had one.
    std::uint64_t (*write)(Pixel* colourRow, const Pixel* shaded, const std::uint8_t* passed, int lo, int hi) = nullptr;
};
// The stages for `samples` (validMsaa) samples per pixel and depth mode `depth`; with Auto and an
// `isa` (available) that has AVX2, a small triangle's box is tested eight pixels at a time (the
// same bits).
MsaaStages msaaStages(int samples, DepthMode depth, MsaaCoverageMethod method = MsaaCoverageMethod::Auto,
                      Isa isa = Isa::Scalar);

// The multisampled fill's first stage (MsaaCoverage.cpp): for triangle `t` inside the scissor,
// fills scratch.rows / covered / passed (the covered samples of each row's pixels, and those
// that passed the depth test, which TestWrite also writes) and scratch.runs (the pixels to
// shade: runs at the centre, single pixels at their centroid). Sample coverage is the top-left
// rule at each sample point; a small triangle is tested with edge functions over its bounding
// box (all samples of a pixel at once, int32), a large one with exact edge walks. With a depth
// test, a small triangle that every stored depth of its box hides (Auto) lists no rows and no runs.
void coverTriangleSamples(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, DepthMode depth,
                          MsaaScratch& scratch, MsaaCoverageMethod method = MsaaCoverageMethod::Auto,
                          Isa isa = Isa::Scalar);

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

template <class ShadeRow, class ShadeRuns>
void fillTriangleSamples(const MsaaStages& stages, const TriangleSetup& t, MsaaBuffer& target, const Scissor& s,
                         MsaaScratch& scratch, ShadeRow& shadeRow, ShadeRuns& shadeRuns, std::uint64_t& shaded,
                         float alpha, AlphaMode texelAlpha, bool linear) {
    const int n = stages.samples;
    const SampleOffset* pattern = msaaPattern(n);
    const double ddx = t.ddx[kPlaneZ];
    // 1. Coverage and the depth test per sample, and the pixels to shade (coverTriangleSamples).
    stages.cover(t, target, s, scratch);
    if (scratch.runs.empty()) return;

    // 2. Shade once per listed pixel, all rows in one call; the colours land in the pixel-sized
    //    shading rows, or (an opaque draw's kernel that can wait: shadeRuns returns true) in the
    //    passing samples themselves, now or once a whole group of lanes is queued, in order.
    const bool opaque = alpha >= 1.0f && texelAlpha == AlphaMode::Off;
    const SampleWrite write{opaque ? &target : nullptr, scratch.passed.data()};
    if (shadeRuns(static_cast<const SpanRun*>(scratch.runs.data()), int(scratch.runs.size()), write)) {
        for (const SpanRun& run : scratch.runs) shaded += std::uint64_t(run.x1 - run.x0);
        return;
    }

    // 3. Write each shaded colour to the samples that passed.
    for (const MsaaScratch::Row& row : scratch.rows) {
        const Pixel* shadedRow = shadeRow(row.y);
        const std::uint8_t* passed = scratch.passed.data() + row.offset;
        Pixel* colour = target.colourRow(row.y);
        if (opaque) { // the common case: each passing sample takes the colour
            shaded += stages.write(colour, shadedRow, passed, row.lo, row.hi);
            continue;
        }
        double zStart[8] = {}; // the most samples validMsaa allows
        if (texelAlpha == AlphaMode::Mask)
            for (int k = 0; k < n; ++k)
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
                    if (pass & (1u << k)) samples[k] = blendOver(c, samples[k], a, linear);
                continue;
            }
            if (texelAlpha == AlphaMode::Mask) { // kept (X 0xFF) or discarded (X 0)
                if ((c >> 24) == 0) {
                    --shaded;
                    continue;
                }
                c |= 0xFF000000u;
                // The depth write the test left to this step (the draw's depth mode is Test): step 1's floats.
                float* depth = target.depthRow(row.y) + std::size_t(x) * std::size_t(n);
                for (int k = 0; k < n; ++k)
                    if (pass & (1u << k)) depth[k] = float(zStart[k] + ddx * double(x - row.lo));
            }
            if (alpha < 1.0f) { // a transparent draw: over each passing sample's own colour
                for (int k = 0; k < n; ++k)
                    if (pass & (1u << k)) samples[k] = blendOver(c, samples[k], alpha, linear);
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
//    attribute is extrapolated outside the triangle), by one call shadeRuns(runs, count, write)
//    per triangle (SpanRun), which writes the colours to shadeRow(y)[x] (pixel-sized scratch
//    rows) and returns false, or writes them to the passing samples itself (SampleWrite, given
//    for opaque draws) and returns true;
//  - the colour goes to every covered sample that passed (alpha < 1: blended over each, Blend.hpp,
//    in linear light when `linear`);
//  - texelAlpha (Mask or Blend; the depth mode is then Test): the shaded colour carries its alpha in the
//    X byte (withMsaaAlpha): Blend blends it over each passing sample, Mask writes a kept pixel's
//    colour and depth to its passing samples and leaves a discarded pixel's samples alone.
// `shaded` counts the pixels shaded (and kept). `stages`: msaaStages(target.samples(), the draw's
// depth mode), chosen once per draw.
template <class ShadeRow, class ShadeRuns>
void fillTriangleMsaa(const MsaaStages& stages, const TriangleSetup& t, MsaaBuffer& target, const Scissor& s,
                      MsaaScratch& scratch, ShadeRow&& shadeRow, ShadeRuns&& shadeRuns, std::uint64_t& shaded,
                      float alpha = 1.0f, AlphaMode texelAlpha = AlphaMode::Off, bool linear = false) {
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= target.width() && s.y1 <= target.height());
    assert(stages.samples == target.samples());
    detail::fillTriangleSamples(stages, t, target, s, scratch, shadeRow, shadeRuns, shaded, alpha, texelAlpha, linear);
}

// The same, choosing the stages for this one triangle and depth mode kDepth.
template <DepthMode kDepth, class ShadeRow, class ShadeRuns>
void fillTriangleMsaa(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch,
                      ShadeRow&& shadeRow, ShadeRuns&& shadeRuns, std::uint64_t& shaded, float alpha = 1.0f,
                      AlphaMode texelAlpha = AlphaMode::Off, bool linear = false) {
    fillTriangleMsaa(msaaStages(target.samples(), kDepth), t, target, s, scratch, shadeRow, shadeRuns, shaded, alpha,
                     texelAlpha, linear);
}

} // namespace sr
