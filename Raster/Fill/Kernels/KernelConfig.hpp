// Which kernel ISAs this compiler and target can build, and the macros that compile a region for one.
#pragma once

// x86-64 only (the baseline has SSE2); elsewhere, or built with SR_NO_KERNELS (CMake's
// SR_KERNELS=OFF), only the scalar reference exists.
#if (defined(__x86_64__) || defined(_M_X64)) && !defined(SR_NO_KERNELS)
#define SR_KERNELS_X86 1
#else
#define SR_KERNELS_X86 0
#endif

// A region of code compiled for one ISA, without compiler flags: everything declared between
// SR_BEGIN_TARGET(...) and SR_END_TARGET gets target(...) (GCC: push_options + target pragma;
// Clang: an attribute pushed onto every function; MSVC emits any intrinsic anywhere). Code outside
// the regions, shared headers included before them among it, stays at the x86-64 baseline, so no
// inline function of a shared header is ever emitted with AVX instructions (which would break
// the one-definition rule on a CPU without them). No FMA is enabled: see Math/Conventions.hpp.
#if defined(__clang__)
#define SR_PRAGMA(x) _Pragma(#x)
#define SR_BEGIN_TARGET(isa) SR_PRAGMA(clang attribute push(__attribute__((target(isa))), apply_to = function))
#define SR_END_TARGET SR_PRAGMA(clang attribute pop)
#elif defined(__GNUC__)
#define SR_PRAGMA(x) _Pragma(#x)
#define SR_BEGIN_TARGET(isa) SR_PRAGMA(GCC push_options) SR_PRAGMA(GCC target(isa))
#define SR_END_TARGET SR_PRAGMA(GCC pop_options)
#else
#define SR_BEGIN_TARGET(isa)
#define SR_END_TARGET
#endif

#define SR_TARGET_STRING_SSE2 "sse2"
#define SR_TARGET_STRING_AVX2 "avx2,popcnt"
#define SR_TARGET_STRING_AVX512 "avx2,popcnt,avx512f,avx512bw,avx512dq,avx512vl"

// Force-inlined vector operations; SR_SIMD_LAMBDA does the same for a lambda (after its
// parameter list); SR_SIMD_NOINLINE keeps a function out of line (one copy per ISA);
// SR_UNLIKELY(x) marks a rarely true condition (its branch is laid out and allocated as cold).
#if defined(__GNUC__) || defined(__clang__)
#define SR_SIMD_INLINE inline __attribute__((always_inline))
#define SR_SIMD_LAMBDA __attribute__((always_inline))
#define SR_SIMD_NOINLINE inline __attribute__((noinline))
#define SR_UNLIKELY(x) __builtin_expect(!!(x), 0)
#else
#define SR_UNLIKELY(x) (x)
#define SR_SIMD_NOINLINE inline __declspec(noinline)
#define SR_SIMD_INLINE __forceinline
#define SR_SIMD_LAMBDA
#endif
