// Colour spaces: the sRGB transfer curve, the colour mode of a frame and the tone-mapping operators.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "Math/Color.hpp"

namespace sr {

// How a frame does its colour arithmetic.
//  Gamma:  on display values, as stored (GL_RGBA8's convention and the llvmpipe reference's):
//          texels, material colours and blends are used as they are, the result stored as it is.
//  Linear: in linear light, as the glTF 2.0 specification asks: sRGB colour textures are decoded
//          texel by texel before filtering, colour factors are linear, light adds linearly, and
//          the result is tone-mapped (ToneMap) and encoded with the sRGB curve once per pixel.
enum class ColorMode { Gamma, Linear };

const char* colorModeName(ColorMode mode);
std::optional<ColorMode> parseColorMode(std::string_view text); // "gamma" | "linear", exact

// The sRGB electro-optical transfer function and its inverse, piecewise and exact (IEC 61966-2-1;
// the glTF specification's and OpenGL's sRGB texture formats'):
//   decode: c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4
//   encode: l <= 0.0031308 ? 12.92 l : 1.055 l^(1/2.4) - 0.055
// Computed in double, rounded once to float. encode clamps to [0, 1] (NaN -> 0).
float srgbToLinear(float c);
float linearToSrgb(float l);

// srgbToLinear(b / 255) for every byte b: the decode of one texel channel is a table lookup.
const std::array<float, 256>& srgbDecodeTable();

// The same decode in 16 bits, the texel storage of the linear-light samplers (Texture's decoded
// levels): round(decode(b / 255) 65535), the curve evaluated in double. A texel read back as
// value / 65535 encodes to its byte again (encodeSrgb8), for every byte.
const std::array<std::uint16_t, 256>& srgbDecode16Table();

// A linear channel value as the stored sRGB byte: linearToSrgb(l) rounded to the nearest byte,
// as a GPU's sRGB render target stores it (a value exactly on a midpoint goes down), found by a
// binary search over the 255 linear values that encode to the midpoints between bytes (no pow
// per pixel). encodeSrgb8(srgbDecodeTable()[b]) == b for every byte b.
std::uint8_t encodeSrgb8(float l);

// The tables behind srgbDecodeTable and encodeSrgb8 as 32-bit words, for the vector kernels'
// gathers: decodeBits[b] = the bits of srgbDecodeTable()[b]. encodeSrgb8(l) for l in (0, 1), with
// the float's bits B: the entry e = encodeBits[max(B >> 16, kSrgbEncodeFirst) - kSrgbEncodeFirst]
// gives k = e & 0xFFFF, the number of midpoints between bytes below the floats of that top 16
// bits, and e >> 16, the low 16 bits of the one midpoint among them (0xFFFF if none); l encodes
// to k + 1 where its low 16 bits exceed those, else k. One gather per channel; the buckets start at
// 2^-13 (below it everything encodes to 0) and end at 1.
inline constexpr int kSrgbEncodeFirst = (127 - 13) << 7; // the top 16 bits of 2^-13
inline constexpr int kSrgbEncodeBuckets = (127 << 7) - kSrgbEncodeFirst;
struct SrgbTables {
    std::uint32_t decodeBits[256];
    std::uint32_t encodeBits[kSrgbEncodeBuckets];
};
const SrgbTables& srgbTables();

// Tone mapping of a linear colour before it is encoded (none: clamp only).
//  Aces:    the ACES filmic fit of Narkowicz (2015), x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14).
//  Neutral: Khronos PBR Neutral (2024), hue-preserving, identity below 0.76 - 0.04.
// Every operator first multiplies by 2^exposure.
enum class ToneMap { None, Aces, Neutral };
const char* toneMapName(ToneMap t);
std::optional<ToneMap> parseToneMap(std::string_view text); // "none" | "aces" | "neutral", exact
Color toneMap(Color linear, ToneMap op, float exposureScale);

// The display pixel of a linear colour: tone-mapped, then each channel encoded (encodeSrgb8).
std::uint32_t packLinearBgra8(Color linear, ToneMap op = ToneMap::None, float exposureScale = 1.0f);
// The linear colour of a stored display pixel (each channel decoded; alpha 1).
Color unpackLinearBgra8(std::uint32_t pixel);

} // namespace sr
