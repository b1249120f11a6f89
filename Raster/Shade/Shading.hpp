// Blinn-Phong lighting terms and the shading modes (unlit, flat, Gouraud, Phong shading).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"

namespace sr {

// Unlit: kd only. Flat: lit once per triangle with its face normal. Gouraud: lit per vertex,
// the terms interpolated. Phong: normals and positions interpolated, lit per pixel (Blinn-Phong).
// Pbr: as Phong, but the glTF metallic-roughness BRDF (Brdf.hpp) with the material's maps; only
// a glTF material has its input (a draw without one is shaded Phong).
enum class ShadingMode { Unlit, Flat, Gouraud, Phong, Pbr };

const char* shadingModeName(ShadingMode mode);
// "unlit", "flat", "gouraud", "phong" (ASCII case-insensitive); anything else: nullopt.
std::optional<ShadingMode> parseShadingMode(std::string_view text);

inline constexpr float kPiF = 3.14159265358979323846f;

// A punctual light (glTF KHR_lights_punctual): directional, point or spot, with a colour that
// already includes its intensity (a plain multiplier on the lit colour: no physical units, no
// exposure). Point and spot lights fall off with the inverse square distance, cut to zero at
// `range` by glTF's recommended window, and spots with the smooth cone of the glTF reference
// (lightTerms below).
enum class LightType { Directional, Point, Spot };

struct Light {
    LightType type = LightType::Directional;
    Vec3 toLight{0.0f, 0.0f, 1.0f};        // directional: unit direction TO the light (world)
    Vec3 position{};                       // point and spot: world position
    Vec3 spotDirection{0.0f, 0.0f, -1.0f}; // spot: unit direction the light shines along
    Color colour{1.0f, 1.0f, 1.0f, 1.0f};  // colour times intensity (alpha unused)
    float range = 0.0f;                    // point and spot: 0 = unlimited
    float coneScale = 0.0f, coneOffset = 1.0f; // spot: cone factor = clamp(cos * scale + offset, 0, 1)^2

