// The span kernels compiled for AVX2 (Kernels.inl in namespace sr::kernels_avx2), for the
// shading model SR_KERNEL_PROGRAM that the including KernelsAvx2<Model>.cpp defines.
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
#include "Raster/Fill/Kernels/SimdAvx2.hpp"
#include "Raster/Fill/Prefetch.hpp"
#include "Raster/Shade/MeshPrograms.hpp"
#include "Raster/Shade/PbrProgram.hpp"

#if SR_KERNELS_X86
SR_BEGIN_TARGET(SR_TARGET_STRING_AVX2)
namespace sr::kernels_avx2 {
using namespace sr::simd_avx2;
#include "Raster/Fill/Kernels/Kernels.inl"
} // namespace sr::kernels_avx2
SR_END_TARGET
#endif
