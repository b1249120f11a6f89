// One draw call through the geometry and raster stages: vertex stage -> clip -> divide and viewport
// -> cull -> triangle setup -> (bin) -> scanline fill (+ optional wireframe overlay), on one lane or
// several.
#pragma once

#include <atomic>
#include <cassert>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

#include "Raster/Fill/RasterizeTriangle.hpp"
#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Frame/ThreadPool.hpp"
#include "Raster/Geometry/PrimitiveStage.hpp"
#include "Raster/Geometry/VertexStage.hpp"
#include "Raster/Setup/Binning.hpp"
#include "Raster/Setup/DrawState.hpp"

namespace sr {
namespace detail {

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

    ClipParams params;
    params.viewportWidth = fb.width();
    params.viewportHeight = fb.height();
    params.clipFar = state.clipFar;
    params.varyingCount = kVaryings;
    const Clipper clipper(params);

    // The vertex stage is skipped when the cache already holds these vertices through this
    // vertex program for this viewport (RenderContext::vertexCache, inside a VertexReuseScope).
    // A binned draw (several lanes, enough triangles: binTriangles) screens its triangles from
    // the vertices' snapped positions, made once per vertex by the vertex stage; so does any draw
    // on several lanes whose vertices a later draw may reuse (that one may bin), so that the
    // cached vertices of a mesh always have them.
    const std::size_t triangles = indexCount / 3;
    // (Each triangle's bin entries index it, or one of its clipped pieces' shared setups.)
    const bool binned = lanes > 1 && triangles >= ctx.binningMinTriangles &&
                        triangles <= std::size_t(kBinIndex) / std::size_t(kMaxClipVertices - 2);
    const bool reusable = vertexSource && ctx.vertexReuse;
    const bool snap = binned || (lanes > 1 && reusable);
    // A binned draw inside a DeferredFillScope waits to be filled with the pass's other draws
    // (RenderContext::deferral); any other draw fills the waiting ones first.
    const bool waits = binned && ctx.deferral.active && state.stopAfter > PipelineStop::Bin;
    if (!waits) ctx.fillDeferred();
    RenderContext::VertexCacheKey key;
    if (reusable)
        key = {vertexSource, &kVertexProgramTag<Program>, vertexVariantOf(program), vertexCount, fb.width(), fb.height(),
               state.clipFar, snap};
    const bool transformed = key.source && ctx.vertexCache == key;
    ctx.vertexCache = key;
    if (!transformed) {
        ctx.stats.verticesTransformed += vertexCount;
        ctx.releaseHeldVertices(); // a waiting draw's vertices stay as they are
    }
    ctx.clipVertices.resize(vertexCount);
    ctx.screenVertices.resize(vertexCount);
    ctx.usable.resize(vertexCount);
    ctx.clipCodes.resize(vertexCount);
    if (snap) ctx.snappedVertices.resize(vertexCount);

