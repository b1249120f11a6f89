// Blinn-Phong for four pixels at once with SSE2, bit-identical to blinnPhong/normalize/packBgra8 per pixel.
#pragma once

#include <cstdint>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"
#include "Raster/Shading.hpp"

#if defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)
#include <emmintrin.h>
#define SR_HAVE_SSE2 1
#else
#define SR_HAVE_SSE2 0
#endif

// AVX2 paths (eight pixels per step), compiled for x86-64 without any compiler flag and used
// only when the CPU has AVX2 (cpuHasAvx2(), checked at run time). GCC and Clang get per-function
// target("avx2") attributes; MSVC accepts AVX2 intrinsics anywhere. MinGW is left out: its GCC
// does not align the stack to 32 bytes for spilled __m256 values (GCC bug 54412).
// No FMA is enabled, so products and sums round exactly like the scalar code.
#if SR_HAVE_SSE2 && (defined(__x86_64__) || defined(_M_X64)) && !defined(__MINGW32__) && \
    (defined(__GNUC__) || defined(__clang__) || defined(_MSC_VER))
#include <immintrin.h>
#define SR_HAVE_AVX2 1
#if defined(__GNUC__) || defined(__clang__)
#define SR_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define SR_TARGET_AVX2
#include <intrin.h>
#endif
#else
#define SR_HAVE_AVX2 0
#endif

namespace sr {

#if SR_HAVE_SSE2
namespace simd {

// Three lanes-of-four vectors (x, y, z of four pixels).
struct Vec3x4 {
    __m128 x, y, z;
};

inline Vec3x4 load3(const float* x, const float* y, const float* z) {
    return {_mm_loadu_ps(x), _mm_loadu_ps(y), _mm_loadu_ps(z)};
}

// dot(a, b) as the scalar code evaluates it: (ax*bx + ay*by) + az*bz, each product rounded
// (no FMA: SSE2 has none, and the scalar build has none either on x86-64 baseline).
inline __m128 dot(const Vec3x4& a, const Vec3x4& b) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a.x, b.x), _mm_mul_ps(a.y, b.y)), _mm_mul_ps(a.z, b.z));
}

// normalize(Vec3)'s fast path lane by lane (Math/Vec.hpp): divide by the largest |component|,
// sum of squares, 1/sqrt, three products. `ok` gets the lanes where that path applies (finite,
// non-zero, no overflow of |x|+|y|+|z|); other lanes must be redone by the scalar code.
inline Vec3x4 normalizeFast(const Vec3x4& v, __m128& ok) {
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF));
    const __m128 ax = _mm_and_ps(v.x, absMask), ay = _mm_and_ps(v.y, absMask), az = _mm_and_ps(v.z, absMask);
    const __m128 m = _mm_max_ps(_mm_max_ps(ax, ay), az);
    const __m128 total = _mm_add_ps(_mm_add_ps(ax, ay), az);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(m, _mm_setzero_ps()),
                                   _mm_cmple_ps(total, _mm_set1_ps(3.40282347e38f))));
    const __m128 x = _mm_div_ps(v.x, m), y = _mm_div_ps(v.y, m), z = _mm_div_ps(v.z, m);
    __m128 sum = _mm_mul_ps(x, x);
    sum = _mm_add_ps(sum, _mm_mul_ps(y, y));
    sum = _mm_add_ps(sum, _mm_mul_ps(z, z));
    const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(sum));
    return {_mm_mul_ps(x, inv), _mm_mul_ps(y, inv), _mm_mul_ps(z, inv)};
}

inline __m128 select(__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }

// toUnorm8 lane by lane (Math/Color.hpp): 0 for !(c > 0), 255 for c >= 1, else c*255 rounded
// to nearest-even with the 2^23 trick (SSE addps rounds like the scalar addss).
inline __m128i toUnorm8(__m128 c) {
    const __m128 x = _mm_mul_ps(c, _mm_set1_ps(255.0f));
    const __m128 two23 = _mm_set1_ps(8388608.0f);
    const __m128 rounded = _mm_sub_ps(_mm_add_ps(x, two23), two23);
    const __m128 value = select(_mm_cmpge_ps(c, _mm_set1_ps(1.0f)), _mm_set1_ps(255.0f),
                                select(_mm_cmpgt_ps(c, _mm_setzero_ps()), rounded, _mm_setzero_ps()));
    return _mm_cvttps_epi32(value);
}

