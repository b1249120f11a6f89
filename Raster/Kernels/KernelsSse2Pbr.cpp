// The SSE2 span kernels of the pbr programs, without and with maps (see Kernels.inl).
#define SR_KERNEL_PROGRAM PbrProgram
#include "Raster/Kernels/KernelsSse2.inl"
