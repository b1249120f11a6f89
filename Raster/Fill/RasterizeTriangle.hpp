// One screen-space triangle on one lane: cull and setup, then the fill (span kernel, scalar loop,
// multisampled or stencilled), clipped to the lane's bands.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "Raster/Fill/Blend.hpp"
#include "Raster/Fill/Kernels/KernelConfig.hpp" // SR_SIMD_NOINLINE, SR_UNLIKELY
#include "Raster/Fill/MsaaFill.hpp"
#include "Raster/Fill/ScanlineFill.hpp"
#include "Raster/Fill/Stencil.hpp"
#include "Raster/Frame/RenderContext.hpp" // RenderStats
#include "Raster/Setup/DrawState.hpp"
#include "Raster/Setup/LaneBalance.hpp"
#include "Raster/Setup/TriangleSetup.hpp"

namespace sr {
namespace detail {

// One fragment of a draw with texel alpha (DrawState::texelAlpha on; the fill tested depth with
// DepthMode::Test): Mask keeps it (writing its depth and colour) or leaves colour and depth as
// they were; Blend blends it over the target. Out of line: the span loops of every program
// inline only the call.
template <class Program, int kVaryings>
SR_SIMD_NOINLINE Pixel texelAlphaFragment(const Program& program, FrameBuffer& fb, const TexelAlpha& texelAlpha,
                                          const Fragment<kVaryings>& f, std::uint64_t& shaded) {
    const float a = texelAlpha.factor * program.fragmentAlpha(f);
    const Pixel behind = fb.colorRow(f.y)[f.x];
    if (texelAlpha.mode == AlphaMode::Mask) {
        if (!(a >= texelAlpha.cutoff)) return behind; // discarded: colour and depth stay
        fb.depthRow(f.y)[f.x] = f.z;
        ++shaded;
        return program.fragment(f);
    }
    ++shaded;
    return blendOver(program.fragment(f), behind, a, texelAlpha.linear);
}

// A triangle hook that does nothing (draws without per-triangle work).
struct NoTriangleHook {
    void operator()(std::size_t, const TriangleSetup&) const {}
};

// Per-lane state of a draw: its own counters and setup record (lanes never share writes; the
// cache-line alignment keeps one lane's per-pixel counter off its neighbour's setup record).
struct alignas(64) LaneState {
    RenderStats stats;
    TriangleSetup setup;
    MsaaScratch msaa; // the multisampled fill's memory (used only while multisampling)
    MsaaStages msaaStages; // the multisampled fill's stages for this draw (chosen by the draw)
};

// Which rows a lane fills. One lane: the whole target. Several: the target is cut into bands
// of kBandRows rows, band b belonging to lane pattern->ownerOfBand(b) (RenderContext::laneBalance:
// a repeated pattern weighted by the lanes' speed), or to lane b % lanes without a pattern; both
// interleave, so a model in the middle of the screen still spreads over every lane. A binned
// draw's lane fills one band at a time, the one it took (onlyBand).
struct LaneBands {
    static constexpr int kBandRows = BandPattern::kBandRows;
    static_assert(FrameBuffer::kMaxDimension <= kBandRows * BandPattern::kMaxBands, "a band owner for every row");
    int lane = 0, lanes = 1, height = 0;
    const BandPattern* pattern = nullptr; // null, or pattern->lanes == lanes
    int onlyBand = -1; // >= 0: the lane fills this band only (the band of a binned draw it took)