// Blinn-Phong + applyTerms + packBgra8 for four pixels with unit-normalised inputs n, v
// (Shading.hpp's blinnPhong and applyTerms, operation for operation). Lanes where a half
// vector is not on the fast normalize path are cleared in `ok`. Returns false (nothing
// written) when the shininess is not a whole number in [0, 1024] (std::pow per pixel then).
// kd per lane (kdR/kdG/kdB: e.g. four texture samples).
inline bool shadeBlinnPhong(const Lighting& lighting, __m128 kdR, __m128 kdG, __m128 kdB, const Vec3x4& n,
                            const Vec3x4& v, __m128& ok, std::uint32_t out[4]) {
    const float s = lighting.shininess;
    if (!(s >= 0.0f && s <= 1024.0f && s == float(int(s)))) return false;
    __m128 diffuse = _mm_set1_ps(lighting.ambient);
    __m128 specular = _mm_setzero_ps();
    for (const Vec3& l : lighting.toLight) {
        const Vec3x4 lv{_mm_set1_ps(l.x), _mm_set1_ps(l.y), _mm_set1_ps(l.z)};
        // dot(n, l): the scalar code computes dot(n, l) with n first.
        const __m128 ndl = dot(n, lv);
        const __m128 lit = _mm_cmpgt_ps(ndl, _mm_setzero_ps());
        diffuse = select(lit, _mm_add_ps(diffuse, ndl), diffuse);
        __m128 hOk = ok;
        const Vec3x4 h = normalizeFast({_mm_add_ps(lv.x, v.x), _mm_add_ps(lv.y, v.y), _mm_add_ps(lv.z, v.z)}, hOk);
        ok = select(lit, hOk, ok); // a bad half vector matters only where it is used
        // std::max(dot(n, h), 0.0f): dot < 0 ? 0 : dot (maxps differs only for NaN, where ok fails)
        const __m128 base0 = _mm_max_ps(dot(n, h), _mm_setzero_ps());
        // shininessPow: binary exponentiation, the same multiplications in the same order.
        unsigned e = unsigned(s);
        __m128 result = _mm_set1_ps(1.0f), base = base0;
        while (e) {
            if (e & 1u) result = _mm_mul_ps(result, base);
            base = _mm_mul_ps(base, base);
            e >>= 1u;
        }
        specular = select(lit, _mm_add_ps(specular, result), specular);
    }
    specular = _mm_mul_ps(specular, _mm_set1_ps(lighting.ks));
    // applyTerms: kd * diffuse + specular per channel, then packBgra8.
    const __m128i r = toUnorm8(_mm_add_ps(_mm_mul_ps(kdR, diffuse), specular));
    const __m128i g = toUnorm8(_mm_add_ps(_mm_mul_ps(kdG, diffuse), specular));
    const __m128i b = toUnorm8(_mm_add_ps(_mm_mul_ps(kdB, diffuse), specular));
    const __m128i packed = _mm_or_si128(_mm_or_si128(_mm_set1_epi32(int(0xFF000000u)), _mm_slli_epi32(r, 16)),
                                        _mm_or_si128(_mm_slli_epi32(g, 8), b));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), packed);
    return true;
}

// The same with one kd for all four pixels.
inline bool shadeBlinnPhong(const Lighting& lighting, Color kd, const Vec3x4& n, const Vec3x4& v, __m128& ok,
                            std::uint32_t out[4]) {
    return shadeBlinnPhong(lighting, _mm_set1_ps(kd.r), _mm_set1_ps(kd.g), _mm_set1_ps(kd.b), n, v, ok, out);
}

} // namespace simd
#endif

#if SR_HAVE_AVX2
// True when the CPU and the OS support AVX2 (checked once). SR_NO_AVX2=1 in the environment
// turns the AVX2 paths off (for timing comparisons and to test the SSE2 paths on AVX2 machines).
bool cpuHasAvx2();

namespace simd8 {

// The eight-lane twins of simd:: above: the same operations in the same order, lane by lane.
struct Vec3x8 {
    __m256 x, y, z;
};

SR_TARGET_AVX2 inline __m256 dot(const Vec3x8& a, const Vec3x8& b) {
    return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y)), _mm256_mul_ps(a.z, b.z));
}

SR_TARGET_AVX2 inline __m256 select(__m256 mask, __m256 a, __m256 b) { return _mm256_blendv_ps(b, a, mask); }

