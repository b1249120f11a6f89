// The fixed-function state of one draw: cull, clip, depth, perspective, blending, stencil, wireframe.
#pragma once

#include "Raster/Fill/Blend.hpp"
#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Fill/Stencil.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Geometry/Cull.hpp"
#include "Raster/Setup/PipelineModes.hpp" // PipelineStop, DepthMode, PerspectiveMode
#include "Raster/Setup/TriangleSetup.hpp" // VaryingRebase

namespace sr {

// Per-draw fixed-function state.
struct DrawState {
    CullMode cull = CullMode::None;
    bool clipFar = true;                    // false for a projection with an infinite far plane
    DepthMode depth = DepthMode::TestWrite; // reversed-Z, GREATER
    PipelineStop stopAfter = PipelineStop::Fill;
    PerspectiveMode perspective = PerspectiveMode::Exact; // how varyings are interpolated
    Isa isa = Isa::Scalar; // the draw's kernels' ISA (RenderSettings::isa); the multisampled coverage follows it
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
    // operations per fragment (Raster/Fill/Stencil.hpp), before the depth test, as OpenGL orders them;
    // the draw is then filled by the scalar loop (detail::stencilFragment). Not applied to a
    // multisampled target (the buffer is per pixel): renderScene draws no stencil passes there.
    StencilState stencil;
    // Honoured by the stencil path only (draws with `stencil` on): colourWrite false leaves the
    // colour as it was (glColorMask off), depthEqualPasses makes the depth test GEQUAL instead of
    // GREATER (a draw of the same triangles again passes where they are what is visible).
    bool colourWrite = true;
    bool depthEqualPasses = false;
};

} // namespace sr
