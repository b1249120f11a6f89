// The stencil buffer: OpenGL's test functions and operations on hand-computed
// cases, a draw with the stencil test (the operation each outcome selects, per pixel), and the
// selection outline that uses it, end to end.
#include "TestFramework.hpp"

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Fill/Stencil.hpp"

using namespace sr;

namespace {

constexpr int kSize = 64;

// Looking down -z from the origin, 90 degrees: a square of side 2 at z = -3 spans the middle
// third of the image (ndc +-1/3: pixels 21.3 .. 42.7).
FrameView frontView() {
    app::CameraSetup c;
    c.eye = {0, 0, 0};
    c.target = {0, 0, -1};
    c.up = {0, 1, 0};
    c.fovDegrees = 90.0;
    c.nearZ = 0.1;
    c.farZ = 100.0;
    return app::makeFrameView(c, kSize, kSize, {0, 0, 1}, {});
}

// A square facing +z at depth z, half side h.
Mesh square(float z, float h) {
    Mesh m;
    m.positions = {{-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z}};
    m.normals.assign(4, {0, 0, 1});
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

SceneDraw drawOf(int mesh, Color kd) {
    SceneDraw d;
    d.mesh = mesh;
    d.indexCount = 6;
    d.kd = kd;
    return d;
}

// A grey wall (draw 0, z = -10, covering the view) and a red square in front (draw 1, z = -3).
Scene wallAndSquare() {
    Scene s;
    s.meshes = {square(-10.0f, 20.0f), square(-3.0f, 1.0f)};
    s.draws = {drawOf(0, {0.5f, 0.5f, 0.5f, 1}), drawOf(1, {1, 0, 0, 1})};
    return s;
}

} // namespace

TEST_CASE("stencil functions: (ref & mask) FUNC (stored & mask), each on hand-computed cases", "[render][stencil]") {
    struct Case {
        StencilFunc func;
        std::uint8_t ref, stored, mask;
        bool passes;
    };
    const Case cases[] = {
        {StencilFunc::Never, 5, 5, 0xFF, false},     {StencilFunc::Always, 5, 9, 0xFF, true},
        {StencilFunc::Less, 3, 4, 0xFF, true},       {StencilFunc::Less, 4, 4, 0xFF, false},
        {StencilFunc::Less, 5, 4, 0xFF, false},      {StencilFunc::LEqual, 4, 4, 0xFF, true},
        {StencilFunc::LEqual, 5, 4, 0xFF, false},    {StencilFunc::Greater, 5, 4, 0xFF, true},
        {StencilFunc::Greater, 4, 4, 0xFF, false},   {StencilFunc::GEqual, 4, 4, 0xFF, true},
        {StencilFunc::GEqual, 3, 4, 0xFF, false},    {StencilFunc::Equal, 7, 7, 0xFF, true},
        {StencilFunc::Equal, 7, 6, 0xFF, false},     {StencilFunc::NotEqual, 7, 6, 0xFF, true},
        {StencilFunc::NotEqual, 7, 7, 0xFF, false},
        // The mask applies to both sides: 0x13 & 0x0F = 3 and 0x23 & 0x0F = 3.
        {StencilFunc::Equal, 0x13, 0x23, 0x0F, true}, {StencilFunc::Equal, 0x13, 0x23, 0xFF, false},
        // 0xF1 & 0x0F = 1 < 0x02: Less passes only under the mask (unmasked 0xF1 > 0x02).
        {StencilFunc::Less, 0xF1, 0x02, 0x0F, true},  {StencilFunc::Less, 0xF1, 0x02, 0xFF, false},
        {StencilFunc::Never, 0, 0, 0x00, false},      {StencilFunc::Equal, 0xAA, 0x55, 0x00, true},
    };
    for (const Case& c : cases) {
        INFO("func " << int(c.func) << " ref " << int(c.ref) << " stored " << int(c.stored) << " mask " << int(c.mask));
        CHECK(stencilPasses(c.func, c.ref, c.stored, c.mask) == c.passes);
    }
}

TEST_CASE("stencil operations: each, with clamping, wrapping and the write mask", "[render][stencil]") {
    struct Case {
        StencilOp op;
        std::uint8_t stored, ref, writeMask, result;
    };
    const Case cases[] = {
        {StencilOp::Keep, 0x5A, 0x01, 0xFF, 0x5A},    {StencilOp::Zero, 0x5A, 0x01, 0xFF, 0x00},
        {StencilOp::Replace, 0x5A, 0x33, 0xFF, 0x33}, {StencilOp::Incr, 0x10, 0, 0xFF, 0x11},
        {StencilOp::Incr, 0xFF, 0, 0xFF, 0xFF},       {StencilOp::IncrWrap, 0xFE, 0, 0xFF, 0xFF},
        {StencilOp::IncrWrap, 0xFF, 0, 0xFF, 0x00},   {StencilOp::Decr, 0x10, 0, 0xFF, 0x0F},
        {StencilOp::Decr, 0x00, 0, 0xFF, 0x00},       {StencilOp::DecrWrap, 0x01, 0, 0xFF, 0x00},
        {StencilOp::DecrWrap, 0x00, 0, 0xFF, 0xFF},   {StencilOp::Invert, 0x0F, 0, 0xFF, 0xF0},
        {StencilOp::Invert, 0xA5, 0, 0xFF, 0x5A},
        // Only the write mask's bits change: Replace 0xAB into 0x12 under 0xF0 -> 0xA2.
        {StencilOp::Replace, 0x12, 0xAB, 0xF0, 0xA2}, {StencilOp::Zero, 0xFF, 0, 0x0F, 0xF0},
        {StencilOp::Invert, 0x0F, 0, 0x3C, 0x33},     {StencilOp::IncrWrap, 0xFF, 0, 0x0F, 0xF0},
        {StencilOp::Replace, 0x12, 0xAB, 0x00, 0x12},
    };
    for (const Case& c : cases) {
        INFO("op " << int(c.op) << " stored " << int(c.stored) << " ref " << int(c.ref) << " mask " << int(c.writeMask));
        CHECK(int(stencilApply(c.op, c.stored, c.ref, c.writeMask)) == int(c.result));
    }
}

TEST_CASE("a draw with the stencil test: each outcome's operation, per pixel, before the depth test", "[render][stencil]") {
    // A red square at z = -3 over a target whose left half holds stencil 1 and right half 0,
    // and whose top half holds the nearest depth (1: the square fails the depth test there).
    // Test Equal 1; fail -> Incr, depth fail -> Invert, pass -> IncrWrap. Per quadrant, inside
    // the square: left top 1 -> depth fails -> 0xFE; left bottom -> passes -> 2, red, depth
    // written; right: the stencil test fails -> 1, colour and depth untouched. Outside the
    // square nothing changes. The same on two render threads.
    const FrameView view = frontView();
    const Mesh quad = square(-3.0f, 1.0f);
    SurfaceMaterial red;
    red.kd = {1, 0, 0, 1};
    const Pixel grey = packBgra(9, 9, 9);
    for (const int threads : {1, 2}) {
        for (const std::uint8_t writeMask : {std::uint8_t(0xFF), std::uint8_t(0x0F)}) {
            INFO("threads " << threads << " write mask " << int(writeMask));
            FrameBuffer fb(kSize, kSize);
            fb.enableStencil();
            fb.clear(grey, FrameBuffer::kFarDepth);
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    fb.stencilRow(y)[x] = std::uint8_t(x < kSize / 2 ? 1 : 0);
                    if (y < kSize / 2) fb.depthRow(y)[x] = 1.0f;
                }
            RenderContext ctx(fb);
            ctx.setThreads(threads);
            RenderSettings s;
            s.shading = ShadingMode::Unlit;
            s.stencil.enabled = true;
            s.stencil.func = StencilFunc::Equal;
            s.stencil.ref = 1;
            s.stencil.writeMask = writeMask;
            s.stencil.fail = StencilOp::Incr;
            s.stencil.depthFail = StencilOp::Invert;
            s.stencil.pass = StencilOp::IncrWrap;
            drawMesh(ctx, view, s, quad, red);
            const auto masked = [&](int was, int now) { return (was & ~writeMask & 0xFF) | (now & writeMask); };
            int inside = 0;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const bool in = x >= 22 && x <= 41 && y >= 22 && y <= 41; // centres well inside
                    const bool edge = !in && x >= 20 && x <= 43 && y >= 20 && y <= 43;
                    if (edge) continue;
                    const bool left = x < kSize / 2, top = y < kSize / 2;
                    const int was = left ? 1 : 0;
                    int stencil = was, colour = int(grey);
                    float depth = top ? 1.0f : FrameBuffer::kFarDepth;
                    if (in) {
                        ++inside;
                        if (!left) stencil = masked(was, 1);           // fail: Incr 0 -> 1
                        else if (top) stencil = masked(was, 0xFE);     // depth fail: Invert 1
                        else {                                          // pass: IncrWrap 1 -> 2
                            stencil = masked(was, 2);
                            colour = int(packBgra(255, 0, 0));
                        }
                    }
                    INFO("pixel " << x << ", " << y << ": stencil " << int(fb.stencil(x, y)) << " depth " << fb.depth(x, y)
                                   << " colour " << std::hex << fb.pixel(x, y) << std::dec);
                    REQUIRE(int(fb.stencil(x, y)) == stencil);
                    REQUIRE(int(fb.pixel(x, y)) == colour);
                    if (in && left && !top) {
                        REQUIRE(fb.depth(x, y) > 0.0f); // written by the passing fragments
                        REQUIRE(fb.depth(x, y) < 1.0f);
                    } else {
                        REQUIRE(fb.depth(x, y) == depth);
                    }
                }
            CHECK(inside == 20 * 20);
        }
    }
}

