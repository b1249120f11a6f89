// The span kernels compiled for SSE2 (Kernels.inl instantiated in namespace sr::kernels_sse2).
#include <algorithm>
#include <cassert>
#include <cstdint>

#include "Raster/Kernels/KernelTable.hpp"
#include "Raster/Kernels/SimdSse2.hpp"
#include "Raster/MeshPrograms.hpp"

#if SR_KERNELS_X86
SR_BEGIN_TARGET(SR_TARGET_STRING_SSE2)
namespace sr::kernels_sse2 {
using namespace sr::simd_sse2;
#include "Raster/Kernels/Kernels.inl"
} // namespace sr::kernels_sse2
SR_END_TARGET
#endif
