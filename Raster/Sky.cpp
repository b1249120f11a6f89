// The sky: the cube map's seamless bilinear sampling, the gradient, and the pass behind the geometry.
#include "Raster/Sky.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "Raster/Msaa.hpp"

namespace sr {

namespace {

std::uint32_t packTexel(const std::uint8_t* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

// Table 8.19: the face of direction r, and (sc, tc, |ma|).
struct FaceCoords {
    int face = 0;
    double sc = 0.0, tc = 0.0, ma = 1.0;
};
FaceCoords faceOf(double rx, double ry, double rz) {
    const double ax = std::fabs(rx), ay = std::fabs(ry), az = std::fabs(rz);
    if (ax >= ay && ax >= az) {
        if (rx >= 0.0) return {int(CubeFace::PosX), -rz, -ry, ax};
        return {int(CubeFace::NegX), rz, -ry, ax};
    }
    if (ay >= az) {
        if (ry >= 0.0) return {int(CubeFace::PosY), rx, rz, ay};
        return {int(CubeFace::NegY), rx, -rz, ay};
    }
    if (rz >= 0.0) return {int(CubeFace::PosZ), rx, -ry, az};
    return {int(CubeFace::NegZ), -rx, -ry, az};
}

// The inverse of faceOf for a point (sc, tc) of `face`'s plane (ma = 1).
void directionOf(int face, double sc, double tc, double& rx, double& ry, double& rz) {
    switch (CubeFace(face)) {
    case CubeFace::PosX: rx = 1; rz = -sc; ry = -tc; return;
    case CubeFace::NegX: rx = -1; rz = sc; ry = -tc; return;
    case CubeFace::PosY: ry = 1; rx = sc; rz = tc; return;
    case CubeFace::NegY: ry = -1; rx = sc; rz = -tc; return;
    case CubeFace::PosZ: rz = 1; rx = sc; ry = -tc; return;
    case CubeFace::NegZ: rz = -1; rx = -sc; ry = -tc; return;
    }
}

float channel(std::uint32_t t, int shift) { return float((t >> shift) & 0xFFu) / 255.0f; }

} // namespace

CubeMap CubeMap::fromRgba8(int size, const std::array<const std::uint8_t*, kCubeFaces>& faces) {
    bool ok = size >= 1 && size <= 16384;
    for (const std::uint8_t* f : faces) ok = ok && f != nullptr;
    assert(ok && "CubeMap::fromRgba8: bad size or a missing face");
    CubeMap m;
    if (!ok) {
        static const std::uint8_t magenta[4] = {255, 0, 255, 255};
        return fromRgba8(1, {magenta, magenta, magenta, magenta, magenta, magenta});
    }
    const int n = size;
    m.size_ = n;
    m.stride_ = n + 2;
    m.texels_.assign(std::size_t(kCubeFaces) * std::size_t(m.stride_) * std::size_t(m.stride_), 0u);
    const auto at = [&](int face, int x, int y) -> std::uint32_t& {
        return m.texels_[(std::size_t(face) * std::size_t(m.stride_) + std::size_t(y + 1)) * std::size_t(m.stride_) +
                         std::size_t(x + 1)];
    };
    for (int f = 0; f < kCubeFaces; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) at(f, x, y) = packTexel(faces[std::size_t(f)] + (std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4);
    // The border: the texel of the neighbouring face nearest to the border texel's centre,
    // found by carrying that centre (just outside the face's square) back through table 8.19.
    for (int f = 0; f < kCubeFaces; ++f)
        for (int y = -1; y <= n; ++y)
            for (int x = -1; x <= n; ++x) {
                if (x >= 0 && x < n && y >= 0 && y < n) continue;
                double rx = 0, ry = 0, rz = 0;
                directionOf(f, 2.0 * (x + 0.5) / n - 1.0, 2.0 * (y + 0.5) / n - 1.0, rx, ry, rz);
                FaceCoords c = faceOf(rx, ry, rz);
                if (c.face == f) { // a corner the tie rule keeps on this face: its nearest own texel
                    at(f, x, y) = at(f, std::clamp(x, 0, n - 1), std::clamp(y, 0, n - 1));
                    continue;
                }
                const int tx = std::clamp(int(std::floor((c.sc / c.ma + 1.0) * 0.5 * n)), 0, n - 1);
                const int ty = std::clamp(int(std::floor((c.tc / c.ma + 1.0) * 0.5 * n)), 0, n - 1);
                at(f, x, y) = at(c.face, tx, ty);
            }
    return m;
}

std::uint32_t CubeMap::texel(int face, int x, int y) const {
    return texels_[(std::size_t(face) * std::size_t(stride_) + std::size_t(y + 1)) * std::size_t(stride_) + std::size_t(x + 1)];
}

Color CubeMap::sample(Vec3 r) const {
    double rx = r.x, ry = r.y, rz = r.z;
    if (!(std::isfinite(rx) && std::isfinite(ry) && std::isfinite(rz)) || (rx == 0.0 && ry == 0.0 && rz == 0.0)) {
        rx = 1.0;
        ry = rz = 0.0;
    }
    const FaceCoords c = faceOf(rx, ry, rz);
    const double n = size_;
    // Texel coordinates with centres at +0.5; |sc|, |tc| <= ma, so u, v lie in [-0.5, n - 0.5]
    // and the 2 x 2 footprint in [-1, n]: inside the bordered face.
    const double u = (c.sc / c.ma + 1.0) * 0.5 * n - 0.5, v = (c.tc / c.ma + 1.0) * 0.5 * n - 0.5;
    const int x0 = std::clamp(int(std::floor(u)), -1, size_ - 1), y0 = std::clamp(int(std::floor(v)), -1, size_ - 1);
    const double fx = std::clamp(u - x0, 0.0, 1.0), fy = std::clamp(v - y0, 0.0, 1.0);
    const std::uint32_t t00 = texel(c.face, x0, y0), t10 = texel(c.face, x0 + 1, y0), t01 = texel(c.face, x0, y0 + 1),
                        t11 = texel(c.face, x0 + 1, y0 + 1);
    const auto mix = [&](int shift) {
        const double top = channel(t00, shift) * (1.0 - fx) + channel(t10, shift) * fx;
        const double bottom = channel(t01, shift) * (1.0 - fx) + channel(t11, shift) * fx;
        return float(top * (1.0 - fy) + bottom * fy);
    };
    return {mix(0), mix(8), mix(16), mix(24)};
}

Color SkyGradient::sample(Vec3 r) const {
    const double len = std::sqrt(double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z);
    const double e = len > 0.0 && std::isfinite(len) ? double(r.y) / len : 0.0;
    if (e < 0.0) return ground;
    const float t = float(std::min(e, 1.0));
    return {horizon.r + (zenith.r - horizon.r) * t, horizon.g + (zenith.g - horizon.g) * t,
            horizon.b + (zenith.b - horizon.b) * t, 1.0f};
}

Color Sky::sample(Vec3 r) const {
    switch (kind) {
    case Kind::None: return {0.0f, 0.0f, 0.0f, 1.0f};
    case Kind::Gradient: return gradient.sample(r);
    case Kind::Cube: return cube ? cube->sample(r) : Color{0.0f, 0.0f, 0.0f, 1.0f};
    }
    return {0.0f, 0.0f, 0.0f, 1.0f};
}

Vec3 ViewRays::at(double ndcX, double ndcY) const {
    return {float(forward.x + ndcX * right.x + ndcY * up.x), float(forward.y + ndcX * right.y + ndcY * up.y),
            float(forward.z + ndcX * right.z + ndcY * up.z)};
}

namespace {

// The direction through the centre of pixel (x, y) of a w x h image.
Vec3 rayThrough(const ViewRays& rays, int x, int y, int w, int h) {
    return rays.at(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h);
}

} // namespace

std::uint64_t drawSkyRows(FrameBuffer& fb, const ViewRays& rays, const Sky& sky, int y0, int y1) {
    std::uint64_t drawn = 0;
    if (!sky.on()) return 0;
    for (int y = y0; y < y1; ++y) {
        Pixel* colour = fb.colorRow(y);
        const float* depth = fb.depthRow(y);
        for (int x = 0; x < fb.width(); ++x) {
            if (depth[x] != FrameBuffer::kFarDepth) continue;
            colour[x] = packBgra8(sky.sample(rayThrough(rays, x, y, fb.width(), fb.height())));
            ++drawn;
        }
    }
    return drawn;
}

std::uint64_t drawSkyMsaaRows(MsaaBuffer& target, const ViewRays& rays, const Sky& sky, int y0, int y1) {
    std::uint64_t drawn = 0;
    if (!sky.on()) return 0;
    const int n = target.samples();
    for (int y = y0; y < y1; ++y) {
        Pixel* colour = target.colourRow(y);
        const float* depth = target.depthRow(y);
        for (int x = 0; x < target.width(); ++x) {
            const std::size_t first = std::size_t(x) * std::size_t(n);
            bool any = false;
            for (int k = 0; k < n; ++k) any = any || depth[first + std::size_t(k)] == FrameBuffer::kFarDepth;
            if (!any) continue;
            const Pixel c = packBgra8(sky.sample(rayThrough(rays, x, y, target.width(), target.height())));
            for (int k = 0; k < n; ++k)
                if (depth[first + std::size_t(k)] == FrameBuffer::kFarDepth) colour[first + std::size_t(k)] = c;
            ++drawn;
        }
    }
    return drawn;
}

} // namespace sr
