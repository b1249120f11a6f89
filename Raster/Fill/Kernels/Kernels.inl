// The span kernels, written once over the vector types of one ISA (SimdSse2/Avx2/Avx512.hpp).
//
// Included by KernelsSse2.inl, KernelsAvx2.inl and KernelsAvx512.inl INSIDE their namespace
// (sr::kernels_<isa>) and target region, after `using namespace sr::simd_<isa>;`, so every
// function here exists once per ISA, compiled for it, and no symbol is shared between ISAs.
// Each of those is in turn included by one small .cpp per shading model
// (Kernels<Isa><Model>.cpp), which names the programs to instantiate (SR_KERNEL_PROGRAM): the
// kernels of one ISA compile as four translation units, in parallel and in a quarter of the
// memory (the single AVX-512 file took 826 s and 5.3 GB under ASan + UBSan at -O2).
// The scalar twins are ScanlineFill.hpp's fillTriangle and the programs of MeshPrograms.hpp:
// every operation below is theirs, in the same order, lane by lane (IEEE, no FMA), so the
// pixels, depths and counters are bit-identical (Tests/Threads/KernelIdentityTests.cpp proves it for every key).

using sr::programs::DrawContext;

// The lane-wise building blocks, one concept per file, in the order they use each other.
#include "Raster/Fill/Kernels/LaneColour.inl"
#include "Raster/Fill/Kernels/LaneShadow.inl"
#include "Raster/Fill/Kernels/LaneSampling.inl"
#include "Raster/Fill/Kernels/LanePbr.inl"
#include "Raster/Fill/Kernels/LaneShade.inl"

// --- The span loop ---------------------------------------------------------------------------
// The fragments of one triangle that passed the depth test in partial groups, waiting to be
// shaded kLanes at a time (left-packed: entries [0, count) are used). Room for two groups: a
// whole vector is stored at `count` < kLanes. With `samples` (the multisampled run shader's
// queue of an opaque draw), each fragment's colour goes to its passing samples there, mask[i].
template <int kV>
struct FragmentQueue {
    int count = 0;
    MsaaBuffer* samples = nullptr;
    alignas(64) std::int32_t x[2 * kLanes];
    alignas(64) std::int32_t y[2 * kLanes];
    alignas(64) float invW[2 * kLanes];
    alignas(64) float v[kV > 0 ? kV : 1][2 * kLanes];
    alignas(64) std::int32_t mask[2 * kLanes];
};

// fillTriangle (ScanlineFill.hpp) kLanes pixels per step. Per span: the plane values at the
// first pixel in double (fillTriangle's very expression), then pixel k of the span gets depth
// and 1/w as start + k * ddx in double (rounded once) and the varyings as start + k * gradient
// in float, as one lane. Groups whose lanes all pass the depth test are
// shaded at once and stored with one vector store; the passing lanes of the other groups go to
// the queue (so the shading runs on few wasted lanes for small triangles). A draw whose
// colour is constant per triangle (no varyings) stores it without shading anything.
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
struct SpanKernel {
    static constexpr int kV = Prog::kVaryings;
    static constexpr int kPlanes = kV > 0 ? kPlaneVarying0 + kV : 1;
    const Prog& p;
    const TriangleSetup& t;
    FrameBuffer& fb;
    std::uint64_t& shaded;
    FragmentQueue<kV>& queue;
    F gradient[kPlanes]; // per plane: its step one pixel right
    F triangleLod = fzero(); // affine trilinear: the triangle's mip level (else unused)
    float alpha = 1.0f; // below 1: a transparent draw, every colour blended over the target (blendOver)
    // On (fillSpans, kDeferrable programs): the queue outlives the triangle, so that a draw of
    // small triangles shades full groups of lanes; see fillSpans.
    bool deferred = false;

    // Transparent draws are drawn with DepthMode::Test (drawStateFor): only those kernels carry
    // the blending code, so the opaque ones have none of it.
    static constexpr bool kMayBlend = kDepth == DepthMode::Test;
    bool blending() const { return kMayBlend && alpha < 1.0f; }
    // Programs whose shading of a fragment reads nothing of its triangle (only the draw's
    // constants and the fragment's own varyings): their queued fragments may wait for the next
    // triangle's. Not flat (lit per triangle) nor trilinear (the triangle's uv gradients).
    static constexpr bool kDeferrable =
        kV > 0 && Prog::kMode != ShadingMode::Flat && !(Prog::kIsTextured && kFilter == TextureFilter::Trilinear);

