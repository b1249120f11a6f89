// Texture sampling at exact positions: each filter and wrap mode, orientation, far/negative/NaN uvs, 1x1 and NPOT.
#include "TestFramework.hpp"

#include <cfloat>
#include <cmath>
#include <vector>

#include "Raster/Shade/ColorSpace.hpp"
#include "TextureReference.hpp"
#include "TextureTestUtil.hpp"

using namespace sr;
using namespace sr::test;

namespace {

const WrapMode kWraps[] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};
const TextureFilter kFilters[] = {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear};

// Every entry point that samples the base level with `filter` (trilinear at lod 0 is GL_LINEAR
// on the base level), fast and reference: all must give the same colour.
std::vector<Color> allBaseSamples(const Texture& t, Vec2 uv, TextureFilter filter, WrapMode wrap) {
    std::vector<Color> out;
    out.push_back(t.sample(uv, 0.0f, filter, wrap));
    out.push_back(sampleReference(t, uv, 0.0f, filter, wrap));
    if (filter == TextureFilter::Nearest) out.push_back(t.sampleNearest(uv, wrap));
    if (filter == TextureFilter::Bilinear) out.push_back(t.sampleBilinear(uv, wrap));
    if (filter == TextureFilter::Trilinear) out.push_back(t.sampleTrilinear(uv, 0.0f, wrap));
    return out;
}

void requireAll(const Texture& t, Vec2 uv, TextureFilter filter, WrapMode wrap, Color expected) {
    INFO("uv = (" << uv.x << ", " << uv.y << "), filter " << filterName(filter) << ", wrap " << wrapName(wrap));
    for (Color c : allBaseSamples(t, uv, filter, wrap)) REQUIRE(bitEqual(c, expected));
}

} // namespace

TEST_CASE("filter and wrap names round-trip and reject anything else", "[texture]") {
    for (TextureFilter f : kFilters) REQUIRE(parseFilter(filterName(f)) == f);
    for (WrapMode w : kWraps) REQUIRE(parseWrap(wrapName(w)) == w);
    REQUIRE(std::string(filterName(TextureFilter::Trilinear)) == "trilinear");
    REQUIRE(std::string(wrapName(WrapMode::Mirror)) == "mirror");
    REQUIRE_FALSE(parseFilter("Bilinear"));
    REQUIRE_FALSE(parseFilter("linear"));
    REQUIRE_FALSE(parseFilter(""));
    REQUIRE_FALSE(parseWrap("clamp_to_edge"));
    REQUIRE_FALSE(parseWrap("repeat "));
}

TEST_CASE("texels read back as byte / 255 with rows stored bottom first", "[texture]") {
    const Texture t = makeTexture(4, 3, distinctTexel);
    REQUIRE(t.width() == 4);
    REQUIRE(t.height() == 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            const Rgba8 e = distinctTexel(x, y);
            REQUIRE(t.texel(0, x, y) == (std::uint32_t(e.r) | std::uint32_t(e.g) << 8 | std::uint32_t(e.b) << 16 |
                                         std::uint32_t(e.a) << 24));
            REQUIRE(bitEqual(t.texelColor(0, x, y), fromRgba8(e.r, e.g, e.b, e.a)));
        }
}

TEST_CASE("v = 0 is the bottom row of the image file (top-row-first bytes are flipped)", "[texture]") {
    // A 2x2 image written top row first: top row red, bottom row blue.
    const std::uint8_t bytes[] = {255, 0, 0, 255, 255, 0, 0, 255,   // image row 0 (top): red
                                  0, 0, 255, 255, 0, 0, 255, 255};  // image row 1 (bottom): blue
    const Texture t = Texture::fromRgba8(2, 2, bytes);
    const Color red{1, 0, 0, 1}, blue{0, 0, 1, 1};
    for (WrapMode w : kWraps)
        for (TextureFilter f : kFilters) {
            requireAll(t, {0.25f, 0.25f}, f, w, blue); // texel centres of the bottom row
            requireAll(t, {0.75f, 0.25f}, f, w, blue);
            requireAll(t, {0.25f, 0.75f}, f, w, red);
        }
    REQUIRE(bitEqual(t.texelColor(0, 0, 0), blue));
    REQUIRE(bitEqual(t.texelColor(0, 1, 1), red));
}

