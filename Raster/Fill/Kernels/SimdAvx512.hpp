// Sixteen-lane vector types over AVX-512 F/BW/DQ/VL (no FMA): the names and meanings of SimdSse2.hpp.
#pragma once

#include <cstdint>

#include "Raster/Fill/Kernels/KernelConfig.hpp"

#if SR_KERNELS_X86
#include <immintrin.h>

SR_BEGIN_TARGET(SR_TARGET_STRING_AVX512)
namespace sr::simd_avx512 {

inline constexpr int kLanes = 16;

struct F { __m512 v; };
struct I { __m512i v; };
struct D { __m512d v; };
struct M { __mmask16 v; }; // one bit per lane (opmask register)

// --- float ------------------------------------------------------------------------------------
SR_SIMD_INLINE F fset(float a) { return {_mm512_set1_ps(a)}; }
SR_SIMD_INLINE F fzero() { return {_mm512_setzero_ps()}; }
SR_SIMD_INLINE F fload(const float* p) { return {_mm512_loadu_ps(p)}; }
SR_SIMD_INLINE void fstore(float* p, F a) { _mm512_storeu_ps(p, a.v); }
SR_SIMD_INLINE F fiota() {
    return {_mm512_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f, 10.0f, 11.0f, 12.0f, 13.0f, 14.0f, 15.0f)};
}
SR_SIMD_INLINE F operator+(F a, F b) { return {_mm512_add_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator-(F a, F b) { return {_mm512_sub_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator*(F a, F b) { return {_mm512_mul_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator/(F a, F b) { return {_mm512_div_ps(a.v, b.v)}; }
SR_SIMD_INLINE F fmin(F a, F b) { return {_mm512_min_ps(a.v, b.v)}; }
SR_SIMD_INLINE F fmax(F a, F b) { return {_mm512_max_ps(a.v, b.v)}; }
SR_SIMD_INLINE F fsqrt(F a) { return {_mm512_sqrt_ps(a.v)}; }
SR_SIMD_INLINE F fabs(F a) { return {_mm512_castsi512_ps(_mm512_and_si512(_mm512_castps_si512(a.v), _mm512_set1_epi32(0x7FFFFFFF)))}; }
SR_SIMD_INLINE M operator>(F a, F b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GT_OQ)}; }
SR_SIMD_INLINE M operator>=(F a, F b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_GE_OQ)}; }
SR_SIMD_INLINE M operator<(F a, F b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)}; }
SR_SIMD_INLINE M operator<=(F a, F b) { return {_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)}; }
SR_SIMD_INLINE F select(M m, F a, F b) { return {_mm512_mask_blend_ps(m.v, b.v, a.v)}; }
// The BRDF's operations (Raster/Shade/Brdf.hpp's maxOf, minOf, ... for float), lane by lane:
// std::max(a, b) is a < b ? b : a, i.e. max(b, a) of the instruction (its first operand when
// greater, else the second, NaN included); std::min(a, b) likewise min(b, a).
SR_SIMD_INLINE F maxOf(F a, F b) { return fmax(b, a); }
SR_SIMD_INLINE F minOf(F a, F b) { return fmin(b, a); }
SR_SIMD_INLINE F sqrtOf(F a) { return fsqrt(a); }
SR_SIMD_INLINE F selectOf(M c, F a, F b) { return select(c, a, b); }
SR_SIMD_INLINE F splatAs(F, float c) { return fset(c); }

// --- masks ------------------------------------------------------------------------------------
SR_SIMD_INLINE M operator&(M a, M b) { return {__mmask16(a.v & b.v)}; }
SR_SIMD_INLINE M operator|(M a, M b) { return {__mmask16(a.v | b.v)}; }
SR_SIMD_INLINE M andNot(M a, M b) { return {__mmask16(a.v & ~b.v)}; }
SR_SIMD_INLINE int bits(M m) { return int(m.v); }
SR_SIMD_INLINE int laneCount(M m) { return _mm_popcnt_u32(unsigned(m.v)); } // how many lanes are set
SR_SIMD_INLINE M mAll() { return {__mmask16(0xFFFF)}; }
SR_SIMD_INLINE M firstN(int n) { return {__mmask16((1u << n) - 1u)}; }

