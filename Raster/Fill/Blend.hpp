// "Over" blending of a transparent draw's colour onto the target, and the texel alpha modes.
#pragma once

#include "Math/Color.hpp"
#include "Raster/Frame/FrameBuffer.hpp" // Pixel
#include "Raster/Shade/ColorSpace.hpp"

namespace sr {

// src over dst with opacity `alpha` in [0, 1], per channel on the stored 8-bit values taken as
// linear (no sRGB decoding, like the reference's GL_RGBA8 target): c = alpha s + (1 - alpha) d
// with s, d = byte / 255, in float, packed with packBgra8's rounding. Alpha 1 gives src exactly.
inline Pixel blendOver(Pixel src, Pixel dst, float alpha) {
    const float keep = 1.0f - alpha;
    const auto mix = [&](unsigned s, unsigned d) { return float(s) / 255.0f * alpha + float(d) / 255.0f * keep; };
    return packBgra8(Color{mix(pixelR(src), pixelR(dst)), mix(pixelG(src), pixelG(dst)), mix(pixelB(src), pixelB(dst)), 1.0f});
}

// The same in linear light (ColorMode::Linear): both stored pixels decoded from sRGB, mixed in
// float, the result encoded again (encodeSrgb8).
inline Pixel blendOverLinear(Pixel src, Pixel dst, float alpha) {
    const Color s = unpackLinearBgra8(src), d = unpackLinearBgra8(dst);
    const float keep = 1.0f - alpha;
    return packLinearBgra8(Color{s.r * alpha + d.r * keep, s.g * alpha + d.g * keep, s.b * alpha + d.b * keep, 1.0f});
}
inline Pixel blendOver(Pixel src, Pixel dst, float alpha, bool linear) {
    return linear ? blendOverLinear(src, dst, alpha) : blendOver(src, dst, alpha);
}

// Per-fragment opacity from the texture (glTF alphaMode MASK or BLEND with a base colour texture
// whose alpha channel is not all 255): the fragment's alpha is a = factor x the filtered texel's
// alpha (the same filter, wrap and lod as its colour).
//  - Mask: the fragment is kept when a >= cutoff (float comparison) and discarded otherwise:
//    neither its colour nor its depth is written (the depth write waits for the test). Drawn
//    with the opaque draws.
//  - Blend: the fragment is blended "over" the target with a (blendOver), depth tested and not
//    written. Drawn with the transparent draws, sorted.
// Off: no per-fragment alpha (the draw's constant alpha, if any, is all there is). A texture
// without alpha below 255 never turns a mode on (the constant rule gives the same image for
// less work: SceneDraw::texelAlpha is only read when Texture::hasAlpha()).
enum class AlphaMode : unsigned char { Off, Mask, Blend };
struct TexelAlpha {
    AlphaMode mode = AlphaMode::Off;
    float factor = 1.0f; // the material's constant alpha (glTF baseColorFactor alpha)
    float cutoff = 0.5f; // Mask only (glTF alphaCutoff)
    bool linear = false; // Blend in linear light (blendOverLinear); set per draw by the colour mode
    bool on() const { return mode != AlphaMode::Off; }
};

} // namespace sr
