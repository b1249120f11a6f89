// Image-based light: the sky on a latitude-longitude grid, its SH irradiance, GGX-prefiltered levels, the split-sum table.
#include "Raster/Shade/Ibl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "Raster/Shade/Brdf.hpp" // kMinRoughness
#include "Raster/Shade/ColorSpace.hpp"

namespace sr {
namespace {

constexpr double kPiIbl = 3.14159265358979323846;

// The unit direction of a grid point: theta from the zenith (+Y), phi from +X toward +Z.
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

} // namespace

Vec3 ImageLight::Grid::sample(Vec3 r) const {
    const double len = std::sqrt(double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z);
    if (!(len > 0.0) || !std::isfinite(len)) return texels[0];
    double phi = std::atan2(double(r.z), double(r.x));
    if (phi < 0.0) phi += 2.0 * kPiIbl;
    const double theta = std::acos(std::clamp(double(r.y) / len, -1.0, 1.0));
    const double fx = phi / (2.0 * kPiIbl) * width - 0.5, fy = theta / kPiIbl * height - 0.5;
    const double x0f = std::floor(fx), y0f = std::floor(fy);
    const float wx = float(fx - x0f), wy = float(fy - y0f);
    const int x0 = ((int(x0f) % width) + width) % width, x1 = (x0 + 1) % width;
    const int y0 = std::clamp(int(y0f), 0, height - 1), y1 = std::clamp(int(y0f) + 1, 0, height - 1);
    const auto at = [&](int x, int y) { return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; };
    const Vec3 top = at(x0, y0) * (1.0f - wx) + at(x1, y0) * wx;
    const Vec3 bottom = at(x0, y1) * (1.0f - wx) + at(x1, y1) * wx;
    return top * (1.0f - wy) + bottom * wy;
}

ImageLight::ImageLight(const Sky& sky) {
    // The sky in linear light on a 128 x 64 grid, each texel the mean of 4 x 4 directions.
    Grid& base = levels_[0];
    base.width = 128;
    base.height = 64;
    base.texels.resize(std::size_t(base.width) * std::size_t(base.height));
    for (int y = 0; y < base.height; ++y)
        for (int x = 0; x < base.width; ++x) {
            double sum[3] = {0, 0, 0};
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    const double theta = kPiIbl * (y + (j + 0.5) / 4.0) / base.height;
                    const double phi = 2.0 * kPiIbl * (x + (i + 0.5) / 4.0) / base.width;
                    const Color c = sky.sample(direction(theta, phi));
                    sum[0] += srgbToLinear(std::clamp(c.r, 0.0f, 1.0f));
                    sum[1] += srgbToLinear(std::clamp(c.g, 0.0f, 1.0f));
                    sum[2] += srgbToLinear(std::clamp(c.b, 0.0f, 1.0f));
                }
            base.texels[std::size_t(y) * std::size_t(base.width) + std::size_t(x)] =
                Vec3{float(sum[0] / 16.0), float(sum[1] / 16.0), float(sum[2] / 16.0)};
        }

    // Irradiance: the projection on bands 0-2 (solid angle sin(theta) dtheta dphi per texel),
    // each band convolved with the clamped cosine (pi, 2 pi / 3, pi / 4), divided by pi.
    std::array<double, 27> coefficients{};
    const double dTheta = kPiIbl / base.height, dPhi = 2.0 * kPiIbl / base.width;
    for (int y = 0; y < base.height; ++y) {
        const double theta = (y + 0.5) * dTheta;
        const double weight = std::sin(theta) * dTheta * dPhi;
        for (int x = 0; x < base.width; ++x) {
            const Vec3 d = direction(theta, (x + 0.5) * dPhi);
            const std::array<double, 9> basis = shBasis(d.x, d.y, d.z);
            const Vec3 l = base.texels[std::size_t(y) * std::size_t(base.width) + std::size_t(x)];
            for (int k = 0; k < 9; ++k) {
                coefficients[std::size_t(3 * k)] += double(l.x) * basis[std::size_t(k)] * weight;
                coefficients[std::size_t(3 * k + 1)] += double(l.y) * basis[std::size_t(k)] * weight;
                coefficients[std::size_t(3 * k + 2)] += double(l.z) * basis[std::size_t(k)] * weight;
            }
        }
    }
    const double band[9] = {kPiIbl, 2.0 * kPiIbl / 3.0, 2.0 * kPiIbl / 3.0, 2.0 * kPiIbl / 3.0, kPiIbl / 4.0, kPiIbl / 4.0, kPiIbl / 4.0, kPiIbl / 4.0, kPiIbl / 4.0};
    for (int k = 0; k < 9; ++k)
        sh_[std::size_t(k)] = Vec3{float(coefficients[std::size_t(3 * k)] * band[k] / kPiIbl),
                                   float(coefficients[std::size_t(3 * k + 1)] * band[k] / kPiIbl),
                                   float(coefficients[std::size_t(3 * k + 2)] * band[k] / kPiIbl)};

