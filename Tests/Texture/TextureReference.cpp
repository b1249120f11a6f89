// The reference sampler of the texture tests: generic per-texel wrap and fetch through Texture's public API.
#include "TextureReference.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace sr::test {

namespace {

// --- Coordinate reduction (Texture.hpp's coordinate policies; OpenGL 4.5 core, 8.14.2) ----------
// The same rules as reduceCoordinate in Raster/Texture/TextureSampling.cpp, written with std::floor (exact
// for every double, as the library's floorExact): false when u has no position (NaN; +-Inf under
// Repeat / Mirror), which selects texel 0 with weight 1 on that axis.
bool reduceCoordinate(float u, WrapMode wrap, double& out) {
    if (std::isnan(u)) return false;
    double d = u;
    switch (wrap) {
    case WrapMode::Repeat:
        if (std::isinf(u)) return false;
        if (std::fabs(d) >= 1.0) d -= std::floor(d);
        break;
    case WrapMode::Mirror:
        if (std::isinf(u)) return false;
        if (std::fabs(d) >= 2.0) d -= 2.0 * std::floor(d * 0.5);
        break;
    case WrapMode::Clamp: d = std::clamp(d, -1.0, 2.0); break;
    }
    out = d;
    return true;
}

// GL_LINEAR along one axis: X = (u * size - 1/2) * 256 rounded to nearest (halves up), first
// (unwrapped) texel i0 = X >> 8, weight of i0 + 1 = (X & 255) / 256.
struct LinearTaps {
    int i0 = 0;
    int w = 0; // in 1/256
};
LinearTaps linearTaps(float u, int size, WrapMode wrap) {
    double d;
    if (!reduceCoordinate(u, wrap, d)) return {0, 0};
    const int x = int(std::floor((d * double(size) - 0.5) * 256.0 + 0.5));
    return {x >> 8, x & 255};
}

// GL_NEAREST along one axis: floor(u * size), unwrapped.
int nearestTap(float u, int size, WrapMode wrap) {
    double d;
    if (!reduceCoordinate(u, wrap, d)) return 0;
    return int(std::floor(d * double(size)));
}

// --- Reference wrap: the formulas of OpenGL 4.5 core, table 8.20 ------------------------------
int wrapReference(int i, int size, WrapMode wrap) {
    switch (wrap) {
    case WrapMode::Repeat: {
        const int m = i % size; // "i mod size" with a non-negative result
        return m < 0 ? m + size : m;
    }
    case WrapMode::Clamp: return std::clamp(i, 0, size - 1);
    case WrapMode::Mirror: {
        // (size - 1) - mirror((i mod 2 size) - size), mirror(a) = a >= 0 ? a : -(1 + a)
        int m = i % (2 * size);
        if (m < 0) m += 2 * size;
        const int a = m - size;
        return (size - 1) - (a >= 0 ? a : -(1 + a));
    }
    }
    return 0;
}

Color nearestReference(const Texture& t, int level, Vec2 uv, WrapModes wrap) {
    const int w = t.levelWidth(level), h = t.levelHeight(level);
    const int x = wrapReference(nearestTap(uv.x, w, wrap.u), w, wrap.u);
    const int y = wrapReference(nearestTap(uv.y, h, wrap.v), h, wrap.v);
    return t.texelColor(level, x, y);
}

// Straightforward GL_LINEAR: each of the 2x2 texels wrapped and fetched on its own, with the
// weights as fractions k / 256 in double. raw = 65536 * sum(texel * weight) is the integer blend
// (exact in double: every term is a small dyadic rational).
void bilinearReferenceRaw(const Texture& t, int level, Vec2 uv, WrapModes wrap, double raw[4]) {
    const int w = t.levelWidth(level), h = t.levelHeight(level);
    const LinearTaps tx = linearTaps(uv.x, w, wrap.u);
    const LinearTaps ty = linearTaps(uv.y, h, wrap.v);
    const double fx = tx.w / 256.0, fy = ty.w / 256.0;
    for (int c = 0; c < 4; ++c) raw[c] = 0.0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const int x = wrapReference(tx.i0 + i, w, wrap.u), y = wrapReference(ty.i0 + j, h, wrap.v);
            const std::uint32_t texel = t.texel(level, x, y);
            const double weight = (i ? fx : 1.0 - fx) * (j ? fy : 1.0 - fy);
            for (int c = 0; c < 4; ++c) raw[c] += double((texel >> (8 * c)) & 0xFFu) * weight * 65536.0;
        }
}

} // namespace

Color sampleReference(const Texture& texture, Vec2 uv, float lod, TextureFilter filter, WrapMode wrap) {
    return sampleReference(texture, uv, lod, filter, WrapModes{wrap, wrap});
}

Color sampleReference(const Texture& texture, Vec2 uv, float lod, TextureFilter filter, WrapModes wrap) {
    // raw / (255 * 65536) per channel, rounded once to float.
    auto toColorRef = [](const double raw[4]) {
        return Color{float(raw[0]) / (255.0f * 65536.0f), float(raw[1]) / (255.0f * 65536.0f),
                     float(raw[2]) / (255.0f * 65536.0f), float(raw[3]) / (255.0f * 65536.0f)};
    };
    switch (filter) {
    case TextureFilter::Nearest: return nearestReference(texture, 0, uv, wrap);
    case TextureFilter::Bilinear: {
        double raw[4];
        bilinearReferenceRaw(texture, 0, uv, wrap, raw);
        return toColorRef(raw);
    }
    case TextureFilter::Trilinear: {
        // OpenGL 4.5 core 8.14.3: d1 = floor(lambda), d2 = d1 + 1, blended by frac(lambda) (here in
        // 8-bit fixed point, the blend rounded half up at the raw scale); at or beyond the last level
        // q, d1 = d2 = q.
        const float q = float(texture.levelCount() - 1);
        const float lambda = std::isnan(lod) ? 0.0f : std::clamp(lod, 0.0f, q);
        const float d1 = std::floor(lambda);
        const float d2 = std::min(d1 + 1.0f, q);
        const double wl = std::floor(double(lambda - d1) * 256.0);
        double raw1[4], raw2[4], mixed[4];
        bilinearReferenceRaw(texture, int(d1), uv, wrap, raw1);
        bilinearReferenceRaw(texture, int(d2), uv, wrap, raw2);
        for (int c = 0; c < 4; ++c) mixed[c] = std::floor((raw1[c] * (256.0 - wl) + raw2[c] * wl + 128.0) / 256.0);
        return toColorRef(mixed);
    }
    }
    return {};
}

} // namespace sr::test
