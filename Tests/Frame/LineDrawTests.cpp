// World-space lines and points (glTF line and point primitives) through renderScene: projection, near-plane clipping, depth test and write, points, multisampling.
#include "TestFramework.hpp"

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Fill/Line.hpp"
#include "Raster/Frame/LineDraw.hpp"
#include "Raster/Geometry/Viewport.hpp"

using namespace sr;

namespace {

constexpr int kW = 96, kH = 64;
const Pixel kBlack = packBgra(0, 0, 0);

FrameView viewFrom(Vec3 eye, Vec3 target) {
    app::CameraSetup c;
    c.eye = eye;
    c.target = target;
    c.up = {0, 1, 0};
    c.fovDegrees = 60.0;
    c.nearZ = 0.5;
    c.farZ = 50.0;
    return app::makeFrameView(c, kW, kH, {0, 0, 1}, {});
}

ScreenVertex project(const FrameView& v, Vec3 p) {
    ClipVertex c;
    c.position = v.viewProj * Vec4(p, 1.0f);
    return toScreen(c, kW, kH, 0);
}

SceneLines linesOf(std::vector<Vec3> positions, std::vector<std::uint32_t> indices, bool points, Color colour) {
    SceneLines l;
    l.positions = std::move(positions);
    l.indices = std::move(indices);
    l.points = points;
    l.colour = colour;
    return l;
}

int countColour(const FrameBuffer& fb, Pixel p) {
    int n = 0;
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x) n += fb.pixel(x, y) == p;
    return n;
}

} // namespace

TEST_CASE("world lines: the DDA line of the projected ends, one pixel per point", "[render][lines]") {
    const FrameView view = viewFrom({0, 0, 5}, {0, 0, 0});
    Scene scene;
    // A slanted segment inside the view, and three points.
    scene.lines.push_back(linesOf({{-1.5f, -0.7f, 0}, {1.2f, 0.9f, -1}}, {0, 1}, false, {1, 0, 0, 1}));
    scene.lines.push_back(linesOf({{0.5f, -1.2f, 0}, {-1.0f, 1.0f, 0}, {1.4f, 0.2f, 0.5f}}, {0, 1, 2}, true, {0, 1, 0, 1}));
    FrameBuffer fb(kW, kH);
    RenderContext ctx(fb);
    renderSceneFrame(ctx, scene, view, RenderSettings{});
    // The reference: the same segment drawn in 2D from its projected ends (Line.hpp's rule).
    FrameBuffer ref(kW, kH);
    ref.clear(kBlack, FrameBuffer::kFarDepth);
    const ScreenVertex a = project(view, {-1.5f, -0.7f, 0}), b = project(view, {1.2f, 0.9f, -1});
    drawLine(ref, LineVertex{a.x, a.y, a.z, packBgra(255, 0, 0)}, LineVertex{b.x, b.y, b.z, packBgra(255, 0, 0)});
    int differing = 0, drawn = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const bool red = fb.pixel(x, y) == packBgra(255, 0, 0);
            drawn += red;
            differing += red != (ref.pixel(x, y) == packBgra(255, 0, 0));
        }
    CHECK(drawn > 20); // about 29 columns
    CHECK(differing == 0);
    // Points: one pixel each, where they project, with their depth written.
    CHECK(countColour(fb, packBgra(0, 255, 0)) == 3);
    for (Vec3 p : {Vec3{0.5f, -1.2f, 0}, Vec3{-1.0f, 1.0f, 0}, Vec3{1.4f, 0.2f, 0.5f}}) {
        const ScreenVertex s = project(view, p);
        CHECK(fb.pixel(int(s.x), int(s.y)) == packBgra(0, 255, 0));
        CHECK(fb.depth(int(s.x), int(s.y)) == s.z);
    }
}

