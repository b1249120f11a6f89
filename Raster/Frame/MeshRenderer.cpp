// drawMesh(): the program for the shading mode and material, and its span kernel, chosen once per draw.
#include "Raster/Frame/MeshRenderer.hpp"

#include <cmath>
#include <memory>
#include <optional>
#include <type_traits>

#include "Raster/Fill/Kernels/KernelTable.hpp"
#include "Raster/Fill/Occlusion.hpp"
#include "Raster/Pipeline.hpp"
#include "Raster/Shade/MeshPrograms.hpp"
#include "Raster/Shade/PbrProgram.hpp"

namespace sr {
namespace {

using programs::DrawContext;
using programs::FlatProgram;
using programs::GouraudProgram;
using programs::PbrProgram;
using programs::PhongProgram;
using programs::UnlitProgram;

// A scalar program plus the span kernel chosen for this draw (null: the scalar loop fills).
template <class Base>
struct KernelProgram : Base {
    FillKernel<Base> kernel = nullptr;
    ShadeRunsKernel<Base> runsKernel = nullptr;
    FlushKernel<Base> flushKernel = nullptr;
    bool depthTested = false; // the draw's test is `z > stored`: a hidden triangle may be skipped
    bool fillKernel(const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, std::uint64_t& shaded) const {
        if (!kernel) return false;
        // Nothing of a triangle the stored depths hide would pass (Occlusion.hpp). The scalar loop,
        // the kernels' reference, fills every triangle.
        if (depthTested && occlusionCandidate(t) && hiddenInFrame(t, fb, s)) return true;
        kernel(*this, t, fb, s, shaded);
        return true;
    }
    void flushFill(FrameBuffer& fb) const {
        if (flushKernel) flushKernel(*this, fb);
    }
    RunShading shadeRuns(const TriangleSetup& t, FrameBuffer& fb, const SpanRun* runs, int count,
                         const SampleWrite& write) const {
        if (!runsKernel) return RunShading::NotDone;
        return runsKernel(*this, t, fb, runs, count, write) ? RunShading::IntoSamples : RunShading::IntoRows;
    }
};

// The vector kernels evaluate shininessPow's whole-number exponentiation only (per pixel, in
// Phong; flat and Gouraud light per triangle / vertex in the scalar program). A surface without
// a specular term raises nothing to a power.
bool kernelsCoverSpecular(const Specular& s) {
    return !s.on() || (s.shininess <= 1024.0f && s.shininess == float(int(s.shininess)));
}

// Whether the span kernels cover the draw's material: a pbr material with a part they do not
// evaluate (kKernelLobes) is filled by the scalar program.
template <class Program>
bool kernelsCoverLobes(const DrawContext& d) {
    if constexpr (Program::kMode == ShadingMode::Pbr) return (programs::pbrLobesOf(*d.material) & ~kKernelLobes) == 0;
    else return true;
}

// Whether a program reads each map at its own address (PbrProgram's kAddressed): no span kernel
// has it, and its uvs are not rebased (a shift by whole periods of the raw set is not one of the
// transformed uvs).
template <class Program, class = void>
struct AddressedMaps : std::false_type {};
template <class Program>
struct AddressedMaps<Program, std::void_t<decltype(Program::kAddressedMaps)>> : std::bool_constant<Program::kAddressedMaps> {};

template <class Program>
void drawWith(RenderContext& ctx, const DrawContext& d, std::size_t indexCount, Program program) {
    DrawState state = programs::drawStateFor(d);
    if constexpr (AddressedMaps<Program>::value) state.rebase = {};
    KernelProgram<Program> withKernel{program};
    // Phong kernels test the shadow maps per pixel as the scalar program does (Kernels.inl's
    // shadowVisibility); flat and Gouraud light per triangle / vertex, unshadowed (Shadow.hpp).
    if constexpr (AddressedMaps<Program>::value) {
    } else if ((Program::kMode != ShadingMode::Phong || kernelsCoverSpecular(d.specular)) && kernelsCoverLobes<Program>(d)) {
        const KernelKey key{state.depth, state.perspective, d.settings.filter, d.settings.wrap};
        withKernel.kernel = selectFillKernel<Program>(d.settings.isa, key);
        withKernel.runsKernel = selectShadeRunsKernel<Program>(d.settings.isa, key);
        withKernel.flushKernel = selectFlushKernel<Program>(d.settings.isa, key);
        // (Mesh draws test depth with `z > stored`, which the check needs; the stencil path, GEQUAL, never reaches it.)
        withKernel.depthTested = state.depth != DepthMode::Off && !state.depthEqualPasses;
    }
    // The programs' vertex() reads the mesh, the view and (Gouraud) the specular constants, which
    // it names in vertexVariant(): draws of one mesh share their vertex stage inside a
    // VertexReuseScope (renderScene) when those agree. A placed draw (an instance) shares none:
    // its vertices are its place's.
    drawProgram<Program::kVaryings>(ctx, state, d.mesh.vertexCount(), d.indices, indexCount, withKernel,
                                    d.placement ? nullptr : &d.mesh);
}

template <bool kTextured>
void drawShaded(RenderContext& ctx, const DrawContext& d, ShadingMode mode, std::size_t indexCount) {
    switch (mode) {
    case ShadingMode::Unlit: // a glTF material's base colour times its vertex colours (COLOR_0), where the mesh has them
        if (d.material && d.material->pbr && d.mesh.hasColours())
            drawWith(ctx, d, indexCount, UnlitProgram<kTextured, true>(&d, programs::encode(d, d.kd)));
        else drawWith(ctx, d, indexCount, UnlitProgram<kTextured>(&d, programs::encode(d, d.kd)));
        break;
    case ShadingMode::Flat: drawWith(ctx, d, indexCount, FlatProgram<kTextured>(&d)); break;
    case ShadingMode::Gouraud:
        if (d.whiteLights) drawWith(ctx, d, indexCount, GouraudProgram<kTextured>(&d));
        else drawWith(ctx, d, indexCount, GouraudProgram<kTextured, true>(&d)); // RGB terms: six varyings
        break;
    case ShadingMode::Phong:
    case ShadingMode::Pbr: // a draw without a glTF material (drawMesh): Phong
        if (programs::phongReadsPosition(d)) drawWith(ctx, d, indexCount, PhongProgram<kTextured>(&d));
        else drawWith(ctx, d, indexCount, PhongProgram<kTextured, true>(&d)); // normals only: three varyings fewer
        break;
    }
}

// What a draw's program points to (its DrawContext and what that refers to): on drawMesh's stack,
// or kept by the context while the draw's fill may wait (RenderContext::deferral).
struct DrawInputs final : RenderContext::Kept {
    RenderSettings settings;
    FrameView phongView;
    SurfaceMaterial material;
    std::optional<Placement> placement;
    std::optional<DrawContext> draw, pbrDraw;
};

// The pbr program for the draw's maps, with or without the mesh's vertex colours.
template <bool kMaps, bool kTangents, bool kAddressed = false>
void drawPbrWith(RenderContext& ctx, const DrawContext& d, std::size_t indexCount) {
    if (d.mesh.hasColours()) drawWith(ctx, d, indexCount, PbrProgram<kMaps, kTangents, true, kAddressed>(&d));
    else drawWith(ctx, d, indexCount, PbrProgram<kMaps, kTangents, false, kAddressed>(&d));
}

bool sameAddress(const MapAddress& a, const MapAddress& b) {
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 3; ++c)
            if (a.m[r][c] != b.m[r][c]) return false;
    return a.uvSet == b.uvSet && a.wrap == b.wrap && a.filter == b.filter;
}

// Whether the maps a draw reads (`read`) have addresses of their own: not all the address of the
// material's first map (the base colour texture, else its first slot), whose uvs and sampler
// the draw has (Mesh::uvs, SurfaceMaterial::wrap / filter).
template <class Read>
bool ownAddresses(const SurfaceMaterial& material, const Read& read) {
    const MapAddressing& a = *material.addressing;
    const MapAddress* first = material.texture ? &a.base : nullptr;
    for (const MapSlot s : kAllMapSlots)
        if (!first && material.maps.has(s)) first = &a[s];
    if (!first) return false;
    if (material.texture && !sameAddress(a.base, *first)) return true;
    for (const MapSlot s : kAllMapSlots)
        if (read(s) && !sameAddress(a[s], *first)) return true;
    return false;
}

// A glTF material under ShadingMode::Pbr: the maps it has (with uvs), the tangents its normal
// map needs (without them the map is not applied), the vertex colours where the mesh has them.
// The occlusion map scales the sky's light only: without --ibl nothing reads it.
void drawPbr(RenderContext& ctx, DrawInputs& in, std::size_t indexCount) {
    const DrawContext& base = *in.draw;
    const SurfaceMaterial& material = in.material;
    const Mesh& mesh = base.mesh;
    // KHR_materials_clearcoat's maps are read only where the material has a coat, KHR_materials_sheen's
    // only where it has a sheen.
    const unsigned lobes = programs::pbrLobesOf(material);
    const bool coat = (lobes & kLobeClearcoat) != 0, sheen = (lobes & kLobeSheen) != 0;
    const auto read = [&](MapSlot s) {
        return material.maps.has(s) && (s != MapSlot::Occlusion || base.view.ibl) && (!isClearcoatSlot(s) || coat) &&
               (!isSheenSlot(s) || sheen);
    };
    const Texture* anyMap = material.texture;
    for (const MapSlot s : kAllMapSlots)
        if (!anyMap && read(s)) anyMap = material.map(s);
    const bool maps = anyMap != nullptr && mesh.hasUvs();
    DrawContext& d = in.pbrDraw.emplace(base);
    d.texture = maps ? anyMap : nullptr; // the uv varyings' rebase (drawStateFor)
    const bool tangents = (read(MapSlot::Normal) || read(MapSlot::ClearcoatNormal)) && mesh.hasTangents();
    if (!maps) drawPbrWith<false, false>(ctx, d, indexCount);
    else if (material.addressing && mesh.hasUvSets() && ownAddresses(material, read)) {
        // Each map at its own address. With a normal map the vertex colours would make 17
        // varyings, one more than a draw interpolates: they are left out (the loader says so).
        if (tangents) drawWith(ctx, d, indexCount, PbrProgram<true, true, false, true>(&d));
        else drawPbrWith<true, false, true>(ctx, d, indexCount);
    } else if (tangents) drawPbrWith<true, true>(ctx, d, indexCount);
    else drawPbrWith<true, false>(ctx, d, indexCount);
}

} // namespace

