// The AVX2 span kernels of the phong programs, untextured and textured (see Kernels.inl).
#define SR_KERNEL_PROGRAM PhongProgram
#include "Raster/Fill/Kernels/KernelsAvx2.inl"
