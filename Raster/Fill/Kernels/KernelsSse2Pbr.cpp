// The SSE2 span kernels of the pbr programs, without and with maps, and with a normal map (see Kernels.inl).
#define SR_KERNEL_PROGRAM PbrProgram
#define SR_KERNEL_NORMAL_MAP_VARIANT
#include "Raster/Fill/Kernels/KernelsSse2.inl"
