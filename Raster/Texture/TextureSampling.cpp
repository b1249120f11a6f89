// Texture sampling: the scalar GL_NEAREST / GL_LINEAR / GL_LINEAR_MIPMAP_LINEAR fast paths (one loop
// per wrap mode, power-of-two masks, a byte -> float table) and texelColor.
#include "Texture.hpp"

#include "Raster/Shade/ColorSpace.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

namespace sr {

namespace {

// byte -> byte / 255.0f, the same value sr::fromRgba8 produces (division is correctly rounded
// both at compile time and at run time).
constexpr std::array<float, 256> makeUnormTable() {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = float(i) / 255.0f;
    return t;
}
constexpr std::array<float, 256> kUnorm8 = makeUnormTable();

Color unpackColor(std::uint32_t t) {
    return {kUnorm8[t & 0xFFu], kUnorm8[(t >> 8) & 0xFFu], kUnorm8[(t >> 16) & 0xFFu], kUnorm8[t >> 24]};
}

// floor(d) for every double, without the libm call std::floor is on x86-64 without SSE4.1
// (this runs several times per bilinear sample): |d| >= 2^52 (or NaN) is already whole or is
// passed through; below that, truncation towards zero plus a one-step correction is exact.
inline double floorExact(double d) {
    if (!(std::fabs(d) < 4503599627370496.0)) return d;
    const double t = double(std::int64_t(d));
    return t > d ? t - 1.0 : t;
}

// --- Coordinate reduction (OpenGL 4.5 core, 8.14.2): exact for every float input ------------
// Replaces u by an equivalent coordinate of small magnitude, so that u * size is formed without
// losing any bit the float input carries. Returns false when u has no position (NaN; +-Inf
// under Repeat / Mirror): the caller then uses texel 0 with weight 1 on that axis.
//  - Repeat has period 1: for |u| >= 1 the float's fraction u - floor(u) is exact (its bits are a
//    subset of u's), and u * size and frac(u) * size differ by a multiple of size. |u| < 1 is kept
//    as is (for tiny negative u, 1 + u would round to 1 and move GL_NEAREST to the wrong texel).
//  - Mirror has period 2 (u - 2 floor(u / 2), exact for |u| >= 2 likewise).
//  - Clamp: every u <= -1 (>= 2) selects only the first (last) texel, even with GL_LINEAR's
//    half-texel offset; clamping there also turns +-Inf into finite values.
inline bool reduceCoordinate(float u, WrapMode wrap, double& out) {
    if (std::isnan(u)) return false;
    double d = u;
    switch (wrap) {
    case WrapMode::Repeat:
        if (std::isinf(u)) return false;
        if (std::fabs(d) >= 1.0) d -= floorExact(d);
        break;
    case WrapMode::Mirror:
        if (std::isinf(u)) return false;
        if (std::fabs(d) >= 2.0) d -= 2.0 * floorExact(d * 0.5);
        break;
    case WrapMode::Clamp: d = std::clamp(d, -1.0, 2.0); break;
    }
    out = d;
    return true;
}

// GL_LINEAR along one axis (8.14.2): i0 = floor(u * size - 1/2), i1 = i0 + 1, weight of i1 =
// frac(u * size - 1/2), in 8-bit fixed point: X = (u * size - 1/2) * 256 rounded to the nearest
// integer (halves up), i0 = X >> 8 and w = X & 255 (the 8 bits of sub-texel precision of
// Direct3D 10+ and of llvmpipe's AoS sampler; rounding rather than truncating keeps a position a
// hair below a texel centre - e.g. u = 0.5f / 3 - on that centre). After the reduction |u| <= 2,
// so X fits an int comfortably; the double arithmetic is exact except for |u * size| below
// 2^-44, where rounding cannot change X.
struct LinearTaps {
    int i0 = 0; // unwrapped; i1 = i0 + 1
    int w = 0;  // weight of i1 in 1/256, [0, 255]
};
inline LinearTaps linearTaps(float u, int size, WrapMode wrap) {
    double d;
    if (!reduceCoordinate(u, wrap, d)) return {0, 0}; // texel 0 with weight 1 (wraps to itself)
    const int x = int(floorExact((d * double(size) - 0.5) * 256.0 + 0.5));
    return {x >> 8, x & 255}; // arithmetic shift = floor division by 256 (C++20-defined, universal)
}

// GL_NEAREST along one axis: floor(u * size), unwrapped (d * size is exact in double).
inline int nearestTap(float u, int size, WrapMode wrap) {
    double d;
    if (!reduceCoordinate(u, wrap, d)) return 0;
    return int(floorExact(d * double(size)));
}

// --- Fast wrap of an index pair, one specialisation per mode ---------------------------------
// Input ranges after reduceCoordinate(): Repeat i0 in [-size - 1, size - 1], Mirror i0 in
// [-2 size - 1, 2 size - 1], Clamp anything (|i0| <= 2 size + 1).
template <WrapMode kWrap>
struct Wrap;

template <>
struct Wrap<WrapMode::Repeat> {
    static void pair(int i0, int size, std::uint32_t mask, int& a, int& b) {
        if (mask != 0) { // power of two: two's complement & is the positive modulo
            a = int(std::uint32_t(i0) & mask);
            b = int(std::uint32_t(i0 + 1) & mask);
            return;
        }
        a = i0;
        if (a < 0) a += size;
        if (a < 0) a += size;
        b = a + 1 == size ? 0 : a + 1;
    }
    static int one(int i, int size, std::uint32_t mask) {
        if (mask != 0) return int(std::uint32_t(i) & mask);
        return i < 0 ? i + size : i; // nearest: i in [-size, size - 1]
    }
};

template <>
struct Wrap<WrapMode::Clamp> {
    static int one(int i, int size, std::uint32_t) { return i < 0 ? 0 : (i >= size ? size - 1 : i); }
    static void pair(int i0, int size, std::uint32_t mask, int& a, int& b) {
        a = one(i0, size, mask);
        b = one(i0 + 1, size, mask);
    }
};

template <>
struct Wrap<WrapMode::Mirror> {
    // Mirrored repeat is symmetric about -1/2 (index j and -1 - j select the same texel) and has
    // period 2 size.
    static int one(int i, int size, std::uint32_t) {
        int m = i < 0 ? -1 - i : i; // [0, 2 size]
        if (m >= 2 * size) m -= 2 * size;
        return m >= size ? 2 * size - 1 - m : m;
    }
    static void pair(int i0, int size, std::uint32_t mask, int& a, int& b) {
        a = one(i0, size, mask);
        b = one(i0 + 1, size, mask);
    }
};

// --- Fixed-point blending ------------------------------------------------------------------
// A filtered colour is kept as four integers at scale 255 * 65536 (texel bytes times two 8-bit
// weights); Color = raw / (255 * 65536), one correctly rounded float division per channel (raw <
// 2^24 is exact in float). So a texel reads exactly byte / 255.0f, a constant region is exact,
// and the midpoint of two texels is the correctly rounded (a + b) / 510.
struct Raw {
    std::uint32_t c[4];
};
constexpr float kRawScale = 255.0f * 65536.0f;

// The 2x2 blend: ((t00 (256 - wx) + t10 wx) (256 - wy) + (t01 (256 - wx) + t11 wx) wy).
inline Raw blend2x2(std::uint32_t t00, std::uint32_t t10, std::uint32_t t01, std::uint32_t t11, int wx, int wy) {
    const std::uint32_t ax = std::uint32_t(256 - wx), bx = std::uint32_t(wx);
    const std::uint32_t ay = std::uint32_t(256 - wy), by = std::uint32_t(wy);
    Raw r;
    for (int k = 0; k < 4; ++k) {
        const int sh = 8 * k;
        const std::uint32_t bottom = ((t00 >> sh) & 0xFFu) * ax + ((t10 >> sh) & 0xFFu) * bx;
        const std::uint32_t top = ((t01 >> sh) & 0xFFu) * ax + ((t11 >> sh) & 0xFFu) * bx;
        r.c[k] = bottom * ay + top * by;
    }
    return r;
}
// Between two mip levels with an 8-bit weight wl, rounded back to the raw scale (half up).
inline Raw blendLevels(const Raw& a, const Raw& b, int wl) {
    Raw r;
    for (int k = 0; k < 4; ++k)
        r.c[k] = std::uint32_t((std::uint64_t(a.c[k]) * std::uint64_t(256 - wl) + std::uint64_t(b.c[k]) * std::uint64_t(wl) + 128u) >> 8);
    return r;
}
// The decoded bilinear blend's scale: 65535 (16-bit texels) times 65536 (two 8-bit weights).
constexpr float kDecodedScale = 65535.0f * 65536.0f;
inline Color toColor(const Raw& r) {
    return {float(r.c[0]) / kRawScale, float(r.c[1]) / kRawScale, float(r.c[2]) / kRawScale, float(r.c[3]) / kRawScale};
}
// The mip blend weight: frac(lod) in 8-bit fixed point, floor(frac * 256).
inline int lodWeight(float frac) { return int(frac * 256.0f); }

} // namespace

// --- Fast paths ---------------------------------------------------------------------------------
// The specialised GL_LINEAR / GL_NEAREST loops live in a struct with access to Level.
struct TextureSampling {
    // GL_LINEAR's 2x2 texels of a level (wrapped columns x0, x1 and rows y0, y1) and the 8-bit
    // weights of x1 and y1; columns wrapped by kU, rows by kV.
    struct Taps {
        int x0, x1, y0, y1, wx, wy;
    };
    template <WrapMode kU, WrapMode kV, class Level>
    static Taps bilinearTaps(const Level& l, Vec2 uv) {
        const LinearTaps tx = linearTaps(uv.x, l.width, kU);
        const LinearTaps ty = linearTaps(uv.y, l.height, kV);
        Taps t;
        Wrap<kU>::pair(tx.i0, l.width, l.maskX, t.x0, t.x1);
        Wrap<kV>::pair(ty.i0, l.height, l.maskY, t.y0, t.y1);
        t.wx = tx.w;
        t.wy = ty.w;
        return t;
    }

