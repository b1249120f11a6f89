// A deliberately general scene renderer (one pipeline for every mode, branching per pixel): the baseline drawMesh's specialised pipelines are tested and timed against.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>

#include "Raster/Frame/RenderScene.hpp"
#include "Raster/Frame/RenderSettings.hpp"
#include "Raster/Pipeline.hpp"
#include "Raster/Texture/TextureLod.hpp"

namespace sr::test {

// What a naive renderer does: the vertex shader always produces everything any mode could need
// (uv, world position, normal, and the per-vertex Blinn-Phong terms per channel), the span loop
// always interpolates all 14 varyings, and the fragment shader branches on the shading mode and
// on "textured" at every pixel; the lighting is always lightTerms (RGB, any lights). Flat shading
// keeps the face normal and centroid per triangle (as drawMesh does) but evaluates the lighting
// per pixel. The arithmetic of each mode is the same as drawMesh's (whose one-number terms for
// white directional lights equal lightTerms' channels bit for bit), so the two produce the same
// image; only the amount of work differs. Opaque draws only (transparency: TransparencyTests).
// Varyings: uv 0-1, world position 2-4, normal 5-7, Gouraud diffuse r, g, b and specular r, g, b
// 8-13 (drawMesh's Phong pipeline interpolates 6 or 8 of them, Gouraud 2, 4, 6 or 8, flat and
// unlit 0 or 2).
inline constexpr int kGeneralVaryings = 14;

inline Vec3 generalFaceNormal(Vec3 p0, Vec3 p1, Vec3 p2) {
    const double ax = double(p1.x) - p0.x, ay = double(p1.y) - p0.y, az = double(p1.z) - p0.z;
    const double bx = double(p2.x) - p0.x, by = double(p2.y) - p0.y, bz = double(p2.z) - p0.z;
    const double nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0.0) || !std::isfinite(len)) return {0.0f, 0.0f, 1.0f};
    return {float(nx / len), float(ny / len), float(nz / len)};
}

inline void drawMeshGeneral(RenderContext& ctx, const FrameView& view, const RenderSettings& settings, const Mesh& mesh,
                            const std::uint32_t* indices, std::size_t indexCount, const SurfaceMaterial& material) {
    const bool textured = material.texture != nullptr && mesh.hasUvs();
    const bool hasNormals = mesh.hasNormals();
    ShadingMode mode = settings.shading;
    if (!hasNormals && (mode == ShadingMode::Gouraud || mode == ShadingMode::Phong)) mode = ShadingMode::Flat;
    DrawState state;
    state.cull = settings.cull;
    state.clipFar = view.finiteFar;
    state.wireframe = settings.wireframe;
    state.perspective = settings.perspective;
    if (textured) state.rebase = {2, wrapPeriod(settings.wrap)}; // varyings 0-1 are the uv
    const TriangleSetup* setup = nullptr;
    Vec3 faceN{0, 0, 1}, centroid{0, 0, 0};
    drawIndexed<kGeneralVaryings>(
        ctx, state, mesh.vertexCount(), indices, indexCount,
        [&](std::size_t i, ClipVertex& out) {
            const Vec3 p = mesh.positions[i];
            const Vec3 n = hasNormals ? mesh.normals[i] : Vec3{0, 0, 1};
            const Vec2 uv = mesh.hasUvs() ? mesh.uvs[i] : Vec2{0, 0};
            out.position = view.viewProj * Vec4(p, 1.0f);
            const RgbTerms t = lightTerms(view.lighting, material.specular, normalize(n), p, normalize(view.eye - p));
            const float v[kGeneralVaryings] = {uv.x,          uv.y,           p.x,            p.y,          p.z,
                                               n.x,           n.y,            n.z,            t.diffuse.r,  t.diffuse.g,
                                               t.diffuse.b,   t.specular.r,   t.specular.g,   t.specular.b};
            for (int k = 0; k < kGeneralVaryings; ++k) out.varyings[std::size_t(k)] = v[k];
        },
        [&](std::size_t t, const TriangleSetup& s) {
            setup = &s;
            const Vec3 p0 = mesh.positions[indices[3 * t]], p1 = mesh.positions[indices[3 * t + 1]],
                       p2 = mesh.positions[indices[3 * t + 2]];
            faceN = generalFaceNormal(p0, p1, p2);
            centroid = (p0 + p1 + p2) / 3.0f;
        },
        [&](const Fragment<kGeneralVaryings>& f) {
            Color kd = material.kd;
            const Color ks = material.specular.ks;
            if (textured) {
                const Vec2 uv{f.varyings[0], f.varyings[1]};
                float lod = 0.0f;
                if (settings.filter == TextureFilter::Trilinear) {
                    const UvDerivatives g =
                        settings.perspective == PerspectiveMode::Affine
                            ? UvDerivatives{float(setup->ddx[kPlaneVarying0]), float(setup->ddx[kPlaneVarying0 + 1]),
                                            float(setup->ddy[kPlaneVarying0]), float(setup->ddy[kPlaneVarying0 + 1])}
                            : uvDerivatives(*setup, kPlaneVarying0, kPlaneVarying0 + 1, f.invW, uv.x, uv.y);
                    lod = mipLevel(g, material.texture->width(), material.texture->height());
                }
                const Color texel = material.texture->sample(uv, lod, settings.filter, settings.wrap);
                kd = {material.tint.r * texel.r, material.tint.g * texel.g, material.tint.b * texel.b, 1.0f};
            }
            switch (mode) {
            case ShadingMode::Unlit: return packBgra8(kd);
            case ShadingMode::Flat:
                return packBgra8(
                    applyTerms(kd, ks, lightTerms(view.lighting, material.specular, faceN, centroid, normalize(view.eye - centroid))));
            case ShadingMode::Gouraud:
                return packBgra8(applyTerms(kd, ks,
                                            RgbTerms{{f.varyings[8], f.varyings[9], f.varyings[10], 1.0f},
                                                     {f.varyings[11], f.varyings[12], f.varyings[13], 1.0f}}));
            case ShadingMode::Phong:
            case ShadingMode::Pbr: { // no glTF material here: drawn as Phong, as drawMesh does
                const Vec3 p{f.varyings[2], f.varyings[3], f.varyings[4]};
                const Vec3 n = normalize(Vec3{f.varyings[5], f.varyings[6], f.varyings[7]});
                return packBgra8(applyTerms(kd, ks, lightTerms(view.lighting, material.specular, n, p, normalize(view.eye - p))));
            }
            }
            return packBgra8(kd);
        });
}

// renderScene() through drawMeshGeneral (same draw order, materials and texture override), for
// scenes without transparent draws (opaqueOnly removes them).
inline void renderSceneGeneral(RenderContext& ctx, const Scene& scene, const FrameView& view,
                               const RenderSettings& settings, const Texture* textureOverride = nullptr) {
    for (const SceneDraw& d : scene.draws) {
        assert(d.alpha >= 1.0f && !d.placement);
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        SurfaceMaterial material;
        material.kd = d.kd;
        material.tint = d.tint;
        material.specular = d.specular;
        if (textureOverride) material.texture = textureOverride;
        else if (d.texture >= 0) material.texture = &scene.textures[std::size_t(d.texture)];
        drawMeshGeneral(ctx, view, settings, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, material);
    }
}

// The scene without its transparent draws.
inline Scene opaqueOnly(Scene scene) {
    scene.draws.erase(std::remove_if(scene.draws.begin(), scene.draws.end(), [](const SceneDraw& d) { return d.alpha < 1.0f; }),
                      scene.draws.end());
    return scene;
}

} // namespace sr::test