TEST_CASE("nearest and bilinear return the texel exactly at every texel centre", "[texture]") {
    // Power-of-two sizes: the centres (i + 0.5) / size are exact floats.
    for (int size : {1, 2, 4, 8}) {
        const Texture t = makeTexture(size, 2 * size, distinctTexel);
        for (int y = 0; y < 2 * size; ++y)
            for (int x = 0; x < size; ++x) {
                const Vec2 uv{(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(2 * size)};
                for (WrapMode w : kWraps)
                    for (TextureFilter f : kFilters) requireAll(t, uv, f, w, toColor(distinctTexel(x, y)));
            }
    }
}

TEST_CASE("bilinear returns the exact average halfway between texels", "[texture]") {
    const Texture t = makeTexture(4, 4, distinctTexel);
    auto tex = [](int x, int y) { return distinctTexel(x, y); };
    for (WrapMode w : kWraps)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x) {
                // Edge between columns x and x + 1 at the centre of row y; between rows; the corner of four.
                const float uEdge = float(x + 1) / 4.0f, vEdge = float(y + 1) / 4.0f;
                const float uCentre = (float(x) + 0.5f) / 4.0f, vCentre = (float(y) + 0.5f) / 4.0f;
                requireAll(t, {uEdge, vCentre}, TextureFilter::Bilinear, w, average(tex(x, y), tex(x + 1, y)));
                requireAll(t, {uCentre, vEdge}, TextureFilter::Bilinear, w, average(tex(x, y), tex(x, y + 1)));
                requireAll(t, {uEdge, vEdge}, TextureFilter::Bilinear, w,
                           average(tex(x, y), tex(x + 1, y), tex(x, y + 1), tex(x + 1, y + 1)));
                // Nearest at a texel edge takes the texel on the right / above (floor(u W)).
                requireAll(t, {uEdge, vEdge}, TextureFilter::Nearest, w, toColor(tex(x + 1, y + 1)));
            }
}

// One axis of a 4-texel-wide texture: u -> the texel index GL_NEAREST selects for each wrap mode.
// All u are exact floats (1e6 lies in [2^19, 2^20), where floats are spaced 1/16).
struct NearestCase {
    float u;
    int repeat, clamp, mirror;
};
const NearestCase kNearestCases[] = {
    {0.375f, 1, 1, 1},
    {0.0f, 0, 0, 0},
    {-0.0f, 0, 0, 0},
    {1.0f, 0, 3, 3},      // u W = 4: repeat wraps to 0, mirror reflects to 3
    {2.0f, 0, 3, 0},
    {-0.375f, 2, 0, 1},   // floor(-1.5) = -2
    {-1.375f, 2, 0, 2},   // mirror: |u| = 1.375 reflects to 0.625
    {-1e-30f, 3, 0, 0},   // tiny negative: floor(-4e-30) = -1 (1 + u would round to 1 in double)
    {1000000.375f, 1, 3, 1},
    {-999999.625f, 1, 0, 1},    // -1e6 + 0.375
    {1000001.375f, 1, 3, 2},    // odd period for mirror: 1.375 -> 0.625
    {1048576.875f, 3, 3, 3},    // 2^20 + 0.875 (spacing 1/8 there)
    {16777216.0f, 0, 3, 0},     // 2^24: an integer, also for mirror (even)
    {3.0e38f, 0, 3, 0},         // a huge even integer
};

TEST_CASE("nearest: wrap modes for negative and far-away u (exact floats up to 1e6 and beyond)", "[texture]") {
    const Texture t = makeTexture(4, 4, distinctTexel);
    for (const NearestCase& c : kNearestCases) {
        const int expected[3] = {c.repeat, c.clamp, c.mirror};
        for (int k = 0; k < 3; ++k) {
            // The same table on both axes: u at row 2's centre, then v at column 1's centre.
            requireAll(t, {c.u, 0.625f}, TextureFilter::Nearest, kWraps[k], toColor(distinctTexel(expected[k], 2)));
            requireAll(t, {0.375f, c.u}, TextureFilter::Nearest, kWraps[k], toColor(distinctTexel(1, expected[k])));
        }
    }
}

