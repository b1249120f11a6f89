// Helpers shared by the pipeline tests: a tiny reversed-Z projection, orientation oracles, polygons.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "Raster/Geometry/Clipper.hpp"
#include "Raster/Geometry/Viewport.hpp"

namespace srtest {

using sr::ClipVertex;
using sr::Vec4;

// Infinite reversed-Z projection of a view-space point (camera looks down -Z), independent of
// Math/Transform.hpp: x_c = x / tan(fov/2), y_c = y / tan(fov/2), z_c = near, w_c = -z.
// The near plane z_c = w_c is then w = near, and points behind the eye have w < 0 < z.
inline Vec4 projectInfinite(float x, float y, float z, float nearZ = 0.1f, float cotHalfFov = 1.0f) {
    return {x * cotHalfFov, y * cotHalfFov, nearZ, -z};
}

inline ClipVertex makeVertex(Vec4 p) {
    ClipVertex v;
    v.position = p;
    return v;
}

// A clip-space vertex that lands on screen position (sx, sy) for a W x H viewport, at the
// given w (> 0) and depth z_ndc.
inline ClipVertex fromScreen(double sx, double sy, int W, int H, double w = 1.0, double zNdc = 0.5) {
    const double xn = 2.0 * sx / W - 1.0;
    const double yn = 1.0 - 2.0 * sy / H;
    return makeVertex({float(xn * w), float(yn * w), float(zNdc * w), float(w)});
}

// det of the (x, y, w) rows: its sign is the orientation of the triangle in the projective
// plane. For vertices all with w > 0 the screen signed area (y down) has the opposite sign.
inline double homogeneousDet(const Vec4& a, const Vec4& b, const Vec4& c) {
    const double ax = a.x, ay = a.y, aw = a.w, bx = b.x, by = b.y, bw = b.w, cx = c.x, cy = c.y, cw = c.w;
    return ax * (by * cw - bw * cy) - ay * (bx * cw - bw * cx) + aw * (bx * cy - by * cx);
}

// Twice the signed screen area in double (y down: negative = CCW as seen).
inline double screenArea2(const sr::ScreenVertex& a, const sr::ScreenVertex& b, const sr::ScreenVertex& c) {
    return (double(b.x) - a.x) * (double(c.y) - a.y) - (double(c.x) - a.x) * (double(b.y) - a.y);
}

struct P2 {
    double x, y;
};

// Sutherland-Hodgman of a 2D polygon against the axis-aligned rectangle [0, W] x [0, H], in double.
inline std::vector<P2> clipToRect(std::vector<P2> poly, double W, double H) {
    auto pass = [](const std::vector<P2>& in, auto dist) {
        std::vector<P2> out;
        const std::size_t n = in.size();
        for (std::size_t i = 0; i < n; ++i) {
            const P2 s = in[(i + n - 1) % n], e = in[i];
            const double ds = dist(s), de = dist(e);
            if (de >= 0) {
                if (ds < 0) {
                    const double t = ds / (ds - de);
                    out.push_back({s.x + t * (e.x - s.x), s.y + t * (e.y - s.y)});
                }
                out.push_back(e);
            } else if (ds >= 0) {
                const double t = ds / (ds - de);
                out.push_back({s.x + t * (e.x - s.x), s.y + t * (e.y - s.y)});
            }
        }
        return out;
    };
    poly = pass(poly, [](P2 p) { return p.x; });
    poly = pass(poly, [W](P2 p) { return W - p.x; });
    poly = pass(poly, [](P2 p) { return p.y; });
    poly = pass(poly, [H](P2 p) { return H - p.y; });
    return poly;
}

inline double polygonArea(const std::vector<P2>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const P2 u = p[i], v = p[(i + 1) % p.size()];
        a += u.x * v.y - v.x * u.y;
    }
    return 0.5 * a;
}

// Deterministic small PRNG (xorshift64*), so failures reproduce on every platform.
struct Rng {
    std::uint64_t s;
    explicit Rng(std::uint64_t seed) : s(seed * 2685821657736338717ull + 1) {}
    std::uint64_t next() {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        return s * 2685821657736338717ull;
    }
    double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * (1.0 / 9007199254740992.0); }
};

} // namespace srtest