    // A constructor, not an aggregate: aggregate initialisation would zero the whole kernel (its
    // plane steps are 8 vectors for Phong) before filling it, every triangle.
    SpanKernel(const Prog& program, const TriangleSetup& setup, FrameBuffer& target, std::uint64_t& shadedCount,
               FragmentQueue<kV>& fragments, float opacity = 1.0f, bool deferQueue = false)
        : p(program), t(setup), fb(target), shaded(shadedCount), queue(fragments), alpha(opacity),
          deferred(deferQueue) {
        for (int k = 0; k < kPlanes; ++k) gradient[k] = fset(setup.ddxStep[k]);
    }

    // Writes the shaded colour of pixel `dst` (opaque: the colour itself; transparent: blendOver,
    // the scalar pipeline's very function, lane by lane).
    void put(Pixel& dst, Pixel colour) const { dst = blending() ? blendOver(colour, dst, alpha, p.d->linear) : colour; }

    // planesAt's vector steps: kLanes planes each, as many as the setup's kMaxPlanes-long arrays
    // hold (past kPlanes their lanes compute unused values); the planes after them one by one.
    static constexpr int kPlanesPadded = (kPlanes + kLanes - 1) / kLanes * kLanes;
    static constexpr int kVectorPlanes = kPlanesPadded <= kMaxPlanes ? kPlanesPadded : kPlanes / kLanes * kLanes;
    static_assert(kVectorPlanes >= kLanes && kLanes / 2 >= kPlaneVarying0, "depth and 1/w in the first step's low half");

    // Every plane's value at (dx, dy) from the setup's origin, fillTriangle's expression
    // value + ddx * dx + ddy * dy in double, its very operations lane by lane (IEEE, no FMA):
    // rounded once to float in f[k] (k < kPlanes), and depth and 1/w unrounded in d[kPlaneZ],
    // d[kPlaneInvW]. A span's start costs a few vector operations instead of a chain per plane.
    void planesAt(double dx, double dy, float* f, double* d) const {
        const D x = dset(dx), y = dset(dy);
        for (int k = 0; k < kVectorPlanes; k += kLanes) {
            constexpr int kHalf = kLanes / 2;
            const D low = dload(t.value + k) + dload(t.ddx + k) * x + dload(t.ddy + k) * y;
            const D high = dload(t.value + k + kHalf) + dload(t.ddx + k + kHalf) * x + dload(t.ddy + k + kHalf) * y;
            if (k == 0) dstore(d, low);
            fstore(f + k, toFloat(low, high));
        }
        for (int k = kVectorPlanes; k < kPlanes; ++k) f[k] = float(t.value[k] + t.ddx[k] * dx + t.ddy[k] * dy);
    }

    // fillTriangle's depth and 1/w: start + step * ddx in double, rounded once.
    F planeInDouble(D startValue, int plane, F step) const {
        const D g = dset(t.ddx[plane]);
        return toFloat(startValue + g * lowHalf(step), startValue + g * highHalf(step));
    }

    // The varyings of the lanes `step` pixels right of a span's first pixel (whose plane values
    // are startF), divided by their 1/w `invW` (Exact): fillTriangle's expressions, lane by lane.
    void varyingsAt(const float* startF, F step, F invW, F* values) const {
        if constexpr (kPersp == PerspectiveMode::Exact) {
            const F w = fset(1.0f) / invW;
            for (int k = 0; k < kV; ++k) values[k] = (fset(startF[kPlaneVarying0 + k]) + gradient[kPlaneVarying0 + k] * step) * w;
        } else {
            for (int k = 0; k < kV; ++k) values[k] = fset(startF[kPlaneVarying0 + k]) + gradient[kPlaneVarying0 + k] * step;
        }
    }

