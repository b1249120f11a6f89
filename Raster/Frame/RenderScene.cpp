// A frame of a scene: the passes in order (shadow maps, opaque draws, lines, sky, transparent draws,
// the selection outline) into a target, supersampled or multisampled and resolved.
#include "Raster/Frame/RenderScene.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "Raster/Frame/LineDraw.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "Raster/Frame/Resolve.hpp"
#include "Raster/Frame/ShadowPass.hpp"
#include "Raster/Shade/Shading.hpp" // blinnPhongLighting

namespace sr {

namespace {

// The outline's band (renderScene): every pixel of `target` that the stencil test NotEqual 1
// passes (not the selected draw's) within `radius` pixels, in x and in y, of one marked 1 (the
// draw's), in `colour`. Separable, inside the mark's bounding box grown by `radius`: each row's
// unmarked pixels within `radius` of a mark in the row are marked 2 (the Replace operation); then
// a pixel passing the test is in the band when a pixel 1 or 2 lies within `radius` of it in its
// column. Rows in parallel (ctx.forRows), two passes.
void drawOutlineBand(RenderContext& ctx, FrameBuffer& target, Pixel colour, int radius) {
    const int w = target.width(), h = target.height();
    int bx0 = w, bx1 = -1, by0 = h, by1 = -1; // the mark's bounding box
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* s = target.stencilRow(y);
        const void* first = std::memchr(s, 1, std::size_t(w));
        if (!first) continue;
        int last = w - 1;
        while (s[last] != 1) --last;
        bx0 = std::min(bx0, int(static_cast<const std::uint8_t*>(first) - s));
        bx1 = std::max(bx1, last);
        by0 = std::min(by0, y);
        by1 = y;
    }
    if (bx1 < 0) return; // nothing of the draw shows
    const int x0 = std::max(0, bx0 - radius), x1 = std::min(w - 1, bx1 + radius);
    ctx.forRows(h, [&](int r0, int r1) {
        for (int y = std::max(r0, by0); y < std::min(r1, by1 + 1); ++y) {
            std::uint8_t* s = target.stencilRow(y);
            int last = -radius - 1; // nearest mark at or left of x
            for (int x = x0; x <= x1; ++x) {
                if (s[x] == 1) last = x;
                else if (x - last <= radius) s[x] = stencilApply(StencilOp::Replace, s[x], 2, 0xFF);
            }
            int next = w + radius + 1; // nearest mark at or right of x
            for (int x = x1; x >= x0; --x) {
                if (s[x] == 1) next = x;
                else if (next - x <= radius) s[x] = stencilApply(StencilOp::Replace, s[x], 2, 0xFF);
            }
        }
    });
    ctx.forRows(h, [&](int r0, int r1) {
        for (int y = std::max(r0, by0 - radius); y < std::min(r1, by1 + radius + 1); ++y) {
            const std::uint8_t* s = target.stencilRow(y);
            Pixel* c = target.colorRow(y);
            const int ya = std::max(by0, y - radius), yb = std::min(by1, y + radius);
            for (int x = x0; x <= x1; ++x) {
                if (!stencilPasses(StencilFunc::NotEqual, 1, s[x], 0xFF)) continue;
                for (int yy = ya; yy <= yb; ++yy) {
                    const std::uint8_t v = target.stencilRow(yy)[x];
                    if (v == 1 || v == 2) {
                        c[x] = colour;
                        break;
                    }
                }
            }
        }
    });
}

const Placement* placementOf(const SceneDraw& d) { return d.placement ? &*d.placement : nullptr; }

// The transparent draws' triangles, sorted (renderScene).
void drawTransparent(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                     const Texture* textureOverride) {
    // Transparent triangles back to front (largest w first; equal keys in draw and file order),
    // drawn as runs of consecutive triangles of one draw.
    using Sorted = RenderContext::TransparentTriangle;
    std::vector<Sorted>& order = ctx.transparentOrder;
    order.clear();
    for (std::size_t i = 0; i < scene.draws.size(); ++i) {
        const SceneDraw& d = scene.draws[i];
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        if (!(d.alpha > 0.0f) || !drawsBlended(materialOf(scene, d, textureOverride), mesh)) continue;
        for (std::uint32_t k = 0; k + 2 < d.indexCount; k += 3) {
            const std::uint32_t* t = mesh.indices.data() + d.firstIndex + k;
            const Vec3 c = (drawnPosition(d, mesh.positions[t[0]]) + drawnPosition(d, mesh.positions[t[1]]) +
                            drawnPosition(d, mesh.positions[t[2]])) /
                           3.0f;
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
        drawMesh(ctx, view, settings, mesh, indices.data(), indices.size(), materialOf(scene, d, textureOverride), placementOf(d));
    }
}

} // namespace

void renderScene(RenderContext& ctx, const Scene& scene, const FrameView& view, const RenderSettings& settings,
                 const Texture* textureOverride) {
    // The meshes and the view are constant during the loop: draws of one mesh with the same
    // shading program transform its vertices once (so material switches cost no vertex work).
    const VertexReuseScope reuse(ctx);
    // The selection outline: a stencil buffer for this frame's target (its mark and band below).
    const Outline& outline = settings.outline;
    const bool outlined = outline.on() && std::size_t(outline.draw) < scene.draws.size() &&
                          settings.stopAfter == PipelineStop::Fill && !ctx.multisampleTarget();
    FrameBuffer& target = ctx.target();
    if (outlined) {
        target.enableStencil();
        target.clearStencil(0);
    } else if (target.hasStencil()) {
        target.releaseStencil(); // memory only while outlining
    }
    bool anyTransparent = false;
    // The opaque draws' fills wait for the end of the loop and then run together, band by band
    // (several threads: RenderContext::deferral).
    DeferredFillScope opaque(ctx);
    for (const SceneDraw& d : scene.draws) {
        assert(d.mesh >= 0 && std::size_t(d.mesh) < scene.meshes.size());
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        assert(std::size_t(d.firstIndex) + d.indexCount <= mesh.indices.size());
        if (!(d.alpha > 0.0f)) continue; // fully transparent (an animated glTF MASK below its cutoff, for one)
        const SurfaceMaterial material = materialOf(scene, d, textureOverride);
        if (drawsBlended(material, mesh)) {
            anyTransparent = true;
            continue;
        }
        drawMesh(ctx, view, settings, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, material, placementOf(d));
    }
    opaque.finish();
    // Lines and points: depth-tested and written, before the transparent surfaces blend over them.
    const int lineWidth = settings.antiAliasing.gridSide();
    for (const SceneLines& l : scene.lines)
        drawWorldLines(ctx, view, l.positions, l.indices, l.points, packBgra8(l.colour), lineWidth);
    // The outline's mark: the selected draw again, no colour, GEQUAL: stencil 1 where it shows.
    if (outlined) {
        const SceneDraw& d = scene.draws[std::size_t(outline.draw)];
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        RenderSettings mark = settings;
        mark.shading = ShadingMode::Unlit;
        mark.wireframe = false;
        mark.colourWrite = false;
        mark.depthEqualPasses = true;
        mark.stencil.enabled = true;
        mark.stencil.ref = 1;
        mark.stencil.pass = StencilOp::Replace;
        SurfaceMaterial plain; // untextured: nothing to sample (no colour is written)
        plain.doubleSided = materialOf(scene, d, textureOverride).doubleSided;
        drawMesh(ctx, view, mark, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, plain, placementOf(d));
    }
    // The sky where nothing opaque was drawn, before the transparent surfaces blend over it.
    if (scene.sky.on() && settings.stopAfter == PipelineStop::Fill) {
        if (MsaaBuffer* samples = ctx.multisampleTarget()) {
            samples->markDrawn();
            ctx.forRows(samples->height(), [&](int y0, int y1) { drawSkyMsaaRows(*samples, view.rays, scene.sky, y0, y1); });
        } else {
            ctx.forRows(target.height(), [&](int y0, int y1) { drawSkyRows(target, view.rays, scene.sky, y0, y1); });
        }
    }
    if (anyTransparent) drawTransparent(ctx, scene, view, settings, textureOverride);
    if (!outlined) return;
    // The outline last, over everything: the band around the mark.
    const float pixels = outline.width * float(settings.antiAliasing.gridSide());
    const int radius = std::isfinite(pixels) ? int(std::clamp(std::lround(pixels), 0L, 256L)) : 0;
    if (radius > 0) drawOutlineBand(ctx, target, packBgra8(outline.colour), radius);
}

bool renderSceneFrame(RenderContext& ctx, const Scene& scene, const FrameView& cameraView, const RenderSettings& settings,
                      const Texture* textureOverride, Pixel clearColour) {
    // The shadow pass first, into the lights' maps (their memory kept while shadows stay on).
    FrameView view = cameraView;
    if (settings.shadows.on && settings.stopAfter == PipelineStop::Fill && !ctx.target().empty()) {
        if (!ctx.shadows) ctx.shadows = std::make_shared<SceneShadows>();
        const bool wasMultisampling = ctx.multisampling;
        ctx.multisampling = false;
        renderShadowMaps(ctx, scene, cameraView, settings.shadows, *ctx.shadows);
        ctx.multisampling = wasMultisampling;
        view.shadows = ctx.shadows.get();
    } else if (ctx.shadows) {
        ctx.shadows.reset();
    }
    // Physical lights as the Blinn-Phong draws see them, once for the frame (drawMesh).
    FrameView blinnPhongView;
    if (view.lighting.physical) {
        blinnPhongView = view;
        blinnPhongView.lighting = blinnPhongLighting(view.lighting);
        view.blinnPhong = &blinnPhongView;
    }
    const AntiAliasing aa = settings.antiAliasing;
    const int factor = aa.gridSide();
    FrameBuffer& out = ctx.target();
    const bool supersample = factor > 1 && !out.empty();
    const bool linear = settings.colour == ColorMode::Linear; // resolved in linear light
    const bool multisample = aa.multisampled() && !out.empty();
    if (!multisample && !ctx.msaa.empty()) ctx.msaa.release(); // memory only while multisampling
    if (multisample && ctx.msaa.resize(out.width(), out.height(), aa.samples())) {
        if (!ctx.supersampleTarget.empty()) ctx.supersampleTarget = FrameBuffer{};
        ctx.multisampling = true;
        ctx.clearTarget(clearColour, FrameBuffer::kFarDepth);
        renderScene(ctx, scene, view, settings, textureOverride);
        ctx.multisampling = false;
        // Resolved and cleared for the next frame in one pass over the samples.
        const auto resolveStart = std::chrono::steady_clock::now();
        ctx.forRows(out.height(), [&](int y0, int y1) {
            resolveAndClearMsaaRows(ctx.msaa, out, y0, y1, clearColour, FrameBuffer::kFarDepth, linear);
        });
        ctx.stats.resolveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - resolveStart).count();
        ctx.msaa.markCleared(clearColour, FrameBuffer::kFarDepth);
        return true;
    }
    if (!supersample || !ctx.supersampleTarget.resize(out.width() * factor, out.height() * factor)) {
        if (!ctx.supersampleTarget.empty()) ctx.supersampleTarget = FrameBuffer{}; // no SSAA: give the sample memory back
        if (!ctx.msaa.empty()) ctx.msaa.release();
        RenderSettings plain = settings;
        plain.antiAliasing = AntiAliasing::none(); // drawn at the output size (also what the wireframe width follows)
        ctx.clearTarget(clearColour, FrameBuffer::kFarDepth);
        renderScene(ctx, scene, view, plain, textureOverride);
        if (aa.postFiltered() && !out.empty() && settings.stopAfter == PipelineStop::Fill) {
            const auto filterStart = std::chrono::steady_clock::now();
            ctx.fxaa.resize(out.width(), out.height(), ctx.threads());
            ctx.forRows(out.height(), [&](int y0, int y1) { fxaaPrepareRows(out, ctx.fxaa, y0, y1, settings.isa); });
            ctx.forBands(out.height(), [&](int band, int y0, int y1) { fxaaFilterRows(ctx.fxaa, out, band, y0, y1, settings.isa); });
            ctx.forBands(out.height(), [&](int band, int, int) { fxaaWriteBand(ctx.fxaa, out, band); });
            ctx.stats.resolveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - filterStart).count();
        }
        if (!aa.postFiltered() && !ctx.fxaa.luma.empty()) ctx.fxaa = FxaaScratch{}; // its memory only while on
        return (factor <= 1 && !multisample) || out.empty();
    }
    // The same view: clip space does not depend on the target size, only the viewport does.
    ctx.setTarget(ctx.supersampleTarget);
    ctx.clearTarget(clearColour, FrameBuffer::kFarDepth);
    renderScene(ctx, scene, view, settings, textureOverride);
    ctx.setTarget(out);
    const auto resolveStart = std::chrono::steady_clock::now();
    ctx.forRows(out.height(), [&](int y0, int y1) { resolveBoxRows(ctx.supersampleTarget, factor, out, y0, y1, linear); });
    ctx.stats.resolveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - resolveStart).count();
    return true;
}

} // namespace sr
