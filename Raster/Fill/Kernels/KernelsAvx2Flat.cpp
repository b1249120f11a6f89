// The AVX2 span kernels of the flat programs, untextured and textured (see Kernels.inl).
#define SR_KERNEL_PROGRAM FlatProgram
#include "Raster/Fill/Kernels/KernelsAvx2.inl"
