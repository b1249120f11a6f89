// Four-lane vector types over SSE2 (the x86-64 baseline): the operations the generic kernels use.
#pragma once

#include <cstdint>

#include "Raster/Fill/Kernels/KernelConfig.hpp"

#if SR_KERNELS_X86
#include <emmintrin.h>

// Every kernel ISA header defines the same names in its own namespace (see Kernels.inl):
//   F (float lanes), I (int32 lanes), D (kLanes / 2 double lanes), M (a lane mask),
// and free functions over them. Operations are IEEE single/double, one rounding each, exactly
// the scalar code's; nothing here fuses a multiply and an add.
namespace sr::simd_sse2 {

inline constexpr int kLanes = 4;

struct F { __m128 v; };
struct I { __m128i v; };
struct D { __m128d v; };
struct M { __m128 v; }; // all ones / all zeros per lane

// --- float ------------------------------------------------------------------------------------
SR_SIMD_INLINE F fset(float a) { return {_mm_set1_ps(a)}; }
SR_SIMD_INLINE F fzero() { return {_mm_setzero_ps()}; }
SR_SIMD_INLINE F fload(const float* p) { return {_mm_loadu_ps(p)}; }
SR_SIMD_INLINE void fstore(float* p, F a) { _mm_storeu_ps(p, a.v); }
SR_SIMD_INLINE F fiota() { return {_mm_setr_ps(0.0f, 1.0f, 2.0f, 3.0f)}; }
SR_SIMD_INLINE F operator+(F a, F b) { return {_mm_add_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator-(F a, F b) { return {_mm_sub_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator*(F a, F b) { return {_mm_mul_ps(a.v, b.v)}; }
SR_SIMD_INLINE F operator/(F a, F b) { return {_mm_div_ps(a.v, b.v)}; }
SR_SIMD_INLINE F fmin(F a, F b) { return {_mm_min_ps(a.v, b.v)}; } // a < b ? a : b
SR_SIMD_INLINE F fmax(F a, F b) { return {_mm_max_ps(a.v, b.v)}; } // a > b ? a : b
SR_SIMD_INLINE F fsqrt(F a) { return {_mm_sqrt_ps(a.v)}; }
SR_SIMD_INLINE F fabs(F a) { return {_mm_and_ps(a.v, _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF)))}; }
SR_SIMD_INLINE M operator>(F a, F b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
SR_SIMD_INLINE M operator>=(F a, F b) { return {_mm_cmpge_ps(a.v, b.v)}; }
SR_SIMD_INLINE M operator<(F a, F b) { return {_mm_cmplt_ps(a.v, b.v)}; }
SR_SIMD_INLINE M operator<=(F a, F b) { return {_mm_cmple_ps(a.v, b.v)}; }
SR_SIMD_INLINE F select(M m, F a, F b) { return {_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v))}; }
// The BRDF's operations (Raster/Shade/Brdf.hpp's maxOf, minOf, ... for float), lane by lane:
// std::max(a, b) is a < b ? b : a, i.e. max(b, a) of the instruction (its first operand when
// greater, else the second, NaN included); std::min(a, b) likewise min(b, a).
SR_SIMD_INLINE F maxOf(F a, F b) { return fmax(b, a); }
SR_SIMD_INLINE F minOf(F a, F b) { return fmin(b, a); }
SR_SIMD_INLINE F sqrtOf(F a) { return fsqrt(a); }
SR_SIMD_INLINE F selectOf(M c, F a, F b) { return select(c, a, b); }
SR_SIMD_INLINE F splatAs(F, float c) { return fset(c); }

// --- masks ------------------------------------------------------------------------------------
SR_SIMD_INLINE M operator&(M a, M b) { return {_mm_and_ps(a.v, b.v)}; }
SR_SIMD_INLINE M operator|(M a, M b) { return {_mm_or_ps(a.v, b.v)}; }
SR_SIMD_INLINE M andNot(M a, M b) { return {_mm_andnot_ps(b.v, a.v)}; } // a & ~b
SR_SIMD_INLINE int bits(M m) { return _mm_movemask_ps(m.v); }
// How many lanes are set: four bits, one entry of a nibble table (no POPCNT at the x86-64 baseline).
SR_SIMD_INLINE int laneCount(M m) { return int((0x4332322132212110ull >> (4 * bits(m))) & 0xFu); }
SR_SIMD_INLINE M mAll() { return {_mm_castsi128_ps(_mm_set1_epi32(-1))}; }
// Lanes [0, n) set, n in [0, kLanes].
SR_SIMD_INLINE M firstN(int n) {
    return {_mm_castsi128_ps(_mm_cmpgt_epi32(_mm_set1_epi32(n), _mm_setr_epi32(0, 1, 2, 3)))};
}

// --- int32 ------------------------------------------------------------------------------------
SR_SIMD_INLINE I iset(int a) { return {_mm_set1_epi32(a)}; }
SR_SIMD_INLINE I iload(const std::int32_t* p) { return {_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))}; }
SR_SIMD_INLINE I iload(const std::uint32_t* p) { return {_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))}; }
SR_SIMD_INLINE void istore(std::int32_t* p, I a) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), a.v); }
SR_SIMD_INLINE void istore(std::uint32_t* p, I a) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), a.v); }
SR_SIMD_INLINE I iiota() { return {_mm_setr_epi32(0, 1, 2, 3)}; }
SR_SIMD_INLINE I operator+(I a, I b) { return {_mm_add_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I operator-(I a, I b) { return {_mm_sub_epi32(a.v, b.v)}; }
SR_SIMD_INLINE I operator&(I a, I b) { return {_mm_and_si128(a.v, b.v)}; }
SR_SIMD_INLINE I operator|(I a, I b) { return {_mm_or_si128(a.v, b.v)}; }
template <int k> SR_SIMD_INLINE I shiftLeft(I a) { return {_mm_slli_epi32(a.v, k)}; }
template <int k> SR_SIMD_INLINE I shiftRightLogical(I a) { return {_mm_srli_epi32(a.v, k)}; }
template <int k> SR_SIMD_INLINE I shiftRightArith(I a) { return {_mm_srai_epi32(a.v, k)}; }
SR_SIMD_INLINE I shiftRightArith(I a, int count) { return {_mm_sra_epi32(a.v, _mm_cvtsi32_si128(count))}; }
SR_SIMD_INLINE M operator==(I a, I b) { return {_mm_castsi128_ps(_mm_cmpeq_epi32(a.v, b.v))}; }
SR_SIMD_INLINE M operator>(I a, I b) { return {_mm_castsi128_ps(_mm_cmpgt_epi32(a.v, b.v))}; }
SR_SIMD_INLINE M operator<(I a, I b) { return {_mm_castsi128_ps(_mm_cmplt_epi32(a.v, b.v))}; }
SR_SIMD_INLINE I select(M m, I a, I b) {
    const __m128i mi = _mm_castps_si128(m.v);
    return {_mm_or_si128(_mm_and_si128(mi, a.v), _mm_andnot_si128(mi, b.v))};
}
SR_SIMD_INLINE I imin(I a, I b) { return select(a < b, a, b); }
SR_SIMD_INLINE I imax(I a, I b) { return select(a > b, a, b); }
// a * b for 0 <= a, b and a * b < 2^32 (SSE2 has no 32-bit mullo: even and odd lanes via pmuludq).
SR_SIMD_INLINE I mulLow(I a, I b) {
    const __m128i even = _mm_mul_epu32(a.v, b.v);
    const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a.v, 32), _mm_srli_epi64(b.v, 32));
    return {_mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                               _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0)))};
}
SR_SIMD_INLINE F toFloat(I a) { return {_mm_cvtepi32_ps(a.v)}; }
SR_SIMD_INLINE I truncToInt(F a) { return {_mm_cvttps_epi32(a.v)}; } // |a| < 2^31
SR_SIMD_INLINE F asFloat(I a) { return {_mm_castsi128_ps(a.v)}; }
SR_SIMD_INLINE I asInt(F a) { return {_mm_castps_si128(a.v)}; }
// base[index[i]] per lane (SSE2 has no gather: four loads).
SR_SIMD_INLINE I gather(const std::uint32_t* base, I index) {
    alignas(16) std::int32_t i[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(i), index.v);
    return {_mm_set_epi32(int(base[i[3]]), int(base[i[2]]), int(base[i[1]]), int(base[i[0]]))};
}
// base[index[i]] and base[index[i] + 1] per lane.
SR_SIMD_INLINE void gatherPair(const std::uint32_t* base, I index, I& first, I& second) {
    alignas(16) std::int32_t i[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(i), index.v);
    first = {_mm_set_epi32(int(base[i[3]]), int(base[i[2]]), int(base[i[1]]), int(base[i[0]]))};
    second = {_mm_set_epi32(int(base[i[3] + 1]), int(base[i[2] + 1]), int(base[i[1] + 1]), int(base[i[0] + 1]))};
}
SR_SIMD_INLINE int firstLane(I a) { return _mm_cvtsi128_si32(a.v); }
// The smallest / largest lane (two halving steps; imin / imax are compare-and-select here).
SR_SIMD_INLINE int reduceMin(I a) {
    a = imin(a, I{_mm_shuffle_epi32(a.v, _MM_SHUFFLE(1, 0, 3, 2))});
    a = imin(a, I{_mm_shuffle_epi32(a.v, _MM_SHUFFLE(2, 3, 0, 1))});
    return _mm_cvtsi128_si32(a.v);
}
SR_SIMD_INLINE int reduceMax(I a) {
    a = imax(a, I{_mm_shuffle_epi32(a.v, _MM_SHUFFLE(1, 0, 3, 2))});
    a = imax(a, I{_mm_shuffle_epi32(a.v, _MM_SHUFFLE(2, 3, 0, 1))});
    return _mm_cvtsi128_si32(a.v);
}

