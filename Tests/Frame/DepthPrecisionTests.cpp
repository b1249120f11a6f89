// Depth precision at the extremes: which depth format resolves two planes 1e-4 apart (relative)
// at distance 1e4 with near 1e-2, for a finite and an infinite far plane. Justifies reversed-Z
// float32 (Math/Conventions.hpp) by measurement.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "Math/Transform.hpp"
#include "RenderTestUtil.hpp"

using namespace sr;
using namespace sr::test;

namespace {

constexpr int W = 64, H = 48;
constexpr float kNear = 1e-2f;
constexpr float kDistance = 1e4f;
constexpr float kGap = 1e-4f * kDistance; // the two planes are 1 unit apart at 10,000

// A square facing the camera (which looks down -Z from the origin) at view distance d, large
// enough to cover the whole 90-degree view.
Mesh wall(float d) {
    Mesh m;
    const float e = 2.0f * d;
    m.positions = {{-e, -e, -d}, {e, -e, -d}, {e, e, -d}, {-e, e, -d}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

// The depth each pixel of a wall gets through the real pipeline (interpolation included).
std::vector<float> depthsOf(const Mesh& m, const Mat4& proj, bool clipFar) {
    std::vector<float> z(W * H, NAN);
    FrameBuffer fb(W, H);
    RenderContext ctx(fb);
    DrawState state;
    state.depth = DepthMode::Off;
    state.clipFar = clipFar;
    drawIndexed<0>(
        ctx, state, m.vertexCount(), m.indices.data(), m.indices.size(),
        [&](std::size_t i, ClipVertex& out) { out.position = proj * Vec4(m.positions[i], 1.0f); },
        [&](const Fragment<0>& f) {
            z[std::size_t(f.y * W + f.x)] = f.z;
            return Pixel(0);
        });
    return z;
}

// Forward (conventional) D3D-style depth: near -> 0, far -> 1 (infinite far: A = -1, B = -n).
Mat4 forwardZ(Mat4 reversed, float n, float f) {
    const double A = std::isinf(f) ? -1.0 : -double(f) / (double(f) - n);
    const double B = std::isinf(f) ? -double(n) : -double(f) * n / (double(f) - n);
    reversed(2, 2) = float(A);
    reversed(2, 3) = float(B);
    return reversed;
}

double quantize(float z, int bits) { return std::nearbyint(double(z) * double((1u << bits) - 1)); }

struct Fighting {
    int reversedF32 = 0, forwardF32 = 0, reversedU24 = 0, forwardU24 = 0, forwardU16 = 0, pixels = 0;
};

Fighting measure(float farZ) {
    const bool finite = !std::isinf(farZ);
    const Mat4 rev = finite ? perspective(radians(90.0f), aspectRatio(W, H), kNear, farZ)
                            : perspectiveInfinite(radians(90.0f), aspectRatio(W, H), kNear);
    const Mat4 fwd = forwardZ(rev, kNear, farZ);
    const Mesh nearWall = wall(kDistance), farWall = wall(kDistance + kGap);
    const auto rn = depthsOf(nearWall, rev, finite), rf = depthsOf(farWall, rev, finite);
    const auto fn = depthsOf(nearWall, fwd, finite), ff = depthsOf(farWall, fwd, finite);
    Fighting r;
    for (std::size_t i = 0; i < rn.size(); ++i) {
        if (!std::isfinite(rn[i]) || !std::isfinite(rf[i]) || !std::isfinite(fn[i]) || !std::isfinite(ff[i]))
            continue; // a pixel some wall did not cover: counted out of `pixels`
        ++r.pixels;
        // A pixel z-fights when the nearer wall does not win strictly.
        r.reversedF32 += !(rn[i] > rf[i]);
        r.forwardF32 += !(fn[i] < ff[i]);
        r.reversedU24 += !(quantize(rn[i], 24) > quantize(rf[i], 24));
        r.forwardU24 += !(quantize(fn[i], 24) < quantize(ff[i], 24));
        r.forwardU16 += !(quantize(fn[i], 16) < quantize(ff[i], 16));
    }
    return r;
}

// Two walls drawn flat-coloured with the depth test (back first or front first): the front one
// kGreen, the back one kRed.
const Pixel kGreen = packBgra(0, 255, 0), kRed = packBgra(255, 0, 0);
FrameBuffer drawFrontAndBack(int w, int h, const Mat4& proj, bool clipFar, const Mesh& front, const Mesh& back,
                             bool backFirst) {
    FrameBuffer fb(w, h);
    fb.clear(packBgra(0, 0, 0));
    RenderContext ctx(fb);
    DrawState state;
    state.clipFar = clipFar;
    auto draw = [&](const Mesh& m, Pixel colour) {
        drawIndexed<0>(
            ctx, state, m.vertexCount(), m.indices.data(), m.indices.size(),
            [&](std::size_t i, ClipVertex& out) { out.position = proj * Vec4(m.positions[i], 1.0f); },
            [colour](const Fragment<0>&) { return colour; });
    };
    if (backFirst) draw(back, kRed);
    draw(front, kGreen);
    if (!backFirst) draw(back, kRed);
    return fb;
}

} // namespace

TEST_CASE("reversed-Z float32 resolves planes 1e-4 apart at 1e4 with near 1e-2; the alternatives fail",
          "[render][depth][precision]") {
    for (float farZ : {2e4f, INFINITY}) {
        CAPTURE(farZ);
        const Fighting f = measure(farZ);
        REQUIRE(f.pixels == W * H);
        // The chosen format: not one z-fighting pixel.
        CHECK(f.reversedF32 == 0);
        // The record of the alternatives (each fails on essentially every pixel): forward float
        // keeps ~1e-6 of spacing near 1.0 for a depth difference of n*gap/d^2 = 1e-10; 24- and
        // 16-bit unorm have a step of 6e-8 / 1.5e-5 against differences of 1e-10 (forward) or
        // 1e-10 relative to z = 1e-6 (reversed).
        CHECK(f.forwardF32 > f.pixels * 9 / 10);
        CHECK(f.reversedU24 > f.pixels * 9 / 10);
        CHECK(f.forwardU24 > f.pixels * 9 / 10);
        CHECK(f.forwardU16 > f.pixels * 9 / 10);
    }
}

TEST_CASE("the nearer wall wins in the depth buffer whatever the draw order", "[render][depth][precision]") {
    const Mat4 proj = perspectiveInfinite(radians(90.0f), aspectRatio(W, H), kNear);
    const Mesh nearWall = wall(kDistance), farWall = wall(kDistance + kGap);
    for (int order = 0; order < 2; ++order) {
        const FrameBuffer fb = drawFrontAndBack(W, H, proj, false, nearWall, farWall, order == 0);
        int notGreen = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) notGreen += fb.pixel(x, y) != kGreen;
        CHECK(notGreen == 0);
    }
}

TEST_CASE("depth and 1/w along spans up to 8192 pixels stay within 2^-20 of the double plane, to a vanishing line",
          "[render][depth][precision]") {
    // One triangle whose top rows are spans across the whole 8192-pixel framebuffer. 1/w falls
    // linearly along x from invW0 at x = 0 to invW1 at x = 8192 (a wall receding to the right);
    // z = near / w, as reversed-Z with an infinite far plane gives. The 1/256-pixel case ends
    // 1/256 pixel beyond the last pixel centre at a vanishing line (1/w = 0), where a float
    // start + k * gradient lost 8.6% (relative) to cancellation.
    constexpr int kW = FrameBuffer::kMaxDimension, kH = 4;
    constexpr float kN = 0.05f;
    struct Ramp {
        double invW0, invW1;
    };
    const double c = 1.0 / 8192.0;
    const Ramp ramps[] = {
        {1.0, 1e-9},                                   // 1/w falls 1e9-fold along the span
        {1.0, 0.01},                                   // 100-fold
        {c * (8192.0 + 1.0 / 256.0), c / 256.0},       // 1/w = c (8192 + 1/256 - x): zero 1/256 px past the end
        {1e-9, 1.0},                                   // rising: the far end first
    };
    FrameBuffer fb(kW, kH);
    for (const Ramp& r : ramps) {
        INFO("1/w from " << r.invW0 << " to " << r.invW1);
        ScreenVertex a, b, d;
        a.x = 0.0f, a.y = 0.0f, a.invW = float(r.invW0);
        b.x = float(kW), b.y = 0.0f, b.invW = float(r.invW1);
        d.x = 0.0f, d.y = 4096.0f, d.invW = float(r.invW0); // tall: the top rows span 8191+ pixels
        for (ScreenVertex* v : {&a, &b, &d}) {
            v->z = kN * v->invW;
            v->varyings[0] = 0.5f;
        }
        const auto setup = setupTriangle(a, b, d, 1);
        REQUIRE(setup);
        double worstZ = 0.0, worstInvW = 0.0;
        long pixels = 0, longest = 0;
        forEachSpan(*setup, fullScissor(fb), [&](int, int x0, int x1) { longest = std::max(longest, long(x1 - x0)); });
        fillTriangle<DepthMode::Off, 1>(*setup, fb, [&](const Fragment<1>& f) {
            const double px = f.x + 0.5, py = f.y + 0.5;
            const double z = setup->planeAt(kPlaneZ, px, py), invW = setup->planeAt(kPlaneInvW, px, py);
            worstZ = std::max(worstZ, std::fabs(double(f.z) - z) / std::fabs(z));
            worstInvW = std::max(worstInvW, std::fabs(double(f.invW) - invW) / std::fabs(invW));
            ++pixels;
            return Pixel(0);
        });
        INFO("worst relative error: depth " << worstZ << ", 1/w " << worstInvW << " over " << pixels << " pixels");
        CHECK(longest >= kW - 8); // the top spans cross (nearly) the whole buffer
        CHECK(worstZ <= 0x1p-20);
        CHECK(worstInvW <= 0x1p-20);
    }
}

TEST_CASE("a receding wall 1e-5 (relative) behind another never shows through, at 1024x768, near 0.05, far 1e4",
          "[render][depth][precision]") {
    constexpr int kW = 1024, kH = 768;
    const Mat4 proj = perspective(radians(60.0f), aspectRatio(kW, kH), 0.05f, 1e4f);
    // A wall from 0.06 to 9,000 units away, receding to the right; the second one is the first
    // scaled by 1 + 1e-5 about the eye: the same screen footprint, every point 1e-5 further.
    Mesh front;
    front.positions = {{-0.05f, -0.05f, -0.06f}, {-0.05f, 0.05f, -0.06f}, {9000.0f, -4000.0f, -9000.0f}, {9000.0f, 4000.0f, -9000.0f}};
    front.indices = {0, 2, 1, 1, 2, 3};
    Mesh back = front;
    for (Vec3& p : back.positions) p = p * 1.00001f;
    for (int order = 0; order < 2; ++order) {
        const FrameBuffer fb = drawFrontAndBack(kW, kH, proj, true, front, back, order == 0);
        int greenPixels = 0, redPixels = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                greenPixels += fb.pixel(x, y) == kGreen;
                redPixels += fb.pixel(x, y) == kRed;
            }
        INFO("draw order " << order << ": " << greenPixels << " front pixels");
        CHECK(greenPixels > kW * kH / 4); // the wall covers a good part of the view
        CHECK(redPixels == 0);
    }
}