TEST_CASE("pickDraw: the opaque draw the ray meets first", "[render][stencil]") {
    Scene s = wallAndSquare();
    CHECK(pickDraw(s, {0, 0, 0}, {0, 0, -1}) == 1);       // the square, in front of the wall
    CHECK(pickDraw(s, {0, 0, 0}, {0.5f, 0, -1}) == 0);    // past the square's side: the wall
    CHECK(pickDraw(s, {0, 0, 0}, {0, 0, 1}) == -1);       // behind the eye: nothing
    CHECK(pickDraw(s, {0, 0, -5}, {0, 0, -1}) == 0);      // from behind the square
    s.draws[1].alpha = 0.5f;                               // transparent: looked through
    CHECK(pickDraw(s, {0, 0, 0}, {0, 0, -1}) == 0);
    CHECK(pickDraw(Scene{}, {0, 0, 0}, {0, 0, -1}) == -1);
}

TEST_CASE("the selection outline: a band around the picked draw's pixels, through the stencil buffer", "[render][stencil]") {
    // The red square covers pixel centres 21..42 in x and y (ndc +-1/3 of 64 pixels: 21.33 ..
    // 42.67). A 3-pixel outline marks every wall pixel within 3 pixels of it (Chebyshev distance
    // d = 1..3) in the outline colour; the square and the wall farther out (d >= 4) are as without
    // the outline. Supersampled (4) the band is 6 samples wide: the pixels at d = 1, 2 are wholly
    // in it, d = 3 half; the rest as before. Two threads draw the same. Phong-shaded: the mark
    // pass (unlit, GEQUAL) must meet the depth the Phong kernels wrote, or holes would show.
    const Scene scene = wallAndSquare();
    const FrameView view = frontView();
    REQUIRE(pickDraw(scene, view.eye, view.rays.forward) == 1);
    for (const int ssaa : {1, 4}) {
        for (const int threads : {1, 2}) {
            INFO("ssaa " << ssaa << " threads " << threads);
            RenderSettings plainSettings;
            plainSettings.antiAliasing = *AntiAliasing::supersample(ssaa);
            RenderSettings outlined = plainSettings;
            outlined.outline.draw = 1;
            outlined.outline.colour = {0, 1, 0, 1};
            outlined.outline.width = 3.0f;
            FrameBuffer plain(kSize, kSize), fb(kSize, kSize);
            {
                RenderContext ctx(plain);
                renderSceneFrame(ctx, scene, view, plainSettings);
            }
            RenderContext ctx(fb);
            ctx.setThreads(threads);
            renderSceneFrame(ctx, scene, view, outlined);
            CHECK((ssaa > 1 ? ctx.supersampleTarget : fb).hasStencil());
            int band = 0, wrong = 0;
            const Pixel green = packBgra(0, 255, 0);
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const int dx = x < 21 ? 21 - x : x > 42 ? x - 42 : 0;
                    const int dy = y < 21 ? 21 - y : y > 42 ? y - 42 : 0;
                    const int d = std::max(dx, dy);
                    const Pixel p = fb.pixel(x, y), q = plain.pixel(x, y);
                    if (d >= 1 && d <= 2) {
                        band += p == green;
                        wrong += p != green;
                    } else if (d == 3) {
                        wrong += ssaa == 1 ? p != green : p == green || p == q;
                    } else if (d >= 4 || ssaa == 1 || (x > 21 && x < 42 && y > 21 && y < 42)) {
                        wrong += p != q;
                    }
                }
            CHECK(wrong == 0);
            CHECK(band == 26 * 26 - 22 * 22);
            // Turned off: the image without it, and the stencil memory given back.
            renderSceneFrame(ctx, scene, view, plainSettings);
            int differing = 0;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) differing += fb.pixel(x, y) != plain.pixel(x, y);
            CHECK(differing == 0);
            CHECK(!fb.hasStencil());
            CHECK(!ctx.supersampleTarget.hasStencil());
        }
    }
}
