// The AVX-512 span kernels of the pbr programs, without and with maps (see Kernels.inl).
#define SR_KERNEL_PROGRAM PbrProgram
#include "Raster/Kernels/KernelsAvx512.inl"
