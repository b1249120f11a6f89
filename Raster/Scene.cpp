// Scene statistics and the per-draw loop.
#include "Raster/Scene.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

#include "Raster/LineDraw.hpp"
#include "Raster/Msaa.hpp"
#include "Raster/Resolve.hpp"

namespace sr {

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const SceneDraw& d : draws) n += d.indexCount / 3;
    return n;
}

namespace {

SurfaceMaterial materialOf(const Scene& scene, const SceneDraw& d, const Texture* textureOverride) {
    SurfaceMaterial material;
    material.kd = d.kd;
    material.tint = d.tint;
    material.specular = d.specular;
    material.alpha = d.alpha;
    material.texelAlpha = d.texelAlpha;
    material.doubleSided = d.doubleSided;
    material.wrap = d.wrap;
    material.filter = d.filter;
    if (textureOverride) material.texture = textureOverride;
    else if (d.texture >= 0) material.texture = &scene.textures[std::size_t(d.texture)];
    return material;
}

} // namespace

void renderScene(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                 const Texture* textureOverride) {
    // The meshes and the view are constant during the loop: draws of one mesh with the same
    // shading program transform its vertices once (issue 14: cost linear in material switches).
    const VertexReuseScope reuse(ctx);
    bool anyTransparent = false;
    for (const SceneDraw& d : scene.draws) {
        assert(d.mesh >= 0 && std::size_t(d.mesh) < scene.meshes.size());
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        assert(std::size_t(d.firstIndex) + d.indexCount <= mesh.indices.size());
        const SurfaceMaterial material = materialOf(scene, d, textureOverride);
        if (drawsBlended(material, mesh)) {
            anyTransparent = true;
            continue;
        }
        drawMesh(ctx, view, settings, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, material);
    }
    // Lines and points: depth-tested and written, before the transparent surfaces blend over them.
    const int lineWidth = std::max(1, ssaaFactor(settings.ssaa));
    for (const SceneLines& l : scene.lines)
        drawWorldLines(ctx, view, l.positions, l.indices, l.points, packBgra8(l.colour), lineWidth);
    // The sky where nothing opaque was drawn, before the transparent surfaces blend over it.
    if (scene.sky.on() && settings.stopAfter == PipelineStop::Fill) {
        if (MsaaBuffer* samples = ctx.multisampleTarget()) {
            samples->markDrawn();
            ctx.forRows(samples->height(), [&](int y0, int y1) { drawSkyMsaaRows(*samples, view.rays, scene.sky, y0, y1); });
        } else {
            FrameBuffer& target = ctx.target();
            ctx.forRows(target.height(), [&](int y0, int y1) { drawSkyRows(target, view.rays, scene.sky, y0, y1); });
        }
    }
    if (!anyTransparent) return;

    // Transparent triangles back to front (largest w first; equal keys in draw and file order),
    // drawn as runs of consecutive triangles of one draw.
    using Sorted = RenderContext::TransparentTriangle;
    std::vector<Sorted>& order = ctx.transparentOrder;
    order.clear();
    for (std::size_t i = 0; i < scene.draws.size(); ++i) {
        const SceneDraw& d = scene.draws[i];
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        if (!drawsBlended(materialOf(scene, d, textureOverride), mesh)) continue;
        for (std::uint32_t k = 0; k + 2 < d.indexCount; k += 3) {
            const std::uint32_t* t = mesh.indices.data() + d.firstIndex + k;
            const Vec3 c = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0f;
            const float w = (view.viewProj * Vec4(c, 1.0f)).w;
            order.push_back({std::isnan(w) ? 0.0f : w, std::uint32_t(i), d.firstIndex + k});
        }
    }
    // (draw, first) is unique and increases in the order above: the comparison is total, and
    // equal depths keep that order without a stable sort's buffer.
    std::sort(order.begin(), order.end(), [](const Sorted& a, const Sorted& b) {
        if (a.w != b.w) return a.w > b.w;
        return a.draw != b.draw ? a.draw < b.draw : a.first < b.first;
    });
    ctx.stats.trianglesSorted += order.size();
    std::vector<std::uint32_t>& indices = ctx.transparentIndices;
    for (std::size_t r = 0; r < order.size();) {
        const std::uint32_t draw = order[r].draw;
        const SceneDraw& d = scene.draws[draw];
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        indices.clear();
        for (; r < order.size() && order[r].draw == draw; ++r)
            indices.insert(indices.end(), mesh.indices.begin() + order[r].first, mesh.indices.begin() + order[r].first + 3);
        drawMesh(ctx, view, settings, mesh, indices.data(), indices.size(), materialOf(scene, d, textureOverride));
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
