// The sky: the cube map's seamless bilinear sampling, the gradient, and the pass behind the geometry.
#include "Raster/Frame/Sky.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "Raster/Frame/Msaa.hpp"

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

std::uint32_t CubeMap::samplePacked(float rx, float ry, float rz) const {
    if (!(std::isfinite(rx) && std::isfinite(ry) && std::isfinite(rz)) || (rx == 0.0f && ry == 0.0f && rz == 0.0f)) {
        rx = 1.0f;
        ry = rz = 0.0f;
    }
    // faceOf in float: the same comparisons on the same values pick the same face.
    const float ax = std::fabs(rx), ay = std::fabs(ry), az = std::fabs(rz);
    int face;
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = rx >= 0.0f ? int(CubeFace::PosX) : int(CubeFace::NegX);
        sc = rx >= 0.0f ? -rz : rz;
        tc = -ry;
        ma = ax;
    } else if (ay >= az) {
        face = ry >= 0.0f ? int(CubeFace::PosY) : int(CubeFace::NegY);
        sc = rx;
        tc = ry >= 0.0f ? rz : -rz;
        ma = ay;
    } else {
        face = rz >= 0.0f ? int(CubeFace::PosZ) : int(CubeFace::NegZ);
        sc = rz >= 0.0f ? rx : -rx;
        tc = -ry;
        ma = az;
    }
    const float half = 0.5f * float(size_), inv = 1.0f / ma;
    const float u = (sc * inv + 1.0f) * half - 0.5f, v = (tc * inv + 1.0f) * half - 0.5f;
    const float fu = std::floor(u), fv = std::floor(v);
    const int x0 = std::clamp(int(fu), -1, size_ - 1), y0 = std::clamp(int(fv), -1, size_ - 1);
    const float fx = std::clamp(u - float(x0), 0.0f, 1.0f), fy = std::clamp(v - float(y0), 0.0f, 1.0f);
    const std::uint32_t* row0 =
        &texels_[(std::size_t(face) * std::size_t(stride_) + std::size_t(y0 + 1)) * std::size_t(stride_) + std::size_t(x0 + 1)];
    const std::uint32_t* row1 = row0 + stride_;
    const std::uint32_t t00 = row0[0], t10 = row0[1], t01 = row1[0], t11 = row1[1];
    const auto mix = [&](int shift) -> std::uint32_t {
        const auto c = [shift](std::uint32_t t) { return float((t >> shift) & 0xFFu); };
        const float top = c(t00) + (c(t10) - c(t00)) * fx, bottom = c(t01) + (c(t11) - c(t01)) * fx;
        const float m = top + (bottom - top) * fy; // in [0, 255]
        return std::uint32_t(std::clamp(m + 0.5f, 0.0f, 255.0f));
    };
    return 0xFF000000u | mix(0) << 16 | mix(8) << 8 | mix(16); // RGBA texel -> BGRX pixel
}

Color SkyGradient::above(float t) const {
    return {horizon.r + (zenith.r - horizon.r) * t, horizon.g + (zenith.g - horizon.g) * t,
            horizon.b + (zenith.b - horizon.b) * t, 1.0f};
}

