// Scene statistics and the per-draw loop.
#include "Raster/Scene.hpp"

#include <cassert>

#include "Raster/Msaa.hpp"
#include "Raster/Resolve.hpp"

namespace sr {

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const SceneDraw& d : draws) n += d.indexCount / 3;
    return n;
}

void renderScene(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                 const Texture* textureOverride) {
    // The meshes and the view are constant during the loop: draws of one mesh with the same
    // shading program transform its vertices once (issue 14: cost linear in material switches).
    const VertexReuseScope reuse(ctx);
    for (const SceneDraw& d : scene.draws) {
        assert(d.mesh >= 0 && std::size_t(d.mesh) < scene.meshes.size());
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        assert(std::size_t(d.firstIndex) + d.indexCount <= mesh.indices.size());
        SurfaceMaterial material;
        material.kd = d.kd;
        material.tint = d.tint;
        material.specular = d.specular;
        if (textureOverride) material.texture = textureOverride;
        else if (d.texture >= 0) material.texture = &scene.textures[std::size_t(d.texture)];
        drawMesh(ctx, view, settings, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, material);
    }
}

bool renderSceneFrame(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                      const Texture* textureOverride, Pixel clearColour) {
    const int factor = ssaaFactor(settings.ssaa);
    assert(factor > 0 && "RenderSettings::ssaa must be 1, 4 or 16");
    assert(validMsaa(settings.msaa) && "RenderSettings::msaa must be 1, 2, 4 or 8");
    FrameBuffer& out = ctx.target();
    const bool supersample = factor > 1 && !out.empty();
    const bool multisample = !supersample && settings.msaa > 1 && !out.empty();
    if (!multisample && !ctx.msaa.empty()) ctx.msaa.release(); // memory only while multisampling
    if (multisample && ctx.msaa.resize(out.width(), out.height(), settings.msaa)) {
        if (!ctx.samples.empty()) ctx.samples = FrameBuffer{};
        ctx.multisampling = true;
        ctx.clearTarget(clearColour, FrameBuffer::kFarDepth);
        renderScene(ctx, scene, view, settings, textureOverride);
        ctx.multisampling = false;
        // Resolved and cleared for the next frame in one pass over the samples.
        ctx.forRows(out.height(), [&](int y0, int y1) {
            resolveAndClearMsaaRows(ctx.msaa, out, y0, y1, clearColour, FrameBuffer::kFarDepth);
        });
        ctx.msaa.markCleared(clearColour, FrameBuffer::kFarDepth);
        return true;
    }
    if (!supersample || !ctx.samples.resize(out.width() * factor, out.height() * factor)) {
        if (!ctx.samples.empty()) ctx.samples = FrameBuffer{}; // no SSAA: give the sample memory back
        if (!ctx.msaa.empty()) ctx.msaa.release();
        RenderSettings plain = settings;
        plain.ssaa = 1; // drawn at the output size (also what the wireframe width follows)
        plain.msaa = 1;
        ctx.clearTarget(clearColour, FrameBuffer::kFarDepth);
        renderScene(ctx, scene, view, plain, textureOverride);
        return (factor <= 1 && !multisample) || out.empty();
    }
    // The same view: clip space does not depend on the target size, only the viewport does.
    ctx.setTarget(ctx.samples);
    ctx.clearTarget(clearColour, FrameBuffer::kFarDepth);
    renderScene(ctx, scene, view, settings, textureOverride);
    ctx.setTarget(out);
    ctx.forRows(out.height(), [&](int y0, int y1) { resolveBoxRows(ctx.samples, factor, out, y0, y1); });
    return true;
}

} // namespace sr
