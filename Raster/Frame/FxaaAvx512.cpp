// FXAA's vector kernels compiled for AVX512 (FxaaLanes.inl in namespace sr::kernels_avx512).
// GCC 12's AVX-512 headers trip -Wuninitialized once inlined (GCC bug 105593): the header is
// parsed here first with those warnings off, as in KernelsAvx512.inl; nothing of ours is covered.
#if defined(__GNUC__) && !defined(__clang__) && (defined(__x86_64__) || defined(_M_X64))
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "Raster/Fill/Kernels/SimdAvx512.hpp"
#include "Raster/Frame/Fxaa.hpp"

#if SR_KERNELS_X86
SR_BEGIN_TARGET(SR_TARGET_STRING_AVX512)
namespace sr::kernels_avx512 {
using namespace sr::simd_avx512;
#include "Raster/Frame/FxaaLanes.inl"
} // namespace sr::kernels_avx512
SR_END_TARGET
#endif
