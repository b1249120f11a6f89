// Draw-level tests of the geometry pipeline: non-finite input, huge triangles against exact
// coverage, a camera inside a closed mesh, and a long seeded random camera walk.
#include "TestFramework.hpp"

#include <cmath>
#include <random>
#include <vector>

#include "Math/Transform.hpp"
#include "Raster/Geometry/Camera.hpp"
#include "RenderTestUtil.hpp"

using namespace sr;
using namespace sr::test;

namespace {

// Renders `mesh` with the world position as 3 perspective-correct varyings, coloured by it.
void drawWorldColoured(RenderContext& ctx, const DrawState& state, const Mesh& mesh, const Mat4& viewProj) {
    drawIndexed<3>(
        ctx, state, mesh.vertexCount(), mesh.indices.data(), mesh.indices.size(),
        [&](std::size_t i, ClipVertex& out) {
            const Vec3 p = mesh.positions[i];
            out.position = viewProj * Vec4(p, 1.0f);
            out.varyings[0] = p.x;
            out.varyings[1] = p.y;
            out.varyings[2] = p.z;
        },
        [](const Fragment<3>& f) {
            auto channel = [](float v) { return std::uint8_t(int(std::fabs(v) * 37.0f) & 255); };
            return packBgra(channel(f.varyings[0]), channel(f.varyings[1]), channel(f.varyings[2]));
        });
}

} // namespace

TEST_CASE("a triangle with a NaN or Inf vertex is dropped and the rest of the draw is unaffected",
          "[render][pipeline][nonfinite]") {
    const Mesh clean = gridMesh(6, 2.0f, 0.0f);
    const Mat4 viewProj = perspective(radians(60.0f), 4.0f / 3.0f, 0.1f, 100.0f) *
                          lookAt({0.3f, 3.0f, 2.5f}, {0, 0, 0}, {0, 1, 0});

    // The same grid with bad triangles spliced into the middle of the index list.
    Mesh dirty = clean;
    const float nan = std::nanf(""), inf = INFINITY;
    const auto base = std::uint32_t(dirty.positions.size());
    dirty.positions.push_back({nan, 0.0f, 0.0f});
    dirty.positions.push_back({0.0f, inf, 0.0f});
    dirty.positions.push_back({0.5f, 0.0f, 0.5f});
    dirty.positions.push_back({0.0f, 0.0f, -inf});
    const std::vector<std::uint32_t> bad = {base, base + 2, 0, base + 1, 1, base + 2, 2, 3, base + 3};
    dirty.indices.insert(dirty.indices.begin() + 30, bad.begin(), bad.end());

    FrameBuffer expected(80, 60), actual(80, 60);
    expected.clear(packBgra(0, 0, 0));
    actual.clear(packBgra(0, 0, 0));
    RenderContext ce(expected), ca(actual);
    drawWorldColoured(ce, {}, clean, viewProj);
    drawWorldColoured(ca, {}, dirty, viewProj);

    CHECK(ca.stats.nonFinite == 3);
    CHECK(ca.stats.trianglesIn == ce.stats.trianglesIn + 3);
    CHECK(ca.stats.rasterized == ce.stats.rasterized);
    REQUIRE(ce.stats.rasterized > 0);
    int colourDiffs = 0, depthDiffs = 0;
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 80; ++x) {
            colourDiffs += expected.pixel(x, y) != actual.pixel(x, y);
            depthDiffs += expected.depth(x, y) != actual.depth(x, y);
        }
    CHECK(colourDiffs == 0);
    CHECK(depthDiffs == 0);
}