    template <WrapMode kU, WrapMode kV, class Level>
    static Raw bilinear(const Level& l, Vec2 uv) {
        const Taps t = bilinearTaps<kU, kV>(l, uv);
        const std::uint32_t* row0 = l.row(t.y0);
        const std::uint32_t* row1 = l.row(t.y1);
        return blend2x2(row0[t.x0], row0[t.x1], row1[t.x0], row1[t.x1], t.wx, t.wy);
    }

    template <WrapMode kU, WrapMode kV, class Level>
    static Color nearest(const Level& l, Vec2 uv) {
        const int x = Wrap<kU>::one(nearestTap(uv.x, l.width, kU), l.width, l.maskX);
        const int y = Wrap<kV>::one(nearestTap(uv.y, l.height, kV), l.height, l.maskY);
        return unpackColor(l.row(y)[x]);
    }

    template <WrapMode kU, WrapMode kV, class Levels>
    static Raw trilinear(const Levels& levels, Vec2 uv, float lod) {
        const int last = int(levels.size()) - 1;
        if (!(lod > 0.0f)) lod = 0.0f; // NaN and magnification -> base level
        if (lod >= float(last)) return bilinear<kU, kV>(levels[std::size_t(last)], uv);
        const int level = int(lod); // floor: 0 <= lod < last
        const int wl = lodWeight(lod - float(level));
        const Raw c0 = bilinear<kU, kV>(levels[std::size_t(level)], uv);
        if (wl == 0) return c0; // == blendLevels(c0, c1, 0) exactly
        return blendLevels(c0, bilinear<kU, kV>(levels[std::size_t(level) + 1], uv), wl);
    }