    // Shades the queue's first kLanes fragments and stores the first `used` colours (to the
    // samples: kToSamples, a queue with samples; else to fb).
    template <bool kToSamples>
    void shadeQueued(int used) const {
        F values[kV > 0 ? kV : 1];
        for (int k = 0; k < kV; ++k) values[k] = fload(queue.v[k]);
        alignas(64) std::uint32_t out[kLanes];
        istore(out, shadeGroup<Prog, kPersp, kFilter>(p, values, fload(queue.invW), iload(queue.x), iload(queue.y), triangleLod));
        if constexpr (kToSamples) {
            withSampleCount([&](auto n) {
                constexpr int kN = decltype(n)::value;
                MsaaBuffer& target = *queue.samples;
                for (int i = 0; i < used; ++i)
                    writeSamples<kN>(target.colourRow(queue.y[i]) + std::size_t(queue.x[i]) * kN, out[i], unsigned(queue.mask[i]));
            });
        } else {
            for (int i = 0; i < used; ++i) put(fb.colorRow(queue.y[i])[queue.x[i]], out[i]);
        }
    }
    // The same, to wherever the queue writes.
    void shadeQueuedAnywhere(int used) const {
        if (queue.samples) shadeQueued<true>(used);
        else shadeQueued<false>(used);
    }

    // f(std::integral_constant<int, n>) for the queue's target's n samples per pixel.
    template <class Body>
    void withSampleCount(Body&& f) const {
        switch (queue.samples->samples()) {
        case 2: f(std::integral_constant<int, 2>{}); break;
        case 4: f(std::integral_constant<int, 4>{}); break;
        case 8: f(std::integral_constant<int, 8>{}); break;
        default: assert(false);
        }
    }

    // Colour c to a pixel's samples whose bits are set in `mask`.
    template <int kN>
    static void writeSamples(Pixel* samples, Pixel c, unsigned mask) {
        if (mask == (1u << kN) - 1u) { // every sample (inside the triangle): stored unmasked
            for (int k = 0; k < kN; ++k) samples[k] = c;
            return;
        }
        for (int k = 0; k < kN; ++k)
            if (mask >> k & 1u) samples[k] = c;
    }

    // After shadeQueued(kLanes): moves the rest (fewer than kLanes) to the front (with their
    // sample masks: kMasks).
    template <bool kMasks>
    void dropShadedGroup() const {
        queue.count -= kLanes;
        istore(queue.x, iload(queue.x + kLanes));
        istore(queue.y, iload(queue.y + kLanes));
        fstore(queue.invW, fload(queue.invW + kLanes));
        for (int k = 0; k < kV; ++k) fstore(queue.v[k], fload(queue.v[k] + kLanes));
        if constexpr (kMasks) istore(queue.mask, iload(queue.mask + kLanes));
    }

    // Shades and writes the queued fragments (fewer than kLanes) and empties the queue.
    void flush() const {
        const int used = queue.count;
        if (used == 0) return;
        // Lanes [used, kLanes) repeat the last fragment (their results are dropped): a vector
        // blend per array, not a scalar store per lane and array.
        const M keep = firstN(used);
        istore(queue.x, select(keep, iload(queue.x), iset(queue.x[used - 1])));
        istore(queue.y, select(keep, iload(queue.y), iset(queue.y[used - 1])));
        fstore(queue.invW, select(keep, fload(queue.invW), fset(queue.invW[used - 1])));
        for (int k = 0; k < kV; ++k) fstore(queue.v[k], select(keep, fload(queue.v[k]), fset(queue.v[k][used - 1])));
        shadeQueuedAnywhere(used);
        queue.count = 0;
    }

    // True when a queued fragment lies in row y, columns [x, x + kLanes): a group about to be
    // written there directly must not be overwritten by an older fragment written later.
    bool queuedIn(int y, int x) const {
        const M used = firstN(queue.count);
        const I qx = iload(queue.x), qy = iload(queue.y);
        const M hit = used & (qy == iset(y)) & (qx > iset(x - 1)) & (qx < iset(x + kLanes));
        return bits(hit) != 0;
    }

