// The SSE2 span kernels of the unlit programs, untextured and textured (see Kernels.inl).
#define SR_KERNEL_PROGRAM UnlitProgram
#include "Raster/Fill/Kernels/KernelsSse2.inl"
