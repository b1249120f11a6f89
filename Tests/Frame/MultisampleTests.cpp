// Multisampling (Raster/Frame/Msaa.hpp, MsaaFill.hpp, renderSceneFrame with msaa > 1): the resolve, the
// resolved coverage of edges against the exact area, depth per sample, shading at the centroid,
// lines, threads, kernels against the scalar reference, memory.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "AntialiasTestUtil.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Fill/Line.hpp"
#include "Raster/Fill/MsaaFill.hpp"
#include "Raster/Frame/AntiAliasing.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Frame/RenderScene.hpp"
#include "Raster/Pipeline.hpp"

using namespace sr;
using namespace sr::test;

namespace {

// The built-in scene (the demo's) and its auto-fitted view at width x height.
app::LoadedScene builtInScene(int width, int height) {
    app::SceneOptions options;
    options.width = width;
    options.height = height;
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    return std::move(scene.value());
}
FrameView builtInView(const app::LoadedScene& scene, int width, int height) {
    app::SceneOptions options;
    options.width = width;
    options.height = height;
    return app::makeFrameView(app::resolveCamera(options, scene), width, height, options.light, scene.lights);
}

// The resolve's rule for one pixel's n samples, written out plainly: per channel the mean rounded
// half up (alpha 0xFF), depth the samples folded in order with std::max.
struct Resolved {
    Pixel colour;
    float depth;
};
Resolved resolveRule(const Pixel* c, const float* d, int n) {
    int r = 0, g = 0, b = 0;
    float nearest = d[0];
    for (int s = 0; s < n; ++s) {
        r += pixelR(c[s]);
        g += pixelG(c[s]);
        b += pixelB(c[s]);
        if (s > 0) nearest = std::max(nearest, d[s]);
    }
    return {packBgra(std::uint8_t((r + n / 2) / n), std::uint8_t((g + n / 2) / n), std::uint8_t((b + n / 2) / n)), nearest};
}

} // namespace

TEST_CASE("AntiAliasing: the factories accept each mode's counts only; 1 is no anti-aliasing", "[msaa]") {
    for (int n = -1; n <= 32; ++n) {
        CAPTURE(n);
        const auto ss = AntiAliasing::supersample(n), ms = AntiAliasing::multisample(n);
        CHECK(ss.has_value() == (n == 1 || n == 4 || n == 16));
        CHECK(ms.has_value() == (n == 1 || n == 2 || n == 4 || n == 8));
        if (ss) {
            CHECK(ss->samples() == n);
            CHECK(ss->supersampled() == (n > 1));
            CHECK_FALSE(ss->multisampled());
            CHECK(ss->msaaSamples() == 1);
            CHECK(ss->gridSide() * ss->gridSide() == n);
        }
        if (ms) {
            CHECK(ms->samples() == n);
            CHECK(ms->multisampled() == (n > 1));
            CHECK_FALSE(ms->supersampled());
            CHECK(ms->ssaaSamples() == 1);
            CHECK(ms->gridSide() == 1);
        }
    }
    CHECK(*AntiAliasing::supersample(1) == AntiAliasing::none());
    CHECK(*AntiAliasing::multisample(1) == AntiAliasing::none());
    CHECK(*AntiAliasing::supersample(4) != *AntiAliasing::multisample(4));
    CHECK(AntiAliasing().mode() == AaMode::None);
}

