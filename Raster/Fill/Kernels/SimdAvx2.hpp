// Eight-lane vector types over AVX2 (no FMA): the same names and meanings as SimdSse2.hpp.
#pragma once

#include <cstdint>

#include "Raster/Fill/Kernels/KernelConfig.hpp"

#if SR_KERNELS_X86
#include <immintrin.h>

SR_BEGIN_TARGET(SR_TARGET_STRING_AVX2)
namespace sr::simd_avx2 {

inline constexpr int kLanes = 8;

struct F { __m256 v; };
struct I { __m256i v; };
struct D { __m256d v; };
struct M { __m256 v; };

// --- float ------------------------------------------------------------------------------------
SR_SIMD_INLINE F fset(float a) { return {_mm256_set1_ps(a)}; }
SR_SIMD_INLINE F fzero() { return {_mm256_setzero_ps()}; }
SR_SIMD_INLINE F fload(const float* p) { return {_mm256_loadu_ps(p)}; }
SR_SIMD_INLINE void fstore(float* p, F a) { _mm256_storeu_ps(p, a.v); }
SR_SIMD_INLINE F fiota() { return {_mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f)}; }
SR_SIMD_INLINE F operator+(F a, F b) { return {_mm256_add_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator-(F a, F b) { return {_mm256_sub_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator*(F a, F b) { return {_mm256_mul_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator/(F a, F b) { return {_mm256_div_ps(a.v, b.v)}; }
SR_SIMD_INLINE F fmin(F a, F b) { return {_mm256_min_ps(a.v, b.v)}; }
SR_SIMD_INLINE F fmax(F a, F b) { return {_mm256_max_ps(a.v, b.v)}; }
SR_SIMD_INLINE F fsqrt(F a) { return {_mm256_sqrt_ps(a.v)}; }
SR_SIMD_INLINE F fabs(F a) { return {_mm256_and_ps(a.v, _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF)))}; }
SR_SIMD_INLINE M operator>(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
SR_SIMD_INLINE M operator>=(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
SR_SIMD_INLINE M operator<(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
SR_SIMD_INLINE M operator<=(F a, F b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
SR_SIMD_INLINE F select(M m, F a, F b) { return {_mm256_blendv_ps(b.v, a.v, m.v)}; }
// The BRDF's operations (Raster/Shade/Brdf.hpp's maxOf, minOf, ... for float), lane by lane:
// std::max(a, b) is a < b ? b : a, i.e. max(b, a) of the instruction (its first operand when
// greater, else the second, NaN included); std::min(a, b) likewise min(b, a).
SR_SIMD_INLINE F maxOf(F a, F b) { return fmax(b, a); }
SR_SIMD_INLINE F minOf(F a, F b) { return fmin(b, a); }
SR_SIMD_INLINE F sqrtOf(F a) { return fsqrt(a); }
SR_SIMD_INLINE F selectOf(M c, F a, F b) { return select(c, a, b); }
SR_SIMD_INLINE F splatAs(F, float c) { return fset(c); }

// --- masks ------------------------------------------------------------------------------------
SR_SIMD_INLINE M operator&(M a, M b) { return {_mm256_and_ps(a.v, b.v)}; }
SR_SIMD_INLINE M operator|(M a, M b) { return {_mm256_or_ps(a.v, b.v)}; }
SR_SIMD_INLINE M andNot(M a, M b) { return {_mm256_andnot_ps(b.v, a.v)}; }
SR_SIMD_INLINE int bits(M m) { return _mm256_movemask_ps(m.v); }
SR_SIMD_INLINE int laneCount(M m) { return _mm_popcnt_u32(unsigned(bits(m))); } // how many lanes are set
SR_SIMD_INLINE M mAll() { return {_mm256_castsi256_ps(_mm256_set1_epi32(-1))}; }
SR_SIMD_INLINE M firstN(int n) {
    return {_mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)))};
}

// --- int32 ------------------------------------------------------------------------------------
SR_SIMD_INLINE I iset(int a) { return {_mm256_set1_epi32(a)}; }
SR_SIMD_INLINE I iload(const std::int32_t* p) { return {_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))}; }
SR_SIMD_INLINE I iload(const std::uint32_t* p) { return {_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))}; }
SR_SIMD_INLINE void istore(std::int32_t* p, I a) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), a.v); }
SR_SIMD_INLINE void istore(std::uint32_t* p, I a) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), a.v); }
SR_SIMD_INLINE I iiota() { return {_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)}; }
SR_SIMD_INLINE I operator+(I a, I b) { return {_mm256_add_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I operator-(I a, I b) { return {_mm256_sub_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I operator&(I a, I b) { return {_mm256_and_si256(a.v, b.v)}; }
SR_SIMD_INLINE I operator|(I a, I b) { return {_mm256_or_si256(a.v, b.v)}; }
template <int k> SR_SIMD_INLINE I shiftLeft(I a) { return {_mm256_slli_epi32(a.v, k)}; }
template <int k> SR_SIMD_INLINE I shiftRightLogical(I a) { return {_mm256_srli_epi32(a.v, k)}; }
template <int k> SR_SIMD_INLINE I shiftRightArith(I a) { return {_mm256_srai_epi32(a.v, k)}; }
SR_SIMD_INLINE I shiftRightArith(I a, int count) { return {_mm256_sra_epi32(a.v, _mm_cvtsi32_si128(count))}; }
SR_SIMD_INLINE M operator==(I a, I b) { return {_mm256_castsi256_ps(_mm256_cmpeq_epi32(a.v, b.v))}; }
SR_SIMD_INLINE M operator>(I a, I b) { return {_mm256_castsi256_ps(_mm256_cmpgt_epi32(a.v, b.v))}; }
SR_SIMD_INLINE M operator<(I a, I b) { return {_mm256_castsi256_ps(_mm256_cmpgt_epi32(b.v, a.v))}; }
SR_SIMD_INLINE I select(M m, I a, I b) {
    return {_mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(b.v), _mm256_castsi256_ps(a.v), m.v))};
}
SR_SIMD_INLINE I imin(I a, I b) { return {_mm256_min_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I imax(I a, I b) { return {_mm256_max_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I mulLow(I a, I b) { return {_mm256_mullo_epi32(a.v, b.v)}; }
SR_SIMD_INLINE F toFloat(I a) { return {_mm256_cvtepi32_ps(a.v)}; }
SR_SIMD_INLINE I truncToInt(F a) { return {_mm256_cvttps_epi32(a.v)}; }
SR_SIMD_INLINE F asFloat(I a) { return {_mm256_castsi256_ps(a.v)}; }
SR_SIMD_INLINE I asInt(F a) { return {_mm256_castps_si256(a.v)}; }
SR_SIMD_INLINE I gather(const std::uint32_t* base, I index) {
    return {_mm256_i32gather_epi32(reinterpret_cast<const int*>(base), index.v, 4)};
}
// base[index[i]] and base[index[i] + 1] per lane, split into the lanes' first and second words:
// one 64-bit load per lane, not two 64-bit gathers (vpgatherdq is microcoded and slow on the
// AVX2-only cores this kernel runs on: Zen 3, textured scenes 0.91-0.98x the time). The
// pairs go in as (0 1 | 4 5) and (2 3 | 6 7), so that one shuffle per 128-bit half leaves the
// first (second) words in lane order.
SR_SIMD_INLINE void gatherPair(const std::uint32_t* base, I index, I& first, I& second) {
    alignas(32) std::int32_t at[8];
    istore(at, index);
    auto pair = [base](std::int32_t a, std::int32_t b) SR_SIMD_LAMBDA {
        const __m128d low = _mm_castsi128_pd(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(base + a)));
        return _mm_castpd_ps(_mm_loadh_pd(low, reinterpret_cast<const double*>(base + b)));
    };
    const __m256 lo = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(at[0], at[1])), pair(at[4], at[5]), 1);
    const __m256 hi = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(at[2], at[3])), pair(at[6], at[7]), 1);
    first = {_mm256_castps_si256(_mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0)))};
    second = {_mm256_castps_si256(_mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1)))};
}
SR_SIMD_INLINE int firstLane(I a) { return _mm_cvtsi128_si32(_mm256_castsi256_si128(a.v)); }
// The smallest / largest lane (three halving steps).
SR_SIMD_INLINE int reduceMin(I a) {
    __m128i m = _mm_min_epi32(_mm256_castsi256_si128(a.v), _mm256_extracti128_si256(a.v, 1));
    m = _mm_min_epi32(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm_min_epi32(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtsi128_si32(m);
}
SR_SIMD_INLINE int reduceMax(I a) {
    __m128i m = _mm_max_epi32(_mm256_castsi256_si128(a.v), _mm256_extracti128_si256(a.v, 1));
    m = _mm_max_epi32(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm_max_epi32(m, _mm_shuffle_epi32(m, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtsi128_si32(m);
}

// --- double -------------------------------------------------------------------------------------
SR_SIMD_INLINE D dset(double a) { return {_mm256_set1_pd(a)}; }
SR_SIMD_INLINE D dload(const double* p) { return {_mm256_loadu_pd(p)}; }
SR_SIMD_INLINE void dstore(double* p, D a) { _mm256_storeu_pd(p, a.v); }
SR_SIMD_INLINE D lowHalf(F a) { return {_mm256_cvtps_pd(_mm256_castps256_ps128(a.v))}; }
SR_SIMD_INLINE D highHalf(F a) { return {_mm256_cvtps_pd(_mm256_extractf128_ps(a.v, 1))}; }
SR_SIMD_INLINE D operator+(D a, D b) { return {_mm256_add_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator-(D a, D b) { return {_mm256_sub_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator*(D a, D b) { return {_mm256_mul_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator/(D a, D b) { return {_mm256_div_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dmin(D a, D b) { return {_mm256_min_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dmax(D a, D b) { return {_mm256_max_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dabs(D a) { return {_mm256_and_pd(a.v, _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FFFFFFFFFFFFFFFLL)))}; }
SR_SIMD_INLINE D dfloor(D a) { return {_mm256_floor_pd(a.v)}; } // exact (roundpd)
SR_SIMD_INLINE I toInt(D low, D high) {
    return {_mm256_set_m128i(_mm256_cvttpd_epi32(high.v), _mm256_cvttpd_epi32(low.v))};
}
SR_SIMD_INLINE F toFloat(D low, D high) { return {_mm256_set_m128(_mm256_cvtpd_ps(high.v), _mm256_cvtpd_ps(low.v))}; }

// --- left-packing ------------------------------------------------------------------------------
// Entry m of the table lists the set bits of m in ascending order (then zeros): the
// permutevar8x32 index that moves the selected lanes to the front.
struct PackTable {
    alignas(32) int lanes[256][8];
    constexpr PackTable() : lanes{} {
        for (int m = 0; m < 256; ++m) {
            int n = 0;
            for (int i = 0; i < 8; ++i)
                if (m & (1 << i)) lanes[m][n++] = i;
        }
    }
};
inline constexpr PackTable kPackTable{};

SR_SIMD_INLINE void compressStore(float* dst, F a, M m) {
    const __m256i pack = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackTable.lanes[bits(m)]));
    _mm256_storeu_ps(dst, _mm256_permutevar8x32_ps(a.v, pack));
}
SR_SIMD_INLINE void compressStore(std::int32_t* dst, I a, M m) {
    const __m256i pack = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackTable.lanes[bits(m)]));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst), _mm256_permutevar8x32_epi32(a.v, pack));
}

} // namespace sr::simd_avx2
SR_END_TARGET
#endif