    // A one-pixel span [x, x + 1) of row y on the setup with its plane origin at `origin`
    // (movedOrigin: a pixel shaded at its centroid), without a depth test: lane 0 of operator()'s
    // one group, computed alone (the same double plane values, the same float operations with
    // step 0) and queued, instead of a whole group of lanes for one. `mask`: its passing samples
    // (a queue with samples).
    void queueOne(int y, int x, PlaneOrigin origin, unsigned mask = 0) const {
        static_assert(kDepth == DepthMode::Off && kV > 0, "the multisampled fill's centroid pixels");
        alignas(64) float startF[kPlanesPadded];
        alignas(64) double startZW[kLanes / 2];
        planesAt((x + 0.5) - origin.x, (y + 0.5) - origin.y, startF, startZW);
        const int at = queue.count;
        const float invW = float(startZW[kPlaneInvW] + t.ddx[kPlaneInvW] * 0.0);
        const float w = 1.0f / invW;
        for (int k = 0; k < kV; ++k) {
            const int plane = kPlaneVarying0 + k;
            const float value = startF[plane] + t.ddxStep[plane] * 0.0f;
            queue.v[k][at] = kPersp == PerspectiveMode::Exact ? value * w : value;
        }
        queue.x[at] = x;
        queue.y[at] = y;
        queue.invW[at] = invW;
        queue.mask[at] = std::int32_t(mask);
        ++shaded;
        queue.count = at + 1;
        if (queue.count == kLanes) {
            shadeQueuedAnywhere(kLanes);
            queue.count = 0;
        }
    }

    // Pixels [x0, x1) of row y at their centres, without a depth test, written to their passing
    // samples masks[x - x0] (a queue with samples): operator()'s values for DepthMode::Off, lane
    // by lane. A whole group of lanes is shaded and written at once (after the queued fragments
    // of its pixels: queuedIn), the rest queued, so that every colour reaches the samples in the
    // order the fragments came.
    void queueRun(int y, int x0, int x1, const std::uint8_t* masks) const {
        static_assert(kDepth == DepthMode::Off && kV > 0, "the multisampled fill's runs");
        alignas(64) float startF[kPlanesPadded];
        alignas(64) double startZW[kLanes / 2];
        planesAt((x0 + 0.5) - t.originX, (y + 0.5) - t.originY, startF, startZW);
        const F lastStep = fset(float(x1 - 1 - x0));
        const I row = iset(y);
        for (int x = x0; x < x1; x += kLanes) {
            const int n = std::min(kLanes, x1 - x);
            const F step = fmin(fset(float(x - x0)) + fiota(), lastStep);
            const F invW = planeInDouble(dset(startZW[kPlaneInvW]), kPlaneInvW, step);
            F values[kV];
            varyingsAt(startF, step, invW, values);
            if (n == kLanes) {
                if (queue.count > 0 && queuedIn(y, x)) flush();
                alignas(64) std::uint32_t out[kLanes];
                istore(out, shadeGroup<Prog, kPersp, kFilter>(p, values, invW, iset(x) + iiota(), row, triangleLod));
                withSampleCount([&](auto samples) {
                    constexpr int kN = decltype(samples)::value;
                    Pixel* at = queue.samples->colourRow(y) + std::size_t(x) * kN;
                    for (int i = 0; i < kLanes; ++i) writeSamples<kN>(at + i * kN, out[i], masks[x - x0 + i]);
                });
                continue;
            }
            const int at = queue.count; // below kLanes: a whole vector fits at `at`
            for (int k = 0; k < kV; ++k) fstore(queue.v[k] + at, values[k]);
            istore(queue.x + at, iset(x) + iiota());
            istore(queue.y + at, row);
            fstore(queue.invW + at, invW);
            for (int i = 0; i < n; ++i) queue.mask[at + i] = masks[x - x0 + i];
            queue.count = at + n;
            if (queue.count >= kLanes) {
                shadeQueued<true>(kLanes);
                dropShadedGroup<true>();
            }
        }
    }