TEST_CASE("resolveMsaaRows: each channel the rounded mean of the samples, depth the nearest", "[msaa]") {
    std::mt19937 rng(99);
    for (int n : {1, 2, 4, 8}) {
        CAPTURE(n);
        const int w = 13, h = 7;
        MsaaBuffer samples;
        REQUIRE(samples.resize(w, h, n));
        for (int y = 0; y < h; ++y)
            for (int i = 0; i < w * n; ++i) {
                // A third of the pixels with all samples alike (the resolve's shortcut), the rest random.
                const bool alike = (i / n) % 3 == 0;
                const int src = alike ? (i / n) * n : i;
                std::mt19937 cell(unsigned(y * 1000 + src));
                samples.colourRow(y)[i] = packBgra(std::uint8_t(cell()), std::uint8_t(cell()), std::uint8_t(cell()));
                samples.depthRow(y)[i] = float(rng() % 1000) / 1000.0f;
            }
        FrameBuffer out(w, h);
        resolveMsaaRows(samples, out, 0, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const Resolved expect = resolveRule(samples.colourRow(y) + x * n, samples.depthRow(y) + x * n, n);
                CAPTURE(x, y);
                REQUIRE(out.pixel(x, y) == expect.colour);
                REQUIRE(out.depth(x, y) == expect.depth);
            }
    }
    // Ties round up: one of two samples at 1 resolves to 1 (0.5 -> 1); three of eight at 255 to 96 (95.6).
    MsaaBuffer two;
    REQUIRE(two.resize(1, 1, 8));
    two.clearRows(0, 1, packBgra(0, 0, 0), 0.0f);
    for (int s = 0; s < 4; ++s) two.colourRow(0)[s] = packBgra(1, 0, 0);
    for (int s = 0; s < 3; ++s) two.colourRow(0)[s] |= packBgra(0, 255, 0);
    FrameBuffer o(1, 1);
    resolveMsaaRows(two, o, 0, 1);
    CHECK(o.pixel(0, 0) == packBgra(1, 96, 0));
}

// The resolve takes four pixels at a time where it can (SSE2) and one at a time for the rest of a
// run, and skips the fast clear's pending blocks: at every width and block phase each pixel must
// be the per-pixel rule's, bit for bit, depths included where samples tie as signed zeros or hold
// NaN (the rule folds the samples in order with std::max: sample 0's NaN stays, a later NaN is
// passed over, the first of equal zeros is kept).
TEST_CASE("resolveMsaaRows: every width and block phase gives the per-pixel rule, signed zeros and NaN depths included",
          "[msaa]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float specials[] = {0.0f, -0.0f, nan, 0.25f, 1.0f, -0.0f};
    auto bits = [](float f) {
        std::uint32_t u = 0;
        std::memcpy(&u, &f, sizeof u);
        return u;
    };
    std::mt19937 rng(4242);
    const Pixel clearColour = packBgra(7, 8, 9) & 0x00FFFFFFu;
    const float clearDepth = -0.0f;
    int mixed = 0, nanFirst = 0, zeroTies = 0;
    for (int n : {2, 4, 8}) {
        for (int w = 1; w <= 53; ++w) {
            CAPTURE(n, w);
            const int h = 3;
            MsaaBuffer samples;
            REQUIRE(samples.resize(w, h, n));
            samples.clearRows(0, h, clearColour, clearDepth);
            // Row 1: a fast clear with one drawn span from w / 2 on (the blocks before it stay pending).
            samples.clearRowsLazily(1, 2, clearColour, clearDepth);
            samples.prepareSpan(1, w / 2, w);
            for (int y = 0; y < h; ++y)
                for (int x = y == 1 ? w / 2 : 0; x < w; ++x) {
                    Pixel* c = samples.colourRow(y) + std::size_t(x) * std::size_t(n);
                    float* d = samples.depthRow(y) + std::size_t(x) * std::size_t(n);
                    const bool alike = rng() % 3 == 0; // the resolve's shortcut in the per-pixel rule
                    const Pixel one = Pixel(rng());
                    for (int s = 0; s < n; ++s) {
                        c[s] = alike ? one : Pixel(rng());
                        d[s] = rng() % 2 ? specials[rng() % 6] : float(rng() % 1000) / 1000.0f;
                    }
                }
            FrameBuffer out(w, h);
            resolveMsaaRows(samples, out, 0, h);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    CAPTURE(x, y);
                    Resolved expect{clearColour | 0xFF000000u, clearDepth};
                    if (!samples.pendingBlock(y, x / kMsaaClearBlock)) {
                        const Pixel* c = samples.colourRow(y) + std::size_t(x) * std::size_t(n);
                        const float* d = samples.depthRow(y) + std::size_t(x) * std::size_t(n);
                        expect = resolveRule(c, d, n);
                        mixed += std::count(c, c + n, c[0]) != n;
                        nanFirst += std::isnan(d[0]);
                        zeroTies += std::count_if(d, d + n, [](float v) { return v == 0.0f; }) > 1;
                    }
                    REQUIRE(out.pixel(x, y) == expect.colour);
                    REQUIRE(bits(out.depth(x, y)) == bits(expect.depth));
                }
        }
    }
    // The cases the assertions are about did occur.
    CHECK(mixed > 1000);
    CHECK(nanFirst > 100);
    CHECK(zeroTies > 100);
}

