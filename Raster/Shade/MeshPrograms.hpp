// The scalar mesh programs (unlit, flat, Gouraud, Phong x textured): the reference twins of the kernels.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "Raster/Fill/ScanlineFill.hpp"
#include "Raster/Frame/RenderSettings.hpp"
#include "Raster/Geometry/Mesh.hpp"
#include "Raster/Geometry/Placement.hpp"
#include "Raster/Pipeline.hpp" // DrawState
#include "Raster/Texture/TextureLod.hpp"

// drawProgram's Programs for drawMesh (MeshRenderer.cpp): vertex(), triangle() and the per-pixel
// fragment(), the readable reference that every SIMD kernel (Raster/Fill/Kernels/Kernels.inl) is
// tested bit-identical against. The kernels read a program's per-draw and per-triangle state
// (d, setup, terms, flat) and call fragment() for the rare lanes they do not handle.
namespace sr::programs {

// Face normal of triangle (p0, p1, p2): normalize((p1 - p0) x (p2 - p0)) in double, as the
// reference renderer computes it; not flipped toward the viewer. Zero area -> (0, 0, 1).
inline Vec3 faceNormal(Vec3 p0, Vec3 p1, Vec3 p2) {
    const double ax = double(p1.x) - p0.x, ay = double(p1.y) - p0.y, az = double(p1.z) - p0.z;
    const double bx = double(p2.x) - p0.x, by = double(p2.y) - p0.y, bz = double(p2.z) - p0.z;
    const double nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0.0) || !std::isfinite(len)) return {0.0f, 0.0f, 1.0f};
    return {float(nx / len), float(ny / len), float(nz / len)};
}

// The state every specialised pipeline shares; one instance per drawMesh call.
struct DrawContext {
    const FrameView& view;
    const RenderSettings& settings;
    const Mesh& mesh;
    const std::uint32_t* indices;
    const Texture* texture; // non-null only when the draw is textured
    Color kd;               // the surface colour; when textured, the texel's multiplier (tint)
    Specular specular;
    float alpha;            // opacity: below 1 the draw is blended over the target (DrawState::blendAlpha)
    bool whiteLights;       // view.lighting.whiteDirectional(): one-number terms (blinnPhong), else RGB (lightTerms)
    bool doubleSided = true; // false: the draw's back faces are culled whatever settings.cull says
    TexelAlpha texelAlpha;   // on only for a textured draw whose texture has alpha (activeTexelAlpha)
    // ColorMode::Linear: texels decoded from sRGB, the colour encoded (encode below).
    bool linear = false;
    float exposureScale = 1.0f;                 // 2^settings.exposure (linear only)
    const SurfaceMaterial* material = nullptr;  // the pbr program's maps and factors
    const Placement* placement = nullptr;       // the mesh drawn as an instance: its place (null: in world space)
};

// A vertex's world-space position, normal and tangent: the mesh's own, or placed (Placement.hpp).
inline Vec3 worldPosition(const DrawContext& d, std::size_t i) {
    return d.placement ? d.placement->position(d.mesh.positions[i]) : d.mesh.positions[i];
}
inline Vec3 worldNormal(const DrawContext& d, std::size_t i) {
    return d.placement ? d.placement->normal(d.mesh.normals[i]) : d.mesh.normals[i];
}
inline Vec4 worldTangent(const DrawContext& d, std::size_t i) {
    return d.placement ? d.placement->tangent(d.mesh.tangents[i]) : d.mesh.tangents[i];
}

// The stored pixel of a shaded colour: on display values as it is (packBgra8); in linear light
// tone-mapped and sRGB-encoded (packLinearBgra8).
inline Pixel encode(const DrawContext& d, Color c) {
    return d.linear ? packLinearBgra8(c, d.settings.toneMap, d.exposureScale) : packBgra8(c);
}

// Whether a Phong draw's shading reads the fragment's position: for the direction to the eye
// (a specular term), to point and spot lights, or for the shadow maps. When it does not,
// drawMesh draws it with PhongProgram<kTextured, true>, whose fragments carry no position.
inline bool phongReadsPosition(const DrawContext& d) { return !d.whiteLights || d.view.shadows || d.specular.on(); }

