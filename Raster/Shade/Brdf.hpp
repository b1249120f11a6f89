// The glTF 2.0 metallic-roughness BRDF (specification, appendix B) and the punctual lights it is lit by.
#pragma once

#include <algorithm>
#include <cmath>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"
#include "Raster/Shade/Shading.hpp" // Lighting, lightAt

namespace sr {

// A glTF material's metallic-roughness values: its factors (linear) and the settings of its maps.
// The maps themselves are the draw's textures (SurfaceMaterial): base colour x baseColorTexture
// (sRGB) x COLOR_0, metallic x the blue and roughness x the green channel of the
// metallicRoughnessTexture, emissive x emissiveTexture (sRGB).
struct PbrFactors {
    Color baseColor{1.0f, 1.0f, 1.0f, 1.0f}; // baseColorFactor (its alpha is the alpha modes')
    float metallic = 1.0f, roughness = 1.0f;
    Vec3 emissive{0.0f, 0.0f, 0.0f}; // emissiveFactor x KHR_materials_emissive_strength
    float normalScale = 1.0f;        // normalTexture.scale
    float occlusionStrength = 1.0f;  // occlusionTexture.strength
    bool unlit = false;              // KHR_materials_unlit: the base colour as it is, no light (MeshRenderer)
    // The dielectric's reflectance at normal incidence, min(((ior - 1) / (ior + 1))^2 x
    // specularColorFactor, 1) (KHR_materials_ior, KHR_materials_specular; 0.04 without them), and
    // the specular weight (specularFactor, 1 without it) that scales its Fresnel term, F0 and F90.
    Vec3 dielectricF0{0.04f, 0.04f, 0.04f};
    float specularWeight = 1.0f;
    // ((ior - 1) / (ior + 1))^2 x specularColorFactor before the clamp: with a
    // specularColorTexture, F0 = min(this x its texel, 1) per pixel (and the weight x the
    // specularTexture's alpha).
    Vec3 specularColorF0{0.04f, 0.04f, 0.04f};
    // KHR_materials_clearcoat: the coat's weight (0: none; x the clearcoatTexture's red), its
    // perceptual roughness (x the clearcoatRoughnessTexture's green) and its normal map's scale.
    float clearcoat = 0.0f, clearcoatRoughness = 0.0f, clearcoatNormalScale = 1.0f;
    // KHR_materials_pbrSpecularGlossiness with a specularGlossinessTexture (kLobeSpecularGlossiness):
    // per pixel, roughness = 1 - glossiness x the texture's alpha and the base colour (its diffuse)
    // x 1 - max(F0) (F0 = specularColorF0 x the texture's RGB). Without the texture the loader folds
    // both into roughness and the base colour.
    bool specularGlossiness = false;
    float glossiness = 1.0f;
    // KHR_materials_sheen: the sheen's colour (linear; x the sheenColorTexture's RGB; black: none)
    // and its roughness (x the sheenRoughnessTexture's alpha).
    Vec3 sheenColor{0.0f, 0.0f, 0.0f};
    float sheenRoughness = 0.0f;
};

// The parts of the pbr model a material may add to appendix B's, one bit each: a draw evaluates
// those its material has and no other (PbrProgram::lobes; in the span kernels a material with
// none shades with the base program's code alone, and the lights' loop is instantiated for each
// set of the bits it reads).
enum PbrLobe : unsigned {
    kLobeDielectricSpecular = 1u, // KHR_materials_ior / _specular values (brdfCosineTerms' kSpecular)
    kLobeClearcoat = 2u,          // KHR_materials_clearcoat (BrdfTerms.inl's coatWeight)
    kLobeSpecularGlossiness = 4u, // KHR_materials_pbrSpecularGlossiness's per-pixel inputs (PbrFactors::specularGlossiness)
    kLobeSheen = 8u,              // KHR_materials_sheen (sheenCosine, sheenImageBrdf; scalar program only)
};
// The bits the span kernels evaluate: a draw whose material has any other is filled by the scalar
// program (MeshRenderer).
inline constexpr unsigned kKernelLobes = kLobeDielectricSpecular | kLobeClearcoat | kLobeSpecularGlossiness;
// The bits the lights' loop reads (the kernels instantiate it for each combination of these).
inline constexpr unsigned kLightLobes = kLobeDielectricSpecular | kLobeClearcoat;

// Whether a material's dielectric differs from appendix B's (F0 0.04, weight 1): the kernels
// evaluate the BRDF without those inputs otherwise (brdfCosineTerms' kSpecular).
inline bool hasDielectricSpecular(const PbrFactors& k) {
    return !(k.specularWeight == 1.0f && k.dielectricF0.x == 0.04f && k.dielectricF0.y == 0.04f && k.dielectricF0.z == 0.04f);
}

// A surface point as the BRDF sees it: linear base colour, metallic and perceptual roughness,
// each already combined from its factor and texture.
struct PbrSurface {
    Vec3 baseColor{1.0f, 1.0f, 1.0f};
    float metallic = 1.0f;
    float roughness = 1.0f;
    Vec3 dielectricF0{0.04f, 0.04f, 0.04f}; // PbrFactors::dielectricF0
    float specularWeight = 1.0f;            // PbrFactors::specularWeight
};

// The smallest perceptual roughness evaluated: the GGX lobe of roughness 0 is a Dirac peak that
// no point light can hit (D would be infinite where N = H and 0 elsewhere); three.js and the
// Khronos sample viewer clamp the same way (0.0525 and 0.03 respectively; ours is the former).
inline constexpr float kMinRoughness = 0.0525f;

// The operations the BRDF is written in, for float here and for each ISA's lane vector F
// (Raster/Fill/Kernels/Simd*.hpp): one source for the scalar reference and the span kernels, so both
// run the same operations in the same order. maxOf / minOf are std::max / std::min exactly
// (NaN included), selectOf is `c ? a : b`, splatAs(x, c) the constant c in x's type.
inline float maxOf(float a, float b) { return std::max(a, b); }
inline float minOf(float a, float b) { return std::min(a, b); }
inline float sqrtOf(float a) { return std::sqrt(a); }
inline float selectOf(bool c, float a, float b) { return c ? a : b; }
inline float splatAs(float, float c) { return c; }

// brdfCosineTerms: appendix B's f(l, v) N.L from the dot products, written once for float and
// for the kernels' lane vectors (BrdfTerms.inl, included here and inside each ISA's kernels).
#include "Raster/Shade/BrdfTerms.inl"

// f(l, v) N.L for one light direction: the reflected radiance per unit of the light's
// irradiance at normal incidence (lux for a directional light), per channel; N, L, V unit.
// multiScatter: brdfMultiScatter's k at this N.V and roughness (0: single scattering alone).
inline Vec3 brdfCosine(const PbrSurface& s, Vec3 n, Vec3 l, Vec3 v, float multiScatter = 0.0f) {
    const Vec3 h = normalize(l + v);
    const Vec3 nxh = cross(n, h);
    const float base[3] = {s.baseColor.x, s.baseColor.y, s.baseColor.z};
    const float f0[3] = {s.dielectricF0.x, s.dielectricF0.y, s.dielectricF0.z};
    float out[3];
    brdfCosineTerms(dot(n, l), dot(n, v), dot(n, h), dot(nxh, nxh), dot(v, h), s.roughness, s.metallic, base, f0, s.specularWeight,
                    multiScatter, out);
    return {out[0], out[1], out[2]};
}

// The sum over the lights that reach p and that the normal `facing` faces of f(l) x colour x
// the light's factor (lightAt's, times the lit fraction visible(i, p, n, l)), per channel: the
// loop pbrRadiance and coatRadiance share. f(l) returns the lobe's cosine-weighted value (Vec3).
template <class Visibility, class Lobe>
inline Vec3 sumOverLights(const Lighting& lighting, Vec3 facing, Vec3 n, Vec3 p, const Visibility& visible, const Lobe& f) {
    Vec3 sum{0.0f, 0.0f, 0.0f};
    for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
        const Light& light = lighting.lights[i];
        Vec3 l;
        float a = lightAt(light, p, l);
        if (!(a > 0.0f) || !(dot(facing, l) > 0.0f)) continue;
        if constexpr (!std::is_same_v<Visibility, AllVisible>) {
            const float seen = visible(i, p, n, l);
            if (seen < 1.0f) a = a * seen;
        }
        const Vec3 c = f(l);
        sum.x += c.x * light.colour.r * a;
        sum.y += c.y * light.colour.g * a;
        sum.z += c.z * light.colour.b * a;
    }
    return sum;
}

