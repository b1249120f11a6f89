// The primitive stage of one lane: every triangle of a draw in submission order, classified from
// its vertices' clip codes, clipped where it crosses a plane, then rasterized (and outlined).
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>

#include "Raster/Fill/Line.hpp"
#include "Raster/Fill/Prefetch.hpp"
#include "Raster/Fill/RasterizeTriangle.hpp"
#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Geometry/Clipper.hpp"
#include "Raster/Geometry/Viewport.hpp"

namespace sr {
namespace detail {

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

// A triangle (vertices i0, i1, i2) that crosses a clip plane, clipped: its polygon's vertices on
// screen, returning how many (0: nothing left; else its fan of polygon.triangleCount() pieces,
// screen[0], screen[k + 1], screen[k + 2], which keeps the input winding, so every piece gets the
// same cull decision).
template <int kVaryings>
int clipToScreen(RenderContext& ctx, const DrawState& state, Clipper& clipper, std::uint32_t i0,
                 std::uint32_t i1, std::uint32_t i2, ClippedPolygon& polygon, ScreenVertex* screen) {
    const FrameBuffer& fb = ctx.target();
    ClipVertex a = ctx.clipVertices[i0], b = ctx.clipVertices[i1], c = ctx.clipVertices[i2];
    detail::rebaseVaryings(state.rebase, a, b, c); // before the clipper interpolates them
    const int n = clipper.clip(a, b, c, polygon);
    for (int k = 0; k < n; ++k) screen[k] = toScreen(polygon.vertices[std::size_t(k)], fb.width(), fb.height(), kVaryings);
    return n;
}

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
    const int n = clipToScreen<kVaryings>(ctx, state, clipper, i0, i1, i2, polygon, screen);
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

} // namespace detail
} // namespace sr
