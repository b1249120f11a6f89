// FXAA's vector kernels compiled for SSE2 (FxaaLanes.inl in namespace sr::kernels_sse2).
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "Raster/Fill/Kernels/SimdSse2.hpp"
#include "Raster/Frame/Fxaa.hpp"

#if SR_KERNELS_X86
SR_BEGIN_TARGET(SR_TARGET_STRING_SSE2)
namespace sr::kernels_sse2 {
using namespace sr::simd_sse2;
#include "Raster/Frame/FxaaLanes.inl"
} // namespace sr::kernels_sse2
SR_END_TARGET
#endif