// The radiance leaving world point p toward the eye (unit v) under every light of `lighting`
// (KHR_lights_punctual units: a directional light's colour x intensity is lux, a point or spot
// light's is candela, falling off as lightAt says), with no ambient term: the specification has
// none. `visible(i, p, n, l)` is the lit fraction of light i (shadow maps), as in lightTerms;
// multiScatter as in brdfCosine.
template <class Visibility = AllVisible>
inline Vec3 pbrRadiance(const Lighting& lighting, const PbrSurface& s, Vec3 n, Vec3 p, Vec3 v, float multiScatter = 0.0f,
                        const Visibility& visible = {}) {
    return sumOverLights(lighting, n, n, p, visible, [&](Vec3 l) { return brdfCosine(s, n, l, v, multiScatter); });
}

// KHR_materials_sheen, as three.js r187 draws it (the glTF viewer this project compares with):
// the Charlie distribution (Estevez and Kulla 2017) with Neubelt's visibility, the spec's
// cheaper alternative to Charlie's own, and the base layer scaled by 1 - 0.157 max(sheen colour)
// (a constant directional albedo where the spec tabulates E(N.V, roughness)). The sheen's
// roughness is clamped to [0.07, 1]; alpha = roughness^2.
//   D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi),  sin^2 at least 1/128
//   V = clamp(1 / (4 (N.L + N.V - N.L N.V)), 0, 1)
inline constexpr float kSheenMinRoughness = 0.07f, kSheenAlbedo = 0.157f;
inline float sheenRoughnessClamped(float r) { return std::min(std::max(r, kSheenMinRoughness), 1.0f); }
inline float sheenDistribution(float roughness, float nDotH) {
    const float alpha = roughness * roughness, invAlpha = 1.0f / alpha;
    const float sin2h = std::max(1.0f - nDotH * nDotH, 0.0078125f);
    return (2.0f + invAlpha) * std::pow(sin2h, invAlpha * 0.5f) / (2.0f * 3.14159265f);
}
inline float sheenVisibility(float nDotL, float nDotV) {
    return std::min(std::max(1.0f / (4.0f * (nDotL + nDotV - nDotL * nDotV)), 0.0f), 1.0f);
}
// The sheen lobe's f(l, v) N.L, per unit of sheen colour (N, L, V unit; N.L, N.V clamped to [0, 1]).
inline float sheenCosine(float roughness, Vec3 n, Vec3 l, Vec3 v) {
    const Vec3 h = normalize(l + v);
    const float nDotL = std::min(std::max(dot(n, l), 0.0f), 1.0f), nDotV = std::min(std::max(dot(n, v), 0.0f), 1.0f);
    const float nDotH = std::min(std::max(dot(n, h), 0.0f), 1.0f);
    return sheenDistribution(roughness, nDotH) * sheenVisibility(nDotL, nDotV) * nDotL;
}
// The sheen's directional albedo under image light, per unit of sheen colour and of the sky's
// irradiance E(n) (three.js's IBLSheenBRDF fit, 1/pi included), in [0, 1].
inline float sheenImageBrdf(float roughness, float nDotV) {
    const float v = std::min(std::max(nDotV, 0.0f), 1.0f), r2 = roughness * roughness;
    const bool smooth = roughness < 0.25f;
    const float a = smooth ? -339.2f * r2 + 161.4f * roughness - 25.9f : -8.48f * r2 + 14.3f * roughness - 9.95f;
    const float b = smooth ? 44.0f * r2 - 23.7f * roughness + 3.26f : 1.97f * r2 - 3.27f * roughness + 0.72f;
    const float dg = std::exp(a * v + b) + (smooth ? 0.0f : 0.1f * (roughness - 0.25f));
    return std::min(std::max(dg * (1.0f / 3.14159265f), 0.0f), 1.0f);
}

