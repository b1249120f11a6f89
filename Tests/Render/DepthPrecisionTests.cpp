// Depth precision at the extremes: which depth format resolves two planes 1e-4 apart (relative)
// at distance 1e4 with near 1e-2, for a finite and an infinite far plane. Justifies reversed-Z
// float32 (Math/Conventions.hpp) by measurement.
#include "TestFramework.hpp"

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
        FrameBuffer fb(W, H);
        fb.clear(packBgra(0, 0, 0));
        RenderContext ctx(fb);
        DrawState state;
        state.clipFar = false;
        auto draw = [&](const Mesh& m, Pixel colour) {
            drawIndexed<0>(
                ctx, state, m.vertexCount(), m.indices.data(), m.indices.size(),
                [&](std::size_t i, ClipVertex& out) { out.position = proj * Vec4(m.positions[i], 1.0f); },
                [colour](const Fragment<0>&) { return colour; });
        };
        const Pixel green = packBgra(0, 255, 0), red = packBgra(255, 0, 0);
        if (order == 0) {
            draw(farWall, red);
            draw(nearWall, green);
        } else {
            draw(nearWall, green);
            draw(farWall, red);
        }
        int notGreen = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) notGreen += fb.pixel(x, y) != green;
        CHECK(notGreen == 0);
    }
}