TEST_CASE("MSAA: resolved coverage approaches the analytic area of a triangle's edges", "[msaa]") {
    const std::vector<std::vector<std::pair<double, double>>> triangles = {
        {{3.3, 4.1}, {60.7, 12.9}, {20.2, 45.6}},
        {{1.05, 47.3}, {62.9, 1.7}, {63.2, 46.8}},   // a long shallow diagonal
        {{10.6, 0.4}, {11.9, 47.6}, {50.25, 30.1}},  // a near-vertical edge
        {{0.5, 23.37}, {63.5, 24.61}, {32.0, 47.0}}, // a near-horizontal edge
    };
    double sum[4] = {};
    for (const auto& tri : triangles) {
        CAPTURE(tri);
        EdgeError e[4];
        for (int i = 0; i < 4; ++i) e[i] = coverageError(1, tri, 64, 48, 1, 1 << i);
        CAPTURE(e[0].mean, e[1].mean, e[2].mean, e[3].mean, e[0].max, e[1].max, e[2].max, e[3].max);
        REQUIRE(e[3].pixels > 60);
        for (int i = 0; i < 4; ++i) sum[i] += e[i].mean;
        // N samples: the coverage of a pixel is a multiple of 1/N; an edge crossing a pixel can
        // misplace at most all but one of them (the error is below 1 - 1/N + 1/510 everywhere),
        // and the D3D patterns (one sample per row and column of the N x N sub-grid) keep the
        // mean far lower on edges of any slope.
        CHECK(e[0].mean > 0.1);
        CHECK(e[1].mean < 0.9 * e[0].mean);
        CHECK(e[2].mean < 0.6 * e[0].mean);
        CHECK(e[3].mean < 0.45 * e[0].mean);
        CHECK(e[2].max <= 0.75 + 0.01);
        CHECK(e[3].max <= 0.5 + 0.01);
    }
    // Over the four triangles: 4 samples cut the one-sample edge error by more than half, 8 by more.
    CAPTURE(sum[0], sum[1], sum[2], sum[3]);
    CHECK(sum[1] < 0.75 * sum[0]);
    CHECK(sum[2] < 0.5 * sum[0]);
    CHECK(sum[3] < sum[2]);
}

TEST_CASE("MSAA: depth per sample resolves the intersection line of two interpenetrating planes", "[msaa]") {
    // As the SSAA case: red nearer left of x = c, green right of it; per pixel the red share is
    // the share of its samples left of c, counted here from the sample pattern.
    const double c = 20.3;
    const Scene scene = crossingPlanes(c);
    FrameView view;
    view.viewProj = Mat4::identity();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    for (int n : {2, 4, 8}) {
        CAPTURE(n);
        int red = 0;
        for (int s = 0; s < n; ++s) red += 20.5 + msaaPattern(n)[s].x / 256.0 < c;
        REQUIRE(red > 0);
        REQUIRE(red < n);
        FrameBuffer fb(64, 8);
        RenderContext ctx(fb);
        settings.antiAliasing = *AntiAliasing::multisample(n);
        REQUIRE(renderSceneFrame(ctx, scene, view, settings));
        for (int y = 0; y < 8; ++y) {
            CHECK(fb.pixel(19, y) == packBgra(255, 0, 0));
            CHECK(int(pixelR(fb.pixel(20, y))) == (red * 255 + n / 2) / n);
            CHECK(int(pixelG(fb.pixel(20, y))) == ((n - red) * 255 + n / 2) / n);
            CHECK(fb.pixel(21, y) == packBgra(0, 255, 0));
        }
    }
}

