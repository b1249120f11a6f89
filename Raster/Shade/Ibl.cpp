// Image-based light: the sky's SH irradiance, its radiance on octahedral levels prefiltered by GGX, the split-sum table.
#include "Raster/Shade/Ibl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "Raster/Shade/ColorSpace.hpp"

namespace sr {
namespace {

constexpr double kPiIbl = 3.14159265358979323846;

// The unit direction of a latitude-longitude point: theta from the zenith (+Y), phi from +X toward +Z.
Vec3 direction(double theta, double phi) {
    return {float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi))};
}

// Van der Corput's radical inverse in base 2 (the Hammersley set's second coordinate).
double radicalInverse(std::uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * 2.3283064365386963e-10;
}

// A GGX-distributed half vector around +Z for sample i of n (Karis 2013, ImportanceSampleGGX).
void ggxHalfVector(int i, int n, double alpha, double& hx, double& hy, double& hz) {
    const double phi = 2.0 * kPiIbl * (double(i) + 0.5) / double(n);
    const double xi = radicalInverse(std::uint32_t(i));
    const double cosTheta = std::sqrt((1.0 - xi) / (1.0 + (alpha * alpha - 1.0) * xi));
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    hx = sinTheta * std::cos(phi);
    hy = sinTheta * std::sin(phi);
    hz = cosTheta;
}

// The real spherical harmonics of bands 0-2 at the unit direction (x, y, z).
std::array<double, 9> shBasis(double x, double y, double z) {
    return {0.282095, 0.488603 * y, 0.488603 * z, 0.488603 * x, 1.092548 * x * y, 1.092548 * y * z,
            0.315392 * (3.0 * z * z - 1.0), 1.092548 * x * z, 0.546274 * (x * x - y * y)};
}

// The sky in linear light along r.
Vec3 linearSky(const Sky& sky, Vec3 r) {
    const Color c = sky.sample(r);
    return {srgbToLinear(std::clamp(c.r, 0.0f, 1.0f)), srgbToLinear(std::clamp(c.g, 0.0f, 1.0f)),
            srgbToLinear(std::clamp(c.b, 0.0f, 1.0f))};
}

// The octahedral square's coordinate of grid column (or row) i plus a fraction f in [0, 1) of
// the texel: column 1 starts at -1, column kSide ends at +1 (columns 0 and kSide + 1 the border).
double gridToSquare(int i, double f) { return (double(i - 1) + f) / double(ImageLight::kSide) * 2.0 - 1.0; }

} // namespace

Vec3 ImageLight::octahedralDirection(double u, double v) {
    // Across an edge of the square the map continues on the same edge, mirrored (u > 1 is
    // (2 - u, -v)): the edges are where the folded lower hemisphere meets itself.
    if (u > 1.0) u = 2.0 - u, v = -v;
    if (u < -1.0) u = -2.0 - u, v = -v;
    if (v > 1.0) v = 2.0 - v, u = -u;
    if (v < -1.0) v = -2.0 - v, u = -u;
    double x = u, z = v;
    const double y = 1.0 - std::fabs(u) - std::fabs(v);
    if (y < 0.0) {
        x = (1.0 - std::fabs(v)) * (u < 0.0 ? -1.0 : 1.0);
        z = (1.0 - std::fabs(u)) * (v < 0.0 ? -1.0 : 1.0);
    }
    const double len = std::sqrt(x * x + y * y + z * z);
    return {float(x / len), float(y / len), float(z / len)};
}