// The lighting terms at world point p with unit normal n and unit view vector v, per channel:
// blinnPhong's one-number terms when every light is white and directional (the same floats as
// lightTerms would give, computed with less work), else lightTerms.
inline RgbTerms litTerms(const DrawContext& d, Vec3 n, Vec3 p, Vec3 v) {
    if (d.whiteLights) return RgbTerms::grey(blinnPhong(d.view.lighting, d.specular, n, v));
    return lightTerms(d.view.lighting, d.specular, n, p, v);
}

// The filtered texel of `texture` at a fragment whose varyings 0 and 1 are (u, v), its colour
// decoded from sRGB when `decode` (linear light). Trilinear filtering needs the screen-space uv
// derivatives, taken analytically from the triangle's planes (no quad shading), and the level of
// detail is the texture's own (its size).
template <int kVaryings>
inline Color sampleTextureAt(const DrawContext& d, const TriangleSetup* setup, const Fragment<kVaryings>& f,
                             const Texture& texture, bool decode) {
    const Vec2 uv{f.varyings[0], f.varyings[1]};
    float lod = 0.0f;
    if (d.settings.filter == TextureFilter::Trilinear) {
        constexpr int kU = kPlaneVarying0, kV = kPlaneVarying0 + 1;
        const bool affine = d.settings.perspective == PerspectiveMode::Affine;
        const UvDerivatives g = affine ? UvDerivatives{float(setup->ddx[kU]), float(setup->ddx[kV]), float(setup->ddy[kU]),
                                                       float(setup->ddy[kV])}
                                       : uvDerivatives(*setup, kU, kV, f.invW, uv.x, uv.y);
        if (d.settings.aniso > 1 && !affine) return sampleAnisotropic(texture, uv, g, d.settings.aniso, wrapModesOf(d.settings), decode);
        lod = mipLevel(g.dudx, g.dvdx, g.dudy, g.dvdy, texture.width(), texture.height());
    }
    return decode ? texture.sampleSrgb(uv, lod, d.settings.filter, wrapModesOf(d.settings))
                  : texture.sample(uv, lod, d.settings.filter, wrapModesOf(d.settings));
}

// sampleTextureAt for a map with its own address (MapAddress): its uv set in varyings 2 s and
// 2 s + 1 through its transform, its sampler's wrap on each axis and its filter (the draw's
// where the settings do not let the file choose, or the sampler names none), its level of detail
// from that set's derivatives through the transform's linear part (the chain rule: the transform
// is affine, so the transformed uv interpolates as the raw one does).
template <int kVaryings>
inline Color sampleAddressedAt(const DrawContext& d, const TriangleSetup* setup, const Fragment<kVaryings>& f, const Texture& texture,
                               bool decode, const MapAddress& a) {
    const int s = a.uvSet;
    const Vec2 raw{f.varyings[2 * s], f.varyings[2 * s + 1]};
    const Vec2 uv = a.apply(raw);
    const WrapModes wrap = d.settings.wrapFromFile ? a.wrap : wrapModesOf(d.settings);
    const TextureFilter filter = d.settings.filterFromFile && a.filter ? *a.filter : d.settings.filter;
    float lod = 0.0f;
    if (filter == TextureFilter::Trilinear) {
        const int kU = kPlaneVarying0 + 2 * s, kV = kU + 1;
        const bool affine = d.settings.perspective == PerspectiveMode::Affine;
        const UvDerivatives g = affine ? UvDerivatives{float(setup->ddx[kU]), float(setup->ddx[kV]), float(setup->ddy[kU]),
                                                       float(setup->ddy[kV])}
                                       : uvDerivatives(*setup, kU, kV, f.invW, raw.x, raw.y);
        const UvDerivatives t{a.m[0][0] * g.dudx + a.m[0][1] * g.dvdx, a.m[1][0] * g.dudx + a.m[1][1] * g.dvdx,
                              a.m[0][0] * g.dudy + a.m[0][1] * g.dvdy, a.m[1][0] * g.dudy + a.m[1][1] * g.dvdy};
        if (d.settings.aniso > 1 && !affine) return sampleAnisotropic(texture, uv, t, d.settings.aniso, wrap, decode);
        lod = mipLevel(t.dudx, t.dvdx, t.dudy, t.dvdy, texture.width(), texture.height());
    }
    return decode ? texture.sampleSrgb(uv, lod, filter, wrap) : texture.sample(uv, lod, filter, wrap);
}