    void operator()(int y, int x0, int x1) const {
        // Plane values at the centre of the span's first pixel (double, rounded once), as fillTriangle.
        alignas(64) float startF[kPlanesPadded];
        alignas(64) double startZW[kLanes / 2]; // depth and 1/w, unrounded: evaluated per lane in double
        planesAt((x0 + 0.5) - t.originX, (y + 0.5) - t.originY, startF, startZW);
        const D startZ = dset(startZW[kPlaneZ]);
        Pixel* colour = fb.colorRow(y);
        float* depth = fb.depthRow(y);
        const int rowWidth = fb.width();
        if (kDepth != DepthMode::Off && y + 1 < t.endRow && y + 1 < fb.height()) {
            // The triangle's next span starts and ends near this one's: ask for its depth and
            // colour lines now, so that their misses overlap with this span's work.
            const std::size_t next = std::size_t(rowWidth);
            prefetchForWrite(depth + next + x0);
            prefetchForWrite(depth + next + (x1 - 1));
            prefetchForWrite(colour + next + x0);
            prefetchForWrite(colour + next + (x1 - 1));
        }
        // Pixel index along the span (whole numbers, exact in float), clamped to the last pixel so
        // that lanes past the end never see values extrapolated off the triangle.
        const F lastStep = fset(float(x1 - 1 - x0));
        const I row = iset(y);
        Pixel constant = 0; // kV == 0: the triangle's one colour, read at its first passing group
        for (int x = x0; x < x1; x += kLanes) {
            const int n = std::min(kLanes, x1 - x);
            const M inside = firstN(n);
            // Whole vectors load and store whenever the group lies in the row: lanes past the
            // span are read and written back unchanged (they belong to this row, i.e. this band).
            const bool inRow = x + kLanes <= rowWidth;
            const F step = fmin(fset(float(x - x0)) + fiota(), lastStep);
            const F z = planeInDouble(startZ, kPlaneZ, step);
            M pass = inside;
            F stored = fzero();
            if constexpr (kDepth != DepthMode::Off) {
                if (inRow) {
                    stored = fload(depth + x);
                } else {
                    alignas(64) float part[kLanes] = {};
                    for (int i = 0; i < n; ++i) part[i] = depth[x + i];
                    stored = fload(part);
                }
                pass = pass & (z > stored);
            }
            const int passBits = bits(pass);
            if (passBits == 0) continue;
            if constexpr (kDepth == DepthMode::TestWrite) {
                if (inRow) {
                    fstore(depth + x, select(pass, z, stored));
                } else {
                    alignas(64) float zs[kLanes];
                    fstore(zs, z);
                    for (int i = 0; i < n; ++i)
                        if (passBits & (1 << i)) depth[x + i] = zs[i];
                }
            }
            const int passed = laneCount(pass);
            shaded += std::uint64_t(passed);
            if constexpr (kV == 0) {
                if constexpr (Prog::kMode == ShadingMode::Flat) p.ensureLit(); // lazy flat lighting
                constant = p.flat;
                if (inRow && !blending()) {
                    istore(colour + x, select(pass, iset(int(constant)), iload(colour + x)));
                } else {
                    for (int i = 0; i < n; ++i)
                        if (passBits & (1 << i)) put(colour[x + i], constant);
                }
                continue;
            } else {
                const F invW = planeInDouble(dset(startZW[kPlaneInvW]), kPlaneInvW, step);
                F values[kV];
                if constexpr (kPersp == PerspectiveMode::Exact) {
                    const F w = fset(1.0f) / invW;
                    for (int k = 0; k < kV; ++k) values[k] = (fset(startF[kPlaneVarying0 + k]) + gradient[kPlaneVarying0 + k] * step) * w;
                } else {
                    for (int k = 0; k < kV; ++k) values[k] = fset(startF[kPlaneVarying0 + k]) + gradient[kPlaneVarying0 + k] * step;
                }
                const I columns = iset(x) + iiota();
                if (passBits == bits(mAll())) {
                    // (A deferred queue may hold older fragments of these pixels: written first.)
                    if (deferred && queue.count > 0 && queuedIn(y, x)) flush();
                    const I shaded = shadeGroup<Prog, kPersp, kFilter>(p, values, invW, columns, row, triangleLod);
                    if (!blending()) {
                        istore(colour + x, shaded);
                    } else {
                        alignas(64) std::uint32_t out[kLanes];
                        istore(out, shaded);
                        for (int i = 0; i < kLanes; ++i) put(colour[x + i], out[i]);
                    }
                    continue;
                }
                const int at = queue.count;
                compressStore(queue.x + at, columns, pass);
                compressStore(queue.y + at, row, pass);
                compressStore(queue.invW + at, invW, pass);
                for (int k = 0; k < kV; ++k) compressStore(queue.v[k] + at, values[k], pass);
                queue.count = at + passed;
                if (queue.count >= kLanes) {
                    shadeQueued<false>(kLanes);
                    dropShadedGroup<false>();
                }
            }
        }
    }
};

