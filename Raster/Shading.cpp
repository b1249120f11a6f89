// Shading-mode names and the shininess power.
#include "Raster/Shading.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

#include "Raster/ShadingSimd.hpp"

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

#if SR_HAVE_AVX2
bool cpuHasAvx2() {
    static const bool has = [] {
        const char* off = std::getenv("SR_NO_AVX2");
        if (off && *off && *off != '0') return false;
#if defined(__GNUC__) || defined(__clang__)
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") != 0; // includes the OS's YMM state check
#else
        int info[4];
        __cpuid(info, 0);
        if (info[0] < 7) return false;
        __cpuid(info, 1);
        const bool osxsave = (info[2] & (1 << 27)) != 0, avx = (info[2] & (1 << 28)) != 0;
        if (!osxsave || !avx || (_xgetbv(0) & 6) != 6) return false;
        __cpuidex(info, 7, 0);
        return (info[1] & (1 << 5)) != 0;
#endif
    }();
    return has;
}
#endif

} // namespace sr
