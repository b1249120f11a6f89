// Supersampling (Raster/Frame/Resolve.hpp, renderSceneFrame): the resolve against a plain reference,
// resolved coverage against the analytic area of a triangle, threads, memory.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "AntialiasTestUtil.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Frame/RenderScene.hpp"
#include "Raster/Frame/Resolve.hpp"

using namespace sr;
using namespace sr::test;


TEST_CASE("resolveBox: each channel the rounded mean of its samples, depth the nearest sample", "[ssaa]") {
    std::mt19937 rng(1234);
    for (int factor : {1, 2, 4}) {
        for (auto [w, h] : {std::pair{1, 1}, std::pair{7, 5}, std::pair{33, 17}}) {
            CAPTURE(factor, w, h);
            FrameBuffer samples(w * factor, h * factor), out(w, h);
            for (int y = 0; y < samples.height(); ++y)
                for (int x = 0; x < samples.width(); ++x) {
                    samples.setPixel(x, y, packBgra(std::uint8_t(rng()), std::uint8_t(rng()), std::uint8_t(rng())));
                    samples.depthRow(y)[x] = (rng() % 4 == 0) ? 0.0f : float(rng() % 100000) / 100000.0f;
                }
            resolveBox(samples, factor, out);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    double r = 0, g = 0, b = 0;
                    float nearest = 0.0f;
                    for (int j = 0; j < factor; ++j)
                        for (int i = 0; i < factor; ++i) {
                            const Pixel p = samples.pixel(x * factor + i, y * factor + j);
                            r += pixelR(p);
                            g += pixelG(p);
                            b += pixelB(p);
                            nearest = std::max(nearest, samples.depth(x * factor + i, y * factor + j));
                        }
                    const double n = factor * factor;
                    const Pixel expect = packBgra(std::uint8_t(std::lround(r / n)), std::uint8_t(std::lround(g / n)),
                                                  std::uint8_t(std::lround(b / n)));
                    REQUIRE(out.pixel(x, y) == expect);
                    REQUIRE(out.depth(x, y) == nearest);
                }
        }
    }
    // Ties round up: two of four samples at 1 resolve to 1 (0.5 -> 1); one of four at 255 to 64 (63.75).
    FrameBuffer s(2, 2), o(1, 1);
    s.clear(packBgra(0, 0, 0), 0.0f);
    s.setPixel(0, 0, packBgra(1, 255, 0));
    s.setPixel(1, 1, packBgra(1, 0, 0));
    resolveBox(s, 2, o);
    CHECK(o.pixel(0, 0) == packBgra(1, 64, 0));
}

TEST_CASE("SSAA: resolved coverage approaches the analytic area of a triangle's edges", "[ssaa]") {
    // Long edges at several slopes, with vertices off the sample grid.
    const std::vector<std::vector<std::pair<double, double>>> triangles = {
        {{3.3, 4.1}, {60.7, 12.9}, {20.2, 45.6}},
        {{1.05, 47.3}, {62.9, 1.7}, {63.2, 46.8}},   // a long shallow diagonal
        {{10.6, 0.4}, {11.9, 47.6}, {50.25, 30.1}},  // a near-vertical edge
        {{0.5, 23.37}, {63.5, 24.61}, {32.0, 47.0}}, // a near-horizontal edge
    };
    for (const auto& tri : triangles) {
        CAPTURE(tri);
        const EdgeError e1 = coverageError(1, tri, 64, 48);
        const EdgeError e4 = coverageError(4, tri, 64, 48);
        const EdgeError e16 = coverageError(16, tri, 64, 48);
        CAPTURE(e1.mean, e4.mean, e16.mean, e1.max, e4.max, e16.max, e16.pixels);
        REQUIRE(e16.pixels > 60);
        // One sample per pixel is either in or out: an edge pixel is off by its area or by one minus it.
        CHECK(e1.mean > 0.1);
        // An ordered grid of k x k samples: per pixel the coverage is a multiple of 1/k^2 and a
        // straight edge misplaces at most one row or column of k samples (1/k), plus the 8-bit
        // rounding (1/510) and the 1/256-pixel vertex snap. The mean is far below the worst case.
        CHECK(e4.max <= 0.5 + 0.01);
        CHECK(e16.max <= 0.25 + 0.01);
        // Measured (these four triangles): e1 0.14-0.21, e4 0.064-0.082, e16 0.020-0.038.
        CHECK(e4.mean < 0.65 * e1.mean);
        CHECK(e16.mean < 0.6 * e4.mean);
        CHECK(e16.mean < 0.05);
    }
}

TEST_CASE("SSAA: the same image on every thread count; sample memory only while supersampling", "[ssaa]") {
    const std::vector<std::pair<double, double>> tri{{3.3, 4.1}, {60.7, 12.9}, {20.2, 45.6}};
    const Scene scene = whiteTriangle(tri, 64, 48);
    FrameView view;
    view.viewProj = Mat4::identity();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    FrameBuffer one(64, 48), two(64, 48);
    RenderContext c1(one), c2(two);
    c2.setThreads(2);
    for (int ssaa : {1, 4, 16, 1}) {
        CAPTURE(ssaa);
        settings.antiAliasing = *AntiAliasing::supersample(ssaa);
        REQUIRE(renderSceneFrame(c1, scene, view, settings));
        REQUIRE(renderSceneFrame(c2, scene, view, settings));
        CHECK(std::equal(one.colorData(), one.colorData() + 64 * 48, two.colorData()));
        CHECK(std::equal(one.depthData(), one.depthData() + 64 * 48, two.depthData()));
        const int f = AntiAliasing::supersample(ssaa)->gridSide();
        CHECK(c1.supersampleTarget.width() == (f > 1 ? 64 * f : 0));
        CHECK(c1.supersampleTarget.height() == (f > 1 ? 48 * f : 0));
        CHECK(&c1.target() == &one); // the output target is restored
    }
    // A sample target above FrameBuffer::kMaxDimension: drawn without SSAA, reported.
    FrameBuffer wide(FrameBuffer::kMaxDimension / 2 + 1, 2);
    RenderContext cw(wide);
    settings.antiAliasing = *AntiAliasing::supersample(4);
    CHECK_FALSE(renderSceneFrame(cw, scene, view, settings));
    CHECK(cw.supersampleTarget.empty());
}