TEST_CASE("huge triangles (vertices at +-1e6 and +-1e9 pixels) cover exactly what the exact triangle covers",
          "[render][pipeline][guardband]") {
    constexpr int W = 64, H = 48;
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const float ws[] = {1.0f, 0.37f, 3.5f};
    std::vector<int> hits(W * H);
    FrameBuffer fb(W, H);
    long long checkedPixels = 0, ambiguous = 0, mismatches = 0, coveredPixels = 0, doubleHits = 0;

    for (int iter = 0; iter < 600; ++iter) {
        const double S = (iter % 2 == 0) ? 1e6 : 1e9;
        // Screen positions: two far away, one either far away too or near the screen so that
        // long edges cross the viewport at every angle.
        double sx[3], sy[3];
        for (int k = 0; k < 3; ++k) {
            const bool near = (k == 0 && iter % 3 != 0);
            sx[k] = near ? W / 2 + unit(rng) * W : unit(rng) * S;
            sy[k] = near ? H / 2 + unit(rng) * H : unit(rng) * S;
        }
        // Clip-space input (what the pipeline sees), and the exact screen triangle it means.
        ClipVertex cv[3];
        double ex[3], ey[3];
        for (int k = 0; k < 3; ++k) {
            const float w = ws[(iter + k) % 3];
            cv[k].position = Vec4(float((sx[k] * 2.0 / W - 1.0) * w), float((1.0 - sy[k] * 2.0 / H) * w), 0.5f * w, w);
            ex[k] = (double(cv[k].position.x) / double(w) + 1.0) * W / 2;
            ey[k] = (1.0 - double(cv[k].position.y) / double(w)) * H / 2;
        }
        std::fill(hits.begin(), hits.end(), 0);
        RenderContext ctx(fb);
        DrawState state;
        state.depth = DepthMode::Off;
        const std::uint32_t idx[3] = {0, 1, 2};
        drawIndexed<0>(
            ctx, state, 3, idx, 3, [&](std::size_t i, ClipVertex& out) { out = cv[i]; },
            [&](const Fragment<0>& f) {
                ++hits[std::size_t(f.y * W + f.x)];
                return Pixel(0);
            });

        // Exact coverage: signed distances of each pixel centre to the three edges (double).
        const double area = (ex[1] - ex[0]) * (ey[2] - ey[0]) - (ex[2] - ex[0]) * (ey[1] - ey[0]);
        if (area == 0) continue;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const double px = x + 0.5, py = y + 0.5;
                bool inside = true, nearEdge = false;
                for (int e = 0; e < 3; ++e) {
                    const int a = e, b = (e + 1) % 3;
                    const double dx = ex[b] - ex[a], dy = ey[b] - ey[a];
                    const double d = (dx * (py - ey[a]) - dy * (px - ex[a])) / std::hypot(dx, dy);
                    const double inward = area > 0 ? d : -d;
                    if (std::fabs(inward) < 0.01) nearEdge = true; // within snapping distance
                    if (inward <= 0) inside = false;
                }
                const int h = hits[std::size_t(y * W + x)];
                doubleHits += h > 1; // the clipped polygon's fan never double-hits a pixel
                if (nearEdge) {
                    ++ambiguous;
                    continue;
                }
                ++checkedPixels;
                coveredPixels += inside;
                mismatches += (h == 1) != inside;
            }
    }
    CHECK(mismatches == 0);
    CHECK(doubleHits == 0);
    CHECK(coveredPixels > 100000);               // the test really covered pixels...
    CHECK(ambiguous * 1000 < checkedPixels);     // ...and almost none were excused
}

TEST_CASE("camera inside a closed box: every pixel is covered exactly once, culling picks the inside",
          "[render][pipeline][clip]") {
    constexpr int W = 48, H = 36;
    const Mesh box = boxMesh({-1, -1, -1}, {1, 1, 1});
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-0.9f, 0.9f), angle(-3.14159f, 3.14159f);
    FrameBuffer fb(W, H);
    std::vector<int> hits(W * H);
    int bad[3] = {0, 0, 0};
    for (int pose = 0; pose < 200; ++pose) {
        Camera cam({pos(rng), pos(rng), pos(rng)}, angle(rng), angle(rng) * 0.45f);
        cam.setFovY(radians(90.0f));
        cam.setNearFar(0.05f, 100.0f);
        const Mat4 viewProj = cam.projection(aspectRatio(W, H)) * cam.view();
        const CullMode modes[3] = {CullMode::None, CullMode::CW, CullMode::CCW};
        for (int m = 0; m < 3; ++m) {
            std::fill(hits.begin(), hits.end(), 0);
            RenderContext ctx(fb);
            DrawState state;
            state.depth = DepthMode::Off;
            state.cull = modes[m];
            drawIndexed<0>(
                ctx, state, box.vertexCount(), box.indices.data(), box.indices.size(),
                [&](std::size_t i, ClipVertex& out) { out.position = viewProj * Vec4(box.positions[i], 1.0f); },
                [&](const Fragment<0>& f) {
                    ++hits[std::size_t(f.y * W + f.x)];
                    return Pixel(0);
                });
            // Seen from inside, the outward-CCW faces are clockwise on screen: cull CW hides all.
            const int expected = modes[m] == CullMode::CW ? 0 : 1;
            for (int h : hits) bad[m] += h != expected;
        }
    }
    CHECK(bad[0] == 0);
    CHECK(bad[1] == 0);
    CHECK(bad[2] == 0);
}