// The draw's texture (a colour map: decoded in linear light).
template <int kVaryings>
inline Color sampleTexel(const DrawContext& d, const TriangleSetup* setup, const Fragment<kVaryings>& f) {
    return sampleTextureAt(d, setup, f, *d.texture, d.linear);
}

// Diffuse colour at a textured fragment: the texel times the draw's kd (the reference's
// uKd * texture(uTex, vUV); kd 1 leaves the texel as it is).
template <int kVaryings>
inline Color sampleKd(const DrawContext& d, const TriangleSetup* setup, const Fragment<kVaryings>& f) {
    const Color texel = sampleTexel(d, setup, f);
    return {d.kd.r * texel.r, d.kd.g * texel.g, d.kd.b * texel.b, 1.0f};
}

inline DrawState drawStateFor(const DrawContext& d) {
    DrawState s;
    s.cull = d.doubleSided ? d.settings.cull : CullMode::CW; // single-sided: back faces (CW on screen) culled
    s.clipFar = d.view.finiteFar;
    s.wireframe = d.settings.wireframe;
    s.wireWidth = d.settings.antiAliasing.gridSide();
    s.stopAfter = d.settings.stopAfter;
    s.perspective = d.settings.perspective;
    s.isa = d.settings.isa;
    if (d.texture != nullptr) { // varyings 0-1 are the uv: a shift by a period of both axes' modes (none if one clamps)
        const WrapModes w = wrapModesOf(d.settings);
        const double pu = wrapPeriod(w.u), pv = wrapPeriod(w.v);
        s.rebase = {2, pu > 0.0 && pv > 0.0 ? std::max(pu, pv) : 0.0};
    }
    if (d.texelAlpha.on()) {
        // Per-fragment alpha (Pipeline.hpp: the fill tests depth, the fragment decides): Blend
        // never writes depth, Mask writes it for the fragments it keeps.
        s.texelAlpha = d.texelAlpha;
        s.depth = DepthMode::Test;
    } else if (d.alpha < 1.0f) { // transparent: tested against the depth buffer, never written to it
        s.blendAlpha = std::max(d.alpha, 0.0f);
        s.depth = DepthMode::Test;
    }
    s.linearBlend = d.linear;
    s.texelAlpha.linear = d.linear;
    s.stencil = d.settings.stencil;
    s.colourWrite = d.settings.colourWrite;
    s.depthEqualPasses = d.settings.depthEqualPasses;
    return s;
}

// Writes the clip position of vertex i at world position p and, when textured, the uv into
// varyings 0-1.
template <bool kTextured>
inline void transformVertex(const DrawContext& d, std::size_t i, Vec3 p, ClipVertex& out) {
    out.position = d.view.viewProj * Vec4(p, 1.0f);
    if constexpr (kTextured) {
        out.varyings[0] = d.mesh.uvs[i].x;
        out.varyings[1] = d.mesh.uvs[i].y;
    }
}
template <bool kTextured>
inline void transformVertex(const DrawContext& d, std::size_t i, ClipVertex& out) {
    transformVertex<kTextured>(d, i, worldPosition(d, i), out);
}

// The four shading programs (drawProgram's Program: vertex, triangle, fragment). Each render
// thread works on its own copy, so the per-triangle state (setup, terms) lives in the object.
// Unlit: kd (times the texel when textured); with kColours also times the vertex colour's RGB
// (a glTF material's COLOR_0), in varyings kC..kC+2 after the uv.
template <bool kTextured, bool kColours = false>
struct UnlitProgram {
    static constexpr ShadingMode kMode = ShadingMode::Unlit;
    static constexpr bool kIsTextured = kTextured;
    static constexpr bool kVertexColours = kColours;
    static constexpr int kC = kTextured ? 2 : 0;
    static constexpr int kVaryings = kC + (kColours ? 3 : 0);
    const DrawContext* d;
    Pixel flat;
    const TriangleSetup* setup = nullptr;
    UnlitProgram(const DrawContext* dc, Pixel colour) : d(dc), flat(colour) {}
    void vertex(std::size_t i, ClipVertex& out) const {
        transformVertex<kTextured>(*d, i, out);
        if constexpr (kColours) {
            const Color c = d->mesh.colours[i];
            out.varyings[kC] = c.r;
            out.varyings[kC + 1] = c.g;
            out.varyings[kC + 2] = c.b;
        }
    }
    void triangle(std::size_t, const TriangleSetup& s) { setup = &s; }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        if constexpr (kColours) {
            Color c = d->kd;
            if constexpr (kTextured) c = sampleKd(*d, setup, f);
            return encode(*d, Color{c.r * f.varyings[kC], c.g * f.varyings[kC + 1], c.b * f.varyings[kC + 2], 1.0f});
        } else if constexpr (kTextured) {
            return encode(*d, sampleKd(*d, setup, f));
        } else {
            return flat;
        }
    }
    template <bool kT = kTextured, std::enable_if_t<kT, int> = 0> // textured programs only (HasFragmentAlpha)
    float fragmentAlpha(const Fragment<kVaryings>& f) const { return sampleTexel(*d, setup, f).a; }
};