// The fill kernels' fragment queue: one per thread and kernel, reused by every triangle (only
// `count` carries over; the rest is written before it is read).
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
FragmentQueue<Prog::kVaryings>& fillQueue() {
    static thread_local FragmentQueue<Prog::kVaryings> queue;
    return queue;
}

// A kDeferrable program's queue is not flushed at the end of the triangle: the fragments of a
// draw's small triangles (the bunny's average 4 pixels at 800x600) fill whole groups of lanes
// together instead of a group each. The colours then reach the target later, in the same order
// (the queue is written first in order; a whole group written directly first flushes the older
// fragments of its pixels, queuedIn), and the depth test stays immediate: the image is the
// same. The pipeline calls flushSpans at the end of each lane's walk of a draw and before
// anything else writes colour (a wireframe edge).
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
void fillSpans(const Prog& p, const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, std::uint64_t& shaded) {
    using Span = SpanKernel<Prog, kDepth, kPersp, kFilter>;
    assert(Prog::kVaryings <= t.varyingCount);
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= fb.width() && s.y1 <= fb.height());
    FragmentQueue<Prog::kVaryings>& queue = fillQueue<Prog, kDepth, kPersp, kFilter>();
    if constexpr (!Span::kDeferrable) queue.count = 0;
    assert(kDepth == DepthMode::Test || p.d->alpha >= 1.0f); // blending kernels: DepthMode::Test only
    Span span(p, t, fb, shaded, queue, p.d->alpha, Span::kDeferrable);
    if constexpr (Prog::kIsTextured && kFilter == TextureFilter::Trilinear && kPersp == PerspectiveMode::Affine)
        span.triangleLod = fset(affineMipLevel(p));
    forEachSpan(t, s, span);
    if constexpr (Prog::kVaryings > 0 && !Span::kDeferrable) span.flush();
}

// The multisampled run shader's queue: one per thread and kernel (as fillQueue).
template <class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
FragmentQueue<Prog::kVaryings>& runQueue() {
    static thread_local FragmentQueue<Prog::kVaryings> queue;
    return queue;
}

// Shades and writes what fillSpans and shadeRunSpans left queued on this thread (nothing for a
// program that is not kDeferrable); `p` is any program of the draw (the queued fragments read
// only its constants).
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
void flushSpans(const Prog& p, FrameBuffer& fb) {
    using Span = SpanKernel<Prog, kDepth, kPersp, kFilter>;
    if constexpr (Span::kDeferrable) {
        const TriangleSetup none{}; // (the shading of a deferrable program reads no triangle)
        std::uint64_t shaded = 0;   // (counted when queued)
        FragmentQueue<Prog::kVaryings>& queue = fillQueue<Prog, kDepth, kPersp, kFilter>();
        if (queue.count > 0) {
            const Span span(p, none, fb, shaded, queue, p.d->alpha, true);
            span.flush();
        }
        FragmentQueue<Prog::kVaryings>& runs = runQueue<Prog, kPersp, kFilter>();
        if (runs.count > 0) {
            const SpanKernel<Prog, DepthMode::Off, kPersp, kFilter> span(p, none, fb, shaded, runs);
            span.flush();
        }
    } else {
        (void)p;
        (void)fb;
    }
}

