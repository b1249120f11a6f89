// Texture: RGBA8 storage, box-filtered mip chain, and the fast and reference GL-style samplers.
#include "Texture.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace sr {

// --- Names ------------------------------------------------------------------------------------
const char* filterName(TextureFilter filter) {
    switch (filter) {
    case TextureFilter::Nearest: return "nearest";
    case TextureFilter::Bilinear: return "bilinear";
    case TextureFilter::Trilinear: return "trilinear";
    }
    return "?";
}

std::optional<TextureFilter> parseFilter(std::string_view name) {
    if (name == "nearest") return TextureFilter::Nearest;
    if (name == "bilinear") return TextureFilter::Bilinear;
    if (name == "trilinear") return TextureFilter::Trilinear;
    return std::nullopt;
}

const char* wrapName(WrapMode wrap) {
    switch (wrap) {
    case WrapMode::Repeat: return "repeat";
    case WrapMode::Clamp: return "clamp";
    case WrapMode::Mirror: return "mirror";
    }
    return "?";
}

std::optional<WrapMode> parseWrap(std::string_view name) {
    if (name == "repeat") return WrapMode::Repeat;
    if (name == "clamp") return WrapMode::Clamp;
    if (name == "mirror") return WrapMode::Mirror;
    return std::nullopt;
}

namespace {

// byte -> byte / 255.0f, the same value sr::fromRgba8 produces (division is correctly rounded
// both at compile time and at run time).
constexpr std::array<float, 256> makeUnormTable() {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = float(i) / 255.0f;
    return t;
}
constexpr std::array<float, 256> kUnorm8 = makeUnormTable();

constexpr std::uint32_t packRgba(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a) {
    return r | (g << 8) | (b << 16) | (a << 24);
}

Color unpackColor(std::uint32_t t) {
    return {kUnorm8[t & 0xFFu], kUnorm8[(t >> 8) & 0xFFu], kUnorm8[(t >> 16) & 0xFFu], kUnorm8[t >> 24]};
}

bool isPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

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
inline Color toColor(const Raw& r) {
    return {float(r.c[0]) / kRawScale, float(r.c[1]) / kRawScale, float(r.c[2]) / kRawScale, float(r.c[3]) / kRawScale};
}
// The mip blend weight: frac(lod) in 8-bit fixed point, floor(frac * 256).
inline int lodWeight(float frac) { return int(frac * 256.0f); }

// Integer division rounded to nearest, ties to even (n >= 0, d > 0).
std::uint32_t divRoundEven(std::uint32_t n, std::uint32_t d) {
    const std::uint32_t q = n / d, r = n % d;
    if (2 * r > d || (2 * r == d && (q & 1u))) return q + 1;
    return q;
}

} // namespace

// --- Fast paths ---------------------------------------------------------------------------------
// The specialised GL_LINEAR / GL_NEAREST loops live in a struct with access to Level.
struct TextureSampling {
    template <WrapMode kWrap, class Level>
    static Raw bilinear(const Level& l, Vec2 uv) {
        const LinearTaps tx = linearTaps(uv.x, l.width, kWrap);
        const LinearTaps ty = linearTaps(uv.y, l.height, kWrap);
        int x0, x1, y0, y1;
        Wrap<kWrap>::pair(tx.i0, l.width, l.maskX, x0, x1);
        Wrap<kWrap>::pair(ty.i0, l.height, l.maskY, y0, y1);
        const std::uint32_t* row0 = l.texels.data() + std::size_t(y0) * std::size_t(l.width);
        const std::uint32_t* row1 = l.texels.data() + std::size_t(y1) * std::size_t(l.width);
        return blend2x2(row0[x0], row0[x1], row1[x0], row1[x1], tx.w, ty.w);
    }

    template <WrapMode kWrap, class Level>
    static Color nearest(const Level& l, Vec2 uv) {
        const int x = Wrap<kWrap>::one(nearestTap(uv.x, l.width, kWrap), l.width, l.maskX);
        const int y = Wrap<kWrap>::one(nearestTap(uv.y, l.height, kWrap), l.height, l.maskY);
        return unpackColor(l.texels[std::size_t(y) * std::size_t(l.width) + std::size_t(x)]);
    }

    template <WrapMode kWrap, class Levels>
    static Raw trilinear(const Levels& levels, Vec2 uv, float lod) {
        const int last = int(levels.size()) - 1;
        if (!(lod > 0.0f)) lod = 0.0f; // NaN and magnification -> base level
        if (lod >= float(last)) return bilinear<kWrap>(levels[std::size_t(last)], uv);
        const int level = int(lod); // floor: 0 <= lod < last
        const int wl = lodWeight(lod - float(level));
        const Raw c0 = bilinear<kWrap>(levels[std::size_t(level)], uv);
        if (wl == 0) return c0; // == blendLevels(c0, c1, 0) exactly
        return blendLevels(c0, bilinear<kWrap>(levels[std::size_t(level) + 1], uv), wl);
    }
};

