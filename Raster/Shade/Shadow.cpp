// Shadow maps: the receiver test (percentage-closer filtering, slope-scaled bias) and the lighting it scales.
#include "Raster/Shade/Shadow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "Math/Transform.hpp"

namespace sr {

float ShadowMap::depthAt(float d) const {
    if (!perspective) return (farZ - d) / (farZ - nearZ); // orthographic: (z_view + far) / (far - near)
    // perspective: z_ndc = -A + B / d with A = n / (f - n), B = f n / (f - n) (Transform.hpp)
    const float a = nearZ / (farZ - nearZ), b = farZ * nearZ / (farZ - nearZ);
    return d > 0.0f ? b / d - a : std::numeric_limits<float>::max();
}

float ShadowMap::visibility(Vec3 p, Vec3 n, Vec3 l, const ShadowSettings& s) const {
    const Vec4 c = viewProj * Vec4(p, 1.0f);
    if (!(c.w > 0.0f)) return 1.0f;
    const int size = target.width();
    const float u = (c.x / c.w + 1.0f) * 0.5f * float(size), v = (1.0f - c.y / c.w) * 0.5f * float(size);
    if (!(u >= 0.0f && v >= 0.0f && u < float(size) && v < float(size))) return 1.0f; // outside: lit
    const float d = dot(p - origin, axis);
    // Slope-scaled bias in world units: the texel's world size at p times (constant + slope x
    // tan(theta)), theta between the normal and the light.
    const float cosT = std::clamp(std::fabs(dot(n, l)), 1e-4f, 1.0f);
    const float tanT = std::min(std::sqrt(std::max(1.0f - cosT * cosT, 0.0f)) / cosT, kMaxBiasTangent);
    const float texelSize = perspective ? texelWorld * d : texelWorld;
    const float receiver = depthAt(d - texelSize * (s.constantBias + s.slopeBias * tanT));
    const int half = std::max(s.pcf, 1) / 2;
    const int tx = int(u), ty = int(v);
    int lit = 0, taps = 0;
    for (int dy = -half; dy <= half; ++dy)
        for (int dx = -half; dx <= half; ++dx) {
            ++taps;
            const int x = tx + dx, y = ty + dy;
            if (x < 0 || y < 0 || x >= size || y >= size) {
                ++lit;
                continue;
            }
            lit += receiver >= texel(x, y); // reversed-Z: not behind the nearest caster
        }
    return float(lit) / float(taps);
}

RgbTerms shadowedTerms(const Lighting& lighting, const Specular& specular, Vec3 n, Vec3 p, Vec3 v,
                       const SceneShadows& shadows) {
    return lightTerms(lighting, specular, n, p, v,
                      [&shadows](std::size_t light, Vec3 q, Vec3 normal, Vec3 l) { return shadows.visibility(light, q, normal, l); });
}

} // namespace sr