void drawMesh(RenderContext& ctx, const FrameView& view, const RenderSettings& frameSettings, const Mesh& mesh,
              const std::uint32_t* indices, std::size_t indexCount, const SurfaceMaterial& surface,
              const Placement* placement) {
    DrawInputs local;
    DrawInputs& in = ctx.deferral.active ? ctx.keep(std::make_unique<DrawInputs>()) : local;
    in.material = surface;
    const SurfaceMaterial& material = in.material;
    const bool textured = material.texture != nullptr && mesh.hasUvs();
    // The texture's own sampler where the settings let the file choose (glTF).
    RenderSettings& settings = in.settings;
    settings = frameSettings;
    const bool mapped = mesh.hasUvs() && (material.texture != nullptr || material.maps.any());
    if (mapped && material.wrap && settings.wrapFromFile) {
        settings.wrap = material.wrap->u;
        if (material.wrap->v != material.wrap->u) settings.wrapV = material.wrap->v;
    }
    if (mapped && material.filter && settings.filterFromFile) settings.filter = *material.filter;
    ShadingMode mode = settings.shading;
    if (!mesh.hasNormals() && (mode == ShadingMode::Gouraud || mode == ShadingMode::Phong || mode == ShadingMode::Pbr))
        mode = ShadingMode::Flat;
    // A glTF material drawn unlit (KHR_materials_unlit under any shading, or --shading unlit) is
    // its base colour: the factor, times the texture (not the Blinn-Phong mapping's kd, which is
    // black for a metal).
    const bool baseColourOnly = material.pbr != nullptr && (material.pbr->unlit || mode == ShadingMode::Unlit);
    if (baseColourOnly) mode = ShadingMode::Unlit;
    const Color baseColour = material.pbr ? Color{material.pbr->baseColor.r, material.pbr->baseColor.g, material.pbr->baseColor.b, 1.0f}
                                          : material.kd;
    const bool pbr = mode == ShadingMode::Pbr && material.pbr != nullptr;
    // The Blinn-Phong models see physical lights divided by pi (Lighting::physical): the frame's
    // copy of the view with those lights, or one made here.
    const FrameView* v = &view;
    if (!pbr && view.lighting.physical) {
        if (view.blinnPhong) {
            v = view.blinnPhong;
        } else {
            in.phongView = view;
            in.phongView.lighting = blinnPhongLighting(view.lighting);
            v = &in.phongView;
        }
    }
    DrawContext& d = in.draw.emplace(DrawContext{*v, settings, mesh, indices, textured ? material.texture : nullptr,
                                                 baseColourOnly ? baseColour : textured ? material.tint : material.kd, material.specular,
                                                 material.alpha, v->lighting.whiteDirectional(), material.doubleSided,
                                                 activeTexelAlpha(material, mesh)});
    d.linear = settings.colour == ColorMode::Linear;
    d.exposureScale = std::exp2(settings.exposure);
    d.material = &material;
    if (placement) d.placement = &in.placement.emplace(*placement);
    if (pbr) drawPbr(ctx, in, indexCount);
    else if (textured) drawShaded<true>(ctx, d, mode, indexCount);
    else drawShaded<false>(ctx, d, mode, indexCount);
}

} // namespace sr
