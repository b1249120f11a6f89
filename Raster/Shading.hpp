// Blinn-Phong lighting terms and the shading modes (unlit, flat, Gouraud, Phong shading).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"

namespace sr {

// Unlit: kd only. Flat: lit once per triangle with its face normal. Gouraud: lit per vertex,
// the terms interpolated. Phong: normals and positions interpolated, lit per pixel.
enum class ShadingMode { Unlit, Flat, Gouraud, Phong };

const char* shadingModeName(ShadingMode mode);
// "unlit", "flat", "gouraud", "phong" (ASCII case-insensitive); anything else: nullopt.
std::optional<ShadingMode> parseShadingMode(std::string_view text);

// White directional lights of intensity 1 and the ambient term every surface shares. The
// defaults mirror the llvmpipe reference renderer (shared/tools/llvmpipe-ref, "Shading").
struct Lighting {
    std::vector<Vec3> toLight{normalize(Vec3(1, 1, 1))}; // unit directions TO each light (world)
    float ambient = 0.1f;
};

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
// SIGGRAPH 1977) with the half vector H = normalize(L + V). N and V must be unit vectors.
// One-sided: a normal facing away from a light gets neither diffuse nor specular from it.
// Without a specular term (!specular.on()) no half vector is formed.
inline LightTerms blinnPhong(const Lighting& lighting, const Specular& specular, Vec3 n, Vec3 v) {
    LightTerms t;
    t.diffuse = lighting.ambient;
    const bool specularOn = specular.on();
    for (const Vec3& l : lighting.toLight) {
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

} // namespace sr