TEST_CASE("MSAA: an edge pixel whose centre is outside is shaded at the centroid, never extrapolated", "[msaa]") {
    // One triangle with a varying u = x / 64 (screen pixels): a fragment shaded at a point inside
    // the triangle gets u within the vertices' range; shaded at the centre of a pixel whose centre
    // is outside, it would not. Also: some pixels are shaded off their centre.
    FrameBuffer fb(64, 48);
    RenderContext ctx(fb);
    REQUIRE(ctx.msaa.resize(64, 48, 4));
    ctx.multisampling = true;
    ctx.clearTarget(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
    const float xs[3] = {3.3f, 60.7f, 20.2f}, ys[3] = {4.1f, 12.9f, 45.6f};
    const std::uint32_t idx[3] = {0, 1, 2};
    float uMin = 1e9f, uMax = -1e9f;
    int offCentre = 0, fragments = 0;
    DrawState state;
    drawIndexed<1>(
        ctx, state, 3, idx, 3,
        [&](std::size_t i, ClipVertex& out) {
            out.position = Vec4(xs[i] / 32.0f - 1.0f, 1.0f - ys[i] / 24.0f, 0.5f, 1.0f);
            out.varyings[0] = xs[i] / 64.0f;
        },
        [&](const Fragment<1>& f) {
            ++fragments;
            uMin = std::min(uMin, f.varyings[0]);
            uMax = std::max(uMax, f.varyings[0]);
            // The centre's u would be (x + 0.5) / 64; the centroid's differs.
            offCentre += std::abs(f.varyings[0] - (f.x + 0.5f) / 64.0f) > 1e-5f;
            return packBgra(255, 255, 255);
        });
    ctx.multisampling = false;
    CAPTURE(uMin, uMax, offCentre, fragments);
    CHECK(fragments > 500);
    CHECK(offCentre > 10);
    CHECK(uMin >= 3.3f / 64.0f - 1e-6f);
    CHECK(uMax <= 60.7f / 64.0f + 1e-6f);
}

TEST_CASE("MSAA: lines cover all samples of their pixels; the wireframe keeps its weight", "[msaa]") {
    const LineVertex a{2.3f, 3.1f, 0.5f, packBgra(255, 255, 255)}, b{61.7f, 40.2f, 0.5f, packBgra(255, 255, 255)};
    FrameBuffer plain(64, 48), resolved(64, 48);
    plain.clear(packBgra(0, 0, 0));
    drawLine(plain, a, b);
    for (int n : {2, 4, 8}) {
        CAPTURE(n);
        MsaaBuffer samples;
        REQUIRE(samples.resize(64, 48, n));
        samples.clearRows(0, 48, packBgra(0, 0, 0), 0.0f);
        drawLine(samples, a, b);
        resolveMsaaRows(samples, resolved, 0, 48);
        CHECK(std::equal(plain.colorData(), plain.colorData() + 64 * 48, resolved.colorData()));
    }
    // The overlay through renderSceneFrame: about as much white as at one sample.
    const std::vector<std::pair<double, double>> tri{{5.3, 6.1}, {58.7, 14.9}, {22.2, 43.6}};
    Scene scene = whiteTriangle(tri, 64, 48);
    scene.draws[0].kd = Color{0, 0, 0, 1};
    FrameView view;
    view.viewProj = Mat4::identity();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    settings.wireframe = true;
    double ink[2] = {};
    for (int i = 0; i < 2; ++i) {
        FrameBuffer fb(64, 48);
        RenderContext ctx(fb);
        settings.antiAliasing = *AntiAliasing::multisample(i == 0 ? 1 : 4);
        REQUIRE(renderSceneFrame(ctx, scene, view, settings));
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) ink[i] += pixelR(fb.pixel(x, y)) / 255.0;
    }
    CAPTURE(ink[0], ink[1]);
    CHECK(ink[0] > 110);
    CHECK(ink[1] > 0.9 * ink[0]);
    CHECK(ink[1] < 1.1 * ink[0]);
}