Color SkyGradient::sample(Vec3 r) const {
    const double len = std::sqrt(double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z);
    const double e = len > 0.0 && std::isfinite(len) ? double(r.y) / len : 0.0;
    if (e < 0.0) return ground;
    return above(float(std::min(e, 1.0)));
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

// The sky pass's colour per pixel centre, set up once per call: the ray of ViewRays::at term for
// term (the same float ray as rays.at(ndcX, ndcY)); the gradient from a table of
// kGradientSteps + 1 colours by elevation (the elevation in float, rounded to the nearest step:
// off by at most 1/(2 kGradientSteps) in t, so within one unit per channel of Sky::sample), the
// cube map through CubeMap::samplePacked. The reference Sky::sample costs a double sqrt, a
// division, a Color and a packBgra8 per pixel; this costs a table load (gradient) or the float
// bilinear (cube).
class SkyPainter {
public:
    SkyPainter(const Sky& sky, const ViewRays& rays, int width, int height)
        : sky_(sky), rays_(rays), width_(width), height_(height) {
        if (sky.kind != Sky::Kind::Gradient) return;
        ground_ = packBgra8(sky.gradient.ground);
        for (int i = 0; i <= kGradientSteps; ++i)
            table_[std::size_t(i)] = packBgra8(sky.gradient.above(float(i) / float(kGradientSteps)));
    }

    void setRow(int y) {
        const double ndcY = 1.0 - 2.0 * (y + 0.5) / height_;
        upX_ = ndcY * rays_.up.x;
        upY_ = ndcY * rays_.up.y;
        upZ_ = ndcY * rays_.up.z;
    }

    std::uint32_t at(int x) const {
        const double ndcX = 2.0 * (x + 0.5) / width_ - 1.0;
        const float rx = float(rays_.forward.x + ndcX * rays_.right.x + upX_);
        const float ry = float(rays_.forward.y + ndcX * rays_.right.y + upY_);
        const float rz = float(rays_.forward.z + ndcX * rays_.right.z + upZ_);
        switch (sky_.kind) {
        case Sky::Kind::Gradient: {
            const float len2 = rx * rx + ry * ry + rz * rz;
            if (!(len2 > 0.0f && len2 <= std::numeric_limits<float>::max())) // zero, NaN, overflow:
                return packBgra8(sky_.sample({rx, ry, rz}));                 // the reference decides
            const float e = ry / std::sqrt(len2);
            if (e < 0.0f) return ground_;
            return table_[std::size_t(std::min(e, 1.0f) * float(kGradientSteps) + 0.5f)];
        }
        case Sky::Kind::Cube:
            if (sky_.cube) return sky_.cube->samplePacked(rx, ry, rz);
            return packBgra8(sky_.sample({rx, ry, rz}));
        case Sky::Kind::None: break;
        }
        return packBgra8(sky_.sample({rx, ry, rz}));
    }

private:
    static constexpr int kGradientSteps = 1024;
    const Sky& sky_;
    const ViewRays& rays_;
    int width_, height_;
    double upX_ = 0.0, upY_ = 0.0, upZ_ = 0.0;
    std::uint32_t ground_ = 0;
    std::array<std::uint32_t, kGradientSteps + 1> table_{};
};

} // namespace

std::uint64_t drawSkyRows(FrameBuffer& fb, const ViewRays& rays, const Sky& sky, int y0, int y1) {
    std::uint64_t drawn = 0;
    if (!sky.on()) return 0;
    SkyPainter painter(sky, rays, fb.width(), fb.height());
    for (int y = y0; y < y1; ++y) {
        Pixel* colour = fb.colorRow(y);
        const float* depth = fb.depthRow(y);
        painter.setRow(y);
        for (int x = 0; x < fb.width(); ++x) {
            if (depth[x] != FrameBuffer::kFarDepth) continue;
            colour[x] = painter.at(x);
            ++drawn;
        }
    }
    return drawn;
}

std::uint64_t drawSkyMsaaRows(MsaaBuffer& target, const ViewRays& rays, const Sky& sky, int y0, int y1) {
    std::uint64_t drawn = 0;
    if (!sky.on()) return 0;
    const int n = target.samples();
    SkyPainter painter(sky, rays, target.width(), target.height());
    for (int y = y0; y < y1; ++y) {
        target.prepareSpan(y, 0, target.width());
        Pixel* colour = target.colourRow(y);
        const float* depth = target.depthRow(y);
        painter.setRow(y);
        for (int x = 0; x < target.width(); ++x) {
            const std::size_t first = std::size_t(x) * std::size_t(n);
            bool any = false;
            for (int k = 0; k < n; ++k) any = any || depth[first + std::size_t(k)] == FrameBuffer::kFarDepth;
            if (!any) continue;
            const Pixel c = painter.at(x);
            for (int k = 0; k < n; ++k)
                if (depth[first + std::size_t(k)] == FrameBuffer::kFarDepth) colour[first + std::size_t(k)] = c;
            ++drawn;
        }
    }
    return drawn;
}

} // namespace sr
