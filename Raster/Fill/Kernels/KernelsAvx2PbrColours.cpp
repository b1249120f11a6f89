// The AVX2 span kernels of the pbr programs with vertex colours (PbrProgram<kMaps, kTangents, true>: untextured, textured, normal-mapped; see Kernels.inl).
#define SR_KERNEL_PROGRAM PbrProgram
#define SR_KERNEL_COLOUR_VARIANTS_ONLY
#include "Raster/Fill/Kernels/KernelsAvx2.inl"
