// Scene: world-space meshes, textures and the draws that bind them; rendered by renderScene().
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "Raster/Brdf.hpp" // PbrFactors
#include "Raster/Mesh.hpp"
#include "Raster/MeshRenderer.hpp"
#include "Raster/Texture.hpp"

namespace sr {

// One draw: a range of a mesh's index list with its surface.
struct SceneDraw {
    int mesh = 0;
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
    int texture = -1;                    // index into Scene::textures, or -1 for kd
    Color kd{0.8f, 0.8f, 0.8f, 1.0f};    // the colour when untextured
    Color tint{1.0f, 1.0f, 1.0f, 1.0f};  // multiplies the texel when textured (1: the texel alone)
    Specular specular;                   // ks and shininess (default: white 0.5, 32)
    float alpha = 1.0f;                  // opacity (MTL d, glTF BLEND); below 1: drawn after the opaque draws
    TexelAlpha texelAlpha;               // glTF MASK / BLEND with the texture's alpha (SurfaceMaterial)
    bool doubleSided = true;             // false (a glTF single-sided material): back faces culled whatever the cull mode
    std::optional<WrapMode> wrap;        // the texture's sampler (glTF), where it says (SurfaceMaterial)
    std::optional<TextureFilter> filter;
    // A glTF material's metallic-roughness input and maps (indices into Scene::textures, -1 =
    // none): what the pbr shading model reads (SurfaceMaterial::pbr).
    std::optional<PbrFactors> pbr;
    int metallicRoughnessTexture = -1, emissiveTexture = -1, normalTexture = -1, occlusionTexture = -1;
};

// World-space line segments (index pairs) or points, in one flat colour (lines are unlit).
struct SceneLines {
    std::vector<Vec3> positions;
    std::vector<std::uint32_t> indices; // 2 per segment, or 1 per point
    bool points = false;
    Color colour{0.8f, 0.8f, 0.8f, 1.0f};
};

// Static geometry is stored in world space, prepared once (no per-frame vertex work besides
// the transform to clip space).
struct Scene {
    std::vector<Mesh> meshes;
    std::vector<Texture> textures;
    std::vector<SceneDraw> draws;
    std::vector<SceneLines> lines; // drawn after the opaque triangles, before the transparent ones
    Sky sky; // behind everything (renderSceneFrame); Kind::None: the clear colour
    Vec3 boundsMin{0, 0, 0}, boundsMax{0, 0, 0}; // for the auto-fit camera

    std::size_t triangleCount() const;
};

// Draws every opaque SceneDraw in order (the order matters only for exact depth ties: first
// wins), then the lines and points (drawWorldLines, LineDraw.hpp), then the sky (Scene::sky), then, if any draw is transparent (drawsBlended: alpha < 1 or texel alpha Blend), the triangles of the transparent draws
// sorted back to front by the clip-space w (view depth) of their centroids, ties in draw and
// file order, each blended over what is behind it without writing depth. A scene without
// transparent draws sorts nothing. `textureOverride`, when not null, replaces every draw's texture.
void renderScene(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                 const Texture* textureOverride = nullptr);

// The opaque draw whose triangle the ray origin + t dir (t > 0) meets first, or -1 (the
// selection outline's pick: the draw at the screen centre is pickDraw(scene, view.eye,
// view.rays.forward)). Transparent draws are looked through. Exact (double) ray-triangle tests,
// every triangle of every opaque draw.
int pickDraw(const Scene& scene, Vec3 origin, Vec3 dir);

// One whole frame into ctx's target: clear (clearColour, far depth), then renderScene. With
// settings.ssaa = 4 or 16 the frame is drawn into ctx.supersampleTarget at 2x2 or 4x4 the target's size and
// box-filtered into the target (Raster/Resolve.hpp): the target ends with the resolved colour and,
// per pixel, its nearest sample's depth. A sample target above FrameBuffer::kMaxDimension cannot
// be made: the frame is then drawn without supersampling and false is returned (true otherwise).
// With settings.msaa = 2, 4 or 8 (and ssaa 1; supersampling wins when both are asked for) the
// frame is drawn multisampled into ctx.msaa and resolved the same way (Raster/Msaa.hpp,
// MsaaFill.hpp); the sample memory is released by the next frame without multisampling. A target
// above kMaxMsaaSamples samples is drawn with one sample and false is returned.
// A scene with a sky (Scene::sky) gets it (renderScene) where the depth is still far after the
// opaque draws and the lines, before the transparent draws blend over it, per sample when
// supersampled or multisampled: drawSkyRows, Sky.hpp; not in the partial pipelines
// (settings.stopAfter before Fill: the bench's stage timing).
bool renderSceneFrame(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                      const Texture* textureOverride = nullptr, Pixel clearColour = packBgra(0, 0, 0));

} // namespace sr
