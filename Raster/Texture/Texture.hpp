// Texture: RGBA8 texel storage with its full mip chain, and GL-style nearest/bilinear/trilinear sampling.
// Storage and the mip chain: Texture.cpp; the samplers: TextureSampling.cpp.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"

namespace sr {

// Filters, named after their OpenGL 4.5 core equivalents (section 8.14, texture minification):
//  Nearest   = GL_NEAREST                 (base level, the texel containing the sample point)
//  Bilinear  = GL_LINEAR                  (base level, 2x2 texels around the point)
//  Trilinear = GL_LINEAR_MIPMAP_LINEAR    (GL_LINEAR in the two levels nearest the lod, blended)
enum class TextureFilter { Nearest, Bilinear, Trilinear };
// Wrap modes (OpenGL 4.5 core section 8.14.2, coordinate wrapping and texel selection):
//  Repeat = GL_REPEAT, Clamp = GL_CLAMP_TO_EDGE, Mirror = GL_MIRRORED_REPEAT.
enum class WrapMode { Repeat, Clamp, Mirror };
// A wrap mode per axis: u (a glTF sampler's wrapS) and v (its wrapT).
struct WrapModes {
    WrapMode u = WrapMode::Repeat, v = WrapMode::Repeat;
    bool operator==(const WrapModes& o) const { return u == o.u && v == o.v; }
    bool operator!=(const WrapModes& o) const { return !(*this == o); }
};

// The uv period of a wrap mode: 1 for Repeat, 2 for Mirror, 0 for Clamp (not periodic).
constexpr double wrapPeriod(WrapMode wrap) {
    return wrap == WrapMode::Repeat ? 1.0 : wrap == WrapMode::Mirror ? 2.0 : 0.0;
}

// "nearest" | "bilinear" | "trilinear" and back; parse is exact and case-sensitive (nullopt else).
const char* filterName(TextureFilter filter);
std::optional<TextureFilter> parseFilter(std::string_view name);
// "repeat" | "clamp" | "mirror" and back.
const char* wrapName(WrapMode wrap);
std::optional<WrapMode> parseWrap(std::string_view name);

// Largest supported width or height (image decoders reject anything larger before we get here).
inline constexpr int kMaxTextureSize = 16384;

// An immutable RGBA8 texture with all its mip levels.
//
// Orientation: texture coordinates follow OBJ/OpenGL: uv (0, 0) is the BOTTOM-left corner of the
// image, v grows upwards. fromRgba8() takes the decoder's top-row-first bytes and stores the rows
// bottom row first, so texel row y of level 0 is image row (height - 1 - y) and v maps directly
// (what stbi_set_flip_vertically_on_load(1) does for the llvmpipe reference).
//
// Texels are packed RGBA8 in a uint32 (r | g << 8 | b << 16 | a << 24, i.e. memory bytes R, G, B, A
// on little-endian). A channel byte b reads as the float b / 255.0f (exactly sr::fromRgba8's
// value). RGBA8 rather than float storage: 4x less memory traffic per bilinear fetch, and the
// reference renderer (Mesa llvmpipe, GL_RGBA8) filters the very same 8-bit values.
//
// Mip chain (built once, at creation), down to 1x1: level k+1 has size max(1, floor(w_k / 2)) x
// max(1, floor(h_k / 2)) - the sizes of OpenGL 4.5 section 8.14.3 (mipmapping). Each texel is a
// box filter of the level above: the 2x2 block (2x, 2y)..(2x+1, 2y+1); along an axis of ODD
// length > 1 the last destination texel also takes the odd edge texel (3 source texels on that
// axis, so a 3x3 block at an odd x odd corner), and an axis of length 1 is not filtered. All
// source texels of a block weigh the same. Each level is computed from the previous STORED
// (8-bit) level, as glGenerateMipmap does, per channel: exact integer sum / count, rounded to
// nearest with ties to even. Alpha is filtered like the colour channels (not premultiplied).
//
// Coordinate policies (every sampling entry point below, and the tests' reference sampler):
//  - Far-away uvs keep their precision: every float uv is handled exactly. For Repeat, |u| >= 1
//    is first reduced to u - floor(u) (exact: the fraction bits of a float are representable); for
//    Mirror, |u| >= 2 to u - 2 floor(u / 2); for Clamp, u is clamped into [-1, 2] (everything
//    beyond samples the same edge texels). The texel coordinate u * size (- 0.5) is then formed in
//    double. So u = 1e6 + 0.375 samples exactly what u = 0.375 samples (both exact floats).
//  - NaN coordinates: a NaN u (or v) selects texel column (row) 0 with weight 1 on that axis,
//    for every filter and wrap mode. +-Inf: Clamp clamps it to the edge texel; Repeat and Mirror
//    have no position for it and treat it like NaN. Never undefined behaviour.
//  - lod (trilinear): NaN -> 0; clamped to [0, levelCount() - 1].
class Texture {
public:
    // A 1x1 opaque white texture (sampling it returns (1, 1, 1, 1)).
    Texture();