// One axis of a 4-texel-wide texture under GL_LINEAR: the expected blend of texels (a, b) with weight
// 0 (a alone) or 0.5 (the exact average), per wrap mode.
struct LinearCase {
    float u;
    int a[3], b[3];   // per wrap mode (repeat, clamp, mirror); a == b means the texel alone
};
const LinearCase kLinearCases[] = {
    {0.375f, {1, 1, 1}, {1, 1, 1}},
    {0.25f, {0, 0, 0}, {1, 1, 1}},
    {0.0f, {3, 0, 0}, {0, 0, 0}},           // repeat blends across the seam; clamp and mirror do not
    {1.0f, {3, 3, 3}, {0, 3, 3}},
    {-0.25f, {2, 0, 1}, {3, 0, 0}},
    {1000000.0f, {3, 3, 0}, {0, 3, 0}},     // 1e6 is even: mirror as at u = 0
    {-999999.75f, {0, 0, 0}, {1, 0, 1}},    // -1e6 + 0.25
    {1000001.25f, {0, 3, 2}, {1, 3, 3}},    // mirror: 1.25 -> texels 3 and 2 (mirrored) blended
    {1000000.375f, {1, 3, 1}, {1, 3, 1}},
    {-1e-30f, {3, 0, 0}, {0, 0, 0}},
    {16777216.0f, {3, 3, 0}, {0, 3, 0}},
    {3.0e38f, {3, 3, 0}, {0, 3, 0}},
    {-3.0e38f, {3, 0, 0}, {0, 0, 0}},
};

TEST_CASE("bilinear: wrap modes for negative and far-away u, texel centres and seams", "[texture]") {
    const Texture t = makeTexture(4, 4, distinctTexel);
    for (const LinearCase& c : kLinearCases)
        for (int k = 0; k < 3; ++k) {
            auto expectAt = [&](auto texelOf) {
                const Rgba8 ta = texelOf(c.a[k]), tb = texelOf(c.b[k]);
                return c.a[k] == c.b[k] ? toColor(ta) : average(ta, tb);
            };
            requireAll(t, {c.u, 0.625f}, TextureFilter::Bilinear, kWraps[k],
                       expectAt([](int i) { return distinctTexel(i, 2); }));
            requireAll(t, {0.375f, c.u}, TextureFilter::Bilinear, kWraps[k],
                       expectAt([](int i) { return distinctTexel(1, i); }));
        }
}

TEST_CASE("a uv far away samples exactly what its reduced uv samples (all filters, wraps, positions)", "[texture]") {
    const Texture t = makeTexture(8, 4, distinctTexel);
    // Offsets that are whole periods for every wrap mode's period (1 or 2): even integers.
    const float offsets[] = {2.0f, -2.0f, 1000000.0f, -1000000.0f, 4194304.0f};
    for (int i = 0; i <= 64; ++i) {
        const float base = float(i) / 64.0f; // (base + 1e6 is exact only for multiples of 1/16)
        for (float off : offsets) {
            const float u = base + off;
            if (double(u) != double(base) + double(off)) continue; // only exactly representable sums
            for (WrapMode w : {WrapMode::Repeat, WrapMode::Mirror})
                for (TextureFilter f : kFilters) {
                    INFO("base " << base << " offset " << off);
                    REQUIRE(bitEqual(t.sample({u, 0.3f}, 0.7f, f, w), t.sample({base, 0.3f}, 0.7f, f, w)));
                    REQUIRE(bitEqual(t.sample({0.3f, u}, 0.7f, f, w), t.sample({0.3f, base}, 0.7f, f, w)));
                }
        }
    }
}

TEST_CASE("NaN and infinite uvs give defined texels: NaN -> index 0, Inf clamps or acts as NaN", "[texture]") {
    const Texture t = makeTexture(4, 4, distinctTexel);
    const float nan = std::nanf(""), inf = INFINITY;
    auto tex = [](int x, int y) { return toColor(distinctTexel(x, y)); };
    for (WrapMode w : kWraps)
        for (TextureFilter f : kFilters) {
            requireAll(t, {nan, nan}, f, w, tex(0, 0));
            requireAll(t, {nan, 0.625f}, f, w, tex(0, 2));
            requireAll(t, {0.375f, nan}, f, w, tex(1, 0));
            const bool clamp = w == WrapMode::Clamp;
            requireAll(t, {inf, 0.625f}, f, w, clamp ? tex(3, 2) : tex(0, 2));
            requireAll(t, {-inf, 0.625f}, f, w, tex(0, 2));
            requireAll(t, {0.375f, inf}, f, w, clamp ? tex(1, 3) : tex(1, 0));
            // Huge even integers: like (0, 0) for repeat and mirror, the corner texels for clamp.
            if (clamp)
                requireAll(t, {FLT_MAX, -FLT_MAX}, f, w, tex(3, 0));
            else
                requireAll(t, {FLT_MAX, -FLT_MAX}, f, w, t.sample({0.0f, 0.0f}, 0.0f, f, w));
            // A NaN lod selects the base level.
            REQUIRE(bitEqual(t.sample({0.3f, 0.6f}, nan, f, w), t.sample({0.3f, 0.6f}, 0.0f, f, w)));
            REQUIRE(bitEqual(sampleReference(t, {0.3f, 0.6f}, nan, f, w), t.sample({0.3f, 0.6f}, 0.0f, f, w)));
        }
}