// The multisampled fill's shading (MsaaFill.hpp): the pixels of the given runs, shaded without a
// depth test as fillSpan<DepthMode::Off> with fragment() does (SpanKernel's values). Into fb's
// rows (SpanKernel's very loop, one span per run; the queue flushed before returning), or, for
// an opaque draw (write.target) of a kDeferrable program, straight into the passing samples:
// a run's whole groups of lanes at once, its other pixels queued with their masks (queueRun,
// queueOne) and written when a whole group is queued. The queue outlives the triangle (a draw of
// small triangles shades full groups, not one per triangle), fragments reach the samples in
// submission order, and flushSpans writes the rest at the end of the lane's walk. The depth test
// was made per sample before (coverTriangleSamples), so the samples are those of the per-triangle
// path, and the shading rows in fb are not used.
template <class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
bool shadeRunSpans(const Prog& p, const TriangleSetup& t, FrameBuffer& fb, const SpanRun* runs, int count,
                   const SampleWrite& write) {
    assert(Prog::kVaryings <= t.varyingCount);
    using Span = SpanKernel<Prog, DepthMode::Off, kPersp, kFilter>;
    FragmentQueue<Prog::kVaryings>& queue = runQueue<Prog, kPersp, kFilter>();
    std::uint64_t shaded = 0; // the multisampled fill counts its pixels itself
    if constexpr (Span::kDeferrable) {
        if (write.target) {
            assert(queue.count == 0 || queue.samples == write.target);
            queue.samples = write.target;
            const Span span(p, t, fb, shaded, queue);
            for (int r = 0; r < count; ++r) {
                const SpanRun& run = runs[r];
                const std::uint8_t* masks = write.passed + run.passedAt;
                if (run.dx != 0.0 || run.dy != 0.0) { // at the centroid: one lane each
                    const PlaneOrigin origin = movedOrigin(t, run);
                    for (int x = run.x0; x < run.x1; ++x) span.queueOne(run.y, x, origin, masks[x - run.x0]);
                    continue;
                }
                span.queueRun(run.y, run.x0, run.x1, masks);
            }
            return true;
        }
    }
    queue.count = 0;
    queue.samples = nullptr;
    // Runs at the centre go through the span loop; a pixel shaded off its centre (at its
    // centroid) is queued on its own with the plane origin moved (queueOne, movedOrigin).
    Span span(p, t, fb, shaded, queue);
    if constexpr (Prog::kIsTextured && kFilter == TextureFilter::Trilinear && kPersp == PerspectiveMode::Affine)
        span.triangleLod = fset(affineMipLevel(p));
    for (int r = 0; r < count; ++r) {
        const SpanRun& run = runs[r];
        if constexpr (Prog::kVaryings > 0) {
            if (run.dx != 0.0 || run.dy != 0.0) { // at the centroid: one lane each
                const PlaneOrigin origin = movedOrigin(t, run);
                for (int x = run.x0; x < run.x1; ++x) span.queueOne(run.y, x, origin);
                continue;
            }
        }
        span(run.y, run.x0, run.x1); // (without varyings the colour is the triangle's wherever it is shaded)
    }
    if constexpr (Prog::kVaryings > 0) span.flush();
    return false;
}

// --- The table ---------------------------------------------------------------------------------
// Both entries of a key: the fill (per depth mode) and the multisampled run shader (the same
// for every depth mode: one instantiation).
template <class Prog>
struct KernelPair {
    FillKernel<Prog> fill = nullptr;
    ShadeRunsKernel<Prog> runs = nullptr;
    FlushKernel<Prog> flush = nullptr; // the fill's deferred queue
};

template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
KernelPair<Prog> entries() {
    return {&fillSpans<Prog, kDepth, kPersp, kFilter>, &shadeRunSpans<Prog, kPersp, kFilter>,
            &flushSpans<Prog, kDepth, kPersp, kFilter>};
}

// Resolves the key's run-time values into template arguments, one level at a time; a program
// that does not read a setting gets the one instantiation that ignores it. (The wrap mode is
// read per group by sampleTexture: the key's wrap selects nothing here.)
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp>
KernelPair<Prog> pickFilter(const KernelKey& key) {
    if constexpr (!Prog::kIsTextured) {
        (void)key;
        return entries<Prog, kDepth, kPersp, TextureFilter::Bilinear>();
    } else {
        switch (key.filter) {
        case TextureFilter::Nearest: return entries<Prog, kDepth, kPersp, TextureFilter::Nearest>();
        case TextureFilter::Bilinear: return entries<Prog, kDepth, kPersp, TextureFilter::Bilinear>();
        case TextureFilter::Trilinear: return entries<Prog, kDepth, kPersp, TextureFilter::Trilinear>();
        }
        return {};
    }
}