    template <WrapMode kU, WrapMode kV, class Levels>
    static Color filtered(const Levels& levels, Vec2 uv, float lod, TextureFilter filter) {
        switch (filter) {
        case TextureFilter::Nearest: return nearest<kU, kV>(levels[0], uv);
        case TextureFilter::Bilinear: return toColor(bilinear<kU, kV>(levels[0], uv));
        case TextureFilter::Trilinear: return toColor(trilinear<kU, kV>(levels, uv, lod));
        }
        return {};
    }

    // The decoded twins (sampleSrgb): the same taps and weights on the decoded storage
    // (Texture::decodedLevelView: two words per texel, r | g << 16 and b | a << 16).
    static Color decoded(const Texture::LevelView& l, int x, int y) {
        const std::uint32_t* t = l.decoded + 2 * (std::size_t(y) * std::size_t(l.stride) + std::size_t(x));
        return {float(t[0] & 0xFFFFu) / 65535.0f, float(t[0] >> 16) / 65535.0f, float(t[1] & 0xFFFFu) / 65535.0f,
                float(t[1] >> 16) / 65535.0f};
    }
    template <WrapMode kU, WrapMode kV>
    static Color bilinearDecoded(const Texture::LevelView& l, Vec2 uv) {
        const Taps t = bilinearTaps<kU, kV>(l, uv);
        auto at = [&](int x, int y) { return l.decoded + 2 * (std::size_t(y) * std::size_t(l.stride) + std::size_t(x)); };
        const std::uint32_t *t00 = at(t.x0, t.y0), *t10 = at(t.x1, t.y0), *t01 = at(t.x0, t.y1), *t11 = at(t.x1, t.y1);
        const std::uint32_t ax = std::uint32_t(256 - t.wx), bx = std::uint32_t(t.wx);
        const float ay = float(256 - t.wy), by = float(t.wy);
        float c[4];
        for (int k = 0; k < 4; ++k) {
            const int word = k >> 1, sh = 16 * (k & 1);
            const std::uint32_t row0 = ((t00[word] >> sh) & 0xFFFFu) * ax + ((t10[word] >> sh) & 0xFFFFu) * bx;
            const std::uint32_t row1 = ((t01[word] >> sh) & 0xFFFFu) * ax + ((t11[word] >> sh) & 0xFFFFu) * bx;
            c[k] = (float(row0) * ay + float(row1) * by) / kDecodedScale;
        }
        return {c[0], c[1], c[2], c[3]};
    }
    template <WrapMode kU, WrapMode kV>
    static Color sampleDecoded(const Texture& texture, Vec2 uv, float lod, TextureFilter filter) {
        if (filter == TextureFilter::Nearest) {
            const Texture::LevelView base = texture.decodedLevelView(0);
            const int x = Wrap<kU>::one(nearestTap(uv.x, base.width, kU), base.width, base.maskX);
            const int y = Wrap<kV>::one(nearestTap(uv.y, base.height, kV), base.height, base.maskY);
            return decoded(base, x, y);
        }
        if (filter == TextureFilter::Bilinear) return bilinearDecoded<kU, kV>(texture.decodedLevelView(0), uv);
        const int last = texture.levelCount() - 1;
        if (!(lod > 0.0f)) lod = 0.0f;
        if (lod >= float(last)) return bilinearDecoded<kU, kV>(texture.decodedLevelView(last), uv);
        const int level = int(lod);
        const int wl = lodWeight(lod - float(level));
        const Color c0 = bilinearDecoded<kU, kV>(texture.decodedLevelView(level), uv);
        if (wl == 0) return c0;
        const Color c1 = bilinearDecoded<kU, kV>(texture.decodedLevelView(level + 1), uv);
        const float w = float(wl) / 256.0f;
        return {c0.r + (c1.r - c0.r) * w, c0.g + (c1.g - c0.g) * w, c0.b + (c1.b - c0.b) * w, c0.a + (c1.a - c0.a) * w};
    }

