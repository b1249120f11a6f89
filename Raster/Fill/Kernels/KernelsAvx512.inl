// The span kernels compiled for AVX512 (Kernels.inl in namespace sr::kernels_avx512), for the
// shading model SR_KERNEL_PROGRAM that the including KernelsAvx512<Model>.cpp defines.
// GCC 12's AVX-512 headers start many intrinsics from _mm512_undefined_*(), whose self-initialised
// variable trips -Wuninitialized once inlined (GCC bug 105593, fixed in GCC 13). The diagnostic
// state of a header line is the one in force when it was parsed, so the header is parsed here
// first, with just those two warnings off; nothing of ours is covered.
#if defined(__GNUC__) && !defined(__clang__) && (defined(__x86_64__) || defined(_M_X64))
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif

#ifndef SR_KERNEL_PROGRAM
#error "define SR_KERNEL_PROGRAM (the program template to instantiate) before including this file"
#endif

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

#include "Raster/Fill/Kernels/KernelTable.hpp"
#include "Raster/Fill/Kernels/SimdAvx512.hpp"
#include "Raster/Fill/Prefetch.hpp"
#include "Raster/Shade/MeshPrograms.hpp"
#include "Raster/Shade/PbrProgram.hpp"

#if SR_KERNELS_X86
SR_BEGIN_TARGET(SR_TARGET_STRING_AVX512)
namespace sr::kernels_avx512 {
using namespace sr::simd_avx512;
#include "Raster/Fill/Kernels/Kernels.inl"
} // namespace sr::kernels_avx512
SR_END_TARGET
#endif