TEST_CASE("a 1x1 texture returns its texel for every uv, lod, filter and wrap", "[texture]") {
    const Texture t = makeTexture(1, 1, [](int, int) { return Rgba8{12, 34, 56, 78}; });
    REQUIRE(t.levelCount() == 1);
    const Color c = fromRgba8(12, 34, 56, 78);
    const float nan = std::nanf("");
    const float values[] = {0.0f, 0.5f, 1.0f, -0.25f, 0.9999f, 1e6f + 0.5f, -3e38f, nan, INFINITY};
    for (float u : values)
        for (float v : values)
            for (WrapMode w : kWraps)
                for (TextureFilter f : kFilters) {
                    requireAll(t, {u, v}, f, w, c);
                    for (float lod : {-1.0f, 0.5f, 3.0f, nan}) {
                        REQUIRE(bitEqual(t.sample({u, v}, lod, f, w), c));
                        REQUIRE(bitEqual(sampleReference(t, {u, v}, lod, f, w), c));
                    }
                }
}

TEST_CASE("the default texture is 1x1 opaque white", "[texture]") {
    const Texture t;
    REQUIRE(t.width() == 1);
    REQUIRE(t.height() == 1);
    REQUIRE(t.levelCount() == 1);
    REQUIRE(bitEqual(t.sample({0.3f, 0.7f}, 2.0f, TextureFilter::Trilinear, WrapMode::Repeat), Color{1, 1, 1, 1}));
}

TEST_CASE("a 3x5 (non-power-of-two) texture: centres, edges and wrap seams", "[texture]") {
    const Texture t = makeTexture(3, 5, distinctTexel);
    auto tex = [](int x, int y) { return toColor(distinctTexel(x, y)); };
    auto avg = [](int x0, int y0, int x1, int y1) { return average(distinctTexel(x0, y0), distinctTexel(x1, y1)); };
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 3; ++x) {
            // (i + 0.5) / 3 is not an exact float (it may lie a hair below the centre); the 8-bit
            // sub-texel position rounds to nearest, so bilinear still returns the texel exactly.
            const Vec2 uv{(float(x) + 0.5f) / 3.0f, (float(y) + 0.5f) / 5.0f};
            for (WrapMode w : kWraps)
                for (TextureFilter f : kFilters) requireAll(t, uv, f, w, tex(x, y));
        }
    // u = 0 and u = 1 (exact): the seams. Row 2's centre v = 0.5 is exact.
    requireAll(t, {0.0f, 0.5f}, TextureFilter::Bilinear, WrapMode::Repeat, avg(2, 2, 0, 2));
    requireAll(t, {0.0f, 0.5f}, TextureFilter::Bilinear, WrapMode::Clamp, tex(0, 2));
    requireAll(t, {0.0f, 0.5f}, TextureFilter::Bilinear, WrapMode::Mirror, tex(0, 2));
    requireAll(t, {1.0f, 0.5f}, TextureFilter::Bilinear, WrapMode::Repeat, avg(2, 2, 0, 2));
    requireAll(t, {1.0f, 0.5f}, TextureFilter::Bilinear, WrapMode::Clamp, tex(2, 2));
    requireAll(t, {1.0f, 0.5f}, TextureFilter::Bilinear, WrapMode::Mirror, tex(2, 2));
    // Nearest far away on the odd axis: u = 1e6 + 0.5 -> floor(1.5) = column 1 for repeat.
    requireAll(t, {1000000.5f, 0.5f}, TextureFilter::Nearest, WrapMode::Repeat, tex(1, 2));
    requireAll(t, {1000001.5f, 0.5f}, TextureFilter::Nearest, WrapMode::Mirror, tex(1, 2)); // 1.5 -> 0.5
    requireAll(t, {1000001.75f, 0.5f}, TextureFilter::Nearest, WrapMode::Mirror, tex(0, 2)); // 1.75 -> 0.25
    // v on the 5-high axis: v = 1e6 + 0.1 is not exact, 1e6 + 0.125 is: floor(0.625) = row 0.
    requireAll(t, {0.5f, 1000000.125f}, TextureFilter::Nearest, WrapMode::Repeat, tex(1, 0));
    requireAll(t, {0.5f, -999999.125f}, TextureFilter::Nearest, WrapMode::Repeat, tex(1, 4)); // frac 0.875
}

