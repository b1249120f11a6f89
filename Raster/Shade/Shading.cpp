// Shading-mode names and the light constructors.
#include "Raster/Shade/Shading.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

namespace sr {

const char* shadingModeName(ShadingMode mode) {
    switch (mode) {
    case ShadingMode::Unlit: return "unlit";
    case ShadingMode::Flat: return "flat";
    case ShadingMode::Gouraud: return "gouraud";
    case ShadingMode::Phong: return "phong";
    case ShadingMode::Pbr: return "pbr";
    }
    return "?";
}

std::optional<ShadingMode> parseShadingMode(std::string_view text) {
    std::string lower(text);
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (ShadingMode m : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong, ShadingMode::Pbr})
        if (lower == shadingModeName(m)) return m;
    return std::nullopt;
}

Lighting blinnPhongLighting(const Lighting& lighting) {
    Lighting out = lighting;
    if (!lighting.physical) return out;
    // A division by the float pi, so the default light of a physical scene (colour pi) becomes
    // exactly white (1) and keeps the one-number terms.
    for (Light& l : out.lights) {
        l.colour.r /= kPiF;
        l.colour.g /= kPiF;
        l.colour.b /= kPiF;
    }
    out.physical = false;
    return out;
}

Light Light::directional(Vec3 toLight, Color colour) {
    Light l;
    l.type = LightType::Directional;
    l.toLight = toLight; // unit: the caller normalises (the default light is normalised in double)
    l.colour = colour;
    return l;
}

Light Light::point(Vec3 position, Color colour, float range) {
    Light l;
    l.type = LightType::Point;
    l.position = position;
    l.colour = colour;
    l.range = std::max(range, 0.0f);
    return l;
}

// The glTF reference's smooth cone: scale = 1 / max(0.001, cos(inner) - cos(outer)),
// offset = -cos(outer) scale, so the factor runs from 0 at the outer angle to 1 at the inner one.
Light Light::spot(Vec3 position, Vec3 direction, Color colour, float innerAngle, float outerAngle, float range) {
    Light l = point(position, colour, range);
    l.type = LightType::Spot;
    l.spotDirection = normalize(direction);
    const float cosOuter = std::cos(outerAngle), cosInner = std::cos(std::min(innerAngle, outerAngle));
    l.coneScale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    l.coneOffset = -cosOuter * l.coneScale;
    return l;
}

} // namespace sr
