// A frame of a scene: every pass, in order, into a render context's target.
#pragma once

#include "Raster/Frame/Scene.hpp"

namespace sr {

// Draws every opaque SceneDraw in order (the order matters only for exact depth ties: first
// wins), then the lines and points (drawWorldLines, LineDraw.hpp), then the sky (Scene::sky),
// then, if any draw is transparent (drawsBlended: alpha < 1 or texel alpha Blend), the triangles
// of the transparent draws sorted back to front by the clip-space w (view depth) of their centroids, ties in draw and
// file order, each blended over what is behind it without writing depth. A scene without
// transparent draws sorts nothing. `textureOverride`, when not null, replaces every draw's texture.
void renderScene(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                 const Texture* textureOverride = nullptr);

// One whole frame into ctx's target: clear (clearColour, far depth), then renderScene.
// Supersampled (settings.antiAliasing: SSAA 4 or 16) the frame is drawn into
// ctx.supersampleTarget at 2x2 or 4x4 the target's size and box-filtered into the target
// (Raster/Frame/Resolve.hpp): the target ends with the resolved colour and, per pixel, its
// nearest sample's depth. A sample target above FrameBuffer::kMaxDimension cannot be made: the
// frame is then drawn without supersampling and false is returned (true otherwise).
// Multisampled (MSAA 2, 4 or 8) the frame is drawn multisampled into ctx.msaa and resolved the
// same way (Raster/Frame/Msaa.hpp, MsaaFill.hpp); the sample memory is released by the next frame without multisampling. A target
// above kMaxMsaaSamples samples is drawn with one sample and false is returned.
// A scene with a sky (Scene::sky) gets it (renderScene) where the depth is still far after the
// opaque draws and the lines, before the transparent draws blend over it, per sample when
// supersampled or multisampled: drawSkyRows, Sky.hpp; not in the partial pipelines
// (settings.stopAfter before Fill: the bench's stage timing).
bool renderSceneFrame(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                      const Texture* textureOverride = nullptr, Pixel clearColour = packBgra(0, 0, 0));

} // namespace sr
