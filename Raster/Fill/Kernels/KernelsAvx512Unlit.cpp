// The AVX-512 span kernels of the unlit programs, untextured and textured, without and with vertex colours (see Kernels.inl).
#define SR_KERNEL_PROGRAM UnlitProgram
#define SR_KERNEL_FLAG_VARIANTS
#include "Raster/Fill/Kernels/KernelsAvx512.inl"