TEST_CASE("MSAA: the same image on every thread count; sample memory only while multisampling", "[msaa]") {
    const auto scene = builtInScene(96, 64);
    const FrameView view = builtInView(scene, 96, 64);
    FrameBuffer one(96, 64), two(96, 64), three(96, 64), plain(96, 64);
    RenderContext c1(one), c2(two), c3(three), c0(plain);
    c2.setThreads(2);
    c3.setThreads(3);
    c3.binningMinTriangles = 0; // every draw binned (the sample rows decide the lanes)
    c3.sharedSetupBands = 1;    // and every triangle set up once
    RenderSettings settings;
    app::renderFrame(c0, scene, view, settings); // the plain path
    for (int n : {1, 2, 4, 8, 1}) {
        CAPTURE(n);
        settings.antiAliasing = *AntiAliasing::multisample(n);
        app::renderFrame(c1, scene, view, settings);
        app::renderFrame(c2, scene, view, settings);
        app::renderFrame(c3, scene, view, settings);
        CHECK(std::equal(one.colorData(), one.colorData() + 96 * 64, two.colorData()));
        CHECK(std::equal(one.depthData(), one.depthData() + 96 * 64, two.depthData()));
        CHECK(std::equal(one.colorData(), one.colorData() + 96 * 64, three.colorData()));
        CHECK(std::equal(one.depthData(), one.depthData() + 96 * 64, three.depthData()));
        // Each triangle set up once, by one lane, whichever lanes fill it.
        CHECK(c3.stats.rasterized > 100);
        CHECK(c3.stats.setupsBuilt == c3.stats.rasterized);
        CHECK(c1.msaa.width() == (n > 1 ? 96 : 0));
        CHECK(c1.msaa.samples() == (n > 1 ? n : 1));
        CHECK_FALSE(c1.multisampling); // only during the frame
        const int differing = int(std::mismatch(one.colorData(), one.colorData() + 96 * 64, plain.colorData()).first -
                                  one.colorData());
        if (n == 1) CHECK(differing == 96 * 64); // --msaa 1 is the plain path, bit for bit
        else CHECK(differing < 96 * 64);         // edges change
    }
    // A target above kMaxMsaaSamples: drawn with one sample, reported, no sample memory.
    {
        FrameBuffer wide(FrameBuffer::kMaxDimension, FrameBuffer::kMaxDimension / 8 + 1);
        RenderContext cw(wide);
        RenderSettings big;
        big.antiAliasing = *AntiAliasing::multisample(8);
        FrameView v;
        v.viewProj = Mat4::identity();
        CHECK_FALSE(renderSceneFrame(cw, Scene{}, v, big));
        CHECK(cw.msaa.empty());
        CHECK_FALSE(cw.msaa.resize(FrameBuffer::kMaxDimension, FrameBuffer::kMaxDimension / 8 + 1, 8));
        CHECK(msaaFits(FrameBuffer::kMaxDimension, FrameBuffer::kMaxDimension / 8, 8));
    }
    // Switched from multisampling to supersampling: the multisample memory goes.
    settings.antiAliasing = *AntiAliasing::supersample(4);
    app::renderFrame(c1, scene, view, settings);
    CHECK(c1.msaa.empty());
    CHECK(c1.supersampleTarget.width() == 2 * 96);
}

TEST_CASE("MSAA: every kernel ISA gives the scalar reference's image, for every program and filter", "[msaa]") {
    const auto scene = builtInScene(80, 56);
    const FrameView view = builtInView(scene, 80, 56);
    for (ShadingMode shading : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong})
        for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear})
            for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine}) {
                RenderSettings settings;
                settings.shading = shading;
                settings.filter = filter;
                settings.perspective = persp;
                settings.antiAliasing = *AntiAliasing::multisample(4);
                settings.isa = Isa::Scalar;
                FrameBuffer reference(80, 56);
                RenderContext cr(reference);
                app::renderFrame(cr, scene, view, settings);
                for (Isa isa : kAllIsas) {
                    if (isa == Isa::Scalar || !isaAvailable(isa)) continue;
                    CAPTURE(shadingModeName(shading), filterName(filter), perspectiveModeName(persp), isaName(isa));
                    settings.isa = isa;
                    FrameBuffer fb(80, 56);
                    RenderContext ctx(fb);
                    app::renderFrame(ctx, scene, view, settings);
                    CHECK(std::equal(fb.colorData(), fb.colorData() + 80 * 56, reference.colorData()));
                }
            }
}

