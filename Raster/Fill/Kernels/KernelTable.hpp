// The per-draw kernel table: which span kernel fills a program's triangles, chosen once per draw.
#pragma once

#include <cstdint>

#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Fill/Kernels/KernelConfig.hpp"
#include "Raster/Fill/MsaaFill.hpp"   // SpanRun
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Setup/PipelineModes.hpp" // DepthMode, PerspectiveMode
#include "Raster/Setup/Scissor.hpp"
#include "Raster/Setup/TriangleSetup.hpp"
#include "Raster/Texture/Texture.hpp"       // TextureFilter, WrapMode

namespace sr {

// What a draw needs from its span kernel besides the program type (shading model, textured):
// depth mode, perspective mode, filter and wrap. As llvmpipe's setup picks its triangle
// function, drawMesh looks the kernel up ONCE per draw; per triangle only the walk runs. The
// wrap mode is the one setting a kernel reads at run time (once per group of lanes, from the
// draw's settings: Kernels.inl's sampleTexture), so it selects no separate kernel.
struct KernelKey {
    DepthMode depth = DepthMode::TestWrite;
    PerspectiveMode perspective = PerspectiveMode::Exact;
    TextureFilter filter = TextureFilter::Bilinear;
    WrapMode wrap = WrapMode::Repeat;
};

// A span kernel: fills the covered pixels of one set-up triangle inside the scissor with the
// program's shading (reading its per-triangle state), adds the fragments that passed the depth
// test to `shaded`. Bit-identical to fillTriangle + Prog::fragment().
template <class Prog>
using FillKernel = void (*)(const Prog&, const TriangleSetup&, FrameBuffer&, const Scissor&, std::uint64_t& shaded);

// The multisampled fill's run shader (MsaaFill.hpp): shades the pixels of `count` runs (SpanRun:
// at their centres or moved) without a depth test, bit-identical to fillSpan<DepthMode::Off> +
// fragment() on the setup (or its moved copy, moveOrigin). Into fb's rows, returning false; or,
// when `write` has a target and the program's shading reads nothing of the triangle, into the
// target's passing samples (queued across the draw's triangles, in order; the flush kernel
// writes the rest), returning true.
template <class Prog>
using ShadeRunsKernel = bool (*)(const Prog&, const TriangleSetup&, FrameBuffer&, const SpanRun* runs, int count,
                                 const SampleWrite& write);

// The fill kernel's deferred queue (Kernels.inl, fillSpans), and the run shader's: shades and
// writes the fragments a draw's kernels left queued on this thread; called by the pipeline at the end of each lane's
// walk of the draw and before a wireframe edge (anything else that writes colour). `p`: any
// program of the draw.
template <class Prog>
using FlushKernel = void (*)(const Prog& p, FrameBuffer& fb);

// One table per ISA (Kernels*.cpp); nullptr where the ISA has no kernel for the key (the
// scalar reference then fills: non-integer shininess).
namespace kernels_sse2 {
template <class Prog>
FillKernel<Prog> fillKernel(const KernelKey& key);
template <class Prog>
ShadeRunsKernel<Prog> shadeRunsKernel(const KernelKey& key);
template <class Prog>
FlushKernel<Prog> flushKernel(const KernelKey& key);
}
namespace kernels_avx2 {
template <class Prog>
FillKernel<Prog> fillKernel(const KernelKey& key);
template <class Prog>
ShadeRunsKernel<Prog> shadeRunsKernel(const KernelKey& key);
template <class Prog>
FlushKernel<Prog> flushKernel(const KernelKey& key);
}
namespace kernels_avx512 {
template <class Prog>
FillKernel<Prog> fillKernel(const KernelKey& key);
template <class Prog>
ShadeRunsKernel<Prog> shadeRunsKernel(const KernelKey& key);
template <class Prog>
FlushKernel<Prog> flushKernel(const KernelKey& key);
}

template <class Prog>
FillKernel<Prog> selectFillKernel(Isa isa, const KernelKey& key) {
    if (!isaAvailable(isa)) return nullptr;
#if SR_KERNELS_X86
    switch (isa) {
    case Isa::Scalar: return nullptr;
    case Isa::Sse2: return kernels_sse2::fillKernel<Prog>(key);
    case Isa::Avx2: return kernels_avx2::fillKernel<Prog>(key);
    case Isa::Avx512: return kernels_avx512::fillKernel<Prog>(key);
    }
#else
    (void)key;
#endif
    return nullptr;
}

// The same for the run shader (the key's depth mode is ignored).
template <class Prog>
ShadeRunsKernel<Prog> selectShadeRunsKernel(Isa isa, const KernelKey& key) {
    if (!isaAvailable(isa)) return nullptr;
#if SR_KERNELS_X86
    switch (isa) {
    case Isa::Scalar: return nullptr;
    case Isa::Sse2: return kernels_sse2::shadeRunsKernel<Prog>(key);
    case Isa::Avx2: return kernels_avx2::shadeRunsKernel<Prog>(key);
    case Isa::Avx512: return kernels_avx512::shadeRunsKernel<Prog>(key);
    }
#else
    (void)key;
#endif
    return nullptr;
}

// The same for the fill kernel's queue: the flush that belongs to selectFillKernel's kernel.
template <class Prog>
FlushKernel<Prog> selectFlushKernel(Isa isa, const KernelKey& key) {
    if (!isaAvailable(isa)) return nullptr;
#if SR_KERNELS_X86
    switch (isa) {
    case Isa::Scalar: return nullptr;
    case Isa::Sse2: return kernels_sse2::flushKernel<Prog>(key);
    case Isa::Avx2: return kernels_avx2::flushKernel<Prog>(key);
    case Isa::Avx512: return kernels_avx512::flushKernel<Prog>(key);
    }
#else
    (void)key;
#endif
    return nullptr;
}

} // namespace sr
