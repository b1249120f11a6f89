// Scene statistics and the per-draw loop.
#include "Raster/Scene.hpp"

#include <cassert>

namespace sr {

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const SceneDraw& d : draws) n += d.indexCount / 3;
    return n;
}

void renderScene(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                 const Texture* textureOverride) {
    for (const SceneDraw& d : scene.draws) {
        assert(d.mesh >= 0 && std::size_t(d.mesh) < scene.meshes.size());
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        assert(std::size_t(d.firstIndex) + d.indexCount <= mesh.indices.size());
        SurfaceMaterial material;
        material.kd = d.kd;
        if (textureOverride) material.texture = textureOverride;
        else if (d.texture >= 0) material.texture = &scene.textures[std::size_t(d.texture)];
        drawMesh(ctx, view, settings, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, material);
    }
}

} // namespace sr