ImageLight::ImageLight(const Sky& sky) {
    // Irradiance: the sky in linear light on a 128 x 64 latitude-longitude grid (each texel the
    // mean of 4 x 4 directions) projected on bands 0-2 (solid angle sin(theta) dtheta dphi per
    // texel), each band convolved with the clamped cosine (pi, 2 pi / 3, pi / 4), divided by pi.
    constexpr int kLatLongW = 128, kLatLongH = 64;
    std::array<double, 27> coefficients{};
    const double dTheta = kPiIbl / kLatLongH, dPhi = 2.0 * kPiIbl / kLatLongW;
    for (int y = 0; y < kLatLongH; ++y) {
        const double theta = (y + 0.5) * dTheta;
        const double weight = std::sin(theta) * dTheta * dPhi;
        for (int x = 0; x < kLatLongW; ++x) {
            double l[3] = {0, 0, 0};
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    const Vec3 c = linearSky(sky, direction(kPiIbl * (y + (j + 0.5) / 4.0) / kLatLongH,
                                                            2.0 * kPiIbl * (x + (i + 0.5) / 4.0) / kLatLongW));
                    l[0] += c.x / 16.0;
                    l[1] += c.y / 16.0;
                    l[2] += c.z / 16.0;
                }
            const Vec3 d = direction(theta, (x + 0.5) * dPhi);
            const std::array<double, 9> basis = shBasis(d.x, d.y, d.z);
            for (int k = 0; k < 9; ++k)
                for (int c = 0; c < 3; ++c) coefficients[std::size_t(3 * k + c)] += double(float(l[c])) * basis[std::size_t(k)] * weight;
        }
    }
    const double band[9] = {kPiIbl, 2.0 * kPiIbl / 3.0, 2.0 * kPiIbl / 3.0, 2.0 * kPiIbl / 3.0, kPiIbl / 4.0, kPiIbl / 4.0, kPiIbl / 4.0, kPiIbl / 4.0, kPiIbl / 4.0};
    for (int k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c) tables_.sh[k][c] = float(coefficients[std::size_t(3 * k + c)] * band[k] / kPiIbl);

    // Level 0: the sky itself, each texel (the border's too, across its fold) the mean of 4 x 4
    // directions within it.
    for (auto& channel : radiance_) channel.assign(std::size_t(kLevels) * std::size_t(kLevelTexels), 0.0f);
    for (std::size_t c = 0; c < 3; ++c) tables_.radiance[c] = radiance_[c].data();
    const BrdfAlbedoTable& lut = brdfAlbedoTable();
    tables_.lutA = lut.a.data();
    tables_.lutB = lut.b.data();
    const auto put = [&](int level, int x, int y, Vec3 c) {
        const std::size_t at = std::size_t(level) * std::size_t(kLevelTexels) + std::size_t(y) * std::size_t(kStride) + std::size_t(x);
        radiance_[0][at] = c.x;
        radiance_[1][at] = c.y;
        radiance_[2][at] = c.z;
    };
    for (int y = 0; y < kStride; ++y)
        for (int x = 0; x < kStride; ++x) {
            double sum[3] = {0, 0, 0};
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    const Vec3 c = linearSky(sky, octahedralDirection(gridToSquare(x, (i + 0.5) / 4.0), gridToSquare(y, (j + 0.5) / 4.0)));
                    sum[0] += c.x;
                    sum[1] += c.y;
                    sum[2] += c.z;
                }
            put(0, x, y, Vec3{float(sum[0] / 16.0), float(sum[1] / 16.0), float(sum[2] / 16.0)});
        }

    // Levels 1-5: GGX around R = N = V, weighted by N.L (Karis 2013), from level 0 (read as the
    // lookups read it), at each texel's centre direction.
    const Tables& t = tables_;
    const auto level0 = [&](Vec3 d) {
        float fx, fy, c[3];
        ibl::iblGridPosition(d.x, d.y, d.z, fx, fy);
        ibl::iblGridSample(t, 0.0f, fx, fy, c);
        return Vec3{c[0], c[1], c[2]};
    };
    constexpr int kSamples = 256;
    for (int level = 1; level < kLevels; ++level) {
        const double roughness = double(level) / double(kLevels - 1);
        const double alpha = roughness * roughness;
        for (int y = 0; y < kStride; ++y)
            for (int x = 0; x < kStride; ++x) {
                const Vec3 n = octahedralDirection(gridToSquare(x, 0.5), gridToSquare(y, 0.5));
                // A frame around n.
                const Vec3 up = std::fabs(n.y) < 0.999f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
                const Vec3 tx = normalize(cross(up, n)), ty = cross(n, tx);
                double sum[3] = {0, 0, 0}, total = 0.0;
                for (int i = 0; i < kSamples; ++i) {
                    double hx, hy, hz;
                    ggxHalfVector(i, kSamples, alpha, hx, hy, hz);
                    const Vec3 h = tx * float(hx) + ty * float(hy) + n * float(hz);
                    const float vDotH = dot(n, h);
                    const Vec3 l = h * (2.0f * vDotH) - n;
                    const float nDotL = dot(n, l);
                    if (!(nDotL > 0.0f)) continue;
                    const Vec3 c = level0(l);
                    sum[0] += double(c.x) * nDotL;
                    sum[1] += double(c.y) * nDotL;
                    sum[2] += double(c.z) * nDotL;
                    total += nDotL;
                }
                put(level, x, y,
                    total > 0.0 ? Vec3{float(sum[0] / total), float(sum[1] / total), float(sum[2] / total)} : level0(n));
            }
    }
}

