// Procedural meshes and textures: ground plane, quad, cube, sphere, torus, checker and bricks.
#include "Resources/Primitives.hpp"

#include <cmath>

namespace sr {
namespace {

void addQuadIndices(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    // a, b, c, d counter-clockwise seen from the front.
    m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
}

// A (segments + 1) x (rows + 1) vertex grid over (s, t) in [0,1]^2 mapped by `at`, with quads
// wound so that the face is counter-clockwise when ds x dt points at the viewer.
template <class At>
Mesh gridSurface(int segments, int rows, At at) {
    Mesh m;
    for (int j = 0; j <= rows; ++j) {
        for (int i = 0; i <= segments; ++i) {
            const float s = float(i) / float(segments), t = float(j) / float(rows);
            Vec3 p, n;
            at(s, t, p, n);
            m.positions.push_back(p);
            m.normals.push_back(n);
            m.uvs.push_back({s, t});
        }
    }
    const auto row = std::uint32_t(segments + 1);
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < segments; ++i) {
            const auto v = std::uint32_t(j) * row + std::uint32_t(i);
            addQuadIndices(m, v, v + 1, v + row + 1, v + row);
        }
    return m;
}

std::uint8_t to8(float c) { return std::uint8_t(std::lround(clamp(c, 0.0f, 1.0f) * 255.0f)); }

} // namespace

Mesh makeGroundPlane(float halfX, float halfZ, int n, float uvScale) {
    // s runs along +X, t along -Z, so ds x dt = +Y: the top face is the front.
    Mesh m = gridSurface(n, n, [&](float s, float t, Vec3& p, Vec3& nrm) {
        p = {-halfX + 2.0f * halfX * s, 0.0f, halfZ - 2.0f * halfZ * t};
        nrm = {0.0f, 1.0f, 0.0f};
    });
    for (Vec2& uv : m.uvs) uv = uv * uvScale;
    return m;
}

Mesh makeQuad() {
    Mesh m;
    m.positions = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}};
    m.normals.assign(4, {0, 0, 1});
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    addQuadIndices(m, 0, 1, 2, 3);
    return m;
}

Mesh makeCube() {
    Mesh m;
    // Each face: normal, and the in-plane axes u (uv.x direction) and v (uv.y) with u x v = n.
    const Vec3 faces[6][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    for (const auto& f : faces) {
        const auto base = std::uint32_t(m.positions.size());
        const Vec3 n = f[0], u = f[1], v = f[2];
        const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (const auto& c : corners) {
            m.positions.push_back(n * 0.5f + u * (c[0] - 0.5f) + v * (c[1] - 0.5f));
            m.normals.push_back(n);
            m.uvs.push_back({c[0], c[1]});
        }
        addQuadIndices(m, base, base + 1, base + 2, base + 3);
    }
    return m;
}

Mesh makeSphere(int segments, int rings) {
    // s = longitude (around +Y, eastward seen from above = clockwise... chosen so ds x dt points
    // outward), t = latitude from the south pole (t = 0) to the north pole (t = 1).
    return gridSurface(segments, rings, [](float s, float t, Vec3& p, Vec3& n) {
        const float phi = -s * 2.0f * kPi, theta = (t - 0.5f) * kPi;
        n = {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
        p = n;
    });
}

Mesh makeTorus(float majorRadius, float minorRadius, int segments, int sides) {
    return gridSurface(segments, sides, [&](float s, float t, Vec3& p, Vec3& n) {
        const float phi = -s * 2.0f * kPi, theta = t * 2.0f * kPi;
        const Vec3 ring{std::cos(phi), 0.0f, std::sin(phi)};
        n = ring * std::cos(theta) + Vec3(0, 1, 0) * std::sin(theta);
        p = ring * majorRadius + n * minorRadius;
    });
}

void transformMesh(Mesh& mesh, const Mat4& transform) {
    for (Vec3& p : mesh.positions) p = transformPoint(transform, p);
    if (const auto nm = normalMatrix(transform))
        for (Vec3& n : mesh.normals) n = normalize(transformDirection(*nm, n));
}

Image makeCheckerImage(int size, int cells, Color a, Color b) {
    Image img;
    img.width = img.height = size;
    img.rgba.resize(std::size_t(size) * std::size_t(size) * 4);
    const int cell = std::max(1, size / cells);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Color c = ((x / cell + y / cell) % 2) ? a : b;
            std::uint8_t* t = img.texel(x, y);
            t[0] = to8(c.r);
            t[1] = to8(c.g);
            t[2] = to8(c.b);
            t[3] = 255;
        }
    return img;
}

Image makeBrickImage(int size) {
    Image img;
    img.width = img.height = size;
    img.rgba.resize(std::size_t(size) * std::size_t(size) * 4);
    const int brickH = std::max(2, size / 8), brickW = brickH * 2, mortar = std::max(1, size / 64);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const int row = y / brickH;
            const int xs = x + (row % 2) * (brickW / 2);
            const bool isMortar = (y % brickH) < mortar || (xs % brickW) < mortar;
            // A little deterministic variation per brick.
            const int brick = row * 31 + xs / brickW;
            const float shade = 0.85f + 0.15f * float((brick * 7919) % 13) / 12.0f;
            const Color c = isMortar ? Color{0.75f, 0.73f, 0.68f} : Color{0.62f * shade, 0.22f * shade, 0.14f * shade};
            std::uint8_t* t = img.texel(x, y);
            t[0] = to8(c.r);
            t[1] = to8(c.g);
            t[2] = to8(c.b);
            t[3] = 255;
        }
    return img;
}

} // namespace sr