TEST_CASE("SSAA: wireframe edges keep their weight after the resolve (k-sample-wide lines)", "[ssaa]") {
    // A black triangle with its white wireframe: the resolved image's total white ("ink", in
    // pixels) is about one pixel per unit of each edge's major-axis extent, at every sample count.
    // One-sample-wide lines would resolve to 1/2 (2x2) or 1/4 (4x4) of it.
    const std::vector<std::pair<double, double>> tri{{5.3, 6.1}, {58.7, 14.9}, {22.2, 43.6}};
    Scene scene = whiteTriangle(tri, 64, 48);
    scene.draws[0].kd = Color{0, 0, 0, 1};
    FrameView view;
    view.viewProj = Mat4::identity();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    settings.wireframe = true;
    double ink[3] = {};
    int k = 0;
    for (int ssaa : {1, 4, 16}) {
        FrameBuffer fb(64, 48);
        RenderContext ctx(fb);
        settings.antiAliasing = *AntiAliasing::supersample(ssaa);
        REQUIRE(renderSceneFrame(ctx, scene, view, settings));
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) ink[k] += pixelR(fb.pixel(x, y)) / 255.0;
        ++k;
    }
    CAPTURE(ink[0], ink[1], ink[2]);
    // Major-axis extents: 53.4 (x), 36.5 (x), 37.5 (y): about 127 pixels of line at 1 sample.
    CHECK(ink[0] > 110);
    CHECK(ink[0] < 140);
    for (int i : {1, 2}) {
        CHECK(ink[i] > 0.85 * ink[0]);
        CHECK(ink[i] < 1.15 * ink[0]);
    }
}

TEST_CASE("SSAA 16 of the built-in scene equals its 4x render, box-filtered by hand", "[ssaa]") {
    // The whole path (sample target, viewport, clear, texture LOD at the sample rate, resolve)
    // against the plain renderer at 4x the size and a box filter written out here.
    app::SceneOptions options;
    options.width = 64;
    options.height = 40;
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    const FrameView view = app::makeFrameView(app::resolveCamera(options, scene.value()), 64, 40, options.light, scene.value().lights);
    for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Trilinear}) {
        CAPTURE(filterName(filter));
        RenderSettings settings;
        settings.filter = filter;
        FrameBuffer big(256, 160), aa(64, 40);
        RenderContext cBig(big), cAa(aa);
        app::renderFrame(cBig, scene.value(), view, settings);
        settings.antiAliasing = *AntiAliasing::supersample(16);
        app::renderFrame(cAa, scene.value(), view, settings);
        int differing = 0;
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 64; ++x) {
                unsigned sum[3] = {};
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 4; ++i) {
                        const Pixel p = big.pixel(4 * x + i, 4 * y + j);
                        sum[0] += pixelR(p);
                        sum[1] += pixelG(p);
                        sum[2] += pixelB(p);
                    }
                const Pixel expect = packBgra(std::uint8_t((sum[0] + 8) / 16), std::uint8_t((sum[1] + 8) / 16),
                                              std::uint8_t((sum[2] + 8) / 16));
                differing += aa.pixel(x, y) != expect;
            }
        CHECK(differing == 0);
    }
}

TEST_CASE("SSAA: depth per sample resolves the intersection line of two interpenetrating planes", "[ssaa]") {
    // Two screen-filling quads: red in front left of x = 20.3 (pixels), green in front right of it
    // (their depths cross there: z_red - z_green = (20.3 - x) / 64). Per pixel the red share is
    // the share of the grid's sample columns left of 20.3: pixel 20 has sample columns at
    // 20 + (i + 0.5) / k: 0 of 1 (k = 1: the centre 20.5 is right of it), 1 of 2 (20.25; 20.75 is
    // right), 1 of 4 (20.125; 20.375 is right).
    const double c = 20.3;
    const Scene scene = crossingPlanes(c);
    FrameView view;
    view.viewProj = Mat4::identity();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    const struct {
        int ssaa;
        int redAt20, greenAt20; // expected levels of pixel column 20: (n 255 + half) / samples
    } cases[] = {{1, 0, 255}, {4, 128, 128}, {16, 64, 191}};
    for (const auto& k : cases) {
        CAPTURE(k.ssaa);
        FrameBuffer fb(64, 8);
        RenderContext ctx(fb);
        settings.antiAliasing = *AntiAliasing::supersample(k.ssaa);
        REQUIRE(renderSceneFrame(ctx, scene, view, settings));
        for (int y = 0; y < 8; ++y) {
            CHECK(fb.pixel(19, y) == packBgra(255, 0, 0));
            CHECK(int(pixelR(fb.pixel(20, y))) == k.redAt20);
            CHECK(int(pixelG(fb.pixel(20, y))) == k.greenAt20);
            CHECK(fb.pixel(21, y) == packBgra(0, 255, 0));
        }
    }
}