// Flat: lit ONCE per triangle (face normal, view vector at the centroid), lazily: triangle()
// only notes the triangle, and the lighting runs when its first fragment passes the depth test
// (ensureLit, from fragment() or the kernel), so a triangle hidden behind others, or facing away
// in a scene drawn without culling, costs no lighting. Same values as lighting in triangle().
// The lazy state is per program copy: every render lane has its own.
template <bool kTextured>
struct FlatProgram {
    static constexpr ShadingMode kMode = ShadingMode::Flat;
    static constexpr bool kIsTextured = kTextured;
    static constexpr int kVaryings = kTextured ? 2 : 0;
    const DrawContext* d;
    const TriangleSetup* setup = nullptr;
    std::size_t tri = 0;
    mutable bool lit = false;
    mutable RgbTerms terms;
    mutable Pixel flat = 0;
    explicit FlatProgram(const DrawContext* dc) : d(dc) {}
    void vertex(std::size_t i, ClipVertex& out) const { transformVertex<kTextured>(*d, i, out); }
    void triangle(std::size_t t, const TriangleSetup& s) {
        setup = &s;
        tri = t;
        lit = false;
    }
    void ensureLit() const {
        if (lit) return;
        lit = true;
        const Vec3 p0 = worldPosition(*d, d->indices[3 * tri]), p1 = worldPosition(*d, d->indices[3 * tri + 1]),
                   p2 = worldPosition(*d, d->indices[3 * tri + 2]);
        const Vec3 centroid = (p0 + p1 + p2) / 3.0f;
        terms = litTerms(*d, faceNormal(p0, p1, p2), centroid, normalize(d->view.eye - centroid));
        if constexpr (!kTextured) flat = encode(*d, applyTerms(d->kd, d->specular.ks, terms));
    }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        ensureLit();
        if constexpr (kTextured) return encode(*d, applyTerms(sampleKd(*d, setup, f), d->specular.ks, terms));
        else return flat;
    }
    template <bool kT = kTextured, std::enable_if_t<kT, int> = 0> // textured programs only (HasFragmentAlpha)
    float fragmentAlpha(const Fragment<kVaryings>& f) const { return sampleTexel(*d, setup, f).a; }
};