// --- int32 ------------------------------------------------------------------------------------
SR_SIMD_INLINE I iset(int a) { return {_mm512_set1_epi32(a)}; }
SR_SIMD_INLINE I iload(const std::int32_t* p) { return {_mm512_loadu_si512(p)}; }
SR_SIMD_INLINE I iload(const std::uint32_t* p) { return {_mm512_loadu_si512(p)}; }
SR_SIMD_INLINE void istore(std::int32_t* p, I a) { _mm512_storeu_si512(p, a.v); }
SR_SIMD_INLINE void istore(std::uint32_t* p, I a) { _mm512_storeu_si512(p, a.v); }
SR_SIMD_INLINE I iiota() { return {_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15)}; }
SR_SIMD_INLINE I operator+(I a, I b) { return {_mm512_add_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I operator-(I a, I b) { return {_mm512_sub_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I operator&(I a, I b) { return {_mm512_and_si512(a.v, b.v)}; }
SR_SIMD_INLINE I operator|(I a, I b) { return {_mm512_or_si512(a.v, b.v)}; }
template <int k> SR_SIMD_INLINE I shiftLeft(I a) { return {_mm512_slli_epi32(a.v, k)}; }
template <int k> SR_SIMD_INLINE I shiftRightLogical(I a) { return {_mm512_srli_epi32(a.v, k)}; }
template <int k> SR_SIMD_INLINE I shiftRightArith(I a) { return {_mm512_srai_epi32(a.v, k)}; }
SR_SIMD_INLINE I shiftRightArith(I a, int count) { return {_mm512_sra_epi32(a.v, _mm_cvtsi32_si128(count))}; }
SR_SIMD_INLINE M operator==(I a, I b) { return {_mm512_cmpeq_epi32_mask(a.v, b.v)}; }
SR_SIMD_INLINE M operator>(I a, I b) { return {_mm512_cmpgt_epi32_mask(a.v, b.v)}; }
SR_SIMD_INLINE M operator<(I a, I b) { return {_mm512_cmplt_epi32_mask(a.v, b.v)}; }
SR_SIMD_INLINE I select(M m, I a, I b) { return {_mm512_mask_blend_epi32(m.v, b.v, a.v)}; }
SR_SIMD_INLINE I imin(I a, I b) { return {_mm512_min_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I imax(I a, I b) { return {_mm512_max_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I mulLow(I a, I b) { return {_mm512_mullo_epi32(a.v, b.v)}; }
SR_SIMD_INLINE F toFloat(I a) { return {_mm512_cvtepi32_ps(a.v)}; }
SR_SIMD_INLINE I truncToInt(F a) { return {_mm512_cvttps_epi32(a.v)}; }
SR_SIMD_INLINE F asFloat(I a) { return {_mm512_castsi512_ps(a.v)}; }
SR_SIMD_INLINE I asInt(F a) { return {_mm512_castps_si512(a.v)}; }
SR_SIMD_INLINE I gather(const std::uint32_t* base, I index) { return {_mm512_i32gather_epi32(index.v, base, 4)}; }
// base[index[i]] and base[index[i] + 1] per lane: one 64-bit load per lane (a gather is
// microcoded on AMD's cores), lanes (4k, 4k + 1) in one vector's 128-bit part k and
// (4k + 2, 4k + 3) in the other's, so one shuffle per part splits first and second words.
SR_SIMD_INLINE void gatherPair(const std::uint32_t* base, I index, I& first, I& second) {
    alignas(64) std::int32_t at[16];
    istore(at, index);
    auto pair = [base](std::int32_t a, std::int32_t b) SR_SIMD_LAMBDA {
        const __m128d low = _mm_castsi128_pd(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(base + a)));
        return _mm_castpd_ps(_mm_loadh_pd(low, reinterpret_cast<const double*>(base + b)));
    };
    auto four = [&pair, &at](int k) SR_SIMD_LAMBDA {
        const __m256 low = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(at[k], at[k + 1])), pair(at[k + 4], at[k + 5]), 1);
        const __m256 high = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(at[k + 8], at[k + 9])), pair(at[k + 12], at[k + 13]), 1);
        return _mm512_insertf32x8(_mm512_castps256_ps512(low), high, 1);
    };
    const __m512 lo = four(0);
    const __m512 hi = four(2);
    first = {_mm512_castps_si512(_mm512_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0)))};
    second = {_mm512_castps_si512(_mm512_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1)))};
}
SR_SIMD_INLINE int firstLane(I a) { return _mm_cvtsi128_si32(_mm512_castsi512_si128(a.v)); }
SR_SIMD_INLINE int reduceMin(I a) { return _mm512_reduce_min_epi32(a.v); }
SR_SIMD_INLINE int reduceMax(I a) { return _mm512_reduce_max_epi32(a.v); }

// --- double -------------------------------------------------------------------------------------
SR_SIMD_INLINE D dset(double a) { return {_mm512_set1_pd(a)}; }
SR_SIMD_INLINE D dload(const double* p) { return {_mm512_loadu_pd(p)}; }
SR_SIMD_INLINE void dstore(double* p, D a) { _mm512_storeu_pd(p, a.v); }
SR_SIMD_INLINE D lowHalf(F a) { return {_mm512_cvtps_pd(_mm512_castps512_ps256(a.v))}; }
SR_SIMD_INLINE D highHalf(F a) {
    return {_mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(a.v), 1)))};
}
SR_SIMD_INLINE D operator+(D a, D b) { return {_mm512_add_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator-(D a, D b) { return {_mm512_sub_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator*(D a, D b) { return {_mm512_mul_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator/(D a, D b) { return {_mm512_div_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dmin(D a, D b) { return {_mm512_min_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dmax(D a, D b) { return {_mm512_max_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dabs(D a) { return {_mm512_abs_pd(a.v)}; }
SR_SIMD_INLINE D dfloor(D a) { return {_mm512_roundscale_pd(a.v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)}; }
SR_SIMD_INLINE I toInt(D low, D high) {
    return {_mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvttpd_epi32(low.v)), _mm512_cvttpd_epi32(high.v), 1)};
}
SR_SIMD_INLINE F toFloat(D low, D high) {
    const __m512d lo = _mm512_castps_pd(_mm512_castps256_ps512(_mm512_cvtpd_ps(low.v)));
    return {_mm512_castpd_ps(_mm512_insertf64x4(lo, _mm256_castps_pd(_mm512_cvtpd_ps(high.v)), 1))};
}

// --- left-packing (register compress, then a plain store: a compress straight to memory is
// microcoded and slow on AMD Zen 4) -----------------------------------------------------------
SR_SIMD_INLINE void compressStore(float* dst, F a, M m) { _mm512_storeu_ps(dst, _mm512_maskz_compress_ps(m.v, a.v)); }
SR_SIMD_INLINE void compressStore(std::int32_t* dst, I a, M m) {
    _mm512_storeu_si512(dst, _mm512_maskz_compress_epi32(m.v, a.v));
}

} // namespace sr::simd_avx512
SR_END_TARGET
#endif
