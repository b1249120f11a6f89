// Length and normalisation of Vec2/3/4, robust against overflow, underflow and non-finite input.
#include "Vec.hpp"

#include <limits>

namespace sr {
namespace {

// Largest |component| of an N-float array (NaN-aware: returns NaN if any component is NaN).
template <int N>
float maxAbs(const float (&c)[N]) {
    float m = 0.0f;
    for (float v : c) {
        if (std::isnan(v)) return v;
        m = std::max(m, std::fabs(v));
    }
    return m;
}

// Euclidean length of c, computed as m * sqrt(sum((c/m)^2)) with m = max|c_i| (LAPACK's
// xNRM2 idea without the incremental update): no overflow below FLT_MAX, no underflow above 0.
template <int N>
float robustLength(const float (&c)[N]) {
    const float m = maxAbs(c);
    if (!(m > 0.0f) || std::isinf(m)) return m; // 0, NaN or Inf
    float sum = 0.0f;
    for (float v : c) {
        const float s = v / m;
        sum += s * s;
    }
    return m * std::sqrt(sum);
}

// c normalised in place; see the contract on normalize() in Vec.hpp.
template <int N>
void robustNormalize(float (&c)[N]) {
    const float m = maxAbs(c);
    if (std::isnan(m)) {
        for (float& v : c) v = std::numeric_limits<float>::quiet_NaN();
        return;
    }
    if (m == 0.0f) return; // zero stays zero
    if (std::isinf(m)) {
        // Keep only the infinite components, as +-1, then normalise those.
        for (float& v : c) v = std::isinf(v) ? (v > 0.0f ? 1.0f : -1.0f) : 0.0f;
        robustNormalize(c);
        return;
    }
    float sum = 0.0f;
    for (float& v : c) {
        v /= m;
        sum += v * v;
    }
    const float inv = 1.0f / std::sqrt(sum);
    for (float& v : c) v *= inv;
}

} // namespace

float length(Vec2 v) { const float c[2] = {v.x, v.y}; return robustLength(c); }
float length(Vec3 v) { const float c[3] = {v.x, v.y, v.z}; return robustLength(c); }
float length(Vec4 v) { const float c[4] = {v.x, v.y, v.z, v.w}; return robustLength(c); }

Vec2 normalize(Vec2 v) {
    float c[2] = {v.x, v.y};
    robustNormalize(c);
    return {c[0], c[1]};
}
Vec3 normalizeRobust(Vec3 v) {
    float c[3] = {v.x, v.y, v.z};
    robustNormalize(c);
    return {c[0], c[1], c[2]};
}
Vec4 normalize(Vec4 v) {
    float c[4] = {v.x, v.y, v.z, v.w};
    robustNormalize(c);
    return {c[0], c[1], c[2], c[3]};
}

} // namespace sr
