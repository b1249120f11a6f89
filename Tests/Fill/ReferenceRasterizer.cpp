// Reference triangle rasterizer: bounding box x per-pixel edge functions with a top-left bias.
#include "ReferenceRasterizer.hpp"

#include <algorithm>
#include <cmath>

namespace sr::ref {

namespace {

struct P {
    std::int64_t x, y;
};

// Edge function of a -> b at p: > 0 on the interior side of a positively oriented triangle
// (doubleArea > 0, clockwise on a y-down screen). Exact: all terms < 2^47.
std::int64_t edge(P a, P b, P p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// Top-left rule in y-down space for a positively oriented triangle (interior where edge() > 0,
// i.e. where cross(d, n) > 0 for the interior direction n, d = b - a): the interior lies at
// larger x (n = (1, 0), a "left" edge) <=> -d.y > 0; a horizontal edge has the interior below
// (n = (0, 1), a "top" edge) <=> d.y == 0 && d.x > 0. Centres exactly on such an edge are in.
bool isTopLeft(P a, P b) {
    const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
    return dy < 0 || (dy == 0 && dx > 0);
}

// Calls f(x, y, w0, w1, w2, area) for each covered pixel, where w_i is the edge function of the
// edge opposite vertex i (so w_i / area is vertex i's barycentric), in input vertex order.
// The sample point of pixel (x, y) is its centre moved by (ox, oy) in 1/256 pixel (0, 0: the centre).
template <class F>
void forEachCovered(const ScreenVertex* v, int width, int height, F&& f, std::int64_t ox = 0, std::int64_t oy = 0) {
    P p[3];
    for (int i = 0; i < 3; ++i) p[i] = {snap(v[i].x), snap(v[i].y)};
    std::int64_t area = edge(p[0], p[1], p[2]);
    if (area == 0) return;
    // Work on a positively oriented copy; map barycentrics back to input order at the end.
    int idx[3] = {0, 1, 2};
    if (area < 0) {
        std::swap(idx[1], idx[2]);
        area = -area;
    }
    const P a = p[idx[0]], b = p[idx[1]], c = p[idx[2]];
    const std::int64_t bias0 = isTopLeft(b, c) ? 0 : -1; // edge opposite a
    const std::int64_t bias1 = isTopLeft(c, a) ? 0 : -1;
    const std::int64_t bias2 = isTopLeft(a, b) ? 0 : -1;

    // The pixels whose sample point can lie in the bounding box (one more on each side: |o| < 1).
    const std::int64_t minX = (std::min({a.x, b.x, c.x}) >> 8) - 1, maxX = (std::max({a.x, b.x, c.x}) >> 8) + 1;
    const std::int64_t minY = (std::min({a.y, b.y, c.y}) >> 8) - 1, maxY = (std::max({a.y, b.y, c.y}) >> 8) + 1;
    for (std::int64_t y = std::max<std::int64_t>(minY, 0); y <= std::min<std::int64_t>(maxY, height - 1); ++y) {
        for (std::int64_t x = std::max<std::int64_t>(minX, 0); x <= std::min<std::int64_t>(maxX, width - 1); ++x) {
            const P centre{x * 256 + 128 + ox, y * 256 + 128 + oy};
            const std::int64_t w0 = edge(b, c, centre), w1 = edge(c, a, centre), w2 = edge(a, b, centre);
            if (w0 + bias0 < 0 || w1 + bias1 < 0 || w2 + bias2 < 0) continue;
            std::int64_t w[3];
            w[idx[0]] = w0;
            w[idx[1]] = w1;
            w[idx[2]] = w2;
            f(int(x), int(y), w[0], w[1], w[2], area);
        }
    }
}

} // namespace

std::int64_t snap(float v) { return std::int64_t(std::floor(double(v) * 256.0 + 0.5)); }

std::vector<int> coverage(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                          int width, int height) {
    const ScreenVertex v[3] = {v0, v1, v2};
    std::vector<int> out;
    forEachCovered(v, width, height, [&](int x, int y, std::int64_t, std::int64_t, std::int64_t,
                                         std::int64_t) { out.push_back(y * width + x); });
    return out;
}

std::vector<int> sampleCoverage(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2, int width,
                                int height, std::int64_t ox, std::int64_t oy) {
    const ScreenVertex v[3] = {v0, v1, v2};
    std::vector<int> out;
    forEachCovered(
        v, width, height,
        [&](int x, int y, std::int64_t, std::int64_t, std::int64_t, std::int64_t) { out.push_back(y * width + x); },
        ox, oy);
    return out;
}

std::vector<Fragment> rasterize(const ScreenVertex& v0, const ScreenVertex& v1,
                                const ScreenVertex& v2, int varyingCount, int width, int height) {
    const ScreenVertex v[3] = {v0, v1, v2};
    std::vector<Fragment> out;
    forEachCovered(v, width, height, [&](int x, int y, std::int64_t w0, std::int64_t w1,
                                         std::int64_t w2, std::int64_t area) {
        const double b[3] = {double(w0) / double(area), double(w1) / double(area),
                             double(w2) / double(area)};
        Fragment f;
        f.x = x;
        f.y = y;
        for (int i = 0; i < 3; ++i) {
            f.z += b[i] * v[i].z;
            f.invW += b[i] * v[i].invW;
        }
        for (int k = 0; k < varyingCount; ++k) {
            double num = 0.0;
            for (int i = 0; i < 3; ++i) num += b[i] * double(v[i].varyings[std::size_t(k)]) * v[i].invW;
            f.varyings[std::size_t(k)] = num / f.invW;
        }
        out.push_back(f);
    });
    return out;
}

} // namespace sr::ref
