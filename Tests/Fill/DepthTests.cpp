// Depth: reversed-Z GREATER test, nearer wins in any draw order, exact ties keep the first drawn.
#include "TestFramework.hpp"

#include <cmath>
#include <vector>

#include "RasterTestUtil.hpp"
#include "ReferenceRasterizer.hpp"

using namespace sr;
using namespace sr::test;

namespace {

constexpr int kW = 32, kH = 32;
constexpr Pixel kRed = packBgra(255, 0, 0), kBlue = packBgra(0, 0, 255), kBlack = packBgra(0, 0, 0);

// Fills a w x h axis-aligned quad as two triangles; z given at the four corners (tl, tr, br, bl).
template <DepthMode kMode>
void drawQuad(FrameBuffer& fb, float x0, float y0, float x1, float y1, const float z[4], Pixel colour) {
    const ScreenVertex tl = vtx(x0, y0, z[0]), tr = vtx(x1, y0, z[1]), br = vtx(x1, y1, z[2]), bl = vtx(x0, y1, z[3]);
    auto flat = [colour](const Fragment<0>&) { return colour; };
    if (auto t = setupTriangle(tl, tr, br, 0)) fillTriangle<kMode, 0>(*t, fb, flat);
    if (auto t = setupTriangle(tl, br, bl, 0)) fillTriangle<kMode, 0>(*t, fb, flat);
}

int countColour(const FrameBuffer& fb, Pixel c) {
    int n = 0;
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x) n += fb.pixel(x, y) == c ? 1 : 0;
    return n;
}

} // namespace

TEST_CASE("the nearer (greater reversed-Z) fragment wins in either draw order", "[raster][depth]") {
    const float nearZ[4] = {0.7f, 0.7f, 0.7f, 0.7f}, farZ[4] = {0.3f, 0.3f, 0.3f, 0.3f};
    for (int order = 0; order < 2; ++order) {
        FrameBuffer fb(kW, kH);
        fb.clear(kBlack);
        if (order == 0) {
            drawQuad<DepthMode::TestWrite>(fb, 2, 2, 20, 20, farZ, kBlue);
            drawQuad<DepthMode::TestWrite>(fb, 10, 10, 30, 30, nearZ, kRed);
        } else {
            drawQuad<DepthMode::TestWrite>(fb, 10, 10, 30, 30, nearZ, kRed);
            drawQuad<DepthMode::TestWrite>(fb, 2, 2, 20, 20, farZ, kBlue);
        }
        CHECK(fb.pixel(15, 15) == kRed); // overlap
        CHECK(fb.pixel(5, 5) == kBlue);
        CHECK(fb.depth(15, 15) == 0.7f);
        CHECK(countColour(fb, kRed) == 20 * 20);
        CHECK(countColour(fb, kBlue) == 18 * 18 - 10 * 10);
    }
}

TEST_CASE("on an exact depth tie the first drawn fragment stays", "[raster][depth]") {
    const float z[4] = {0.25f, 0.5f, 0.75f, 0.5f}; // sloped: equal only because identical
    FrameBuffer fb(kW, kH);
    fb.clear(kBlack);
    drawQuad<DepthMode::TestWrite>(fb, 1, 1, 31, 31, z, kBlue);
    drawQuad<DepthMode::TestWrite>(fb, 1, 1, 31, 31, z, kRed);
    CHECK(countColour(fb, kBlue) == 30 * 30);
    CHECK(countColour(fb, kRed) == 0);
}

TEST_CASE("intersecting sloped surfaces: per pixel the greater depth wins, in both orders", "[raster][depth]") {
    // Quad A rises left->right, quad B falls: they cross at x = 16. Expected winner per pixel from
    // the reference's double-precision depth (pixels within 1e-5 of the crossing are skipped).
    const float zA[4] = {0.2f, 0.8f, 0.8f, 0.2f}, zB[4] = {0.8f, 0.2f, 0.2f, 0.8f};
    for (int order = 0; order < 2; ++order) {
        FrameBuffer fb(kW, kH);
        fb.clear(kBlack);
        if (order == 0) {
            drawQuad<DepthMode::TestWrite>(fb, 0.25f, 0, 31.75f, 32, zA, kRed);
            drawQuad<DepthMode::TestWrite>(fb, 0.25f, 0, 31.75f, 32, zB, kBlue);
        } else {
            drawQuad<DepthMode::TestWrite>(fb, 0.25f, 0, 31.75f, 32, zB, kBlue);
            drawQuad<DepthMode::TestWrite>(fb, 0.25f, 0, 31.75f, 32, zA, kRed);
        }
        int checked = 0, wrong = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                // Depth of A at the centre, from the reference plane (z is linear in x only).
                const double za = 0.2 + 0.6 * (x + 0.5 - 0.25) / 31.5, zb = 1.0 - za;
                if (std::fabs(za - zb) < 1e-5) continue;
                ++checked;
                wrong += fb.pixel(x, y) != (za > zb ? kRed : kBlue) ? 1 : 0;
                wrong += std::fabs(fb.depth(x, y) - std::max(za, zb)) > 1e-6 ? 1 : 0;
            }
        CHECK(checked == kW * kH);
        CHECK(wrong == 0);
    }
}

TEST_CASE("depth modes: Off ignores the buffer, Test reads without writing", "[raster][depth]") {
    const float nearZ[4] = {0.9f, 0.9f, 0.9f, 0.9f}, farZ[4] = {0.1f, 0.1f, 0.1f, 0.1f};
    FrameBuffer fb(kW, kH);
    fb.clear(kBlack);
    drawQuad<DepthMode::TestWrite>(fb, 0, 0, 16, 16, nearZ, kRed);
    drawQuad<DepthMode::Off>(fb, 0, 0, 16, 16, farZ, kBlue); // last drawn wins, depth untouched
    CHECK(countColour(fb, kBlue) == 256);
    CHECK(fb.depth(3, 3) == 0.9f);
    drawQuad<DepthMode::Test>(fb, 8, 8, 24, 24, farZ, kRed); // passes only where depth is 0
    CHECK(fb.pixel(10, 10) == kBlue);
    CHECK(fb.pixel(20, 20) == kRed);
    CHECK(fb.depth(20, 20) == FrameBuffer::kFarDepth); // not written
}

TEST_CASE("fill depth matches the reference's double-precision depth", "[raster][depth]") {
    std::mt19937 rng(5);
    double worst = 0.0;
    for (int i = 0; i < 500; ++i) {
        const ScreenVertex a = vtx(uniform(rng, -20, 52), uniform(rng, -20, 52), uniform(rng, 0, 1));
        const ScreenVertex b = vtx(uniform(rng, -20, 52), uniform(rng, -20, 52), uniform(rng, 0, 1));
        const ScreenVertex c = vtx(uniform(rng, -20, 52), uniform(rng, -20, 52), uniform(rng, 0, 1));
        FrameBuffer fb(kW, kH);
        fb.clear(kBlack, -1.0f);
        if (auto t = setupTriangle(a, b, c, 0))
            fillTriangle<DepthMode::TestWrite, 0>(*t, fb, [](const Fragment<0>&) { return kRed; });
        for (const ref::Fragment& f : ref::rasterize(a, b, c, 0, kW, kH))
            worst = std::max(worst, std::fabs(double(fb.depth(f.x, f.y)) - f.z));
    }
    CHECK(worst < 3e-7); // a few float ulps of z (span start in double, float steps)
}