template <class Prog, DepthMode kDepth>
KernelPair<Prog> pickPerspective(const KernelKey& key) {
    if constexpr (Prog::kVaryings == 0) {
        return pickFilter<Prog, kDepth, PerspectiveMode::Exact>(key); // nothing to interpolate
    } else {
        switch (key.perspective) {
        case PerspectiveMode::Exact: return pickFilter<Prog, kDepth, PerspectiveMode::Exact>(key);
        case PerspectiveMode::Affine: return pickFilter<Prog, kDepth, PerspectiveMode::Affine>(key);
        }
        return {};
    }
}

template <class Prog>
KernelPair<Prog> pickDepth(const KernelKey& key) {
    switch (key.depth) {
    case DepthMode::Off: return pickPerspective<Prog, DepthMode::Off>(key);
    case DepthMode::Test: return pickPerspective<Prog, DepthMode::Test>(key);
    case DepthMode::TestWrite: return pickPerspective<Prog, DepthMode::TestWrite>(key);
    }
    return {};
}

template <class Prog>
FillKernel<Prog> fillKernel(const KernelKey& key) {
    return pickDepth<Prog>(key).fill;
}

template <class Prog>
ShadeRunsKernel<Prog> shadeRunsKernel(const KernelKey& key) {
    return pickPerspective<Prog, DepthMode::Off>(key).runs; // no depth test: the fill did it per sample
}

template <class Prog>
FlushKernel<Prog> flushKernel(const KernelKey& key) {
    return pickDepth<Prog>(key).flush;
}

// The one shading model this translation unit instantiates, untextured and textured:
// SR_KERNEL_PROGRAM, defined by the file that includes Kernels<Isa>.inl (one file per ISA and
// shading model, so that no single file compiles all 2 x 4 programs' kernels).
#if !defined(SR_KERNEL_FLAG_VARIANTS_ONLY) && !defined(SR_KERNEL_COLOUR_VARIANTS_ONLY) // (variants in files of their own)
template FillKernel<programs::SR_KERNEL_PROGRAM<false>> fillKernel(const KernelKey&);
template FillKernel<programs::SR_KERNEL_PROGRAM<true>> fillKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<false>> shadeRunsKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true>> shadeRunsKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<false>> flushKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true>> flushKernel(const KernelKey&);
#endif
#ifdef SR_KERNEL_NORMAL_MAP_VARIANT // the textured program's normal-mapped variant too (pbr)
template FillKernel<programs::SR_KERNEL_PROGRAM<true, true>> fillKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true, true>> shadeRunsKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true, true>> flushKernel(const KernelKey&);
#endif
// The pbr programs with vertex colours (COLOR_0): without and with maps, and normal-mapped.
#ifdef SR_KERNEL_COLOUR_VARIANTS_ONLY
template FillKernel<programs::SR_KERNEL_PROGRAM<false, false, true>> fillKernel(const KernelKey&);
template FillKernel<programs::SR_KERNEL_PROGRAM<true, false, true>> fillKernel(const KernelKey&);
template FillKernel<programs::SR_KERNEL_PROGRAM<true, true, true>> fillKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<false, false, true>> shadeRunsKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true, false, true>> shadeRunsKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true, true, true>> shadeRunsKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<false, false, true>> flushKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true, false, true>> flushKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true, true, true>> flushKernel(const KernelKey&);
#endif
// The program's variants with its second flag set: Gouraud's RGB terms (under coloured lights),
// Phong's normal-only programs (no position varyings), Unlit's vertex colours.
#if defined(SR_KERNEL_FLAG_VARIANTS) || defined(SR_KERNEL_FLAG_VARIANTS_ONLY)
template FillKernel<programs::SR_KERNEL_PROGRAM<false, true>> fillKernel(const KernelKey&);
template FillKernel<programs::SR_KERNEL_PROGRAM<true, true>> fillKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<false, true>> shadeRunsKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true, true>> shadeRunsKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<false, true>> flushKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true, true>> flushKernel(const KernelKey&);
#endif
