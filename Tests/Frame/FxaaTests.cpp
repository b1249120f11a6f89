// FXAA (Raster/Frame/Fxaa.hpp): the kernels against the scalar reference, what it changes and
// what it leaves, and that it lowers the edge error of a one-sample frame.
#include <cstdint>
#include <random>

#include "AntialiasTestUtil.hpp"
#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Frame/Fxaa.hpp"
#include "TestFramework.hpp"

namespace sr {
namespace {

// A test image: random blocks of random grey or colour (hard edges in both directions, some of
// them one pixel wide), with `noise` of the pixels random on their own.
FrameBuffer blockImage(int w, int h, std::uint32_t seed, double noise) {
    FrameBuffer fb(w, h);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> level(0, 255);
    fb.clearColor(packBgra(40, 40, 40));
    for (int k = 0; k < 12; ++k) {
        const int x0 = std::uniform_int_distribution<int>(-4, w)(rng), y0 = std::uniform_int_distribution<int>(-4, h)(rng);
        const int bw = std::uniform_int_distribution<int>(1, w)(rng), bh = std::uniform_int_distribution<int>(1, h)(rng);
        const Pixel c = packBgra(std::uint8_t(level(rng)), std::uint8_t(level(rng)), std::uint8_t(level(rng)));
        for (int y = std::max(y0, 0); y < std::min(y0 + bh, h); ++y)
            for (int x = std::max(x0, 0); x < std::min(x0 + bw, w); ++x) fb.setPixel(x, y, c);
    }
    std::bernoulli_distribution speck(noise);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (speck(rng)) fb.setPixel(x, y, packBgra(std::uint8_t(level(rng)), std::uint8_t(level(rng)), std::uint8_t(level(rng))));
    return fb;
}

// A white triangle with long, shallow edges (the staircases FXAA is for).
FrameBuffer renderTriangle(const std::vector<std::pair<double, double>>& tri, int w, int h, AntiAliasing aa, int threads,
                           Isa isa = bestIsa()) {
    return test::renderWhiteTriangle(tri, w, h, aa, threads, isa);
}

int differingPixels(const FrameBuffer& a, const FrameBuffer& b) {
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) n += a.pixel(x, y) != b.pixel(x, y);
    return n;
}

const std::vector<std::pair<double, double>> kShallow{{3.2, 5.1}, {93.7, 14.6}, {21.3, 57.9}};

} // namespace

TEST_CASE("FXAA: the kernels of every ISA equal the scalar reference, bit for bit", "[fxaa][kernels]") {
    // Sizes with partial vector groups, one-pixel rows and columns, and more edges than flat.
    const std::pair<int, int> sizes[] = {{1, 1}, {1, 9}, {9, 1}, {5, 3}, {17, 17}, {37, 29}, {64, 48}, {100, 7}};
    std::uint32_t seed = 1;
    for (auto [w, h] : sizes)
        for (double noise : {0.0, 0.05, 0.5}) {
            const FrameBuffer source = blockImage(w, h, seed++, noise);
            FrameBuffer reference = source;
            FxaaScratch scratch;
            applyFxaa(reference, scratch, Isa::Scalar);
            for (Isa isa : kAllIsas) {
                if (isa == Isa::Scalar || !isaAvailable(isa)) continue;
                FrameBuffer image = source;
                FxaaScratch s;
                applyFxaa(image, s, isa);
                INFO(isaName(isa) << " " << w << "x" << h << " noise " << noise);
                CHECK(differingPixels(image, reference) == 0);
            }
        }
    // A rendered triangle: the same again, and the filter changed something there.
    const FrameBuffer plain = renderTriangle(kShallow, 97, 61, AntiAliasing::none(), 1);
    FrameBuffer reference = plain;
    FxaaScratch scratch;
    applyFxaa(reference, scratch, Isa::Scalar);
    CHECK(differingPixels(reference, plain) > 40);
    for (Isa isa : kAllIsas) {
        if (!isaAvailable(isa)) continue;
        INFO(isaName(isa));
        CHECK(differingPixels(renderTriangle(kShallow, 97, 61, AntiAliasing::fxaa(), 1, isa), reference) == 0);
    }
}

