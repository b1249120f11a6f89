// The run-time quality and mode knobs of a frame, and the per-frame view they render with.
#pragma once

#include <optional>

#include "Math/Mat4.hpp"
#include "Raster/Fill/Blend.hpp" // TexelAlpha
#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Fill/Stencil.hpp"
#include "Raster/Frame/AntiAliasing.hpp"
#include "Raster/Frame/Sky.hpp" // ViewRays
#include "Raster/Geometry/Cull.hpp"
#include "Raster/Setup/PipelineModes.hpp" // PerspectiveMode, PipelineStop
#include "Raster/Shade/ColorSpace.hpp" // ColorMode, ToneMap
#include "Raster/Shade/MaterialMaps.hpp"
#include "Raster/Shade/Shading.hpp"
#include "Raster/Shade/Shadow.hpp"
#include "Raster/Texture/Texture.hpp"

namespace sr {

struct PbrFactors; // Brdf.hpp
class ImageLight; // Ibl.hpp

// A selection outline (what the stencil buffer serves): after the opaque draws, scene draw
// `draw` (an opaque one) is drawn again without colour and with the GEQUAL depth test, marking 1
// in the stencil buffer (the Replace operation) the pixels where it is what is visible; after
// everything else, every pixel not marked within `width` output pixels (horizontally and
// vertically: a square neighbourhood) of a marked one takes `colour`: a band around what shows
// of the object, over everything. Not drawn multisampled (the stencil buffer is per pixel) nor
// in partial pipelines. draw < 0: off, and no stencil buffer is allocated.
struct Outline {
    int draw = -1;
    Color colour{1.0f, 0.78f, 0.1f, 1.0f};
    float width = 3.0f;
    // The demo's and the headless command's --outline: app::renderFrame sets `draw` each frame to
    // the draw at the image centre (pickDraw, Scene.hpp); renderScene reads only `draw`.
    bool pickCentre = false;
    bool on() const { return draw >= 0; }
};

struct RenderSettings {
    ShadingMode shading = ShadingMode::Phong;
    CullMode cull = CullMode::None;
    TextureFilter filter = TextureFilter::Bilinear;
    WrapMode wrap = WrapMode::Repeat;
    // A draw's wrap along v where it differs from `wrap` (a glTF sampler's wrapT apart from its
    // wrapS, set by drawMesh); unset: `wrap` on both axes (wrapModesOf).
    std::optional<WrapMode> wrapV;
    PerspectiveMode perspective = PerspectiveMode::Exact;
    // Anisotropic filtering: at most this many trilinear taps along a pixel's footprint
    // (1, 2, 4, 8 or 16; TextureLod.hpp's sampleAnisotropic). Only with the trilinear filter and
    // exact perspective; 1: plain trilinear.
    int aniso = 1;
    bool wireframe = false; // overlay triangle edges (DDA lines) on the shaded image
    PipelineStop stopAfter = PipelineStop::Fill; // partial pipelines, for per-stage timing only
    Isa isa = bestIsa(); // which span kernels fill (Raster/Fill/Kernels/Isa.hpp); Scalar = the reference loop
    AntiAliasing antiAliasing; // one sample, SSAA 4 / 16 or MSAA 2 / 4 / 8 (AntiAliasing.hpp)
    // A material's own sampler (SurfaceMaterial::wrap / filter, from a glTF file) overrides
    // `wrap` / `filter` for its draw while these are true; false once the user chose them
    // (--wrap, --filter, the demo's T key, the report's sweep).
    bool wrapFromFile = true, filterFromFile = true;
    // A selection outline around one opaque draw of the scene (Outline above; renderScene).
    Outline outline;
    // Shadow maps for the directional and spot lights (Raster/Shade/Shadow.hpp); off: none made.
    ShadowSettings shadows;
    // Per-draw fixed-function state that renderScene sets for its own passes (the outline's
    // mark): the stencil test and operations (DrawState::stencil), the colour write turned off
    // and the GEQUAL depth test (DrawState::colourWrite, depthEqualPasses: the stencil path only).
    StencilState stencil;
    bool colourWrite = true, depthEqualPasses = false;
    // Colour arithmetic (ColorSpace.hpp): Gamma on display values, Linear in linear light with
    // the result tone-mapped (toneMap, at 2^exposure) and sRGB-encoded, by the span kernels as
    // by the scalar programs.
    ColorMode colour = ColorMode::Gamma;
    ToneMap toneMap = ToneMap::None;
    float exposure = 0.0f; // EV: the linear colour is scaled by 2^exposure before tone mapping
};

// The draw's wrap along u and v.
inline WrapModes wrapModesOf(const RenderSettings& s) { return {s.wrap, s.wrapV.value_or(s.wrap)}; }

// What every draw of one frame shares.
struct FrameView {
    Mat4 viewProj;          // world -> clip (reversed-Z)
    Vec3 eye;               // world-space camera position (for the view vector)
    bool finiteFar = true;  // the projection has a far plane to clip against
    Lighting lighting;
    ViewRays rays;          // the eye ray through each image point (the sky; Sky.hpp)
    // This frame's shadow maps (renderSceneFrame sets it when RenderSettings::shadows is on;
    // Phong-shaded draws then test each fragment against them, Shadow.hpp). Null: no shadows.
    const SceneShadows* shadows = nullptr;
    // Light from the sky (Ibl.hpp: --ibl), read by the pbr model only. Null: none.
    const ImageLight* ibl = nullptr;
    // With physical lights: this view with the lights as the Blinn-Phong models see them
    // (blinnPhongLighting), made once per frame by renderSceneFrame for the draws not shaded pbr.
    // Null: drawMesh makes it for the draw.
    const FrameView* blinnPhong = nullptr;
};

// The surface of one draw: a texture (used when the mesh has uvs) times `tint`, or the flat
// colour kd; and its specular constants.
struct SurfaceMaterial {
    const Texture* texture = nullptr;
    Color kd{0.8f, 0.8f, 0.8f, 1.0f};   // untextured colour
    Color tint{1.0f, 1.0f, 1.0f, 1.0f}; // multiplies the texel when textured (MTL Kd; 1: the texel alone)
    Specular specular;
    float alpha = 1.0f; // opacity; below 1 the draw is blended "over" what is behind it (Blend.hpp)
    // Per-fragment alpha from the texture (glTF MASK / BLEND), used when the texture has alpha
    // (activeTexelAlpha, MeshRenderer.hpp); its factor then replaces `alpha`.
    TexelAlpha texelAlpha;
    bool doubleSided = true; // false: back faces (clockwise on screen) are culled whatever RenderSettings::cull says
    // The texture's own sampler (glTF), where it says: the draw's wrap and filter when the
    // settings let the file choose (RenderSettings::wrapFromFile / filterFromFile).
    std::optional<WrapModes> wrap;
    std::optional<TextureFilter> filter;
    // A glTF material's metallic-roughness input (the pbr shading model's; null for OBJ/MTL and
    // the built-in scene) and its other maps (null: none; used when the mesh has uvs).
    const PbrFactors* pbr = nullptr;
    MaterialMaps<const Texture*> maps;
    const Texture* map(MapSlot slot) const { return maps[slot]; }
    // Each map's uv set, transform and sampler, where they are not one for all (the pbr program
    // then reads Mesh::uvSets); null: every map reads the draw's uvs under its wrap and filter.
    const MapAddressing* addressing = nullptr;
};

} // namespace sr
