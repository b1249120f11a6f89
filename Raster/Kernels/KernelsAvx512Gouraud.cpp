// The AVX512 span kernels of the gouraud programs, untextured and textured (see Kernels.inl).
#define SR_KERNEL_PROGRAM GouraudProgram
#include "Raster/Kernels/KernelsAvx512.inl"