TEST_CASE("a seeded random camera walk of 10,000 frames never produces NaN/Inf or stray writes",
          "[render][pipeline][walk]") {
    constexpr int W = 40, H = 30;
    Mesh scene = gridMesh(8, 10.0f, 0.0f);
    append(scene, boxMesh({-1, 0, -1}, {1, 2, 1}));
    append(scene, boxMesh({3, 0, 2}, {3.5f, 5, 2.5f}));
    // A 64-triangle fan standing upright, and a sliver.
    Mesh fan;
    fan.positions.push_back({-4, 1, -4});
    for (int k = 0; k <= 64; ++k) {
        const float a = float(k) * 2.0f * kPi / 64.0f;
        fan.positions.push_back({-4 + std::cos(a), 1 + std::sin(a), -4});
    }
    for (std::uint32_t k = 1; k <= 64; ++k) fan.indices.insert(fan.indices.end(), {0, k, k + 1});
    append(scene, fan);
    scene.positions.insert(scene.positions.end(), {{5, 0.01f, -5}, {-5, 0.011f, 5}, {5, 0.012f, -5.0001f}});
    const auto s = std::uint32_t(scene.positions.size());
    scene.indices.insert(scene.indices.end(), {s - 3, s - 2, s - 1});

    std::mt19937 rng(424242);
    std::uniform_real_distribution<float> coord(-12.0f, 12.0f), height(-1.0f, 6.0f), angle(-3.2f, 3.2f);
    std::uniform_int_distribution<std::size_t> vertexPick(0, scene.positions.size() - 1);
    FrameBuffer fb(W, H);
    Camera cam;
    long long nonFinitePixels = 0, nonFiniteVaryings = 0, drawnTriangles = 0;
    for (int frame = 0; frame < 10000; ++frame) {
        // Every fourth pose is adversarial: exactly at a vertex, or exactly in the ground
        // plane y = 0 (in the plane of 128 triangles), or in a box face plane (x = -1).
        Vec3 p{coord(rng), height(rng), coord(rng)};
        switch (frame % 8) {
        case 1: p = scene.positions[vertexPick(rng)]; break;
        case 3: p.y = 0.0f; break;
        case 5: p.x = -1.0f; break;
        case 7: p = {-4.0f, 1.0f, -4.0f}; break; // the fan's centre vertex
        default: break;
        }
        cam.setPosition(p);
        cam.setYawPitch(angle(rng), angle(rng) * 0.5f);
        if (frame % 8 == 3) cam.setYawPitch(angle(rng), 0.0f); // looking along the plane
        cam.setNearFar(frame % 2 ? 0.01f : 1e-4f, frame % 3 ? 1000.0f : Camera::kInfinity);
        const Mat4 viewProj = cam.projection(aspectRatio(W, H)) * cam.view();

        fb.clear(packBgra(0, 0, 0));
        RenderContext ctx(fb);
        DrawState state;
        state.clipFar = !cam.infiniteFar();
        state.cull = CullMode(frame % 3);
        state.wireframe = frame % 5 == 0;
        drawIndexed<3>(
            ctx, state, scene.vertexCount(), scene.indices.data(), scene.indices.size(),
            [&](std::size_t i, ClipVertex& out) {
                const Vec3 q = scene.positions[i];
                out.position = viewProj * Vec4(q, 1.0f);
                out.varyings[0] = q.x;
                out.varyings[1] = q.y;
                out.varyings[2] = q.z;
            },
            [&](const Fragment<3>& f) {
                for (float v : f.varyings) nonFiniteVaryings += !std::isfinite(v);
                return packBgra(std::uint8_t(f.x), std::uint8_t(f.y), 0);
            });
        drawnTriangles += long(ctx.stats.rasterized);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) nonFinitePixels += !std::isfinite(fb.depth(x, y));
    }
    CHECK(nonFinitePixels == 0);
    CHECK(nonFiniteVaryings == 0);
    CHECK(drawnTriangles > 10000); // the walk really looked at the scene
}