TEST_CASE("MSAA: shading queued across a draw's triangles gives the scalar reference's samples", "[msaa]") {
    // An opaque draw's kernel queues each pixel with its passing samples across triangles and
    // writes the colours once a whole group of lanes is queued (Kernels.inl, shadeRunSpans), the
    // rest at the end of the draw. A soup of 700 small triangles drawn twice, overlapping in
    // random depths (every 5th in one depth plane: exact ties keep the first drawn, so any
    // reordering of the writes shows) and random normals and uvs, untextured and textured
    // (bilinear: queued; trilinear: shaded per triangle), Gouraud and Phong, 2/4/8 samples, on 1
    // and 3 threads: the resolved colours and depths equal the scalar loop's. Sampled with a
    // fixed seed.
    constexpr int kW = 75, kH = 58;
    std::mt19937 rng(2911);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Scene scene;
    Mesh soup;
    for (int t = 0; t < 700; ++t) {
        const float cx = unit(rng) * 2.2f - 1.1f, cy = unit(rng) * 2.2f - 1.1f;
        const float r = (t % 3 == 0 ? 0.15f : 0.04f) * unit(rng) + 0.005f; // up to ~6 pixels, or ~0.2
        const float z = t % 5 == 0 ? 0.5f : 0.05f + 0.9f * unit(rng);
        for (int k = 0; k < 3; ++k) {
            soup.positions.push_back({cx + r * (2 * unit(rng) - 1), cy + r * (2 * unit(rng) - 1), z});
            soup.normals.push_back(normalize(Vec3(2 * unit(rng) - 1, 2 * unit(rng) - 1, 1.0f)));
            soup.uvs.push_back({3 * unit(rng), 3 * unit(rng)});
            soup.indices.push_back(std::uint32_t(soup.indices.size()));
        }
    }
    scene.meshes.push_back(soup);
    {
        std::vector<std::uint8_t> rgba(32 * 16 * 4);
        for (auto& b : rgba) b = std::uint8_t(rng() & 0xFFu);
        scene.textures.push_back(Texture::fromRgba8(32, 16, rgba.data()));
    }
    const auto count = std::uint32_t(soup.indices.size());
    scene.draws.push_back(untexturedDraw(0, count, Color{0.9f, 0.5f, 0.2f, 1.0f}));
    SceneDraw textured = untexturedDraw(0, count, Color{1, 1, 1, 1});
    textured.texture = 0;
    scene.draws.push_back(textured);
    FrameView view;
    view.viewProj = Mat4::identity();
    view.eye = {0.2f, 0.1f, 3.0f};
    int drawn = 0;
    for (ShadingMode shading : {ShadingMode::Gouraud, ShadingMode::Phong})
        for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Trilinear})
            for (int n : {2, 4, 8}) {
                RenderSettings settings;
                settings.shading = shading;
                settings.filter = filter;
                settings.antiAliasing = *AntiAliasing::multisample(n);
                settings.isa = Isa::Scalar;
                FrameBuffer reference(kW, kH);
                RenderContext cr(reference);
                REQUIRE(renderSceneFrame(cr, scene, view, settings));
                REQUIRE(cr.stats.rasterized > 1000);
                for (Isa isa : kAllIsas) {
                    if (isa == Isa::Scalar || !isaAvailable(isa)) continue;
                    for (int threads : {1, 3}) {
                        CAPTURE(shadingModeName(shading), filterName(filter), n, isaName(isa), threads);
                        settings.isa = isa;
                        FrameBuffer fb(kW, kH);
                        RenderContext ctx(fb);
                        ctx.setThreads(threads);
                        REQUIRE(renderSceneFrame(ctx, scene, view, settings));
                        CHECK(std::equal(fb.colorData(), fb.colorData() + kW * kH, reference.colorData()));
                        CHECK(std::memcmp(fb.depthData(), reference.depthData(), sizeof(float) * kW * kH) == 0);
                        CHECK(ctx.stats.fragmentsShaded == cr.stats.fragmentsShaded);
                        ++drawn;
                    }
                }
            }
    CHECK(drawn >= 2 * 2 * 3 * 2); // at least one kernel ISA
}

