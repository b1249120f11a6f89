// Helpers for draw-level tests: simple meshes and the plainest shaders.
#pragma once

#include <cstdint>
#include <vector>

#include "Math/Mat4.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Geometry/Mesh.hpp"
#include "Raster/Pipeline.hpp"

namespace sr::test {

// The pixels where two frames differ in colour or in depth.
inline int differingPixels(const FrameBuffer& a, const FrameBuffer& b) {
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) n += a.pixel(x, y) != b.pixel(x, y) || a.depth(x, y) != b.depth(x, y);
    return n;
}

// An axis-aligned box [lo, hi] with outward-facing CCW triangles (12 triangles, 8 vertices).
inline Mesh boxMesh(Vec3 lo, Vec3 hi) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    // Each face as a quad (a, b, c, d) counter-clockwise seen from outside.
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.indices.insert(m.indices.end(), {std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
        m.indices.insert(m.indices.end(), {std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
    }
    return m;
}

// An n x n grid of quads on the plane y = height spanning [-size, size] in x and z, CCW seen from +Y.
inline Mesh gridMesh(int n, float size, float height) {
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.positions.push_back({-size + 2 * size * float(i) / float(n), height, -size + 2 * size * float(j) / float(n)});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const auto v = std::uint32_t(j * (n + 1) + i);
            const auto row = std::uint32_t(n + 1);
            m.indices.insert(m.indices.end(), {v, v + row, v + row + 1});
            m.indices.insert(m.indices.end(), {v, v + row + 1, v + 1});
        }
    return m;
}

// Appends mesh b to mesh a (positions and re-based indices).
inline void append(Mesh& a, const Mesh& b) {
    const auto base = std::uint32_t(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    for (std::uint32_t i : b.indices) a.indices.push_back(base + i);
}

// Draws `mesh` transformed by `mvp`, triangle t in the flat colour packBgra of the id t + 1, so
// an image tells which triangle won each pixel. One 3-vertex draw per triangle.
inline void drawIdColoured(RenderContext& ctx, const DrawState& state, const Mesh& mesh, const Mat4& mvp) {
    static const std::uint32_t local[3] = {0, 1, 2};
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t id = std::uint32_t(t + 1);
        const Pixel colour = packBgra(std::uint8_t(id >> 16), std::uint8_t(id >> 8), std::uint8_t(id));
        drawIndexed<0>(
            ctx, state, 3, local, 3,
            [&](std::size_t i, ClipVertex& out) {
                out.position = mvp * Vec4(mesh.positions[mesh.indices[t * 3 + i]], 1.0f);
            },
            [colour](const Fragment<0>&) { return colour; });
    }
}

} // namespace sr::test