    // Specular levels: GGX around R = N = V, weighted by N.L (Karis 2013), from the base grid.
    constexpr int kSamples = 256;
    for (int level = 1; level < kLevels; ++level) {
        const double roughness = double(level) / double(kLevels - 1);
        const double alpha = roughness * roughness;
        Grid& g = levels_[std::size_t(level)];
        g.width = 64;
        g.height = 32;
        g.texels.resize(std::size_t(g.width) * std::size_t(g.height));
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x) {
                const Vec3 n = direction(kPiIbl * (y + 0.5) / g.height, 2.0 * kPiIbl * (x + 0.5) / g.width);
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
                    const Vec3 c = base.sample(l);
                    sum[0] += double(c.x) * nDotL;
                    sum[1] += double(c.y) * nDotL;
                    sum[2] += double(c.z) * nDotL;
                    total += nDotL;
                }
                g.texels[std::size_t(y) * std::size_t(g.width) + std::size_t(x)] =
                    total > 0.0 ? Vec3{float(sum[0] / total), float(sum[1] / total), float(sum[2] / total)} : base.sample(n);
            }
    }

    // The split sum's table: for V at N.V in the plane xz and N = +Z, the GGX lobe's samples
    // weighted by Vis 4 N.L V.H / N.H (Vis the height-correlated Smith term of Brdf.hpp), split
    // by Schlick's (1 - V.H)^5 into the scale and the bias of F0.
    lutA_.assign(std::size_t(kLut) * std::size_t(kLut), 0.0f);
    lutB_.assign(std::size_t(kLut) * std::size_t(kLut), 0.0f);
    for (int j = 0; j < kLut; ++j) {
        const double roughness = std::max(double(j) / double(kLut - 1), double(kMinRoughness));
        const double alpha = roughness * roughness, a2 = alpha * alpha;
        for (int i = 0; i < kLut; ++i) {
            const double nDotV = std::max(double(i) / double(kLut - 1), 1e-4);
            const double vx = std::sqrt(1.0 - nDotV * nDotV), vz = nDotV;
            double a = 0.0, b = 0.0;
            for (int s = 0; s < kSamples; ++s) {
                double hx, hy, hz;
                ggxHalfVector(s, kSamples, alpha, hx, hy, hz);
                const double vDotH = vx * hx + vz * hz;
                const double lz = 2.0 * vDotH * hz - vz;
                if (!(lz > 0.0) || !(vDotH > 0.0)) continue;
                const double nDotL = lz;
                const double vis = 0.5 / (nDotL * std::sqrt(nDotV * nDotV * (1.0 - a2) + a2) +
                                          nDotV * std::sqrt(nDotL * nDotL * (1.0 - a2) + a2));
                const double g = vis * 4.0 * nDotL * vDotH / hz;
                const double fc = std::pow(1.0 - vDotH, 5.0);
                a += (1.0 - fc) * g;
                b += fc * g;
            }
            lutA_[std::size_t(j * kLut + i)] = float(a / kSamples);
            lutB_[std::size_t(j * kLut + i)] = float(b / kSamples);
        }
    }
}

Vec3 ImageLight::diffuse(Vec3 n) const {
    const std::array<double, 9> basis = shBasis(n.x, n.y, n.z);
    double e[3] = {0, 0, 0};
    for (int k = 0; k < 9; ++k) {
        e[0] += double(sh_[std::size_t(k)].x) * basis[std::size_t(k)];
        e[1] += double(sh_[std::size_t(k)].y) * basis[std::size_t(k)];
        e[2] += double(sh_[std::size_t(k)].z) * basis[std::size_t(k)];
    }
    return {float(std::max(e[0], 0.0)), float(std::max(e[1], 0.0)), float(std::max(e[2], 0.0))};
}

Vec3 ImageLight::specular(Vec3 r, float roughness) const {
    const float t = (roughness >= 0.0f ? std::min(roughness, 1.0f) : 0.0f) * float(kLevels - 1);
    const int lo = std::min(int(t), kLevels - 2);
    const float w = t - float(lo);
    const Vec3 a = levels_[std::size_t(lo)].sample(r), b = levels_[std::size_t(lo + 1)].sample(r);
    return a * (1.0f - w) + b * w;
}

void ImageLight::brdfScaleBias(float nDotV, float roughness, float& a, float& b) const {
    const auto unit = [](float x) { return x >= 0.0f ? std::min(x, 1.0f) : 0.0f; };
    const float fx = unit(nDotV) * float(kLut - 1), fy = unit(roughness) * float(kLut - 1);
    const int x0 = std::min(int(fx), kLut - 2), y0 = std::min(int(fy), kLut - 2);
    const float wx = fx - float(x0), wy = fy - float(y0);
    const auto bilinear = [&](const std::vector<float>& t) {
        const auto at = [&](int x, int y) { return t[std::size_t(y * kLut + x)]; };
        const float top = at(x0, y0) * (1.0f - wx) + at(x0 + 1, y0) * wx;
        const float bottom = at(x0, y0 + 1) * (1.0f - wx) + at(x0 + 1, y0 + 1) * wx;
        return top * (1.0f - wy) + bottom * wy;
    };
    a = bilinear(lutA_);
    b = bilinear(lutB_);
}

} // namespace sr