    // fn(kU, kV) for the modes of `wrap` (nine instantiations).
    template <class Fn>
    static Color withWraps(WrapModes wrap, const Fn& fn) {
        const auto along = [&](auto u) {
            switch (wrap.v) {
            case WrapMode::Repeat: return fn(u, std::integral_constant<WrapMode, WrapMode::Repeat>{});
            case WrapMode::Clamp: return fn(u, std::integral_constant<WrapMode, WrapMode::Clamp>{});
            case WrapMode::Mirror: return fn(u, std::integral_constant<WrapMode, WrapMode::Mirror>{});
            }
            return Color{};
        };
        switch (wrap.u) {
        case WrapMode::Repeat: return along(std::integral_constant<WrapMode, WrapMode::Repeat>{});
        case WrapMode::Clamp: return along(std::integral_constant<WrapMode, WrapMode::Clamp>{});
        case WrapMode::Mirror: return along(std::integral_constant<WrapMode, WrapMode::Mirror>{});
        }
        return {};
    }
};

Color Texture::sampleSrgb(Vec2 uv, float lod, TextureFilter filter, WrapMode wrap) const {
    switch (wrap) {
    case WrapMode::Repeat: return TextureSampling::sampleDecoded<WrapMode::Repeat, WrapMode::Repeat>(*this, uv, lod, filter);
    case WrapMode::Clamp: return TextureSampling::sampleDecoded<WrapMode::Clamp, WrapMode::Clamp>(*this, uv, lod, filter);
    case WrapMode::Mirror: return TextureSampling::sampleDecoded<WrapMode::Mirror, WrapMode::Mirror>(*this, uv, lod, filter);
    }
    return {};
}

Color Texture::sampleSrgb(Vec2 uv, float lod, TextureFilter filter, WrapModes wrap) const {
    return TextureSampling::withWraps(wrap, [&](auto u, auto v) {
        return TextureSampling::sampleDecoded<decltype(u)::value, decltype(v)::value>(*this, uv, lod, filter);
    });
}

Color Texture::sampleNearest(Vec2 uv, WrapMode wrap) const {
    const Level& l = levels_[0];
    switch (wrap) {
    case WrapMode::Repeat: return TextureSampling::nearest<WrapMode::Repeat, WrapMode::Repeat>(l, uv);
    case WrapMode::Clamp: return TextureSampling::nearest<WrapMode::Clamp, WrapMode::Clamp>(l, uv);
    case WrapMode::Mirror: return TextureSampling::nearest<WrapMode::Mirror, WrapMode::Mirror>(l, uv);
    }
    return {};
}

Color Texture::sampleBilinear(Vec2 uv, WrapMode wrap) const {
    const Level& l = levels_[0];
    switch (wrap) {
    case WrapMode::Repeat: return toColor(TextureSampling::bilinear<WrapMode::Repeat, WrapMode::Repeat>(l, uv));
    case WrapMode::Clamp: return toColor(TextureSampling::bilinear<WrapMode::Clamp, WrapMode::Clamp>(l, uv));
    case WrapMode::Mirror: return toColor(TextureSampling::bilinear<WrapMode::Mirror, WrapMode::Mirror>(l, uv));
    }
    return {};
}

Color Texture::sampleTrilinear(Vec2 uv, float lod, WrapMode wrap) const {
    switch (wrap) {
    case WrapMode::Repeat: return toColor(TextureSampling::trilinear<WrapMode::Repeat, WrapMode::Repeat>(levels_, uv, lod));
    case WrapMode::Clamp: return toColor(TextureSampling::trilinear<WrapMode::Clamp, WrapMode::Clamp>(levels_, uv, lod));
    case WrapMode::Mirror: return toColor(TextureSampling::trilinear<WrapMode::Mirror, WrapMode::Mirror>(levels_, uv, lod));
    }
    return {};
}

Color Texture::sample(Vec2 uv, float lod, TextureFilter filter, WrapMode wrap) const {
    switch (filter) {
    case TextureFilter::Nearest: return sampleNearest(uv, wrap);
    case TextureFilter::Bilinear: return sampleBilinear(uv, wrap);
    case TextureFilter::Trilinear: return sampleTrilinear(uv, lod, wrap);
    }
    return {};
}

Color Texture::sample(Vec2 uv, float lod, TextureFilter filter, WrapModes wrap) const {
    if (wrap.u == wrap.v) return sample(uv, lod, filter, wrap.u);
    return TextureSampling::withWraps(wrap, [&](auto u, auto v) {
        return TextureSampling::filtered<decltype(u)::value, decltype(v)::value>(levels_, uv, lod, filter);
    });
}

// --- One texel, read as the samplers read it (kUnorm8) ---------------------------------------------
Color Texture::texelColor(int level, int x, int y) const { return unpackColor(texel(level, x, y)); }

} // namespace sr
