// The glTF 2.0 metallic-roughness BRDF (specification, appendix B) and the punctual lights it is lit by.
#pragma once

#include <algorithm>
#include <cmath>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"
#include "Raster/Shading.hpp" // Lighting, lightAt

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
};

// A surface point as the BRDF sees it: linear base colour, metallic and perceptual roughness,
// each already combined from its factor and texture.
struct PbrSurface {
    Vec3 baseColor{1.0f, 1.0f, 1.0f};
    float metallic = 1.0f;
    float roughness = 1.0f;
};

// The smallest perceptual roughness evaluated: the GGX lobe of roughness 0 is a Dirac peak that
// no point light can hit (D would be infinite where N = H and 0 elsewhere); three.js and the
// Khronos sample viewer clamp the same way (0.0525 and 0.03 respectively; ours is the former).
inline constexpr float kMinRoughness = 0.0525f;

// The terms of appendix B ("Specular BRDF", "Complete model"), alpha = roughness^2:
//   D(h)   = alpha^2 / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2)                        (GGX / Trowbridge-Reitz)
//   V(l,v) = 1 / (N.L sqrt((N.V)^2 (1 - alpha^2) + alpha^2) + N.V sqrt((N.L)^2 (1 - alpha^2) + alpha^2))
//            / 2                                                                 (Smith, height-correlated)
//   F      = F0 + (1 - F0) (1 - V.H)^5, F0 = mix(0.04, baseColor, metallic)     (Schlick)
//   f      = (1 - F) c_diff / pi + F D V, c_diff = mix(baseColor, 0, metallic)
// The V above is the specification's Vis = G / (4 N.L N.V) (it carries the 1/2 of its two
// 2 N.L N.V denominators combined). Each function is written as the specification writes it and
// checked against its double-precision twin (Tests/Render/BrdfTests.cpp).
// D's denominator (N.H)^2 (alpha^2 - 1) + 1 is written as |N x H|^2 + (N.H)^2 alpha^2 (equal for
// unit N and H): in float, a2 - 1 keeps only a few bits of a small alpha^2, which near the peak
// (N.H ~ 1) is all that is left: 0.7% off at roughness 0.05; the cross product keeps them.
inline float ggxDistribution(float nDotH, float sin2NH, float alpha) {
    const float a2 = alpha * alpha;
    const float d = sin2NH + nDotH * nDotH * a2;
    return d > 0.0f ? a2 / (kPiF * d * d) : 0.0f;
}

inline float smithVisibility(float nDotL, float nDotV, float alpha) {
    const float a2 = alpha * alpha;
    const float gv = nDotL * std::sqrt(nDotV * nDotV * (1.0f - a2) + a2);
    const float gl = nDotV * std::sqrt(nDotL * nDotL * (1.0f - a2) + a2);
    const float sum = gv + gl;
    return sum > 0.0f ? 0.5f / sum : 0.0f;
}

inline float schlickWeight(float vDotH) {
    const float m = std::clamp(1.0f - vDotH, 0.0f, 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
}

// f(l, v) N.L for one light direction: the reflected radiance per unit of the light's
// irradiance at normal incidence (lux for a directional light), per channel. N, L, V unit;
// 0 where the light or the viewer is behind the surface (N.L <= 0 or N.V <= 0: no light on the
// side it does not face; a viewer below the surface sees the normal's back, which gets nothing).
inline Vec3 brdfCosine(const PbrSurface& s, Vec3 n, Vec3 l, Vec3 v) {
    const float nDotL = dot(n, l);
    if (!(nDotL > 0.0f)) return {0.0f, 0.0f, 0.0f};
    // A viewer at grazing or slightly behind (interpolated normals) still sees the lit surface:
    // N.V is clamped to a small positive value rather than cutting the light off, as viewers do.
    const float nDotV = std::max(dot(n, v), 1e-4f);
    const Vec3 hRaw = l + v;
    const float hLen = length(hRaw);
    const Vec3 h = hLen > 0.0f ? hRaw / hLen : n;
    const float nDotH = std::max(dot(n, h), 0.0f), vDotH = std::max(dot(v, h), 0.0f);
    // Clamped into range; a NaN factor (from a map or a file) reads as the range's end it fails.
    const float roughness = s.roughness >= kMinRoughness ? std::min(s.roughness, 1.0f) : kMinRoughness;
    const float metallic = s.metallic > 0.0f ? std::min(s.metallic, 1.0f) : 0.0f;
    const float alpha = roughness * roughness;
    const float fw = schlickWeight(vDotH);
    const Vec3 nxh = cross(n, h);
    const float specular = ggxDistribution(nDotH, dot(nxh, nxh), alpha) * smithVisibility(nDotL, nDotV, alpha);
    const auto channel = [&](float base) {
        const float f0 = 0.04f + (base - 0.04f) * metallic;
        const float f = f0 + (1.0f - f0) * fw;
        const float diffuse = (1.0f - f) * (base * (1.0f - metallic)) / kPiF;
        return (diffuse + f * specular) * nDotL;
    };
    return {channel(s.baseColor.x), channel(s.baseColor.y), channel(s.baseColor.z)};
}

// The radiance leaving world point p toward the eye (unit v) under every light of `lighting`
// (KHR_lights_punctual units: a directional light's colour x intensity is lux, a point or spot
// light's is candela, falling off as lightAt says), with no ambient term: the specification has
// none. `visible(i, p, n, l)` is the lit fraction of light i (shadow maps), as in lightTerms.
template <class Visibility = AllVisible>
inline Vec3 pbrRadiance(const Lighting& lighting, const PbrSurface& s, Vec3 n, Vec3 p, Vec3 v,
                        const Visibility& visible = {}) {
    Vec3 sum{0.0f, 0.0f, 0.0f};
    for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
        const Light& light = lighting.lights[i];
        Vec3 l;
        float a = lightAt(light, p, l);
        if (!(a > 0.0f) || !(dot(n, l) > 0.0f)) continue;
        if constexpr (!std::is_same_v<Visibility, AllVisible>) {
            const float seen = visible(i, p, n, l);
            if (seen < 1.0f) a = a * seen;
        }
        const Vec3 f = brdfCosine(s, n, l, v);
        sum.x += f.x * light.colour.r * a;
        sum.y += f.y * light.colour.g * a;
        sum.z += f.z * light.colour.b * a;
    }
    return sum;
}

} // namespace sr