// Gouraud: Blinn-Phong per vertex; the diffuse and specular terms are interpolated
// (perspective-correct) and combined per pixel, so a texture still modulates per pixel. With
// white directional lights only, two terms (diffuse, specular); with any other light (kRgb) six,
// one per channel (diffuse r, g, b, specular r, g, b).
template <bool kTextured, bool kRgb = false>
struct GouraudProgram {
    static constexpr ShadingMode kMode = ShadingMode::Gouraud;
    static constexpr bool kIsTextured = kTextured;
    static constexpr bool kRgbTerms = kRgb;
    static constexpr int kT = kTextured ? 2 : 0; // first varying of the lighting terms
    static constexpr int kVaryings = kT + (kRgb ? 6 : 2);
    const DrawContext* d;
    const TriangleSetup* setup = nullptr;
    explicit GouraudProgram(const DrawContext* dc) : d(dc) {}
    // vertex() depends on the specular constants besides the mesh and view: part of the vertex
    // cache's key (Pipeline.hpp), so draws of one mesh with different exponents do not share.
    std::uint64_t vertexVariant() const {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &d->specular.shininess, sizeof bits);
        return d->specular.on() ? (std::uint64_t(1) << 32) | bits : 0;
    }
    void vertex(std::size_t i, ClipVertex& out) const {
        const Vec3 p = worldPosition(*d, i);
        transformVertex<kTextured>(*d, i, p, out);
        const Vec3 n = normalize(worldNormal(*d, i)), v = normalize(d->view.eye - p);
        if constexpr (kRgb) {
            const RgbTerms t = lightTerms(d->view.lighting, d->specular, n, p, v);
            const float terms[6] = {t.diffuse.r, t.diffuse.g, t.diffuse.b, t.specular.r, t.specular.g, t.specular.b};
            for (int k = 0; k < 6; ++k) out.varyings[kT + k] = terms[k];
        } else {
            const LightTerms t = blinnPhong(d->view.lighting, d->specular, n, v);
            out.varyings[kT] = t.diffuse;
            out.varyings[kT + 1] = t.specular;
        }
    }
    void triangle(std::size_t, const TriangleSetup& s) { setup = &s; }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        Color kd = d->kd;
        if constexpr (kTextured) kd = sampleKd(*d, setup, f);
        if constexpr (kRgb) {
            const RgbTerms t{{f.varyings[kT], f.varyings[kT + 1], f.varyings[kT + 2], 1.0f},
                             {f.varyings[kT + 3], f.varyings[kT + 4], f.varyings[kT + 5], 1.0f}};
            return encode(*d, applyTerms(kd, d->specular.ks, t));
        } else {
            return encode(*d, applyTerms(kd, d->specular.ks, LightTerms{f.varyings[kT], f.varyings[kT + 1]}));
        }
    }
    template <bool kT = kTextured, std::enable_if_t<kT, int> = 0> // textured programs only (HasFragmentAlpha)
    float fragmentAlpha(const Fragment<kVaryings>& f) const { return sampleTexel(*d, setup, f).a; }
};

// Phong shading: world position and normal interpolated (perspective-correct), the normal
// renormalised and Blinn-Phong evaluated per pixel (litTerms: any lights). kNormalOnly: the
// variant for draws whose shading reads no position (phongReadsPosition false: white
// directional lights, no specular term, no shadows), without the three position varyings.
template <bool kTextured, bool kNormalOnly = false>
struct PhongProgram {
    static constexpr ShadingMode kMode = ShadingMode::Phong;
    static constexpr bool kIsTextured = kTextured;
    static constexpr bool kPositions = !kNormalOnly;
    static constexpr int kP = kTextured ? 2 : 0;         // position varyings kP..kP+2 (kPositions)
    static constexpr int kN = kPositions ? kP + 3 : kP; // normal kN..kN+2
    static constexpr int kVaryings = kN + 3;
    const DrawContext* d;
    const TriangleSetup* setup = nullptr;
    explicit PhongProgram(const DrawContext* dc) : d(dc) {}
    void vertex(std::size_t i, ClipVertex& out) const {
        const Vec3 p = worldPosition(*d, i);
        transformVertex<kTextured>(*d, i, p, out);
        const Vec3 n = worldNormal(*d, i);
        if constexpr (kPositions) {
            out.varyings[kP] = p.x;
            out.varyings[kP + 1] = p.y;
            out.varyings[kP + 2] = p.z;
        }
        out.varyings[kN] = n.x;
        out.varyings[kN + 1] = n.y;
        out.varyings[kN + 2] = n.z;
    }
    void triangle(std::size_t, const TriangleSetup& s) { setup = &s; }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        const Vec3 n = normalize(Vec3{f.varyings[kN], f.varyings[kN + 1], f.varyings[kN + 2]});
        RgbTerms t;
        if constexpr (kPositions) {
            const Vec3 p{f.varyings[kP], f.varyings[kP + 1], f.varyings[kP + 2]};
            const Vec3 v = normalize(d->view.eye - p);
            t = d->view.shadows ? shadowedTerms(d->view.lighting, d->specular, n, p, v, *d->view.shadows) : litTerms(*d, n, p, v);
        } else {
            assert(!phongReadsPosition(*d));
            t = RgbTerms::grey(blinnPhong(d->view.lighting, d->specular, n, Vec3{})); // (no specular: no direction to the eye)
        }
        if constexpr (kTextured) return encode(*d, applyTerms(sampleKd(*d, setup, f), d->specular.ks, t));
        else return encode(*d, applyTerms(d->kd, d->specular.ks, t));
    }
    template <bool kT = kTextured, std::enable_if_t<kT, int> = 0> // textured programs only (HasFragmentAlpha)
    float fragmentAlpha(const Fragment<kVaryings>& f) const { return sampleTexel(*d, setup, f).a; }
};

} // namespace sr::programs