    static Light directional(Vec3 toLight, Color colour = {1.0f, 1.0f, 1.0f, 1.0f});
    static Light point(Vec3 position, Color colour, float range = 0.0f);
    // innerAngle and outerAngle in radians from the axis (glTF's innerConeAngle, outerConeAngle).
    static Light spot(Vec3 position, Vec3 direction, Color colour, float innerAngle, float outerAngle,
                      float range = 0.0f);
    // White (colour exactly 1) and directional: what blinnPhong's one-number terms assume.
    bool whiteDirectional() const {
        return type == LightType::Directional && colour.r == 1.0f && colour.g == 1.0f && colour.b == 1.0f;
    }
};

// The lights and the ambient term every surface shares. The default, one white directional
// light from (1, 1, 1), mirrors the llvmpipe reference renderer (shared/tools/llvmpipe-ref,
// "Shading").
struct Lighting {
    std::vector<Light> lights{Light::directional(normalize(Vec3(1, 1, 1)))};
    float ambient = 0.1f;
    // The lights are in KHR_lights_punctual's units (colour x intensity in lux or candela: a glTF
    // scene's), as the pbr model reads them. The Blinn-Phong models, whose kd x N.L is the
    // albedo's full colour, are lit by them divided by pi (blinnPhongLighting), so that a
    // Lambertian surface looks the same in both.
    bool physical = false;
    // Every light white and directional: the terms are one number each (LightTerms, blinnPhong),
    // the cheaper path; otherwise RGB terms (lightTerms).
    bool whiteDirectional() const {
        for (const Light& l : lights)
            if (!l.whiteDirectional()) return false;
        return true;
    }
};

// The lighting the Blinn-Phong models see: `lighting` itself, or with physical lights each
// colour divided by pi (Lighting::physical).
Lighting blinnPhongLighting(const Lighting& lighting);

// The specular constants of one surface (a material's MTL Ks and Ns). The defaults are the
// reference's values for a surface without a material: white ks 0.5, shininess 32.
struct Specular {
    Color ks{0.5f, 0.5f, 0.5f, 1.0f}; // specular colour (alpha unused)
    float shininess = 32.0f;
    // The reference's rule: no specular term at all when Ns <= 0 or Ks is black (x^0 would
    // otherwise light every lit pixel with ks).
    bool on() const { return shininess > 0.0f && (ks.r != 0.0f || ks.g != 0.0f || ks.b != 0.0f); }
};

// The two scalar terms a colour is built from: c = kd * diffuse + ks * specular.
struct LightTerms {
    float diffuse = 0.0f;  // ambient + sum over lights of max(N.L, 0)
    float specular = 0.0f; // sum over lights of (N.L > 0 ? max(N.H, 0)^shininess : 0); 0 when !on()
};

// x^s for x in [0, 1]: exact repeated squaring/multiplication when s is a whole number in
// [0, 1024] (32 -> five squarings), std::pow otherwise.
// Inline (per pixel in Phong); the whole-number test is a truncating conversion rather than a
// std::floor library call (the same for s in [0, 1024]).
inline float shininessPow(float x, float s) {
    if (s >= 0.0f && s <= 1024.0f && s == float(int(s))) {
        // Binary exponentiation: exact for the common powers of two (x^32 = five squarings).
        unsigned e = unsigned(s);
        float result = 1.0f, base = x;
        while (e) {
            if (e & 1u) result *= base;
            base *= base;
            e >>= 1u;
        }
        return result;
    }
    return std::pow(x, s);
}

// Blinn-Phong (Blinn, "Models of light reflection for computer synthesized pictures",
// SIGGRAPH 1977) with the half vector H = normalize(L + V), for white directional lights only
// (Lighting::whiteDirectional; their toLight is L). N and V must be unit vectors.
// One-sided: a normal facing away from a light gets neither diffuse nor specular from it.
// Without a specular term (!specular.on()) no half vector is formed.
inline LightTerms blinnPhong(const Lighting& lighting, const Specular& specular, Vec3 n, Vec3 v) {
    LightTerms t;
    t.diffuse = lighting.ambient;
    const bool specularOn = specular.on();
    for (const Light& light : lighting.lights) {
        const Vec3 l = light.toLight;
        const float ndl = dot(n, l);
        if (ndl > 0.0f) {
            t.diffuse += ndl;
            if (!specularOn) continue;
            const Vec3 h = normalize(l + v);
            t.specular += shininessPow(std::max(dot(n, h), 0.0f), specular.shininess);
        }
    }
    return t;
}

// kd * diffuse + ks * specular per channel (with ks 0.5 the same floats as the former
// kd * diffuse + (0.5 * specular): a power-of-two scale is exact).
inline Color applyTerms(Color kd, Color ks, LightTerms t) {
    return {kd.r * t.diffuse + ks.r * t.specular, kd.g * t.diffuse + ks.g * t.specular,
            kd.b * t.diffuse + ks.b * t.specular, 1.0f};
}

// The terms per colour channel, for any lights: c = kd * diffuse + ks * specular channel by
// channel (the alpha of both is unused).
struct RgbTerms {
    Color diffuse{0.0f, 0.0f, 0.0f, 1.0f};  // ambient + sum over lights of colour a max(N.L, 0)
    Color specular{0.0f, 0.0f, 0.0f, 1.0f}; // sum over lit lights of colour a max(N.H, 0)^shininess
    static RgbTerms grey(LightTerms t) {
        return {{t.diffuse, t.diffuse, t.diffuse, 1.0f}, {t.specular, t.specular, t.specular, 1.0f}};
    }
};

// Point and spot lights closer than this (squared distance) light as if at this distance.
inline constexpr float kMinLightDistance2 = 1e-6f;

// Where light `light` comes from at world point p, and how strongly: the unit vector L toward
// the light and the factor a its colour is scaled by (0: no light reaches p).
//   directional: L = toLight, a = 1;
//   point, spot: d = position - p, L = normalize(d), a = 1 / max(|d|^2, kMinLightDistance2),
//     times clamp(1 - (|d| / range)^4, 0, 1) when range > 0 (glTF's recommended window),
//     and for a spot times clamp(dot(spotDirection, -L) coneScale + coneOffset, 0, 1)^2.
// Every operation in this order: the kernels' lightsRgb repeats it lane by lane.
inline float lightAt(const Light& light, Vec3 p, Vec3& l) {
    if (light.type == LightType::Directional) {
        l = light.toLight;
        return 1.0f;
    }
    const Vec3 d = light.position - p;
    const float d2 = dot(d, d);
    l = normalize(d);
    float a = 1.0f / std::max(d2, kMinLightDistance2);
    if (light.range > 0.0f) {
        const float q = d2 / (light.range * light.range);
        a = a * std::clamp(1.0f - q * q, 0.0f, 1.0f);
    }
    if (light.type == LightType::Spot) {
        const float c = std::clamp(-dot(light.spotDirection, l) * light.coneScale + light.coneOffset, 0.0f, 1.0f);
        a = a * (c * c);
    }
    return a;
}

// Every light fully visible: lightTerms without shadows.
struct AllVisible {
    float operator()(std::size_t, Vec3, Vec3, Vec3) const { return 1.0f; }
};

// Blinn-Phong for any lights at world point p (N, V unit): per light L and a from lightAt, then
// the one-sided terms scaled by colour * a. For white directional lights (a = 1, colour 1) every
// channel equals blinnPhong's terms bit for bit (x * 1 is x). `visible(i, p, n, l)` is the lit
// fraction of light i at p (shadow maps: Shadow.hpp's shadowedTerms), asked only where the light
// would add something; below 1 it scales a. With AllVisible, nothing is asked.
template <class Visibility = AllVisible>
inline RgbTerms lightTerms(const Lighting& lighting, const Specular& specular, Vec3 n, Vec3 p, Vec3 v,
                           const Visibility& visible = {}) {
    RgbTerms t;
    t.diffuse = {lighting.ambient, lighting.ambient, lighting.ambient, 1.0f};
    const bool specularOn = specular.on();
    for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
        const Light& light = lighting.lights[i];
        Vec3 l;
        float a = lightAt(light, p, l);
        if (!(a > 0.0f)) continue;
        const float ndl = dot(n, l);
        if (!(ndl > 0.0f)) continue;
        if constexpr (!std::is_same_v<Visibility, AllVisible>) {
            const float seen = visible(i, p, n, l);
            if (seen < 1.0f) a = a * seen;
        }
        const float diffuse = ndl * a;
        t.diffuse.r += light.colour.r * diffuse;
        t.diffuse.g += light.colour.g * diffuse;
        t.diffuse.b += light.colour.b * diffuse;
        if (!specularOn) continue;
        const Vec3 h = normalize(l + v);
        const float s = shininessPow(std::max(dot(n, h), 0.0f), specular.shininess) * a;
        t.specular.r += light.colour.r * s;
        t.specular.g += light.colour.g * s;
        t.specular.b += light.colour.b * s;
    }
    return t;
}

inline Color applyTerms(Color kd, Color ks, const RgbTerms& t) {
    return {kd.r * t.diffuse.r + ks.r * t.specular.r, kd.g * t.diffuse.g + ks.g * t.specular.g,
            kd.b * t.diffuse.b + ks.b * t.specular.b, 1.0f};
}

} // namespace sr