SR_TARGET_AVX2 inline Vec3x8 normalizeFast(const Vec3x8& v, __m256& ok) {
    const __m256 absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF));
    const __m256 ax = _mm256_and_ps(v.x, absMask), ay = _mm256_and_ps(v.y, absMask), az = _mm256_and_ps(v.z, absMask);
    const __m256 m = _mm256_max_ps(_mm256_max_ps(ax, ay), az);
    const __m256 total = _mm256_add_ps(_mm256_add_ps(ax, ay), az);
    ok = _mm256_and_ps(ok, _mm256_and_ps(_mm256_cmp_ps(m, _mm256_setzero_ps(), _CMP_GT_OQ),
                                         _mm256_cmp_ps(total, _mm256_set1_ps(3.40282347e38f), _CMP_LE_OQ)));
    const __m256 x = _mm256_div_ps(v.x, m), y = _mm256_div_ps(v.y, m), z = _mm256_div_ps(v.z, m);
    __m256 sum = _mm256_mul_ps(x, x);
    sum = _mm256_add_ps(sum, _mm256_mul_ps(y, y));
    sum = _mm256_add_ps(sum, _mm256_mul_ps(z, z));
    const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(sum));
    return {_mm256_mul_ps(x, inv), _mm256_mul_ps(y, inv), _mm256_mul_ps(z, inv)};
}

SR_TARGET_AVX2 inline __m256i toUnorm8(__m256 c) {
    const __m256 x = _mm256_mul_ps(c, _mm256_set1_ps(255.0f));
    const __m256 two23 = _mm256_set1_ps(8388608.0f);
    const __m256 rounded = _mm256_sub_ps(_mm256_add_ps(x, two23), two23);
    const __m256 value = select(_mm256_cmp_ps(c, _mm256_set1_ps(1.0f), _CMP_GE_OQ), _mm256_set1_ps(255.0f),
                                select(_mm256_cmp_ps(c, _mm256_setzero_ps(), _CMP_GT_OQ), rounded, _mm256_setzero_ps()));
    return _mm256_cvttps_epi32(value);
}

// simd::shadeBlinnPhong for eight pixels (kd per lane).
SR_TARGET_AVX2 inline bool shadeBlinnPhong(const Lighting& lighting, __m256 kdR, __m256 kdG, __m256 kdB,
                                           const Vec3x8& n, const Vec3x8& v, __m256& ok, std::uint32_t out[8]) {
    const float s = lighting.shininess;
    if (!(s >= 0.0f && s <= 1024.0f && s == float(int(s)))) return false;
    __m256 diffuse = _mm256_set1_ps(lighting.ambient);
    __m256 specular = _mm256_setzero_ps();
    for (const Vec3& l : lighting.toLight) {
        const Vec3x8 lv{_mm256_set1_ps(l.x), _mm256_set1_ps(l.y), _mm256_set1_ps(l.z)};
        const __m256 ndl = dot(n, lv);
        const __m256 lit = _mm256_cmp_ps(ndl, _mm256_setzero_ps(), _CMP_GT_OQ);
        diffuse = select(lit, _mm256_add_ps(diffuse, ndl), diffuse);
        __m256 hOk = ok;
        const Vec3x8 h = normalizeFast({_mm256_add_ps(lv.x, v.x), _mm256_add_ps(lv.y, v.y), _mm256_add_ps(lv.z, v.z)}, hOk);
        ok = select(lit, hOk, ok);
        const __m256 base0 = _mm256_max_ps(dot(n, h), _mm256_setzero_ps());
        unsigned e = unsigned(s);
        __m256 result = _mm256_set1_ps(1.0f), base = base0;
        while (e) {
            if (e & 1u) result = _mm256_mul_ps(result, base);
            base = _mm256_mul_ps(base, base);
            e >>= 1u;
        }
        specular = select(lit, _mm256_add_ps(specular, result), specular);
    }
    specular = _mm256_mul_ps(specular, _mm256_set1_ps(lighting.ks));
    const __m256i r = toUnorm8(_mm256_add_ps(_mm256_mul_ps(kdR, diffuse), specular));
    const __m256i g = toUnorm8(_mm256_add_ps(_mm256_mul_ps(kdG, diffuse), specular));
    const __m256i b = toUnorm8(_mm256_add_ps(_mm256_mul_ps(kdB, diffuse), specular));
    const __m256i packed = _mm256_or_si256(_mm256_or_si256(_mm256_set1_epi32(int(0xFF000000u)), _mm256_slli_epi32(r, 16)),
                                           _mm256_or_si256(_mm256_slli_epi32(g, 8), b));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), packed);
    return true;
}

} // namespace simd8
#endif

} // namespace sr