    // The multisampled fill's stages, chosen once for the draw.
    MsaaStages stages;
    if (const MsaaBuffer* msaaTarget = ctx.multisampleTarget())
        stages = msaaStages(msaaTarget->samples(), state.depth, MsaaCoverageMethod::Auto, state.isa);
    if (lanes <= 1) {
        LaneState lane;
        lane.msaaStages = stages;
        if (!transformed) vertexRange<kVaryings>(ctx, clipper, 0, vertexCount, program, false);
        rasterLane<kVaryings>(ctx, state, clipper, LaneBands{0, 1, fb.height()}, lane, indices, indexCount, program);
        flushFill(program, fb);
        ctx.stats += lane.stats;
        return;
    }
    // The bands' owners (weighted by the lanes' speed, LaneBalance); the vertex and binning
    // stages split their items by the same weights, so that a slower lane gets less of each.
    const BandPattern* pattern = ctx.laneBalance.pattern().lanes == lanes ? &ctx.laneBalance.pattern() : nullptr;
    const int* weights = pattern ? ctx.laneBalance.weights() : nullptr;
    // 1. Vertex stage split by vertex ranges (each lane with its own copy of the program), unless
    //    there are too few vertices to pay for waking the workers (tens of microseconds, against
    //    about 20 ns per vertex): then the calling thread transforms them all.
    ThreadPool& pool = *ctx.pool();
    if (transformed) {
        // Reused from an earlier draw of the same vertices.
    } else if (vertexCount < kMinVerticesPerLane * std::size_t(lanes)) {
        vertexRange<kVaryings>(ctx, clipper, 0, vertexCount, program, snap);
    } else {
        auto vertexJob = [&](int l) {
            Program copy = program;
            const ItemRange part = weightedPart(vertexCount, l, lanes, weights);
            vertexRange<kVaryings>(ctx, clipper, part.begin, part.end, copy, snap);
        };
        pool.run(vertexJob);
    }
    LaneState laneStates[kMaxRenderThreads];
    for (int l = 0; l < lanes; ++l) laneStates[l].msaaStages = stages;
    // Each lane's time in the raster job, reported back so that the next draws' weights follow
    // the lanes' speed (LaneBalance).
    double busy[kMaxRenderThreads] = {};
    auto timed = [&busy](int l, auto&& work) {
        const auto start = std::chrono::steady_clock::now();
        work();
        busy[l] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    if (binned) {
        // 2. Binned primitive stage: each lane screens a chunk of the triangles into the bands'
        //    bins, then each lane takes the bands of its own part of the rows, the largest first,
        //    then what the others left (binTriangles, bandsByWork, BandQueue, fillBinnedBand); or,
        //    inside a DeferredFillScope, the draw waits to be filled band by band with the pass's
        //    other waiting draws (DeferredDrawOf, fillDeferredDraws).
        const int bandsHigh = bandCount(fb.height());
        const std::size_t binCount = std::size_t(lanes) * std::size_t(bandsHigh);
        if (ctx.bins.size() < binCount) ctx.bins.resize(binCount);
        if (ctx.sharedSetups.size() < std::size_t(lanes)) ctx.sharedSetups.resize(std::size_t(lanes));
        RenderStats chunkStats[kMaxRenderThreads];
        auto binJob = [&](int c) {
            for (int b = 0; b < bandsHigh; ++b) ctx.bins[std::size_t(c) * std::size_t(bandsHigh) + std::size_t(b)].clear();
            const ItemRange chunk = weightedPart(triangles, c, lanes, weights);
            binTriangles<kVaryings>(ctx, state, clipper, c, indices, chunk.begin, chunk.end, chunkStats[c]);
        };
        pool.run(binJob);
        for (int l = 0; l < lanes; ++l) ctx.stats += chunkStats[l];
        if (state.stopAfter <= PipelineStop::Bin) return; // binning also clipped and culled
        if (waits) {
            auto draw = std::make_unique<DeferredDrawOf<kVaryings, Program>>(state, program, stages);
            RenderContext::Deferral& q = ctx.deferral;
            draw->bins = std::exchange(ctx.bins, q.takeSpare(q.spareBins));
            draw->sharedSetups = std::exchange(ctx.sharedSetups, q.takeSpare(q.spareSetups));
            draw->vertices = ctx.screenVertices.data();
            draw->chunks = lanes;
            q.holdsCurrent = true;
            q.fill = &fillDeferredDraws;
            q.draws.push_back(std::move(draw));
            return;
        }
        bandsByWork(ctx, lanes, bandsHigh, lanes);
        BandQueue queue(bandsHigh, lanes);
        const BinnedDraw draw{ctx.bins.data(), ctx.sharedSetups.data(), ctx.screenVertices.data(), lanes, bandsHigh};
        MsaaBuffer* msaa = ctx.multisampleTarget();
        auto bandJob = [&](int l) {
            Program copy = program;
            for (int k = queue.next(l); k >= 0; k = queue.next(l))
                fillBinnedBand<kVaryings>(fb, msaa, draw, state, ctx.bandOrder[std::size_t(k)], laneStates[l], copy);
            flushFill(copy, fb);
        };
        pool.run(bandJob);
        for (int l = 0; l < lanes; ++l) ctx.stats += laneStates[l].stats;
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
