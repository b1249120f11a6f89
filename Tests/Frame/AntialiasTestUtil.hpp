// Shared helpers of the anti-aliasing tests (SSAA and MSAA): exact pixel coverage of a triangle,
// a one-triangle scene in screen pixels, resolved edge coverage against the exact area.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Frame/RenderScene.hpp"
#include "TestFramework.hpp"

namespace sr::test {

// A draw of mesh `mesh`'s first `indexCount` indices in the flat colour kd (untextured).
inline SceneDraw untexturedDraw(int mesh, std::uint32_t indexCount, Color kd) {
    SceneDraw d;
    d.mesh = mesh;
    d.indexCount = indexCount;
    d.kd = kd;
    return d;
}

// Area of the triangle (a, b, c) inside the unit pixel square [px, px + 1] x [py, py + 1]:
// Sutherland-Hodgman clipping of the triangle against the square's four sides, then the shoelace
// formula, in double.
inline double areaInPixel(const std::vector<std::pair<double, double>>& tri, int px, int py) {
    std::vector<std::pair<double, double>> poly = tri, next;
    auto clip = [&](auto inside, auto cross) {
        next.clear();
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const auto& p = poly[i];
            const auto& q = poly[(i + 1) % poly.size()];
            const bool pin = inside(p), qin = inside(q);
            if (pin) next.push_back(p);
            if (pin != qin) next.push_back(cross(p, q));
        }
        poly.swap(next);
    };
    const double x0 = px, x1 = px + 1.0, y0 = py, y1 = py + 1.0;
    auto atX = [](double x) {
        return [x](auto p, auto q) { const double t = (x - p.first) / (q.first - p.first); return std::make_pair(x, p.second + t * (q.second - p.second)); };
    };
    auto atY = [](double y) {
        return [y](auto p, auto q) { const double t = (y - p.second) / (q.second - p.second); return std::make_pair(p.first + t * (q.first - p.first), y); };
    };
    clip([&](auto p) { return p.first >= x0; }, atX(x0));
    clip([&](auto p) { return p.first <= x1; }, atX(x1));
    clip([&](auto p) { return p.second >= y0; }, atY(y0));
    clip([&](auto p) { return p.second <= y1; }, atY(y1));
    double twice = 0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const auto& p = poly[i];
        const auto& q = poly[(i + 1) % poly.size()];
        twice += p.first * q.second - q.first * p.second;
    }
    return std::abs(twice) * 0.5;
}

// A white unlit triangle given in screen pixels on a width x height target, as a one-draw scene
// whose view is the identity (clip = NDC, w = 1): x_ndc = 2 x / W - 1, y_ndc = 1 - 2 y / H.
inline Scene whiteTriangle(const std::vector<std::pair<double, double>>& tri, int width, int height) {
    Scene scene;
    Mesh m;
    for (const auto& [x, y] : tri)
        m.positions.push_back({float(2.0 * x / width - 1.0), float(1.0 - 2.0 * y / height), 0.5f});
    m.indices = {0, 1, 2};
    scene.meshes.push_back(m);
    scene.draws.push_back(untexturedDraw(0, 3, Color{1, 1, 1, 1}));
    return scene;
}

struct EdgeError {
    double mean = 0, max = 0;
    int pixels = 0;
};

// whiteTriangle rendered unlit with `aa` on `threads` threads by the span kernels of `isa`.
inline FrameBuffer renderWhiteTriangle(const std::vector<std::pair<double, double>>& tri, int width, int height,
                                       AntiAliasing aa, int threads = 1, Isa isa = bestIsa()) {
    FrameBuffer fb(width, height);
    RenderContext ctx(fb);
    ctx.setThreads(threads);
    FrameView view;
    view.viewProj = Mat4::identity();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    settings.antiAliasing = aa;
    settings.isa = isa;
    REQUIRE(renderSceneFrame(ctx, whiteTriangle(tri, width, height), view, settings));
    return fb;
}

// Resolved intensity against the exact covered area, over the pixels an edge crosses
// (0 < area < 1).
inline EdgeError coverageError(int ssaa, const std::vector<std::pair<double, double>>& tri, int width, int height,
                               int threads = 1, int msaa = 1) {
    const FrameBuffer fb = renderWhiteTriangle(
        tri, width, height, msaa > 1 ? *AntiAliasing::multisample(msaa) : *AntiAliasing::supersample(ssaa), threads);
    EdgeError e;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double area = areaInPixel(tri, x, y);
            if (area <= 1e-9 || area >= 1 - 1e-9) continue;
            const double err = std::abs(pixelR(fb.pixel(x, y)) / 255.0 - area);
            e.mean += err;
            e.max = std::max(e.max, err);
            ++e.pixels;
        }
    e.mean /= std::max(e.pixels, 1);
    return e;
}

// Two screen-filling quads on a 64-pixel-wide target with the identity view: red nearer left of
// x = c (pixels), green nearer right of it (z_red - z_green = (c - x) / 64; reversed-Z, larger is
// nearer: red 0.5 + (c - x) / 128, green 0.5 - (c - x) / 128). Unlit colours.
inline Scene crossingPlanes(double c) {
    Scene scene;
    auto quad = [&](double zLeft, double zRight) {
        Mesh m;
        for (auto [x, y] : {std::pair{-1.0, -1.0}, std::pair{1.0, -1.0}, std::pair{1.0, 1.0}, std::pair{-1.0, 1.0}}) {
            const double px = (x + 1.0) * 32.0; // pixels, on a 64-wide target
            m.positions.push_back({float(x), float(y), float(zLeft + (zRight - zLeft) * px / 64.0)});
        }
        m.indices = {0, 1, 2, 0, 2, 3};
        return m;
    };
    scene.meshes.push_back(quad(0.5 + c / 128.0, 0.5 + (c - 64.0) / 128.0));
    scene.meshes.push_back(quad(0.5 - c / 128.0, 0.5 - (c - 64.0) / 128.0));
    scene.draws.push_back(untexturedDraw(0, 6, Color{1, 0, 0, 1}));
    scene.draws.push_back(untexturedDraw(1, 6, Color{0, 1, 0, 1}));
    return scene;
}

} // namespace sr::test
