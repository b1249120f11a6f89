// The AVX512 span kernels of the phong programs without position varyings (PhongProgram<kTextured, true>), untextured and textured (see Kernels.inl).
#define SR_KERNEL_PROGRAM PhongProgram
#define SR_KERNEL_FLAG_VARIANTS_ONLY
#include "Raster/Fill/Kernels/KernelsAvx512.inl"
