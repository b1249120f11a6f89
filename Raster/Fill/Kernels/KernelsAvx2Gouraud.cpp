// The AVX2 span kernels of the gouraud programs, untextured and textured, with two or six (RGB) terms (see Kernels.inl).
#define SR_KERNEL_PROGRAM GouraudProgram
#define SR_KERNEL_FLAG_VARIANTS
#include "Raster/Fill/Kernels/KernelsAvx2.inl"
