// "Over" blending of a transparent draw's colour onto the target, with a constant alpha.
#pragma once

#include "Math/Color.hpp"
#include "Raster/FrameBuffer.hpp" // Pixel

namespace sr {

// src over dst with opacity `alpha` in [0, 1], per channel on the stored 8-bit values taken as
// linear (no sRGB decoding, like the reference's GL_RGBA8 target): c = alpha s + (1 - alpha) d
// with s, d = byte / 255, in float, packed with packBgra8's rounding. Alpha 1 gives src exactly.
inline Pixel blendOver(Pixel src, Pixel dst, float alpha) {
    const float keep = 1.0f - alpha;
    const auto mix = [&](unsigned s, unsigned d) { return float(s) / 255.0f * alpha + float(d) / 255.0f * keep; };
    return packBgra8(Color{mix(pixelR(src), pixelR(dst)), mix(pixelG(src), pixelG(dst)), mix(pixelB(src), pixelB(dst)), 1.0f});
}

} // namespace sr