// --- double (kLanes / 2 lanes: the low and high halves of an F) ------------------------------
SR_SIMD_INLINE D dset(double a) { return {_mm_set1_pd(a)}; }
SR_SIMD_INLINE D dload(const double* p) { return {_mm_loadu_pd(p)}; }
SR_SIMD_INLINE void dstore(double* p, D a) { _mm_storeu_pd(p, a.v); }
SR_SIMD_INLINE D lowHalf(F a) { return {_mm_cvtps_pd(a.v)}; }
SR_SIMD_INLINE D highHalf(F a) { return {_mm_cvtps_pd(_mm_movehl_ps(a.v, a.v))}; }
SR_SIMD_INLINE D operator+(D a, D b) { return {_mm_add_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator-(D a, D b) { return {_mm_sub_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator*(D a, D b) { return {_mm_mul_pd(a.v, b.v)}; }
SR_SIMD_INLINE D operator/(D a, D b) { return {_mm_div_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dmin(D a, D b) { return {_mm_min_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dmax(D a, D b) { return {_mm_max_pd(a.v, b.v)}; }
SR_SIMD_INLINE D dabs(D a) { return {_mm_and_pd(a.v, _mm_castsi128_pd(_mm_set1_epi64x(0x7FFFFFFFFFFFFFFFLL)))}; }
// floor, exact for |a| < 2^31 (truncate, then one down where that went up).
SR_SIMD_INLINE D dfloor(D a) {
    const __m128d t = _mm_cvtepi32_pd(_mm_cvttpd_epi32(a.v));
    return {_mm_sub_pd(t, _mm_and_pd(_mm_cmpgt_pd(t, a.v), _mm_set1_pd(1.0)))};
}
// Whole-number doubles of the two halves (|value| < 2^31) as one I.
SR_SIMD_INLINE I toInt(D low, D high) { return {_mm_unpacklo_epi64(_mm_cvttpd_epi32(low.v), _mm_cvttpd_epi32(high.v))}; }
// The two halves rounded to float (to nearest, as float(double) does) as one F.
SR_SIMD_INLINE F toFloat(D low, D high) { return {_mm_movelh_ps(_mm_cvtpd_ps(low.v), _mm_cvtpd_ps(high.v))}; }

// --- left-packing ------------------------------------------------------------------------------
// Stores the lanes of `a` selected by `m` to dst[0 .. popcount(m)), in lane order. dst must have
// room for kLanes values (the wider ISAs store a whole vector).
SR_SIMD_INLINE void compressStore(float* dst, F a, M m) {
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, a.v);
    int n = 0;
    for (int b = bits(m), i = 0; i < 4; ++i)
        if (b & (1 << i)) dst[n++] = lanes[i];
}
SR_SIMD_INLINE void compressStore(std::int32_t* dst, I a, M m) {
    alignas(16) std::int32_t lanes[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes), a.v);
    int n = 0;
    for (int b = bits(m), i = 0; i < 4; ++i)
        if (b & (1 << i)) dst[n++] = lanes[i];
}

} // namespace sr::simd_sse2
#endif
