// The AVX512 span kernels of the flat programs, untextured and textured (see Kernels.inl).
#define SR_KERNEL_PROGRAM FlatProgram
#define SR_KERNEL_SAMPLERS_APART // this ISA's samplers for wrap modes apart on u and v (LaneSampling.inl)
#include "Raster/Fill/Kernels/KernelsAvx512.inl"