const BrdfAlbedoTable& brdfAlbedoTable() {
    // For V at N.V in the plane xz and N = +Z, the GGX lobe's samples weighted by
    // Vis 4 N.L V.H / N.H (Vis the height-correlated Smith term of Brdf.hpp), split by Schlick's
    // (1 - V.H)^5 into the scale and the bias of F0. 4096 samples a cell keep E_ss within 0.1% of
    // its converged value (1024 leave 1.2% near grazing); each row's half vectors are made once.
    // Made on first use (thread-safe), about 20 ms.
    static const BrdfAlbedoTable table = [] {
        constexpr int kLut = BrdfAlbedoTable::kSize;
        constexpr int kSamples = 4096;
        BrdfAlbedoTable t;
        std::vector<double> hxs(kSamples), hzs(kSamples);
        for (int j = 0; j < kLut; ++j) {
            const double roughness = std::max(double(j) / double(kLut - 1), double(kMinRoughness));
            const double alpha = roughness * roughness, a2 = alpha * alpha;
            for (int s = 0; s < kSamples; ++s) {
                double hy;
                ggxHalfVector(s, kSamples, alpha, hxs[std::size_t(s)], hy, hzs[std::size_t(s)]);
            }
            for (int i = 0; i < kLut; ++i) {
                const double nDotV = std::max(double(i) / double(kLut - 1), 1e-4);
                const double vx = std::sqrt(1.0 - nDotV * nDotV), vz = nDotV;
                const double gv = std::sqrt(nDotV * nDotV * (1.0 - a2) + a2);
                double a = 0.0, b = 0.0;
                for (std::size_t s = 0; s < std::size_t(kSamples); ++s) {
                    const double hx = hxs[s], hz = hzs[s];
                    const double vDotH = vx * hx + vz * hz;
                    const double nDotL = 2.0 * vDotH * hz - vz;
                    if (!(nDotL > 0.0) || !(vDotH > 0.0)) continue;
                    const double vis = 0.5 / (nDotL * gv + nDotV * std::sqrt(nDotL * nDotL * (1.0 - a2) + a2));
                    const double g = vis * 4.0 * nDotL * vDotH / hz;
                    const double m = 1.0 - vDotH, m2 = m * m, fc = m2 * m2 * m;
                    a += (1.0 - fc) * g;
                    b += fc * g;
                }
                const std::size_t at = std::size_t(j * kLut + i);
                t.a[at] = float(a / kSamples);
                t.b[at] = float(b / kSamples);
                t.ess[at] = float((a + b) / kSamples);
            }
        }
        return t;
    }();
    return table;
}

Vec3 ImageLight::diffuse(Vec3 n) const {
    float e[3];
    ibl::iblDiffuse(tables(), n.x, n.y, n.z, e);
    return {e[0], e[1], e[2]};
}

Vec3 ImageLight::specular(Vec3 r, float roughness) const {
    float s[3];
    ibl::iblSpecular(tables(), r.x, r.y, r.z, roughness, s);
    return {s[0], s[1], s[2]};
}

void ImageLight::brdfScaleBias(float nDotV, float roughness, float& a, float& b) const {
    ibl::iblScaleBias(tables(), nDotV, roughness, a, b);
}

} // namespace sr