// --- Linear light: sampleSrgb on the decoded storage -------------------------------------------
namespace {

double decodeCurve(int byte) {
    const double x = double(byte) / 255.0;
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}
Color decodedTexel(Rgba8 t) {
    const auto& d = srgbDecode16Table();
    return {float(d[t.r]) / 65535.0f, float(d[t.g]) / 65535.0f, float(d[t.b]) / 65535.0f, float(t.a) / 255.0f};
}

} // namespace

TEST_CASE("the 16-bit decode of every byte lies within half a step of the sRGB curve and encodes back to it", "[texture][srgb]") {
    const auto& d = srgbDecode16Table();
    for (int b = 0; b < 256; ++b) {
        INFO("byte " << b);
        REQUIRE(std::fabs(double(d[std::size_t(b)]) - decodeCurve(b) * 65535.0) <= 0.5);
        REQUIRE(int(encodeSrgb8(float(d[std::size_t(b)]) / 65535.0f)) == b);
        if (b > 0) REQUIRE(d[std::size_t(b)] > d[std::size_t(b - 1)]); // distinct, increasing
    }
    REQUIRE(d[0] == 0);
    REQUIRE(d[255] == 65535);
}

TEST_CASE("sampleSrgb returns each texel decoded at its centre, alpha as a / 255, for every filter and wrap", "[texture][srgb]") {
    for (int size : {1, 2, 4, 8}) {
        const Texture t = makeTexture(size, 2 * size, distinctTexel);
        for (int y = 0; y < 2 * size; ++y)
            for (int x = 0; x < size; ++x) {
                const Vec2 uv{(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(2 * size)};
                for (WrapMode w : kWraps)
                    for (TextureFilter f : kFilters) {
                        INFO("size " << size << " texel " << x << "," << y << " " << filterName(f) << " " << wrapName(w));
                        REQUIRE(bitEqual(t.sampleSrgb(uv, 0.0f, f, w), decodedTexel(distinctTexel(x, y))));
                    }
            }
    }
}

TEST_CASE("sampleSrgb filters decoded values: halfway between texels is the mean of their decodes, not the decode of their mean", "[texture][srgb]") {
    const Rgba8 dark{20, 50, 0, 255}, light{220, 200, 255, 0};
    const Texture t = makeTexture(2, 1, [&](int x, int) { return x == 0 ? dark : light; });
    const Color c = t.sampleSrgb({0.5f, 0.5f}, 0.0f, TextureFilter::Bilinear, WrapMode::Clamp);
    const Color a = decodedTexel(dark), b = decodedTexel(light);
    REQUIRE(c.r == Approx((a.r + b.r) / 2).epsilon(1e-6));
    REQUIRE(c.g == Approx((a.g + b.g) / 2).epsilon(1e-6));
    REQUIRE(c.b == Approx((a.b + b.b) / 2).epsilon(1e-6));
    REQUIRE(c.a == Approx(0.5f).epsilon(1e-6));
    // Display-space filtering would give decode(120 / 255) = 0.188 for red; the mean of the decodes is 0.358.
    REQUIRE(c.r > float(decodeCurve(120)) + 0.15f);
    // A quarter of the way: 3/4 of the first texel (8-bit weight 128 -> 64 along u).
    const Color q = t.sampleSrgb({0.375f, 0.5f}, 0.0f, TextureFilter::Bilinear, WrapMode::Clamp);
    REQUIRE(q.r == Approx(0.75f * a.r + 0.25f * b.r).epsilon(1e-6));
}

TEST_CASE("sampleSrgb trilinear mixes the two levels' decoded results by frac(lod)", "[texture][srgb]") {
    // 2x2 of two bytes: level 1 is their box average (rounded), decoded.
    const Texture t = makeTexture(2, 2, [](int x, int y) { return (x + y) % 2 ? Rgba8{0, 0, 0, 255} : Rgba8{255, 255, 255, 255}; });
    REQUIRE(t.levelCount() == 2);
    const Vec2 uv{0.25f, 0.25f}; // texel (0, 0): white at level 0
    const Color level0 = t.sampleSrgb(uv, 0.0f, TextureFilter::Trilinear, WrapMode::Repeat);
    const Color level1 = t.sampleSrgb(uv, 1.0f, TextureFilter::Trilinear, WrapMode::Repeat);
    const Color half = t.sampleSrgb(uv, 0.5f, TextureFilter::Trilinear, WrapMode::Repeat);
    REQUIRE(level0.r == 1.0f);
    const Rgba8 avg = unpackTexel(t.texel(1, 0, 0));
    REQUIRE(bitEqual(level1, decodedTexel(avg)));
    REQUIRE(half.r == level0.r + (level1.r - level0.r) * 0.5f);
}