TEST_CASE("world lines: clipped at the near plane, never drawn from behind the eye", "[render][lines]") {
    // From (0, -1, 0) in front of the eye (at z = 5) to (0, -1, 20) behind it. Unclipped, the end
    // behind the eye would project through w < 0 onto the upper half; clipped, the line runs
    // from the point's pixel down to the bottom edge (the near-plane end is below the view).
    const FrameView view = viewFrom({0, 0, 5}, {0, 0, 0});
    Scene scene;
    scene.lines.push_back(linesOf({{0, -1, 0}, {0, -1, 20}}, {0, 1}, false, {1, 1, 1, 1}));
    FrameBuffer fb(kW, kH);
    RenderContext ctx(fb);
    renderSceneFrame(ctx, scene, view, RenderSettings{});
    const Pixel white = packBgra(255, 255, 255);
    const ScreenVertex front = project(view, {0, -1, 0});
    int above = 0, below = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (fb.pixel(x, y) != white) continue;
            (y < int(front.y) ? above : below) += 1;
            CHECK(fb.depth(x, y) >= 0.0f);
            CHECK(fb.depth(x, y) <= 1.0f);
        }
    CHECK(above == 0);
    CHECK(below >= kH - int(front.y) - 1); // down to the bottom row
    CHECK(fb.pixel(int(front.x), kH - 1) == white);

    // Entirely behind the eye: nothing.
    Scene behind;
    behind.lines.push_back(linesOf({{0, -1, 6}, {0, 1, 30}}, {0, 1}, false, {1, 1, 1, 1}));
    FrameBuffer fb2(kW, kH);
    RenderContext ctx2(fb2);
    renderSceneFrame(ctx2, behind, view, RenderSettings{});
    CHECK(countColour(fb2, white) == 0);
}

TEST_CASE("world lines: depth-tested against the surfaces, and written", "[render][lines]") {
    const FrameView view = viewFrom({0, 0, 5}, {0, 0, 0});
    Scene scene;
    Mesh quad;
    quad.positions = {{-0.5f, -3, 0}, {0.5f, -3, 0}, {0.5f, 3, 0}, {-0.5f, 3, 0}}; // a vertical strip at z = 0
    quad.normals.assign(4, {0, 0, 1});
    quad.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(quad);
    SceneDraw d;
    d.indexCount = 6;
    d.kd = {0, 0, 1, 1};
    scene.draws.push_back(d);
    // A horizontal line behind the strip (z = -1) and one in front of it (z = 1).
    scene.lines.push_back(linesOf({{-3, 0.5f, -1}, {3, 0.5f, -1}}, {0, 1}, false, {1, 0, 0, 1}));
    scene.lines.push_back(linesOf({{-3, -0.5f, 1}, {3, -0.5f, 1}}, {0, 1}, false, {0, 1, 0, 1}));
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    FrameBuffer fb(kW, kH);
    RenderContext ctx(fb);
    renderSceneFrame(ctx, scene, view, settings);
    const ScreenVertex mid = project(view, {0, 0.5f, -1}), left = project(view, {-2, 0.5f, -1});
    CHECK(fb.pixel(int(mid.x), int(mid.y)) == packBgra(0, 0, 255));  // hidden behind the strip
    CHECK(fb.pixel(int(left.x), int(left.y)) == packBgra(255, 0, 0)); // visible beside it
    const ScreenVertex front = project(view, {0, -0.5f, 1});
    CHECK(fb.pixel(int(front.x), int(front.y)) == packBgra(0, 255, 0)); // in front: drawn over it
    CHECK(fb.depth(int(front.x), int(front.y)) == Approx(front.z).epsilon(1e-5)); // and its depth written
}

TEST_CASE("world points under MSAA cover their whole pixel; under SSAA 4 they stay one pixel", "[render][lines]") {
    const FrameView view = viewFrom({0, 0, 5}, {0, 0, 0});
    Scene scene;
    scene.lines.push_back(linesOf({{0.3f, 0.2f, 0}}, {0}, true, {1, 1, 1, 1}));
    const ScreenVertex s = project(view, {0.3f, 0.2f, 0});
    for (const int mode : {0, 1}) {
        INFO((mode == 0 ? "msaa 4" : "ssaa 4"));
        RenderSettings settings;
        if (mode == 0) settings.antiAliasing = *AntiAliasing::multisample(4);
        else settings.antiAliasing = *AntiAliasing::supersample(4);
        FrameBuffer fb(kW, kH);
        RenderContext ctx(fb);
        renderSceneFrame(ctx, scene, view, settings);
        CHECK(fb.pixel(int(s.x), int(s.y)) == packBgra(255, 255, 255));
        CHECK(countColour(fb, kBlack) == kW * kH - 1);
    }
}