Color Texture::sampleNearest(Vec2 uv, WrapMode wrap) const {
    const Level& l = levels_[0];
    switch (wrap) {
    case WrapMode::Repeat: return TextureSampling::nearest<WrapMode::Repeat>(l, uv);
    case WrapMode::Clamp: return TextureSampling::nearest<WrapMode::Clamp>(l, uv);
    case WrapMode::Mirror: return TextureSampling::nearest<WrapMode::Mirror>(l, uv);
    }
    return {};
}

Color Texture::sampleBilinear(Vec2 uv, WrapMode wrap) const {
    const Level& l = levels_[0];
    switch (wrap) {
    case WrapMode::Repeat: return toColor(TextureSampling::bilinear<WrapMode::Repeat>(l, uv));
    case WrapMode::Clamp: return toColor(TextureSampling::bilinear<WrapMode::Clamp>(l, uv));
    case WrapMode::Mirror: return toColor(TextureSampling::bilinear<WrapMode::Mirror>(l, uv));
    }
    return {};
}

Color Texture::sampleTrilinear(Vec2 uv, float lod, WrapMode wrap) const {
    switch (wrap) {
    case WrapMode::Repeat: return toColor(TextureSampling::trilinear<WrapMode::Repeat>(levels_, uv, lod));
    case WrapMode::Clamp: return toColor(TextureSampling::trilinear<WrapMode::Clamp>(levels_, uv, lod));
    case WrapMode::Mirror: return toColor(TextureSampling::trilinear<WrapMode::Mirror>(levels_, uv, lod));
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

// --- Reference path -----------------------------------------------------------------------------
Color Texture::nearestReference(const Level& l, Vec2 uv, WrapMode wrap) const {
    const int x = wrapReference(nearestTap(uv.x, l.width, wrap), l.width, wrap);
    const int y = wrapReference(nearestTap(uv.y, l.height, wrap), l.height, wrap);
    return unpackColor(l.texels[std::size_t(y) * std::size_t(l.width) + std::size_t(x)]);
}

// Straightforward GL_LINEAR: each of the 2x2 texels wrapped and fetched on its own, with the
// weights as fractions k / 256 in double. raw = 65536 * sum(texel * weight) is the integer blend
// (exact in double: every term is a small dyadic rational).
void Texture::bilinearReferenceRaw(const Level& l, Vec2 uv, WrapMode wrap, double raw[4]) const {
    const LinearTaps tx = linearTaps(uv.x, l.width, wrap);
    const LinearTaps ty = linearTaps(uv.y, l.height, wrap);
    const double fx = tx.w / 256.0, fy = ty.w / 256.0;
    for (int c = 0; c < 4; ++c) raw[c] = 0.0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const int x = wrapReference(tx.i0 + i, l.width, wrap), y = wrapReference(ty.i0 + j, l.height, wrap);
            const std::uint32_t t = l.texels[std::size_t(y) * std::size_t(l.width) + std::size_t(x)];
            const double weight = (i ? fx : 1.0 - fx) * (j ? fy : 1.0 - fy);
            for (int c = 0; c < 4; ++c) raw[c] += double((t >> (8 * c)) & 0xFFu) * weight * 65536.0;
        }
}

Color Texture::sampleReference(Vec2 uv, float lod, TextureFilter filter, WrapMode wrap) const {
    // raw / (255 * 65536) per channel, rounded once to float.
    auto toColorRef = [](const double raw[4]) {
        return Color{float(raw[0]) / (255.0f * 65536.0f), float(raw[1]) / (255.0f * 65536.0f),
                     float(raw[2]) / (255.0f * 65536.0f), float(raw[3]) / (255.0f * 65536.0f)};
    };
    switch (filter) {
    case TextureFilter::Nearest: return nearestReference(levels_[0], uv, wrap);
    case TextureFilter::Bilinear: {
        double raw[4];
        bilinearReferenceRaw(levels_[0], uv, wrap, raw);
        return toColorRef(raw);
    }
    case TextureFilter::Trilinear: {
        // OpenGL 4.5 core 8.14.3: d1 = floor(lambda), d2 = d1 + 1, blended by frac(lambda) (here in
        // 8-bit fixed point, the blend rounded half up at the raw scale); at or beyond the last level
        // q, d1 = d2 = q.
        const float q = float(levelCount() - 1);
        const float lambda = std::isnan(lod) ? 0.0f : std::clamp(lod, 0.0f, q);
        const float d1 = std::floor(lambda);
        const float d2 = std::min(d1 + 1.0f, q);
        const double wl = std::floor(double(lambda - d1) * 256.0);
        double raw1[4], raw2[4], mixed[4];
        bilinearReferenceRaw(levels_[std::size_t(d1)], uv, wrap, raw1);
        bilinearReferenceRaw(levels_[std::size_t(d2)], uv, wrap, raw2);
        for (int c = 0; c < 4; ++c) mixed[c] = std::floor((raw1[c] * (256.0 - wl) + raw2[c] * wl + 128.0) / 256.0);
        return toColorRef(mixed);
    }
    }
    return {};
}

// --- Storage and the mip chain --------------------------------------------------------------------
Texture::Level Texture::makeLevel(int width, int height) {
    Level l;
    l.width = width;
    l.height = height;
    l.maskX = isPowerOfTwo(width) ? std::uint32_t(width - 1) : 0u;
    l.maskY = isPowerOfTwo(height) ? std::uint32_t(height - 1) : 0u;
    // A size of 1 is a power of two with mask 0: the generic branch handles it (index 0 always).
    l.texels.assign(std::size_t(width) * std::size_t(height), 0u);
    return l;
}

// One box-filter step (see the header): destination texel x takes source texels 2x, 2x + 1, and
// 2x + 2 as well when it is the last one and the source length is odd; a length of 1 maps to itself.
Texture::Level Texture::downsample(const Level& src) {
    const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
    Level dst = makeLevel(w, h);
    auto span = [](int i, int srcSize, int dstSize, int& first, int& count) {
        if (srcSize == 1) {
            first = 0;
            count = 1;
            return;
        }
        first = 2 * i;
        count = (i == dstSize - 1 && (srcSize & 1)) ? 3 : 2;
    };
    for (int y = 0; y < h; ++y) {
        int y0, ny;
        span(y, src.height, h, y0, ny);
        for (int x = 0; x < w; ++x) {
            int x0, nx;
            span(x, src.width, w, x0, nx);
            std::uint32_t sum[4] = {0, 0, 0, 0};
            for (int j = y0; j < y0 + ny; ++j)
                for (int i = x0; i < x0 + nx; ++i) {
                    const std::uint32_t t = src.texels[std::size_t(j) * std::size_t(src.width) + std::size_t(i)];
                    for (int c = 0; c < 4; ++c) sum[c] += (t >> (8 * c)) & 0xFFu;
                }
            const std::uint32_t n = std::uint32_t(nx * ny);
            dst.texels[std::size_t(y) * std::size_t(w) + std::size_t(x)] =
                packRgba(divRoundEven(sum[0], n), divRoundEven(sum[1], n), divRoundEven(sum[2], n),
                         divRoundEven(sum[3], n));
        }
    }
    return dst;
}

Texture::Texture() {
    levels_.push_back(makeLevel(1, 1));
    levels_[0].texels[0] = 0xFFFFFFFFu;
}

Texture Texture::fromRgba8(int width, int height, const std::uint8_t* rgbaTopRowFirst) {
    assert(width >= 1 && width <= kMaxTextureSize && height >= 1 && height <= kMaxTextureSize);
    assert(rgbaTopRowFirst != nullptr);
    Texture t;
    if (width < 1 || width > kMaxTextureSize || height < 1 || height > kMaxTextureSize || !rgbaTopRowFirst) {
        t.levels_[0].texels[0] = packRgba(255, 0, 255, 255); // release builds: visible "bad texture"
        return t;
    }
    t.levels_.clear();
    Level base = makeLevel(width, height);
    // Flip: texel row y (bottom-first) is image row height - 1 - y.
    for (int y = 0; y < height; ++y) {
        const std::uint8_t* src = rgbaTopRowFirst + std::size_t(height - 1 - y) * std::size_t(width) * 4;
        std::uint32_t* dst = base.texels.data() + std::size_t(y) * std::size_t(width);
        for (int x = 0; x < width; ++x, src += 4) dst[x] = packRgba(src[0], src[1], src[2], src[3]);
    }
    t.levels_.push_back(std::move(base));
    while (t.levels_.back().width > 1 || t.levels_.back().height > 1) {
        Level next = downsample(t.levels_.back());
        t.levels_.push_back(std::move(next));
    }
    return t;
}

std::uint32_t Texture::texel(int level, int x, int y) const {
    assert(level >= 0 && level < levelCount());
    const Level& l = levels_[std::size_t(level)];
    assert(x >= 0 && x < l.width && y >= 0 && y < l.height);
    return l.texels[std::size_t(y) * std::size_t(l.width) + std::size_t(x)];
}

Color Texture::texelColor(int level, int x, int y) const { return unpackColor(texel(level, x, y)); }

} // namespace sr
