// Shading-mode names and the shininess power.
#include "Raster/Shading.hpp"

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
    }
    return "?";
}

std::optional<ShadingMode> parseShadingMode(std::string_view text) {
    std::string lower(text);
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (ShadingMode m : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong})
        if (lower == shadingModeName(m)) return m;
    return std::nullopt;
}

} // namespace sr
