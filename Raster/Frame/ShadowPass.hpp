// The shadow pass: each shadow-casting light's maps drawn depth-only through our own rasterizer.
#pragma once

#include "Raster/Shade/Shadow.hpp"

namespace sr {

struct FrameView;
struct Scene;
class RenderContext;

// The shadow pass: a map per directional and spot light of view.lighting (point lights cast
// none), each drawn depth-only with every opaque draw of the scene (transparent draws cast no
// shadow) into out.maps, reusing their memory. A directional light's orthographic frustum is
// fitted to the part of the scene's bounds the camera sees (the camera's view pyramid out to
// the farthest bound, intersected with the bounds, across the light); a spot light's is its
// cone. The counters of ctx.stats are left as they were.
void renderShadowMaps(RenderContext& ctx, const Scene& scene, const FrameView& view, const ShadowSettings& settings,
                      SceneShadows& out);

} // namespace sr
