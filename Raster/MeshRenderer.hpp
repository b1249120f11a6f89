// Draws a world-space mesh with a material, choosing the specialised span loop once per draw.
#pragma once

#include <cstddef>
#include <cstdint>

#include "Raster/Mesh.hpp"
#include "Raster/RenderContext.hpp"
#include "Raster/RenderSettings.hpp"

namespace sr {

// Draws the triangles indices[0 .. indexCount) of `mesh` (positions in world space).
// "Model only what the scene requires": the shading mode and the material pick one of eight
// specialised pipelines, each interpolating only what its fragment stage reads:
//   unlit          depth only (constant kd)          | + uv (2) when textured
//   flat           depth only, lit once per triangle | + uv (2) when textured
//   gouraud        diffuse + specular terms (2)      | + uv (2)
//   phong          world position + normal (6)       | + uv (2)
// A mesh without normals is drawn with its face normals in the Gouraud and Phong modes
// (as flat). Texturing needs both a texture and mesh uvs.
void drawMesh(RenderContext& ctx, const FrameView& view, const RenderSettings& settings, const Mesh& mesh,
              const std::uint32_t* indices, std::size_t indexCount, const SurfaceMaterial& material);

inline void drawMesh(RenderContext& ctx, const FrameView& view, const RenderSettings& settings, const Mesh& mesh,
                     const SurfaceMaterial& material) {
    drawMesh(ctx, view, settings, mesh, mesh.indices.data(), mesh.indices.size(), material);
}

} // namespace sr
