// One draw call through the geometry and raster stages: vertex shader -> clip -> divide and
// viewport -> cull -> triangle setup -> scanline fill (+ optional wireframe overlay).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "Raster/Clipper.hpp"
#include "Raster/Cull.hpp"
#include "Raster/Line.hpp"
#include "Raster/RenderContext.hpp"
#include "Raster/ScanlineFill.hpp"
#include "Raster/TriangleSetup.hpp"
#include "Raster/Viewport.hpp"

namespace sr {

// Where a draw stops: the bench command times partial pipelines to split a frame's time into
// stages (geometry = vertex shader + clip + divide + cull; setup; fill = span loop + shading).
enum class PipelineStop { Geometry, Setup, Fill };

// Per-draw fixed-function state.
struct DrawState {
    CullMode cull = CullMode::None;
    bool clipFar = true;                    // false for a projection with an infinite far plane
    DepthMode depth = DepthMode::TestWrite; // reversed-Z, GREATER
    PipelineStop stopAfter = PipelineStop::Fill;
    PerspectiveMode perspective = PerspectiveMode::Exact; // how varyings are interpolated
    bool wireframe = false;                 // overlay the (clipped) triangle outlines
    Pixel wireColour = packBgra(255, 255, 255);
};

namespace detail {

// Wireframe depth bias: lines sample the edge itself while the fill samples pixel centres
// inside it, so an unbiased edge would z-fight with its own triangle. Reversed-Z: nearer is
// larger, so the line's depth is raised by a relative 2^-12 (it shows through a surface only
// if that surface is within 0.025% of the line's depth in z_ndc).
inline float wireDepth(float z) { return z * (1.0f + 1.0f / 4096.0f); }

inline void drawWireEdge(FrameBuffer& fb, const ScreenVertex& a, const ScreenVertex& b, Pixel colour,
                         bool depthTest) {
    LineOptions options;
    options.depthTest = depthTest;
    drawLine(fb, LineVertex{a.x, a.y, wireDepth(a.z), colour}, LineVertex{b.x, b.y, wireDepth(b.z), colour},
             options);
}

// A triangle hook that does nothing (draws without per-triangle work).
struct NoTriangleHook {
    void operator()(std::size_t, const TriangleSetup&) const {}
};

// Culls, sets up and fills one screen-space triangle (index t of the draw). Returns true when
// it was not culled. The hook runs once per set-up triangle, right before its fill.
template <int kVaryings, class TriangleHook, class FragmentShader>
bool rasterizeTriangle(RenderContext& ctx, const DrawState& state, std::size_t t, const ScreenVertex& v0,
                       const ScreenVertex& v1, const ScreenVertex& v2, TriangleHook& hook, FragmentShader& shader) {
    if (isCulled(state.cull, v0, v1, v2)) {
        ++ctx.stats.culled;
        return false;
    }
    if (state.stopAfter == PipelineStop::Geometry) return true;
    const bool affine = kVaryings > 0 && state.perspective == PerspectiveMode::Affine;
    const auto setup = setupTriangle(v0, v1, v2, kVaryings, !affine);
    if (!setup) return true; // covers no pixel-centre row: nothing to do, but not culled
    ++ctx.stats.rasterized;
    if (state.stopAfter == PipelineStop::Setup) return true;
    hook(t, *setup);
    // Count the fragments that pass the depth test (one add per pixel: overdraw statistics).
    auto counted = [&ctx, &shader](const Fragment<kVaryings>& f) {
        ++ctx.stats.fragmentsShaded;
        return shader(f);
    };
    FrameBuffer& fb = ctx.target();
    // Depth mode x perspective mode, resolved once per triangle; without varyings only Exact
    // exists (nothing to interpolate), which keeps the number of instantiated loops down.
    auto fill = [&](auto depthTag) {
        constexpr DepthMode kDepth = decltype(depthTag)::value;
        if constexpr (kVaryings == 0) {
            fillTriangle<kDepth, kVaryings>(*setup, fb, counted);
        } else {
            switch (state.perspective) {
            case PerspectiveMode::Exact: fillTriangle<kDepth, kVaryings, PerspectiveMode::Exact>(*setup, fb, counted); break;
            case PerspectiveMode::Span16: fillTriangle<kDepth, kVaryings, PerspectiveMode::Span16>(*setup, fb, counted); break;
            case PerspectiveMode::Span8: fillTriangle<kDepth, kVaryings, PerspectiveMode::Span8>(*setup, fb, counted); break;
            case PerspectiveMode::Affine: fillTriangle<kDepth, kVaryings, PerspectiveMode::Affine>(*setup, fb, counted); break;
            }
        }
    };
    switch (state.depth) {
    case DepthMode::Off: fill(std::integral_constant<DepthMode, DepthMode::Off>{}); break;
    case DepthMode::Test: fill(std::integral_constant<DepthMode, DepthMode::Test>{}); break;
    case DepthMode::TestWrite: fill(std::integral_constant<DepthMode, DepthMode::TestWrite>{}); break;
    }
    return true;
}

} // namespace detail

// Draws the indexed triangle list `indices` (indexCount / 3 triangles) over `vertexCount`
// vertices into ctx.target().
//  - vertexShader(std::size_t i, ClipVertex& out) runs ONCE per vertex (a post-transform cache
//    of the whole draw) and writes the clip-space position and the first kVaryings varyings.
//  - fragmentShader(const Fragment<kVaryings>&) -> Pixel runs per covered pixel that passes the
//    depth test, with perspective-correct varyings. Both are inlined (templates): the span
//    loop is specialised per shader, and a draw with kVaryings == 0 interpolates nothing but
//    depth.
// Triangles with a non-finite vertex are dropped without affecting the rest of the draw.
// Per triangle: trivial reject / accept first (an on-screen triangle costs no clipping), else
// homogeneous clipping (near plane always, guard band and far plane when needed), then the
// divide (cached per vertex for accepted triangles), cull, setup and fill.
//  - triangleHook(std::size_t t, const TriangleSetup&) runs once per triangle that reaches the
//    fill (t = index of the triangle in this draw, i.e. indices[3t..3t+2]), before its pixels:
//    per-triangle work such as flat shading, or keeping the setup's gradients for texture
//    derivatives, goes there, never in the fragment shader.
// Precondition (asserted): every index < vertexCount and indexCount % 3 == 0.
template <int kVaryings, class VertexShader, class TriangleHook, class FragmentShader>
void drawIndexed(RenderContext& ctx, const DrawState& state, std::size_t vertexCount, const std::uint32_t* indices,
                 std::size_t indexCount, VertexShader&& vertexShader, TriangleHook&& triangleHook,
                 FragmentShader&& fragmentShader) {
    static_assert(kVaryings >= 0 && kVaryings <= kMaxVaryings, "too many varyings");
    assert(indexCount % 3 == 0);
    FrameBuffer& fb = ctx.target();
    const int width = fb.width(), height = fb.height();

    // 1. Vertex stage, once per vertex; the divide too wherever it is defined (w > 0).
    ctx.clipVertices.resize(vertexCount);
    ctx.screenVertices.resize(vertexCount);
    ctx.usable.resize(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i) {
        ClipVertex& cv = ctx.clipVertices[i];
        vertexShader(i, cv);
        const bool usable = isFinite(cv.position) && cv.position.w > 0.0f;
        ctx.usable[i] = usable;
        if (usable) ctx.screenVertices[i] = toScreen(cv, width, height, kVaryings);
    }

    // 2. Primitive stage, triangle by triangle in submission order.
    ClipParams params;
    params.viewportWidth = width;
    params.viewportHeight = height;
    params.clipFar = state.clipFar;
    params.varyingCount = kVaryings;
    Clipper clipper(params);
    ClippedPolygon polygon;
    ScreenVertex screen[kMaxClipVertices];
    const bool wireDepthTest = state.depth != DepthMode::Off;

    for (std::size_t t = 0; t + 2 < indexCount; t += 3) {
        const std::uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
        assert(i0 < vertexCount && i1 < vertexCount && i2 < vertexCount);
        const ClipVertex& a = ctx.clipVertices[i0];
        const ClipVertex& b = ctx.clipVertices[i1];
        const ClipVertex& c = ctx.clipVertices[i2];
        ++ctx.stats.trianglesIn;

        switch (clipper.classify(a, b, c)) {
        case ClipClass::Reject:
            ++ctx.stats.trivialRejected;
            if (!isFinite(a.position) || !isFinite(b.position) || !isFinite(c.position)) ++ctx.stats.nonFinite;
            break;
        case ClipClass::Accept: {
            const ScreenVertex& s0 = ctx.screenVertices[i0];
            const ScreenVertex& s1 = ctx.screenVertices[i1];
            const ScreenVertex& s2 = ctx.screenVertices[i2];
            assert(ctx.usable[i0] && ctx.usable[i1] && ctx.usable[i2]);
            if (detail::rasterizeTriangle<kVaryings>(ctx, state, t / 3, s0, s1, s2, triangleHook, fragmentShader) && state.wireframe) {
                detail::drawWireEdge(fb, s0, s1, state.wireColour, wireDepthTest);
                detail::drawWireEdge(fb, s1, s2, state.wireColour, wireDepthTest);
                detail::drawWireEdge(fb, s2, s0, state.wireColour, wireDepthTest);
            }
            break;
        }
        case ClipClass::Clip: {
            ++ctx.stats.clipped;
            const int n = clipper.clip(a, b, c, polygon);
            for (int k = 0; k < n; ++k) screen[k] = toScreen(polygon.vertices[std::size_t(k)], width, height, kVaryings);
            // The fan keeps the input winding, so every piece gets the same cull decision.
            bool drawn = false;
            for (int k = 0; k < polygon.triangleCount(); ++k) {
                drawn |= detail::rasterizeTriangle<kVaryings>(ctx, state, t / 3, screen[0], screen[k + 1],
                                                              screen[k + 2], triangleHook, fragmentShader);
            }
            if (drawn && state.wireframe) {
                for (int k = 0; k < n; ++k)
                    detail::drawWireEdge(fb, screen[k], screen[(k + 1) % n], state.wireColour, wireDepthTest);
            }
            break;
        }
        }
    }
}

// The same draw without per-triangle work.
template <int kVaryings, class VertexShader, class FragmentShader>
void drawIndexed(RenderContext& ctx, const DrawState& state, std::size_t vertexCount, const std::uint32_t* indices,
                 std::size_t indexCount, VertexShader&& vertexShader, FragmentShader&& fragmentShader) {
    detail::NoTriangleHook none;
    drawIndexed<kVaryings>(ctx, state, vertexCount, indices, indexCount, vertexShader, none, fragmentShader);
}

} // namespace sr