    int ownerOfBand(int band) const { return pattern ? pattern->ownerOfBand(band) : band % lanes; }
    int ownerOfRow(int row) const { return ownerOfBand(std::clamp(row, 0, std::max(height - 1, 0)) / kBandRows); }
    // True when some band of this lane meets rows [rowBegin, rowEnd) of the target.
    bool meets(int rowBegin, int rowEnd) const {
        rowBegin = std::max(rowBegin, 0);
        rowEnd = std::min(rowEnd, height);
        if (rowBegin >= rowEnd) return false;
        const int first = rowBegin / kBandRows, last = (rowEnd - 1) / kBandRows;
        // Every lane owns a band of every period of the pattern (of every `lanes` bands without one).
        if (last - first + 1 >= (pattern ? pattern->period : lanes)) return true;
        for (int b = first; b <= last; ++b)
            if (ownerOfBand(b) == lane) return true;
        return false;
    }
};

// Programs with their own span kernel: bool fillKernel(const TriangleSetup&, FrameBuffer&, const
// Scissor&, std::uint64_t& shaded) fills the triangle (bit-identical to fillTriangle with the
// program's fragment()) and returns true, or returns false to leave it to the scalar loop.
// drawMesh's programs carry the kernel chosen once per draw (Raster/Fill/Kernels/KernelTable.hpp).
template <class Program, class = void>
struct HasFillKernel : std::false_type {};
// ... and optionally RunShading shadeRuns(const TriangleSetup&, FrameBuffer&, const SpanRun*, int
// count, const SampleWrite&): shades the runs' pixels (SpanRun: at the centre or moved) into fb's
// rows or the samples (no depth test), as fillSpan with DepthMode::Off and fragment() would, or
// does nothing (the multisampled fill).
template <class Program, class = void>
struct HasShadeRuns : std::false_type {};
template <class Program>
struct HasShadeRuns<Program, std::void_t<decltype(std::declval<Program&>().shadeRuns(
                                 std::declval<const TriangleSetup&>(), std::declval<FrameBuffer&>(),
                                 std::declval<const SpanRun*>(), 0, std::declval<const SampleWrite&>()))>>
    : std::true_type {};
// ... and optionally float fragmentAlpha(const Fragment<kVaryings>&): the fragment's texel alpha,
// for draws with DrawState::texelAlpha on.
template <class Program, int kVaryings, class = void>
struct HasFragmentAlpha : std::false_type {};
template <class Program, int kVaryings>
struct HasFragmentAlpha<Program, kVaryings,
                        std::void_t<decltype(std::declval<const Program&>().fragmentAlpha(
                            std::declval<const Fragment<kVaryings>&>()))>> : std::true_type {};
template <class Program>
struct HasFillKernel<Program, std::void_t<decltype(std::declval<Program&>().fillKernel(
                                  std::declval<const TriangleSetup&>(), std::declval<FrameBuffer&>(),
                                  std::declval<const Scissor&>(), std::declval<std::uint64_t&>()))>>
    : std::true_type {};
// ... and optionally void flushFill(FrameBuffer&): writes what the fill kernel has queued on
// this thread (its colours may wait for later triangles of the draw: Kernels.inl, fillSpans).
template <class Program, class = void>
struct HasFlushFill : std::false_type {};
template <class Program>
struct HasFlushFill<Program,
                    std::void_t<decltype(std::declval<const Program&>().flushFill(std::declval<FrameBuffer&>()))>>
    : std::true_type {};
// The fill kernel's queued colours written: at the end of a lane's walk of a draw, and before
// anything else writes colour there (a wireframe edge).
template <class Program>
void flushFill(const Program& program, FrameBuffer& fb) {
    if constexpr (HasFlushFill<Program>::value) program.flushFill(fb);
}

// One fragment of a draw with the stencil test on (DrawState::stencil; the fill ran without a
// depth test, which is made here after the stencil test). OpenGL's order: a texel-alpha Mask
// discard first (a discarded fragment touches nothing), then the stencil test (fail: the `fail`
// operation), the depth test per `depth` (fail: `depthFail`), then `pass`, the depth write and
// the colour (blended when the draw is transparent; none without colourWrite). Returns the
// colour the pixel ends with.
template <class Program, int kVaryings>
SR_SIMD_NOINLINE Pixel stencilFragment(Program& program, FrameBuffer& fb, const DrawState& state,
                                       const Fragment<kVaryings>& f, std::uint64_t& shaded) {
    const Pixel behind = fb.colorRow(f.y)[f.x];
    float a = state.blendAlpha;
    if constexpr (HasFragmentAlpha<Program, kVaryings>::value) {
        if (state.texelAlpha.on()) {
            a = state.texelAlpha.factor * program.fragmentAlpha(f);
            if (state.texelAlpha.mode == AlphaMode::Mask) {
                if (!(a >= state.texelAlpha.cutoff)) return behind;
                a = 1.0f;
            }
        }
    }
    const StencilState& st = state.stencil;
    std::uint8_t& stored = fb.stencilRow(f.y)[f.x];
    if (!stencilPasses(st.func, st.ref, stored, st.readMask)) {
        stored = stencilApply(st.fail, stored, st.ref, st.writeMask);
        return behind;
    }
    float& depth = fb.depthRow(f.y)[f.x];
    if (state.depth != DepthMode::Off && !(state.depthEqualPasses ? f.z >= depth : f.z > depth)) {
        stored = stencilApply(st.depthFail, stored, st.ref, st.writeMask);
        return behind;
    }
    stored = stencilApply(st.pass, stored, st.ref, st.writeMask);
    if (state.depth == DepthMode::TestWrite || (state.texelAlpha.on() && state.texelAlpha.mode == AlphaMode::Mask))
        depth = f.z;
    if (!state.colourWrite) return behind;
    ++shaded;
    if (a < 1.0f) return blendOver(program.fragment(f), behind, a, state.linearBlend);
    return program.fragment(f);
}

// Rows [begin, end) of a triangle with snapped y extent [minY, maxY]: those whose centres it can
// cover (the rows setupTriangle computes), or with `multisampled` (a multisampled draw) every row the
// extent touches (msaaRowRange).
inline void rowsOfSnappedExtent(Fixed minY, Fixed maxY, bool multisampled, int& begin, int& end) {
    begin = multisampled ? int(floorDiv(minY, kSubPixelScale)) : int(firstCentreAtOrAfter(minY, 1));
    end = multisampled ? int(floorDiv(maxY, kSubPixelScale)) + 1 : int(firstCentreAtOrAfter(maxY, 1));
}
// The same from the screen vertices' y coordinates only: a cheap band test before the setup.
inline void snappedRowRange(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2, bool multisampled,
                            int& begin, int& end) {
    const Fixed y0 = snapToFixed(v0.y), y1 = snapToFixed(v1.y), y2 = snapToFixed(v2.y);
    rowsOfSnappedExtent(std::min({y0, y1, y2}), std::max({y0, y1, y2}), multisampled, begin, end);
}

// The rows that decide which bands a screen triangle meets and which one counts it (the band of
// the first): snappedRowRange's, or [0, 0) when a vertex lies outside the guard band.
inline void rowsForBands(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2, bool multisampled,
                         int& begin, int& end) {
    begin = end = 0;
    if (std::fabs(v0.y) <= kGuardBand && std::fabs(v1.y) <= kGuardBand && std::fabs(v2.y) <= kGuardBand)
        snappedRowRange(v0, v1, v2, multisampled, begin, end);
}

// A lane's part in a triangle when the caller already knows it (binned draws: the bin entry
// says): the Owner counts it, a Helper only fills its band of it.
enum class LaneRole { Unknown, Owner, Helper };

// The draw's setup of a screen triangle into `out` (setupTriangleCulled with the draw's cull,
// perspective and rebase; every row a sample can cover when multisampled).
template <int kVaryings>
SetupOutcome setupForDraw(TriangleSetup& out, const DrawState& state, bool multisampled, const ScreenVertex& v0,
                          const ScreenVertex& v1, const ScreenVertex& v2) {
    const bool affine = kVaryings > 0 && state.perspective == PerspectiveMode::Affine;
    return setupTriangleCulled(out, v0, v1, v2, state.cull, kVaryings, !affine, state.rebase, multisampled);
}

template <int kVaryings, class Program>
void fillSetUpTriangle(FrameBuffer& fb, MsaaBuffer* msaa, const DrawState& state, const LaneBands& bands,
                       LaneState& lane, RenderStats& stats, std::size_t t, const TriangleSetup& setup, Program& program);

// Culls, sets up and fills one screen-space triangle (index t of the draw) on one lane.
// Returns true when it was not culled. The program's triangle() runs once per set-up
// triangle, right before its fill. With several lanes, the lane owning the band of the
// triangle's first row counts it (so the counters equal a single-lane draw's), and every lane
// whose bands it meets sets it up and fills it clipped to those bands, in submission order:
// the image is bit-identical to one lane's.
template <int kVaryings, class Program>
bool rasterizeTriangle(FrameBuffer& fb, MsaaBuffer* msaa, const DrawState& state, const LaneBands& bands, LaneState& lane,
                       RenderStats& sink, std::size_t t, const ScreenVertex& v0, const ScreenVertex& v1,
                       const ScreenVertex& v2, Program& program, LaneRole role = LaneRole::Unknown) {
    RenderStats* stats = &lane.stats;
    if (role == LaneRole::Helper) stats = &sink; // binned: another band counts it
    if (bands.lanes > 1 && role == LaneRole::Unknown) {
        int rowBegin = 0, rowEnd = 0;
        rowsForBands(v0, v1, v2, msaa != nullptr, rowBegin, rowEnd);
        const bool owner = bands.ownerOfRow(rowBegin) == bands.lane;
        if (!owner) {
            if (state.stopAfter <= PipelineStop::Bin || !bands.meets(rowBegin, rowEnd)) return false;
            stats = &sink; // fills its bands, counts nothing
        }
    }
    if (state.stopAfter <= PipelineStop::Bin) { // no bins here (an unbinned walk): as Geometry
        if (isCulled(state.cull, v0, v1, v2)) {
            ++stats->culled;
            return false;
        }
        return true;
    }
    switch (setupForDraw<kVaryings>(lane.setup, state, msaa != nullptr, v0, v1, v2)) {
    case SetupOutcome::Culled: ++stats->culled; return false;
    case SetupOutcome::Empty: return true; // covers no sample: nothing to do, but not culled
    case SetupOutcome::Ready: break;
    }
    ++lane.stats.setupsBuilt; // by this lane, whichever lane counts the triangle
    fillSetUpTriangle<kVaryings>(fb, msaa, state, bands, lane, *stats, t, lane.setup, program);
    return true;
}

// A set-up triangle (index t of the draw) filled on one lane, clipped to the lane's bands; `stats`
// is the lane's own counters when it counts the triangle, a sink otherwise.
template <int kVaryings, class Program>
void fillSetUpTriangle(FrameBuffer& fb, MsaaBuffer* msaa, const DrawState& state, const LaneBands& bands,
                       LaneState& lane, RenderStats& stats, std::size_t t, const TriangleSetup& setup, Program& program) {
    ++stats.rasterized;
    if (state.stopAfter == PipelineStop::Setup) return;
    program.triangle(t, setup);
    // Count the fragments that pass the depth test (one add per pixel: overdraw statistics).
    std::uint64_t& shaded = lane.stats.fragmentsShaded;
    const float alpha = state.blendAlpha;
    const bool linearBlend = state.linearBlend;
    const TexelAlpha texelAlpha = state.texelAlpha;
    constexpr bool kFragmentAlpha = HasFragmentAlpha<Program, kVaryings>::value;
    auto counted = [&shaded, &program, &fb, alpha, linearBlend, texelAlpha](const Fragment<kVaryings>& f) {
        if constexpr (kFragmentAlpha) {
            if (SR_UNLIKELY(texelAlpha.on())) return detail::texelAlphaFragment(program, fb, texelAlpha, f, shaded);
        }
        ++shaded;
        if (alpha < 1.0f) return blendOver(program.fragment(f), fb.colorRow(f.y)[f.x], alpha, linearBlend);
        return program.fragment(f);
    };
    // The program's own kernel if it has one for this draw; else the scalar loop, depth mode x
    // perspective mode resolved once per triangle (without varyings only Exact exists: nothing
    // to interpolate, which keeps the number of instantiated loops down).
    // Multisampled: coverage and depth per sample, the program's fragments once per pixel (at the
    // centre or the centroid) through its run shader, or else the scalar loop.
    // (The depth mode is in the draw's stages, lane.msaaStages.)
    auto fillSamples = [&](const Scissor& scissor, auto perspTag) {
        constexpr PerspectiveMode kPersp = decltype(perspTag)::value;
        auto shadeRow = [&fb](int y) -> const Pixel* { return fb.colorRow(y); };
        auto shadeRuns = [&](const SpanRun* runs, int count, const SampleWrite& write) {
            if constexpr (HasShadeRuns<Program>::value) {
                if (!texelAlpha.on()) {
                    const RunShading done = program.shadeRuns(setup, fb, runs, count, write);
                    if (done != RunShading::NotDone) return done == RunShading::IntoSamples;
                }
            } else {
                (void)write;
            }
            // With texel alpha, the alpha rides in the shading row's X byte (MsaaAlpha).
            auto fragment = [&program, texelAlpha](const Fragment<kVaryings>& f) {
                if constexpr (kFragmentAlpha) {
                    if (texelAlpha.on())
                        return withMsaaAlpha(program.fragment(f), texelAlpha, texelAlpha.factor * program.fragmentAlpha(f));
                }
                return program.fragment(f);
            };
            for (int r = 0; r < count; ++r) {
                if (runs[r].dx == 0.0 && runs[r].dy == 0.0) {
                    fillSpan<DepthMode::Off, kVaryings, kPersp>(setup, fb, runs[r].y, runs[r].x0, runs[r].x1, fragment);
                    continue;
                }
                TriangleSetup moved = setup; // shaded off the centre: at the centroid
                moveOrigin(setup, runs[r], moved);
                fillSpan<DepthMode::Off, kVaryings, kPersp>(moved, fb, runs[r].y, runs[r].x0, runs[r].x1, fragment);
            }
            return false;
        };
        fillTriangleMsaa(lane.msaaStages, setup, *msaa, scissor, lane.msaa, shadeRow, shadeRuns, shaded, alpha,
                         texelAlpha.mode, state.linearBlend);
    };
    // (Inlined: out of line, as GCC 12 leaves it once the kernel call grows, each triangle pays a call.)
    auto fillIn = [&](auto depthTag, const Scissor& scissor) SR_SIMD_LAMBDA {
        constexpr DepthMode kDepth = decltype(depthTag)::value;
        if (msaa) {
            if (kVaryings > 0 && state.perspective == PerspectiveMode::Affine)
                fillSamples(scissor, std::integral_constant<PerspectiveMode, PerspectiveMode::Affine>{});
            else fillSamples(scissor, std::integral_constant<PerspectiveMode, PerspectiveMode::Exact>{});
            return;
        }
        if (SR_UNLIKELY(state.stencil.on() && fb.hasStencil())) {
            auto stencilled = [&program, &fb, &state, &shaded](const Fragment<kVaryings>& f) {
                return stencilFragment(program, fb, state, f, shaded);
            };
            if (kVaryings > 0 && state.perspective == PerspectiveMode::Affine)
                fillTriangle<DepthMode::Off, kVaryings, PerspectiveMode::Affine>(setup, fb, scissor, stencilled);
            else fillTriangle<DepthMode::Off, kVaryings, PerspectiveMode::Exact>(setup, fb, scissor, stencilled);
            return;
        }
        if constexpr (HasFillKernel<Program>::value) {
            // (A transparent draw's kernel blends each colour over the target itself, as `counted`.)
            if (!texelAlpha.on() && program.fillKernel(setup, fb, scissor, shaded)) return;
        }
        if constexpr (kVaryings == 0) {
            fillTriangle<kDepth, kVaryings>(setup, fb, scissor, counted);
        } else {
            switch (state.perspective) {
            case PerspectiveMode::Exact: fillTriangle<kDepth, kVaryings, PerspectiveMode::Exact>(setup, fb, scissor, counted); break;
            case PerspectiveMode::Affine: fillTriangle<kDepth, kVaryings, PerspectiveMode::Affine>(setup, fb, scissor, counted); break;
            }
        }
    };
    auto fill = [&](auto depthTag) {
        if (bands.onlyBand >= 0) {
            const int y0 = bands.onlyBand * LaneBands::kBandRows;
            fillIn(depthTag, Scissor{0, y0, fb.width(), std::min(y0 + LaneBands::kBandRows, fb.height())});
            return;
        }
        if (bands.lanes == 1) {
            fillIn(depthTag, fullScissor(fb));
            return;
        }
        // This lane's bands that meet the triangle's rows, top to bottom.
        int rowBegin = setup.firstRow, rowEnd = setup.endRow;
        if (msaa) msaaRowRange(setup, rowBegin, rowEnd);
        rowBegin = std::max(rowBegin, 0);
        rowEnd = std::min(rowEnd, fb.height());
        for (int b = rowBegin / LaneBands::kBandRows; b * LaneBands::kBandRows < rowEnd; ++b) {
            if (bands.ownerOfBand(b) != bands.lane) continue;
            const int y0 = b * LaneBands::kBandRows;
            fillIn(depthTag, Scissor{0, y0, fb.width(), std::min(y0 + LaneBands::kBandRows, fb.height())});
        }
    };
    switch (state.depth) {
    case DepthMode::Off: fill(std::integral_constant<DepthMode, DepthMode::Off>{}); break;
    case DepthMode::Test: fill(std::integral_constant<DepthMode, DepthMode::Test>{}); break;
    case DepthMode::TestWrite: fill(std::integral_constant<DepthMode, DepthMode::TestWrite>{}); break;
    }
}

} // namespace detail
} // namespace sr
