// The sRGB curve, its decode table and byte encoder, and the tone-mapping operators.
#include "Raster/Shade/ColorSpace.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace sr {

const char* colorModeName(ColorMode mode) { return mode == ColorMode::Linear ? "linear" : "gamma"; }

std::optional<ColorMode> parseColorMode(std::string_view text) {
    if (text == "linear") return ColorMode::Linear;
    if (text == "gamma") return ColorMode::Gamma;
    return std::nullopt;
}

float srgbToLinear(float c) {
    const double x = c;
    return float(x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4));
}

float linearToSrgb(float l) {
    if (!(l > 0.0f)) return 0.0f;
    if (l >= 1.0f) return 1.0f;
    const double x = l;
    return float(x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
}

namespace {

// The tables are built once, at static initialisation (namespace scope: no guard per call).
const std::array<float, 256> kDecode = [] {
    std::array<float, 256> t{};
    for (int b = 0; b < 256; ++b) t[std::size_t(b)] = srgbToLinear(float(b) / 255.0f);
    return t;
}();

const std::array<std::uint16_t, 256> kDecode16 = [] {
    std::array<std::uint16_t, 256> t{};
    for (int b = 0; b < 256; ++b) {
        const double x = double(b) / 255.0;
        const double l = x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
        t[std::size_t(b)] = std::uint16_t(std::lround(l * 65535.0));
    }
    return t;
}();

// kMidpoints[k] = decode((k + 0.5) / 255): the linear value whose encoding lies halfway between
// bytes k and k + 1, so l above it encodes, rounded to the nearest byte, to k + 1 or more.
const std::array<float, 255> kMidpoints = [] {
    std::array<float, 255> m{};
    for (std::size_t k = 0; k < 255; ++k) m[k] = srgbToLinear(float((double(k) + 0.5) / 255.0));
    return m;
}();

// The encoder's buckets (SrgbTables::encodeBits): bucket i holds the floats whose top 16 bits
// are kSrgbEncodeFirst + i (i = 0 also every float below 2^-13, none of which reaches the first
// midpoint, 1.5e-4). Its entry: the number of midpoints below its first float, and the low 16
// bits of the midpoint inside it, 0xFFFF when there is none. The midpoints are farther apart
// than any bucket is wide (1 / (12.92 x 255) on the linear segment; at least 0.0059 in [0.5, 1),
// where buckets are 0.0039 wide), so a bucket holds at most one (the tests check it).
const SrgbTables kTables = [] {
    SrgbTables t{};
    for (std::size_t b = 0; b < 256; ++b) std::memcpy(&t.decodeBits[b], &kDecode[b], 4);
    std::size_t k = 0;
    for (std::uint32_t i = 0; i < std::uint32_t(kSrgbEncodeBuckets); ++i) {
        const std::uint32_t top = std::uint32_t(kSrgbEncodeFirst) + i;
        float first;
        const std::uint32_t firstBits = top << 16;
        std::memcpy(&first, &firstBits, 4);
        while (k < kMidpoints.size() && kMidpoints[k] < first) ++k;
        std::uint32_t threshold = 0xFFFFu;
        if (k < kMidpoints.size()) {
            std::uint32_t mid;
            std::memcpy(&mid, &kMidpoints[k], 4);
            if ((mid >> 16) == top) threshold = mid & 0xFFFFu;
        }
        t.encodeBits[i] = std::uint32_t(k) | threshold << 16;
    }
    return t;
}();

} // namespace

const std::array<float, 256>& srgbDecodeTable() { return kDecode; }
const std::array<std::uint16_t, 256>& srgbDecode16Table() { return kDecode16; }
const SrgbTables& srgbTables() { return kTables; }

std::uint8_t encodeSrgb8(float l) {
    if (!(l > 0.0f)) return 0; // NaN, negatives
    if (l >= 1.0f) return 255;
    // The number of midpoints below l is the nearest byte (ties, l == a midpoint, go down): those
    // below l's bucket, plus its own where l lies above it.
    std::uint32_t bits;
    std::memcpy(&bits, &l, 4);
    const std::uint32_t top = bits >> 16;
    const std::uint32_t e = kTables.encodeBits[top > std::uint32_t(kSrgbEncodeFirst) ? top - std::uint32_t(kSrgbEncodeFirst) : 0u];
    return std::uint8_t((e & 0xFFFFu) + ((bits & 0xFFFFu) > (e >> 16) ? 1u : 0u));
}

const char* toneMapName(ToneMap t) {
    switch (t) {
    case ToneMap::None: return "none";
    case ToneMap::Aces: return "aces";
    case ToneMap::Neutral: return "neutral";
    }
    return "?";
}

std::optional<ToneMap> parseToneMap(std::string_view text) {
    for (ToneMap t : {ToneMap::None, ToneMap::Aces, ToneMap::Neutral})
        if (text == toneMapName(t)) return t;
    return std::nullopt;
}

Color toneMap(Color c, ToneMap op, float exposureScale) {
    c.r *= exposureScale;
    c.g *= exposureScale;
    c.b *= exposureScale;
    switch (op) {
    case ToneMap::None: break;
    case ToneMap::Aces: {
        const auto f = [](float x) {
            x = std::max(x, 0.0f);
            return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
        };
        c = {f(c.r), f(c.g), f(c.b), c.a};
        break;
    }
    case ToneMap::Neutral: {
        // Khronos PBR Neutral tone mapper (github.com/KhronosGroup/ToneMapping, PBR_Neutral).
        constexpr float kStart = 0.8f - 0.04f, kDesaturation = 0.15f;
        const float x = std::min(c.r, std::min(c.g, c.b));
        const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
        c.r -= offset;
        c.g -= offset;
        c.b -= offset;
        const float peak = std::max(c.r, std::max(c.g, c.b));
        if (!(peak >= kStart)) break; // includes NaN: left to the encoder's clamp
        constexpr float d = 1.0f - kStart;
        const float newPeak = 1.0f - d * d / (peak + d - kStart);
        const float s = newPeak / peak;
        c.r *= s;
        c.g *= s;
        c.b *= s;
        const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
        c.r += (newPeak - c.r) * g;
        c.g += (newPeak - c.g) * g;
        c.b += (newPeak - c.b) * g;
        break;
    }
    }
    return c;
}

std::uint32_t packLinearBgra8(Color linear, ToneMap op, float exposureScale) {
    if (op != ToneMap::None || exposureScale != 1.0f) linear = toneMap(linear, op, exposureScale);
    return 0xFF000000u | (std::uint32_t(encodeSrgb8(linear.r)) << 16) | (std::uint32_t(encodeSrgb8(linear.g)) << 8) |
           std::uint32_t(encodeSrgb8(linear.b));
}

Color unpackLinearBgra8(std::uint32_t pixel) {
    const auto& d = srgbDecodeTable();
    return {d[(pixel >> 16) & 0xFFu], d[(pixel >> 8) & 0xFFu], d[pixel & 0xFFu], 1.0f};
}

} // namespace sr
