// Scene: world-space meshes, textures and the draws that bind them (drawn by RenderScene.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "Raster/Frame/MeshRenderer.hpp"
#include "Raster/Geometry/Mesh.hpp"
#include "Raster/Geometry/Placement.hpp"
#include "Raster/Shade/Brdf.hpp" // PbrFactors
#include "Raster/Shade/MaterialMaps.hpp"
#include "Raster/Texture/Texture.hpp"

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
    std::optional<WrapModes> wrap;       // the maps' sampler (glTF), where it says (SurfaceMaterial)
    std::optional<TextureFilter> filter;
    // A glTF material's metallic-roughness input and maps (indices into Scene::textures, -1 =
    // none): what the pbr shading model reads (SurfaceMaterial::pbr).
    std::optional<PbrFactors> pbr;
    MaterialMaps<int> maps; // (a slot that readsAlpha: the alpha copy)
    std::optional<MapAddressing> addressing; // each map's own uv set, transform and sampler (SurfaceMaterial)
    // One instance of a mesh stored once in its own space (glTF EXT_mesh_gpu_instancing): where
    // this draw puts it. Unset: the mesh is in world space.
    std::optional<Placement> placement;
};

// Where a draw puts a vertex of its mesh: placed (an instance), or as stored (world space).
inline Vec3 drawnPosition(const SceneDraw& d, Vec3 p) { return d.placement ? d.placement->position(p) : p; }

// World-space line segments (index pairs) or points, in one flat colour (lines are unlit).
struct SceneLines {
    std::vector<Vec3> positions;
    std::vector<std::uint32_t> indices; // 2 per segment, or 1 per point
    bool points = false;
    Color colour{0.8f, 0.8f, 0.8f, 1.0f};
};

// Static geometry is stored in world space, prepared once (no per-frame vertex work besides
// the transform to clip space); an instanced mesh once in its own space, placed by its draws.
struct Scene {
    std::vector<Mesh> meshes;
    std::vector<Texture> textures;
    std::vector<SceneDraw> draws;
    std::vector<SceneLines> lines; // drawn after the opaque triangles, before the transparent ones
    Sky sky; // behind everything (renderSceneFrame); Kind::None: the clear colour
    Vec3 boundsMin{0, 0, 0}, boundsMax{0, 0, 0}; // for the auto-fit camera

    std::size_t triangleCount() const;
};

// The surface a draw is drawn with: its own material, or with `textureOverride` (when not null)
// in place of its texture.
SurfaceMaterial materialOf(const Scene& scene, const SceneDraw& d, const Texture* textureOverride);

// The opaque draw whose triangle the ray origin + t dir (t > 0) meets first, or -1 (the
// selection outline's pick: the draw at the screen centre is pickDraw(scene, view.eye,
// view.rays.forward)). Transparent draws are looked through. Exact (double) ray-triangle tests,
// every triangle of every opaque draw.
int pickDraw(const Scene& scene, Vec3 origin, Vec3 dir);

} // namespace sr