TEST_CASE("MSAA fast clear: pending blocks resolve to the clear and are written only where drawn", "[msaa]") {
    // The same triangles and lines drawn into a buffer cleared the slow way (every sample written)
    // and into one cleared lazily over stale contents: the resolved images (colour and depth) must
    // be equal, and the lazily cleared one must have written only the blocks that were drawn in.
    constexpr int kW = 45, kH = 30; // 45: the last block of a row is partial
    const Pixel clear = packBgra(10, 20, 30), stale = packBgra(200, 0, 200);
    std::mt19937 rng(26);
    auto uniform = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
    auto vtx = [](float x, float y, float z) {
        ScreenVertex v;
        v.x = x;
        v.y = y;
        v.z = z;
        v.invW = 1.0f;
        return v;
    };
    for (int n : {2, 4, 8}) {
        CAPTURE(n);
        MsaaBuffer written, lazy;
        REQUIRE(written.resize(kW, kH, n));
        REQUIRE(lazy.resize(kW, kH, n));
        written.clearRows(0, kH, clear, FrameBuffer::kFarDepth);
        lazy.clearRows(0, kH, stale, 0.75f); // what the last frame left
        lazy.clearRowsLazily(0, kH, clear, FrameBuffer::kFarDepth);
        FrameBuffer shading(kW, kH);
        MsaaScratch scratch;
        std::vector<std::pair<int, int>> drawnBlocks; // (row, block) of every pixel a triangle shaded
        for (int i = 0; i < 12; ++i) {
            const float x = uniform(0, kW), y = uniform(0, kH), z = uniform(0.1f, 0.9f);
            const ScreenVertex a = vtx(x, y, z), b = vtx(x + uniform(-6, 6), y + uniform(-6, 6), z),
                               c = vtx(x + uniform(-6, 6), y + uniform(-6, 6), z);
            TriangleSetup t;
            if (setupTriangleCulled(t, a, b, c, CullMode::None, 0, true, {}, true) != SetupOutcome::Ready) continue;
            const Pixel ink = packBgra(std::uint8_t(20 * i), 255, std::uint8_t(255 - 20 * i));
            auto shadeRow = [&](int row) -> const Pixel* { return shading.colorRow(row); };
            auto shadeRuns = [&](const SpanRun* runs, int count, const SampleWrite&) {
                for (int r = 0; r < count; ++r)
                    for (int px = runs[r].x0; px < runs[r].x1; ++px) {
                        shading.colorRow(runs[r].y)[px] = ink;
                        drawnBlocks.push_back({runs[r].y, px / kMsaaClearBlock});
                    }
                return false;
            };
            for (MsaaBuffer* target : {&written, &lazy}) {
                std::uint64_t shaded = 0;
                fillTriangleMsaa<DepthMode::TestWrite>(t, *target, Scissor{0, 0, kW, kH}, scratch, shadeRow, shadeRuns,
                                                       shaded);
            }
        }
        const LineVertex from{1.5f, 28.2f, 0.95f, packBgra(255, 255, 255)}, to{44.0f, 27.0f, 0.95f, packBgra(255, 255, 255)};
        drawLine(written, from, to);
        drawLine(lazy, from, to);
        FrameBuffer a(kW, kH), b(kW, kH);
        resolveMsaaRows(written, a, 0, kH);
        resolveMsaaRows(lazy, b, 0, kH);
        CHECK(std::equal(a.colorData(), a.colorData() + kW * kH, b.colorData()));
        CHECK(std::equal(a.depthData(), a.depthData() + kW * kH, b.depthData()));
        // Drawn blocks are real; most of the rest are still pending (never written).
        REQUIRE(drawnBlocks.size() > 50);
        for (const auto& [row, block] : drawnBlocks) REQUIRE_FALSE(lazy.pendingBlock(row, block));
        int pending = 0;
        for (int y = 0; y < kH; ++y)
            for (int block = 0; block * kMsaaClearBlock < kW; ++block) pending += lazy.pendingBlock(y, block) ? 1 : 0;
        CHECK(pending > 10);
        CHECK(pending < kH * 3 - 10);
        // A pending block's memory still holds the stale frame: the resolve did not read it.
        for (int y = 0; y < kH; ++y)
            if (lazy.pendingBlock(y, 0)) CHECK(lazy.colourRow(y)[0] == stale);
    }
}
