// FXAA's vector kernels compiled for AVX2 (FxaaLanes.inl in namespace sr::kernels_avx2).
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "Raster/Fill/Kernels/SimdAvx2.hpp"
#include "Raster/Frame/Fxaa.hpp"

#if SR_KERNELS_X86
SR_BEGIN_TARGET(SR_TARGET_STRING_AVX2)
namespace sr::kernels_avx2 {
using namespace sr::simd_avx2;
#include "Raster/Frame/FxaaLanes.inl"
} // namespace sr::kernels_avx2
SR_END_TARGET
#endif