    // Builds the texture and its mip chain from width * height RGBA8 pixels, TOP row first (as
    // image decoders produce them). Preconditions (asserted): 1 <= width, height <= kMaxTextureSize
    // and a non-null pointer; release builds return a 1x1 opaque magenta texture instead.
    static Texture fromRgba8(int width, int height, const std::uint8_t* rgbaTopRowFirst);

    int width() const { return levels_[0].width; }
    int height() const { return levels_[0].height; }
    int levelCount() const { return int(levels_.size()); }
    // Levels [0, halvingLevels()) have along each axis either the base size / 2^k exactly (no
    // rounding on the way down) or size 1: a texel coordinate on such a level follows from the
    // base level's by a shift (the SIMD trilinear sampler's levelX). Every level of a
    // power-of-two texture; levels 0-5 of a 640 x 480 one (480 / 2^6 is not whole).
    int halvingLevels() const { return halvingLevels_; }
    int levelWidth(int level) const { return levels_[std::size_t(level)].width; }
    int levelHeight(int level) const { return levels_[std::size_t(level)].height; }
    // Whether any base-level texel has alpha below 255 (then so may every filtered value; else
    // every sample's alpha is exactly 1). Found once, at creation.
    bool hasAlpha() const { return hasAlpha_; }

    // Texel (x, y) of `level`, y = 0 the BOTTOM row. Preconditions (asserted): valid indices.
    std::uint32_t texel(int level, int x, int y) const;
    Color texelColor(int level, int x, int y) const;

    // One level's storage, for the SIMD samplers of Raster/Fill/Kernels: packed RGBA8 texels, bottom
    // row first, texel (x, y) at texels[y * stride + x]; mask = size - 1 for a power-of-two size,
    // else 0. stride = width + 1: each row ends with a copy of its texel 0 (texels[y * stride +
    // width]), so that a texel and its right neighbour under GL_REPEAT lie next to each other in
    // memory for every x, the last one included: one 64-bit load fetches a bilinear pair.
    // decoded: the level's decoded storage (decodedLevelView only, else null).
    struct LevelView {
        const std::uint32_t* texels = nullptr;
        int width = 0, height = 0, stride = 0;
        std::uint32_t maskX = 0, maskY = 0;
        const std::uint32_t* decoded = nullptr;
    };
    LevelView levelView(int level) const {
        const Level& l = levels_[std::size_t(level)];
        return {l.texels.data(), l.width, l.height, l.stride(), l.maskX, l.maskY, nullptr};
    }
    // The same with the level's decoded storage for linear light: texel (x, y) as two 32-bit words
    // at decoded[2 (y * stride + x)], r | g << 16 and b | a << 16, the colour channels the 16-bit
    // linear values of srgbDecode16Table (ColorSpace.hpp), alpha a * 257 (a / 255 in 16 bits).
    // Made from every level the first time any level is asked for (once, thread-safe), so a
    // texture never sampled in linear light holds none.
    LevelView decodedLevelView(int level) const;

    // --- Sampling -------------------------------------------------------------------------------
    // General entry: Nearest and Bilinear read the base level and ignore lod; Trilinear uses lod
    // (see mipLevel() in TextureLod.hpp). Dispatches to the specialised paths below.
    Color sample(Vec2 uv, float lod, TextureFilter filter, WrapMode wrap) const;
    // The same with its own wrap mode on each axis: each axis's taps wrapped by its mode (the
    // same operations: {w, w} returns exactly sample(..., w)).
    Color sample(Vec2 uv, float lod, TextureFilter filter, WrapModes wrap) const;

