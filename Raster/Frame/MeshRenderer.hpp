// Draws a world-space mesh with a material, choosing the specialised span loop once per draw.
#pragma once

#include <cstddef>
#include <cstdint>

#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Frame/RenderSettings.hpp"
#include "Raster/Geometry/Mesh.hpp"
#include "Raster/Geometry/Placement.hpp"

namespace sr {

// Draws the triangles indices[0 .. indexCount) of `mesh`: its positions in world space, or with
// `placement` (not null) in its own space, drawn at that place (one instance: Placement.hpp).
// "Model only what the scene requires": the shading mode and the material pick one of eight
// specialised pipelines, each interpolating only what its fragment stage reads:
//   unlit          depth only (constant kd)          | + uv (2) when textured
//   flat           depth only, lit once per triangle | + uv (2) when textured
//   gouraud        diffuse + specular terms (2)      | + uv (2)
//   phong          world position + normal (6)       | + uv (2)
// A mesh without normals is drawn with its face normals in the Gouraud and Phong modes
// (as flat). Texturing needs both a texture and mesh uvs.
void drawMesh(RenderContext& ctx, const FrameView& view, const RenderSettings& settings, const Mesh& mesh,
              const std::uint32_t* indices, std::size_t indexCount, const SurfaceMaterial& material,
              const Placement* placement = nullptr);

// The texel alpha a draw of `material` on `mesh` uses: the material's mode when the draw is
// textured (a texture and mesh uvs) and the texture has alpha below 255, else Off (Blend.hpp).
inline TexelAlpha activeTexelAlpha(const SurfaceMaterial& material, const Mesh& mesh) {
    const bool textured = material.texture != nullptr && mesh.hasUvs();
    return textured && material.texture->hasAlpha() ? material.texelAlpha : TexelAlpha{};
}
// Whether such a draw is blended (drawn after the opaque draws, sorted): a constant alpha below
// 1, or texel alpha in Blend mode.
inline bool drawsBlended(const SurfaceMaterial& material, const Mesh& mesh) {
    return material.alpha < 1.0f || activeTexelAlpha(material, mesh).mode == AlphaMode::Blend;
}

inline void drawMesh(RenderContext& ctx, const FrameView& view, const RenderSettings& settings, const Mesh& mesh,
                     const SurfaceMaterial& material) {
    drawMesh(ctx, view, settings, mesh, mesh.indices.data(), mesh.indices.size(), material);
}

} // namespace sr
