// One draw call through the geometry and raster stages: vertex shader -> clip -> divide and
// viewport -> cull -> triangle setup -> scanline fill (+ optional wireframe overlay).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "Raster/Blend.hpp"
#include "Raster/Clipper.hpp"
#include "Raster/Cull.hpp"
#include "Raster/Kernels/KernelConfig.hpp" // SR_SIMD_NOINLINE, SR_UNLIKELY
#include "Raster/LaneBalance.hpp"
#include "Raster/Line.hpp"
#include "Raster/MsaaFill.hpp"
#include "Raster/PipelineModes.hpp" // PipelineStop, DepthMode, PerspectiveMode
#include "Raster/Prefetch.hpp"
#include "Raster/RenderContext.hpp"
#include "Raster/ScanlineFill.hpp"
#include "Raster/Stencil.hpp"
#include "Raster/ThreadPool.hpp"
#include "Raster/TriangleSetup.hpp"
#include "Raster/Viewport.hpp"

namespace sr {

// Per-draw fixed-function state.
struct DrawState {
    CullMode cull = CullMode::None;
    bool clipFar = true;                    // false for a projection with an infinite far plane
    DepthMode depth = DepthMode::TestWrite; // reversed-Z, GREATER
    PipelineStop stopAfter = PipelineStop::Fill;
    PerspectiveMode perspective = PerspectiveMode::Exact; // how varyings are interpolated
    bool wireframe = false;                 // overlay the (clipped) triangle outlines
    VaryingRebase rebase;                   // uv varyings shifted per triangle (textured draws)
    Pixel wireColour = packBgra(255, 255, 255);
    // Wireframe lines are this many target pixels wide: 1, or under supersampling the grid side
    // k (RenderSettings::ssaa), so that after the k x k resolve an edge still covers whole output
    // pixels (a 1-sample line would resolve to 1/k of its colour).
    int wireWidth = 1;
    // Below 1: a transparent draw, blended "over" the target with this constant opacity
    // (Blend.hpp), per pixel or, multisampled, per sample; the span kernels blend as the scalar
    // loop does (their colours go through blendOver). Such a draw is drawn with DepthMode::Test.
    float blendAlpha = 1.0f;
    // Blends in linear light (blendOverLinear: ColorMode::Linear), per pixel or per sample; linear
    // draws have no span kernels.
    bool linearBlend = false;
    // On: per-fragment alpha from the program's fragmentAlpha (Blend.hpp's TexelAlpha: Mask keeps
    // or discards, Blend blends with it); the draw is then filled by the scalar loop with
    // DepthMode::Test, a kept Mask fragment writing its own depth.
    TexelAlpha texelAlpha;
    // On (and the target has a stencil buffer, FrameBuffer::enableStencil): the stencil test and
    // operations per fragment (Raster/Stencil.hpp), before the depth test, as OpenGL orders them;
    // the draw is then filled by the scalar loop (detail::stencilFragment). Not applied to a
    // multisampled target (the buffer is per pixel): renderScene draws no stencil passes there.
    StencilState stencil;
    // Honoured by the stencil path only (draws with `stencil` on): colourWrite false leaves the
    // colour as it was (glColorMask off), depthEqualPasses makes the depth test GEQUAL instead of
    // GREATER (a draw of the same triangles again passes where they are what is visible).
    bool colourWrite = true;
    bool depthEqualPasses = false;
};

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

// A clipped triangle's uv varyings rebased before clipping (VaryingRebase), so the clipper's
// interpolation runs on small values too: for vertices offset by whole periods the shifted
// values, and hence every clipped vertex, are the same floats.
inline void rebaseVaryings(const VaryingRebase& rebase, ClipVertex& a, ClipVertex& b, ClipVertex& c) {
    for (int k = 0; k < rebase.count; ++k) {
        const std::size_t i = std::size_t(k);
        const double offset = rebaseOffset(a.varyings[i], b.varyings[i], c.varyings[i], rebase.period);
        a.varyings[i] = float(a.varyings[i] - offset);
        b.varyings[i] = float(b.varyings[i] - offset);
        c.varyings[i] = float(c.varyings[i] - offset);
    }
}

// Wireframe depth bias: lines sample the edge itself while the fill samples pixel centres
// inside it, so an unbiased edge would z-fight with its own triangle. Reversed-Z: nearer is
// larger, so the line's depth is raised by a relative 2^-12 (it shows through a surface only
// if that surface is within 0.025% of the line's depth in z_ndc).
inline float wireDepth(float z) { return z * (1.0f + 1.0f / 4096.0f); }

// One wireframe edge, `width` pixels wide (drawWideLine), with the wireframe's depth bias.
inline void drawWireEdge(FrameBuffer& fb, MsaaBuffer* msaa, const ScreenVertex& a, const ScreenVertex& b,
                         Pixel colour, bool depthTest, int width = 1) {
    LineOptions options;
    options.depthTest = depthTest;
    drawWideLine(fb, msaa, LineVertex{a.x, a.y, wireDepth(a.z), colour}, LineVertex{b.x, b.y, wireDepth(b.z), colour},
                 options, width);
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
};

// Which rows a lane fills. One lane: the whole target. Several: the target is cut into bands
// of kBandRows rows, band b belonging to lane pattern->ownerOfBand(b) (RenderContext::laneBalance:
// a repeated pattern weighted by the lanes' speed), or to lane b % lanes without a pattern; both
// interleave, so a model in the middle of the screen still spreads over every lane.
struct LaneBands {
    static constexpr int kBandRows = 16;
    int lane = 0, lanes = 1, height = 0;
    const BandPattern* pattern = nullptr; // null, or pattern->lanes == lanes

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
// drawMesh's programs carry the kernel chosen once per draw (Raster/Kernels/KernelTable.hpp).
template <class Program, class = void>
struct HasFillKernel : std::false_type {};
// ... and optionally bool shadeRuns(const TriangleSetup&, FrameBuffer&, const SpanRun*, int count):
// shades the runs' pixels (SpanRun: at the centre or moved) into fb's rows (no depth test), as
// fillSpan with DepthMode::Off and fragment() would, or returns false (the multisampled fill).
template <class Program, class = void>
struct HasShadeRuns : std::false_type {};
template <class Program>
struct HasShadeRuns<Program, std::void_t<decltype(std::declval<Program&>().shadeRuns(
                                 std::declval<const TriangleSetup&>(), std::declval<FrameBuffer&>(),
                                 std::declval<const SpanRun*>(), 0))>> : std::true_type {};
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

// A lane's part in a triangle when the caller already knows it (binned draws: binTriangles):
// the Owner counts it, a Helper only fills its own bands of it.
enum class LaneRole { Unknown, Owner, Helper };

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
    if (role == LaneRole::Helper) stats = &sink; // binned: this lane's bands meet it, another lane counts it
    if (bands.lanes > 1 && role == LaneRole::Unknown) {
        int rowBegin = 0, rowEnd = 0;
        if (std::fabs(v0.y) <= kGuardBand && std::fabs(v1.y) <= kGuardBand && std::fabs(v2.y) <= kGuardBand) {
            snappedRowRange(v0, v1, v2, msaa != nullptr, rowBegin, rowEnd);
        }
        const bool owner = bands.ownerOfRow(rowBegin) == bands.lane;
        if (!owner) {
            if (state.stopAfter == PipelineStop::Geometry || !bands.meets(rowBegin, rowEnd)) return false;
            stats = &sink; // fills its bands, counts nothing
        }
    }
    if (state.stopAfter == PipelineStop::Geometry) {
        if (isCulled(state.cull, v0, v1, v2)) {
            ++stats->culled;
            return false;
        }
        return true;
    }
    const bool affine = kVaryings > 0 && state.perspective == PerspectiveMode::Affine;
    TriangleSetup& setup = lane.setup;
    switch (setupTriangleCulled(setup, v0, v1, v2, state.cull, kVaryings, !affine, state.rebase, msaa != nullptr)) {
    case SetupOutcome::Culled: ++stats->culled; return false;
    case SetupOutcome::Empty: return true; // covers no sample: nothing to do, but not culled
    case SetupOutcome::Ready: break;
    }
    ++stats->rasterized;
    if (state.stopAfter == PipelineStop::Setup) return true;
    program.triangle(t, static_cast<const TriangleSetup&>(setup));
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
    auto fillSamples = [&](auto depthTag, const Scissor& scissor, auto perspTag) {
        constexpr DepthMode kDepth = decltype(depthTag)::value;
        constexpr PerspectiveMode kPersp = decltype(perspTag)::value;
        auto shadeRow = [&fb](int y) -> const Pixel* { return fb.colorRow(y); };
        auto shadeRuns = [&](const SpanRun* runs, int count) {
            if constexpr (HasShadeRuns<Program>::value) {
                if (!texelAlpha.on() && program.shadeRuns(static_cast<const TriangleSetup&>(setup), fb, runs, count)) return;
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
        };
        fillTriangleMsaa<kDepth>(setup, *msaa, scissor, lane.msaa, shadeRow, shadeRuns, shaded, alpha, texelAlpha.mode,
                                 state.linearBlend);
    };
    auto fillIn = [&](auto depthTag, const Scissor& scissor) {
        constexpr DepthMode kDepth = decltype(depthTag)::value;
        if (msaa) {
            if (kVaryings > 0 && state.perspective == PerspectiveMode::Affine)
                fillSamples(depthTag, scissor, std::integral_constant<PerspectiveMode, PerspectiveMode::Affine>{});
            else fillSamples(depthTag, scissor, std::integral_constant<PerspectiveMode, PerspectiveMode::Exact>{});
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
            if (!texelAlpha.on() && program.fillKernel(static_cast<const TriangleSetup&>(setup), fb, scissor, shaded)) return;
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
    return true;
}

// The lambda API as a Program (used on one lane only: the lambdas may share state).
template <class VertexShader, class TriangleHook, class FragmentShader>
struct LambdaProgram {
    VertexShader& vertexShader;
    TriangleHook& hook;
    FragmentShader& fragmentShader;
    void vertex(std::size_t i, ClipVertex& out) { vertexShader(i, out); }
    void triangle(std::size_t t, const TriangleSetup& s) { hook(t, s); }
    template <class F>
    Pixel fragment(const F& f) { return fragmentShader(f); }
};

// A triangle (index t, vertices i0, i1, i2) that crosses a clip plane: clipped, its fan of
// pieces rasterized on this lane (each piece's owner counts it).
template <int kVaryings, class Program>
void clipAndRasterize(RenderContext& ctx, const DrawState& state, Clipper& clipper, const LaneBands& bands,
                      LaneState& lane, RenderStats& sink, std::size_t t, std::uint32_t i0, std::uint32_t i1,
                      std::uint32_t i2, Program& program) {
    FrameBuffer& fb = ctx.target();
    MsaaBuffer* msaa = ctx.multisampleTarget();
    ClippedPolygon polygon;
    ScreenVertex screen[kMaxClipVertices];
    ClipVertex a = ctx.clipVertices[i0], b = ctx.clipVertices[i1], c = ctx.clipVertices[i2];
    detail::rebaseVaryings(state.rebase, a, b, c); // before the clipper interpolates them
    const int n = clipper.clip(a, b, c, polygon);
    for (int k = 0; k < n; ++k) screen[k] = toScreen(polygon.vertices[std::size_t(k)], fb.width(), fb.height(), kVaryings);
    // The fan keeps the input winding, so every piece gets the same cull decision.
    bool drawn = false;
    for (int k = 0; k < polygon.triangleCount(); ++k)
        drawn |= rasterizeTriangle<kVaryings>(fb, msaa, state, bands, lane, sink, t, screen[0], screen[k + 1], screen[k + 2],
                                              program);
    if (drawn && state.wireframe) {
        flushFill(program, fb);
        for (int k = 0; k < n; ++k)
            drawWireEdge(fb, msaa, screen[k], screen[(k + 1) % n], state.wireColour, state.depth != DepthMode::Off,
                         state.wireWidth);
    }
}

// Vertices are prefetched this many triangles ahead of the one being drawn (index order jumps
// around a vertex array; the misses then overlap with the fills in between).
inline constexpr std::size_t kPrefetchTriangles = 8;

// The primitive stage of one lane: every triangle in submission order, classified from the
// cached per-vertex clip codes, then clipped if needed, culled, set up and filled.
template <int kVaryings, class Program>
void rasterLane(RenderContext& ctx, const DrawState& state, const Clipper& clipperProto, const LaneBands& bands,
                LaneState& lane, const std::uint32_t* indices, std::size_t indexCount, Program& program) {
    FrameBuffer& fb = ctx.target();
    MsaaBuffer* msaa = ctx.multisampleTarget();
    Clipper clipper = clipperProto;
    RenderStats sink;
    const bool wireDepthTest = state.depth != DepthMode::Off;
    const bool countsShared = bands.lane == 0; // per-triangle counters not tied to a band
    const unsigned* codes = ctx.clipCodes.data();
    // Vertices are read in index order, which jumps around a mesh's vertex array: ask for those of
    // the triangle kAhead triangles on now, so that their misses overlap with this one's fill.
    constexpr std::size_t kAhead = 3 * kPrefetchTriangles;
    for (std::size_t t = 0; t + 2 < indexCount; t += 3) {
        const std::uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
        const unsigned c0 = codes[i0], c1 = codes[i1], c2 = codes[i2];
        if (countsShared) ++lane.stats.trianglesIn;
        if (t + kAhead + 2 < indexCount) {
            for (std::size_t k = t + kAhead; k < t + kAhead + 3; ++k) {
                const ScreenVertex* v = ctx.screenVertices.data() + indices[k];
                prefetchForRead(v);
                prefetchForRead(reinterpret_cast<const char*>(v + 1) - 1);
                prefetchForRead(codes + indices[k]);
            }
        }

        switch (clipper.classifyCodes(c0, c1, c2)) {
        case ClipClass::Reject:
            if (countsShared) {
                ++lane.stats.trivialRejected;
                if ((c0 | c1 | c2) & kCodeNonFinite) ++lane.stats.nonFinite;
            }
            break;
        case ClipClass::Accept: {
            const ScreenVertex& s0 = ctx.screenVertices[i0];
            const ScreenVertex& s1 = ctx.screenVertices[i1];
            const ScreenVertex& s2 = ctx.screenVertices[i2];
            assert(ctx.usable[i0] && ctx.usable[i1] && ctx.usable[i2]);
            if (rasterizeTriangle<kVaryings>(fb, msaa, state, bands, lane, sink, t / 3, s0, s1, s2, program) &&
                state.wireframe) {
                flushFill(program, fb);
                drawWireEdge(fb, msaa, s0, s1, state.wireColour, wireDepthTest, state.wireWidth);
                drawWireEdge(fb, msaa, s1, s2, state.wireColour, wireDepthTest, state.wireWidth);
                drawWireEdge(fb, msaa, s2, s0, state.wireColour, wireDepthTest, state.wireWidth);
            }
            break;
        }
        case ClipClass::Clip:
            if (countsShared) ++lane.stats.clipped;
            clipAndRasterize<kVaryings>(ctx, state, clipper, bands, lane, sink, t / 3, i0, i1, i2, program);
            break;
        }
    }
}

// --- Binned draws (several lanes, many triangles) ----------------------------------------------
// Every lane of the plain walk classifies every triangle, and sets up every one its bands meet,
// the culled ones included; with several lanes that front end is repeated per lane. A binned draw
// screens each triangle once instead: lane c classifies and culls chunk c of the triangles
// (screenTriangle: the decisions setupTriangleCulled would make) and appends each survivor to the
// bins of the lanes whose bands it meets, marked for the lane that counts it; then every lane
// draws its bins chunk by chunk, so still in submission order. Same image, same counters.
inline constexpr std::uint32_t kBinOwner = 1u << 31; // this lane counts the triangle
inline constexpr std::uint32_t kBinClip = 1u << 30;  // crosses a clip plane: clipped by the lane
inline constexpr std::uint32_t kBinIndex = kBinClip - 1u;

inline void binTriangles(RenderContext& ctx, const DrawState& state, const Clipper& clipper, int chunk, int lanes,
                         const BandPattern* pattern, const std::uint32_t* indices, std::size_t triangleBegin,
                         std::size_t triangleEnd, RenderStats& stats) {
    const unsigned* codes = ctx.clipCodes.data();
    const int height = ctx.target().height();
    const bool multisampled = ctx.multisampleTarget() != nullptr;
    std::vector<std::uint32_t>* bins = ctx.bins.data() + std::size_t(chunk) * std::size_t(lanes);
    for (std::size_t tri = triangleBegin; tri < triangleEnd; ++tri) {
        const std::uint32_t i0 = indices[3 * tri], i1 = indices[3 * tri + 1], i2 = indices[3 * tri + 2];
        const unsigned c0 = codes[i0], c1 = codes[i1], c2 = codes[i2];
        ++stats.trianglesIn;
        if (tri + kPrefetchTriangles < triangleEnd) {
            for (std::size_t k = 3 * (tri + kPrefetchTriangles); k < 3 * (tri + kPrefetchTriangles) + 3; ++k) {
                prefetchForRead(ctx.screenVertices.data() + indices[k]);
                prefetchForRead(codes + indices[k]);
            }
        }
        switch (clipper.classifyCodes(c0, c1, c2)) {
        case ClipClass::Reject:
            ++stats.trivialRejected;
            if ((c0 | c1 | c2) & kCodeNonFinite) ++stats.nonFinite;
            break;
        case ClipClass::Clip:
            for (int l = 0; l < lanes; ++l) bins[l].push_back(std::uint32_t(tri) | kBinClip);
            break;
        case ClipClass::Accept: {
            const TriangleScreening screened = screenTriangle(ctx.screenVertices[i0], ctx.screenVertices[i1],
                                                              ctx.screenVertices[i2], state.cull, multisampled);
            if (screened.outcome == SetupOutcome::Culled) ++stats.culled; // isCulled's decision too
            if (screened.outcome != SetupOutcome::Ready || state.stopAfter == PipelineStop::Geometry) break;
            // rasterizeTriangle's decision: the owner of the first row counts it, every other lane
            // whose bands meet its rows fills them.
            int rowBegin = 0, rowEnd = 0;
            rowsOfSnappedExtent(screened.minY, screened.maxY, multisampled, rowBegin, rowEnd);
            const int owner = LaneBands{0, lanes, height, pattern}.ownerOfRow(rowBegin);
            for (int l = 0; l < lanes; ++l) {
                if (l == owner) bins[l].push_back(std::uint32_t(tri) | kBinOwner);
                else if (LaneBands{l, lanes, height, pattern}.meets(rowBegin, rowEnd))
                    bins[l].push_back(std::uint32_t(tri));
            }
            break;
        }
        }
    }
}

// Lane `bands.lane`'s share of a binned draw: its bins of every chunk, in chunk order.
template <int kVaryings, class Program>
void rasterBinned(RenderContext& ctx, const DrawState& state, const Clipper& clipperProto, const LaneBands& bands,
                  LaneState& lane, const std::uint32_t* indices, Program& program) {
    FrameBuffer& fb = ctx.target();
    MsaaBuffer* msaa = ctx.multisampleTarget();
    Clipper clipper = clipperProto;
    RenderStats sink;
    const ScreenVertex* vertices = ctx.screenVertices.data();
    for (int chunk = 0; chunk < bands.lanes; ++chunk) {
        const std::vector<std::uint32_t>& bin = ctx.bins[std::size_t(chunk) * std::size_t(bands.lanes) + std::size_t(bands.lane)];
        const std::size_t count = bin.size();
        for (std::size_t k = 0; k < count; ++k) {
            if (k + kPrefetchTriangles < count) {
                const std::uint32_t* ahead = indices + 3 * std::size_t(bin[k + kPrefetchTriangles] & kBinIndex);
                for (int j = 0; j < 3; ++j) {
                    prefetchForRead(vertices + ahead[j]);
                    prefetchForRead(reinterpret_cast<const char*>(vertices + ahead[j] + 1) - 1);
                }
            }
            const std::uint32_t entry = bin[k];
            const std::size_t t = entry & kBinIndex;
            const std::uint32_t i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
            if (entry & kBinClip) {
                if (bands.lane == 0) ++lane.stats.clipped;
                clipAndRasterize<kVaryings>(ctx, state, clipper, bands, lane, sink, t, i0, i1, i2, program);
                continue;
            }
            // (No wireframe here: a wireframe draw runs on one lane.)
            rasterizeTriangle<kVaryings>(fb, msaa, state, bands, lane, sink, t, vertices[i0], vertices[i1], vertices[i2],
                                         program, (entry & kBinOwner) ? LaneRole::Owner : LaneRole::Helper);
        }
    }
}

// The vertex stage is split across lanes only when each lane gets at least this many vertices.
inline constexpr std::size_t kMinVerticesPerLane = 4096;

// The vertex stage for vertices [begin, end): program.vertex, the clip code, and the divide
// wherever it is defined (w > 0).
template <int kVaryings, class Program>
void vertexRange(RenderContext& ctx, const Clipper& clipper, std::size_t begin, std::size_t end, Program& program) {
    const int width = ctx.target().width(), height = ctx.target().height();
    for (std::size_t i = begin; i < end; ++i) {
        ClipVertex& cv = ctx.clipVertices[i];
        program.vertex(i, cv);
        const unsigned code = clipper.vertexCode(cv.position);
        ctx.clipCodes[i] = code;
        // Finite with w > 0 (the MinW bit is w - 1e-12 < 0 in double; test w itself).
        const bool usable = !(code & kCodeNonFinite) && cv.position.w > 0.0f;
        ctx.usable[i] = usable;
        if (usable) ctx.screenVertices[i] = toScreen(cv, width, height, kVaryings);
    }
}

// A distinct address per Program type: the vertex-cache key's program identity.
template <class Program>
inline constexpr char kVertexProgramTag = 0;

// A program whose vertex() also reads per-draw constants (Gouraud: the specular exponent)
// returns them packed in vertexVariant(); the vertex-cache key includes it (0 otherwise).
template <class Program, class = void>
struct HasVertexVariant : std::false_type {};
template <class Program>
struct HasVertexVariant<Program, std::void_t<decltype(std::declval<const Program&>().vertexVariant())>>
    : std::true_type {};
template <class Program>
std::uint64_t vertexVariantOf(const Program& program) {
    if constexpr (HasVertexVariant<Program>::value) return program.vertexVariant();
    else return 0;
}

// drawProgram's body: `lanes` lanes (1 = on the calling thread only).
template <int kVaryings, class Program>
void drawLanes(RenderContext& ctx, const DrawState& state, std::size_t vertexCount, const std::uint32_t* indices,
               std::size_t indexCount, Program& program, int lanes, const void* vertexSource = nullptr) {
    static_assert(kVaryings >= 0 && kVaryings <= kMaxVaryings, "too many varyings");
    assert(indexCount % 3 == 0);
    FrameBuffer& fb = ctx.target();
#ifndef NDEBUG
    for (std::size_t t = 0; t < indexCount; ++t) assert(indices[t] < vertexCount);
#endif
    if (MsaaBuffer* msaaTarget = ctx.multisampleTarget()) msaaTarget->markDrawn();
    ctx.clipVertices.resize(vertexCount);
    ctx.screenVertices.resize(vertexCount);
    ctx.usable.resize(vertexCount);
    ctx.clipCodes.resize(vertexCount);

    ClipParams params;
    params.viewportWidth = fb.width();
    params.viewportHeight = fb.height();
    params.clipFar = state.clipFar;
    params.varyingCount = kVaryings;
    const Clipper clipper(params);

    // The vertex stage is skipped when the cache already holds these vertices through this
    // vertex program for this viewport (RenderContext::vertexCache, inside a VertexReuseScope).
    RenderContext::VertexCacheKey key;
    if (vertexSource && ctx.vertexReuse)
        key = {vertexSource,          &kVertexProgramTag<Program>, vertexVariantOf(program), vertexCount, fb.width(),
               fb.height(), state.clipFar};
    const bool transformed = key.source && ctx.vertexCache == key;
    ctx.vertexCache = key;
    if (!transformed) ctx.stats.verticesTransformed += vertexCount;

    if (lanes <= 1) {
        LaneState lane;
        if (!transformed) vertexRange<kVaryings>(ctx, clipper, 0, vertexCount, program);
        rasterLane<kVaryings>(ctx, state, clipper, LaneBands{0, 1, fb.height()}, lane, indices, indexCount, program);
        flushFill(program, fb);
        ctx.stats += lane.stats;
        return;
    }
    // 1. Vertex stage split by vertex ranges (each lane with its own copy of the program), unless
    //    there are too few vertices to pay for waking the workers (tens of microseconds, against
    //    about 20 ns per vertex): then the calling thread transforms them all.
    ThreadPool& pool = *ctx.pool();
    if (transformed) {
        // Reused from an earlier draw of the same vertices.
    } else if (vertexCount < kMinVerticesPerLane * std::size_t(lanes)) {
        vertexRange<kVaryings>(ctx, clipper, 0, vertexCount, program);
    } else {
        auto vertexJob = [&](int l) {
            Program copy = program;
            const std::size_t begin = vertexCount * std::size_t(l) / std::size_t(lanes);
            const std::size_t end = vertexCount * std::size_t(l + 1) / std::size_t(lanes);
            vertexRange<kVaryings>(ctx, clipper, begin, end, copy);
        };
        pool.run(vertexJob);
    }
    LaneState laneStates[kMaxRenderThreads];
    // The bands' owners (weighted by the lanes' speed), and each lane's time in the raster job,
    // reported back so that the next draws' weights follow the lanes' speed (LaneBalance).
    const BandPattern* pattern = ctx.laneBalance.pattern().lanes == lanes ? &ctx.laneBalance.pattern() : nullptr;
    double busy[kMaxRenderThreads] = {};
    auto timed = [&busy](int l, auto&& work) {
        const auto start = std::chrono::steady_clock::now();
        work();
        busy[l] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    const std::size_t triangles = indexCount / 3;
    if (triangles >= ctx.binningMinTriangles && triangles <= std::size_t(kBinIndex)) {
        // 2. Binned primitive stage: each lane screens a chunk of the triangles into the lanes'
        //    bins, then each lane draws its bins (binTriangles, rasterBinned).
        const std::size_t binCount = std::size_t(lanes) * std::size_t(lanes);
        if (ctx.bins.size() < binCount) ctx.bins.resize(binCount);
        RenderStats chunkStats[kMaxRenderThreads];
        auto binJob = [&](int c) {
            for (int l = 0; l < lanes; ++l) ctx.bins[std::size_t(c) * std::size_t(lanes) + std::size_t(l)].clear();
            binTriangles(ctx, state, clipper, c, lanes, pattern, indices,
                         triangles * std::size_t(c) / std::size_t(lanes),
                         triangles * std::size_t(c + 1) / std::size_t(lanes), chunkStats[c]);
        };
        pool.run(binJob);
        auto binnedJob = [&](int l) {
            timed(l, [&] {
                Program copy = program;
                rasterBinned<kVaryings>(ctx, state, clipper, LaneBands{l, lanes, fb.height(), pattern}, laneStates[l],
                                        indices, copy);
                flushFill(copy, fb);
            });
        };
        pool.run(binnedJob);
        ctx.laneBalance.record(busy);
        for (int l = 0; l < lanes; ++l) {
            ctx.stats += chunkStats[l];
            ctx.stats += laneStates[l].stats;
        }
        return;
    }
    // 2. Primitive stage: every lane walks the triangles in order and fills its own bands.
    auto rasterJob = [&](int l) {
        timed(l, [&] {
            Program copy = program;
            rasterLane<kVaryings>(ctx, state, clipper, LaneBands{l, lanes, fb.height(), pattern}, laneStates[l],
                                  indices, indexCount, copy);
            flushFill(copy, fb);
        });
    };
    pool.run(rasterJob);
    ctx.laneBalance.record(busy);
    for (int l = 0; l < lanes; ++l) ctx.stats += laneStates[l].stats;
}

} // namespace detail

// Draws the indexed triangle list `indices` (indexCount / 3 triangles) over `vertexCount`
// vertices into ctx.target(), with a Program: an object with
//  - void vertex(std::size_t i, ClipVertex& out): runs ONCE per vertex (a post-transform cache
//    of the whole draw) and writes the clip-space position and the first kVaryings varyings;
//  - void triangle(std::size_t t, const TriangleSetup&): runs once per triangle that reaches
//    the fill (t = index of the triangle in this draw, i.e. indices[3t..3t+2]), before its
//    pixels: per-triangle work such as flat shading or keeping the setup for texture
//    derivatives goes there, never in the fragment shader;
//  - Pixel fragment(const Fragment<kVaryings>&): runs per covered pixel that passes the depth
//    test, with perspective-correct varyings;
//  - optionally bool fillKernel(setup, fb, scissor, shaded): a span kernel of its own (SIMD),
//    giving exactly what the scalar loop with fragment() gives (HasFillKernel above).
// All are inlined (templates): the span loop is specialised per program, and a draw with
// kVaryings == 0 interpolates nothing but depth.
// Threads: with ctx.threads() > 1 (and no wireframe, whose lines cross bands) each lane works
// on its own COPY of the program, so vertex() must not write shared state and triangle() /
// fragment() may keep per-triangle state only in the program object. The image, depth and
// counters are identical to a single-threaded draw (Pipeline.hpp, LaneBands).
// Triangles with a non-finite vertex are dropped without affecting the rest of the draw.
// Per triangle: trivial reject / accept first from the per-vertex clip codes (an on-screen
// triangle costs no clipping), else homogeneous clipping (near plane always, guard band and far
// plane when needed), then the divide (cached per vertex for accepted triangles), cull and
// setup in one pass, and the fill.
// Precondition (asserted): every index < vertexCount and indexCount % 3 == 0.
// `vertexSource`, when not null, names the vertex data (e.g. the Mesh) for the shared vertex
// stage: inside a VertexReuseScope, a draw of the same source with the same Program type reuses
// the previous draw's transformed vertices (so Program::vertex must depend only on the source
// and the scope's constant view, not on per-draw state such as the material).
template <int kVaryings, class Program>
void drawProgram(RenderContext& ctx, const DrawState& state, std::size_t vertexCount, const std::uint32_t* indices,
                 std::size_t indexCount, Program& program, const void* vertexSource = nullptr) {
    const int lanes = state.wireframe || !ctx.pool() ? 1 : ctx.pool()->lanes();
    detail::drawLanes<kVaryings>(ctx, state, vertexCount, indices, indexCount, program, lanes, vertexSource);
}

// The same with three callables (always on the calling thread: they may share state):
// vertexShader(i, ClipVertex&), triangleHook(t, const TriangleSetup&) and
// fragmentShader(const Fragment<kVaryings>&) -> Pixel, as the Program members above.
template <int kVaryings, class VertexShader, class TriangleHook, class FragmentShader>
void drawIndexed(RenderContext& ctx, const DrawState& state, std::size_t vertexCount, const std::uint32_t* indices,
                 std::size_t indexCount, VertexShader&& vertexShader, TriangleHook&& triangleHook,
                 FragmentShader&& fragmentShader) {
    detail::LambdaProgram<std::remove_reference_t<VertexShader>, std::remove_reference_t<TriangleHook>,
                          std::remove_reference_t<FragmentShader>>
        program{vertexShader, triangleHook, fragmentShader};
    detail::drawLanes<kVaryings>(ctx, state, vertexCount, indices, indexCount, program, 1);
}

// The same draw without per-triangle work.
template <int kVaryings, class VertexShader, class FragmentShader>
void drawIndexed(RenderContext& ctx, const DrawState& state, std::size_t vertexCount, const std::uint32_t* indices,
                 std::size_t indexCount, VertexShader&& vertexShader, FragmentShader&& fragmentShader) {
    detail::NoTriangleHook none;
    drawIndexed<kVaryings>(ctx, state, vertexCount, indices, indexCount, vertexShader, none, fragmentShader);
}

} // namespace sr
