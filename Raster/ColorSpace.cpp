// The sRGB curve, its decode table and byte encoder, and the tone-mapping operators.
#include "Raster/ColorSpace.hpp"

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

// kBucketStart[i] = the number of midpoints below i / kBuckets: where the search for any l in
// [i / kBuckets, (i + 1) / kBuckets) starts. The midpoints are at least 1 / (12.92 x 255) apart
// (the curve's linear segment; wider above), more than a bucket, so a bucket holds at most one
// and the search takes one step at most.
constexpr int kBuckets = kSrgbBuckets;
const std::array<std::uint8_t, kBuckets> kBucketStart = [] {
    std::array<std::uint8_t, kBuckets> b{};
    std::size_t k = 0;
    for (int i = 0; i < kBuckets; ++i) {
        const float edge = float(i) / float(kBuckets);
        while (k < kMidpoints.size() && kMidpoints[k] < edge) ++k;
        b[std::size_t(i)] = std::uint8_t(k);
    }
    return b;
}();

const SrgbTables kTables = [] {
    SrgbTables t{};
    for (std::size_t b = 0; b < 256; ++b) std::memcpy(&t.decodeBits[b], &kDecode[b], 4);
    for (std::size_t k = 0; k < 255; ++k) std::memcpy(&t.midpointBits[k], &kMidpoints[k], 4);
    const float inf = std::numeric_limits<float>::infinity();
    std::memcpy(&t.midpointBits[255], &inf, 4);
    for (std::size_t i = 0; i < std::size_t(kBuckets); ++i) t.bucketStart[i] = kBucketStart[i];
    return t;
}();

} // namespace

const std::array<float, 256>& srgbDecodeTable() { return kDecode; }
const std::array<std::uint16_t, 256>& srgbDecode16Table() { return kDecode16; }
const SrgbTables& srgbTables() { return kTables; }

std::uint8_t encodeSrgb8(float l) {
    if (!(l > 0.0f)) return 0; // NaN, negatives
    if (l >= 1.0f) return 255;
    // The number of midpoints below l is the nearest byte (ties, l == a midpoint, go down).
    unsigned k = kBucketStart[std::size_t(l * float(kBuckets))];
    while (k < kMidpoints.size() && kMidpoints[k] < l) ++k;
    return std::uint8_t(k);
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