// The sheen's lobe under every light (sheenCosine on the normal n at the sheen's roughness),
// where the light reaches p and n faces it; `visible` as in pbrRadiance.
template <class Visibility = AllVisible>
inline Vec3 sheenRadiance(const Lighting& lighting, float roughness, Vec3 n, Vec3 p, Vec3 v, const Visibility& visible = {}) {
    return sumOverLights(lighting, n, n, p, visible, [&](Vec3 l) {
        const float f = sheenCosine(roughness, n, l, v);
        return Vec3{f, f, f};
    });
}

// The clear coat's lobe under every light (KHR_materials_clearcoat; BrdfTerms.inl's
// coatCosineTerm on the coat normal nc, unit, at the coat's roughness), where the light reaches
// the point and nc faces it; `visible` as in pbrRadiance, asked with the base's normal n.
template <class Visibility = AllVisible>
inline Vec3 coatRadiance(const Lighting& lighting, Vec3 nc, float coatRoughness, Vec3 n, Vec3 p, Vec3 v,
                         const Visibility& visible = {}) {
    return sumOverLights(lighting, nc, n, p, visible, [&](Vec3 l) {
        const Vec3 h = normalize(l + v);
        const Vec3 nxh = cross(nc, h);
        const float f = coatCosineTerm(dot(nc, l), dot(nc, v), dot(nc, h), dot(nxh, nxh), coatRoughness);
        return Vec3{f, f, f};
    });
}

} // namespace sr