TEST_CASE("FXAA: flat regions and low contrast stay, depth stays, alpha is opaque", "[fxaa]") {
    FrameBuffer flat(33, 21);
    flat.clear(packBgra(200, 100, 50), 0.25f);
    FrameBuffer image = flat;
    FxaaScratch scratch;
    applyFxaa(image, scratch, Isa::Scalar);
    CHECK(differingPixels(image, flat) == 0);
    // A step of 8 levels on a bright grey is below the threshold (range 8/255 < 0.0625).
    FrameBuffer faint(33, 21);
    faint.clear(packBgra(180, 180, 180), 0.5f);
    for (int y = 0; y < 21; ++y)
        for (int x = y; x < 33; ++x) faint.setPixel(x, y, packBgra(188, 188, 188));
    image = faint;
    applyFxaa(image, scratch, Isa::Scalar);
    CHECK(differingPixels(image, faint) == 0);
    // A hard diagonal staircase is changed, only along it, and depth is untouched.
    FrameBuffer stairs(33, 21);
    stairs.clear(packBgra(0, 0, 0), 0.5f);
    for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 33; ++x)
            if (x >= 2 * y) stairs.setPixel(x, y, packBgra(255, 255, 255));
    image = stairs;
    applyFxaa(image, scratch, Isa::Scalar);
    int changed = 0, farFromEdge = 0;
    for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 33; ++x) {
            if (image.pixel(x, y) == stairs.pixel(x, y)) continue;
            ++changed;
            farFromEdge += std::abs(x - 2 * y) > 3;
            CHECK((image.pixel(x, y) >> 24) == 0xFFu);
            CHECK(image.depth(x, y) == 0.5f);
        }
    CHECK(changed > 20);
    CHECK(farFromEdge == 0);
}

TEST_CASE("FXAA: a shallow edge's pixels move toward their covered area", "[fxaa]") {
    // Against the exact area each edge pixel's triangle covers (the truth of an infinitely
    // supersampled image): one sample alone is 0 or 1 there; FXAA must take a good part of that off.
    const int w = 97, h = 61;
    const FrameBuffer plain = renderTriangle(kShallow, w, h, AntiAliasing::none(), 1);
    const FrameBuffer filtered = renderTriangle(kShallow, w, h, AntiAliasing::fxaa(), 1);
    double errPlain = 0, errFiltered = 0;
    int pixels = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double area = test::areaInPixel(kShallow, x, y);
            if (area <= 1e-9 || area >= 1 - 1e-9) continue;
            errPlain += std::abs(pixelR(plain.pixel(x, y)) / 255.0 - area);
            errFiltered += std::abs(pixelR(filtered.pixel(x, y)) / 255.0 - area);
            ++pixels;
        }
    REQUIRE(pixels > 100);
    INFO("mean edge error: one sample " << errPlain / pixels << ", FXAA " << errFiltered / pixels);
    CHECK(errFiltered < 0.7 * errPlain);
}

TEST_CASE("FXAA: the same image on 1, 2, 3 and 8 threads; its memory only while on", "[fxaa][threads]") {
    const FrameBuffer one = renderTriangle(kShallow, 97, 61, AntiAliasing::fxaa(), 1);
    for (int threads : {2, 3, 8}) {
        INFO(threads << " threads");
        CHECK(differingPixels(renderTriangle(kShallow, 97, 61, AntiAliasing::fxaa(), threads), one) == 0);
    }
    FrameBuffer fb(40, 30);
    RenderContext ctx(fb);
    FrameView view;
    view.viewProj = Mat4::identity();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    settings.antiAliasing = AntiAliasing::fxaa();
    const Scene scene = test::whiteTriangle(kShallow, 40, 30);
    REQUIRE(renderSceneFrame(ctx, scene, view, settings));
    CHECK(ctx.fxaa.luma.size() >= std::size_t(42 * 32));
    settings.antiAliasing = AntiAliasing::none();
    REQUIRE(renderSceneFrame(ctx, scene, view, settings));
    CHECK(ctx.fxaa.luma.empty());
}

} // namespace sr