    // Specialised paths (one loop per wrap mode, power-of-two masks, a byte -> float table).
    // GL_NEAREST on the base level: texel floor(u * W), floor(v * H), wrapped.
    Color sampleNearest(Vec2 uv, WrapMode wrap) const;
    // GL_LINEAR on the base level: texel centres at +0.5, i.e. the 2x2 texels around
    // (u * W - 0.5, v * H - 0.5). The fractions are taken in 8-bit fixed point (X = 256 x rounded to
    // nearest, i0 = X >> 8, weight w = X & 255: the 8 sub-texel bits of Direct3D 10+ hardware and of
    // llvmpipe's AoS sampler) and the blend
    //   ((t00 (256 - wx) + t10 wx) (256 - wy) + (t01 (256 - wx) + t11 wx) wy) / (255 * 65536)
    // is exact in integers, rounded ONCE to float. Hence: at a texel centre the result is the
    // texel exactly (byte / 255.0f); halfway between two texels it is the correctly rounded
    // (a + b) / 510; a region of equal texels returns that texel exactly at every uv.
    Color sampleBilinear(Vec2 uv, WrapMode wrap) const;
    // GL_LINEAR_MIPMAP_LINEAR: lod clamped to [0, levelCount() - 1]; GL_LINEAR in levels floor(lod)
    // and floor(lod) + 1, blended by frac(lod) in 8-bit fixed point (wl = floor(256 frac), the
    // integer blends mixed as (c0 (256 - wl) + c1 wl + 128) >> 8). wl == 0 and the last level
    // read one level only.
    Color sampleTrilinear(Vec2 uv, float lod, WrapMode wrap) const;

    // The same filters on decoded texels (linear light, ColorSpace.hpp): the colour channels
    // decoded from sRGB BEFORE they are weighted (as a GPU samples an SRGB8_ALPHA8 texture), from
    // the decoded storage (decodedLevelView: 16-bit linear values d, alpha a * 257); same taps and
    // 8-bit weights as the paths above. Nearest: d / 65535. Bilinear, per channel: the rows
    // t0 (256 - wx) + t1 wx in integers (below 2^24, exact in float), then
    // (row0 (256 - wy) + row1 wy) / (65535 * 65536) in float: at a texel centre exactly d / 65535.
    // Trilinear: the two levels' results mixed in float, c0 + (c1 - c0) wl / 256. The mip levels
    // are those of the stored bytes, decoded.
    Color sampleSrgb(Vec2 uv, float lod, TextureFilter filter, WrapMode wrap) const;
    Color sampleSrgb(Vec2 uv, float lod, TextureFilter filter, WrapModes wrap) const;

    // The fast paths above are tested bit-identical to a straightforward reference of sample()
    // (generic per-texel wrap and fetch through this public API, no specialisation): the test-only
    // sampleReference of Tests/Texture/TextureReference.hpp.

private:
    struct Level {
        int width = 0, height = 0;
        std::uint32_t maskX = 0, maskY = 0; // width - 1 / height - 1 when a power of two, else 0
        // Packed RGBA8, bottom row first; each row is followed by a copy of its first texel
        // (LevelView: the GL_REPEAT neighbour of its last), set by padRows.
        std::vector<std::uint32_t> texels;
        int stride() const { return width + 1; }
        std::uint32_t* row(int y) { return texels.data() + std::size_t(y) * std::size_t(stride()); }
        const std::uint32_t* row(int y) const { return texels.data() + std::size_t(y) * std::size_t(stride()); }
        void padRows(); // copies each row's texel 0 after its last
    };

    static Level makeLevel(int width, int height);
    static Level downsample(const Level& src);

    // The decoded storage of every level (decodedLevelView), made once on first use; shared by
    // copies, which hold the same texels.
    struct Decoded {
        std::once_flag once;
        std::vector<std::vector<std::uint32_t>> levels;
    };
    const Decoded& decoded() const;

    std::vector<Level> levels_; // levels_[0] is the base level; never empty
    std::shared_ptr<Decoded> decoded_ = std::make_shared<Decoded>();
    bool hasAlpha_ = false;
    int halvingLevels_ = 1;
};

} // namespace sr
