// Scanline fill: exact fixed-point edge walking, top-left spans, depth test and a templated span loop.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "Raster/FixedPoint.hpp"
#include "Raster/FrameBuffer.hpp"
#include "Raster/ShadingSimd.hpp" // SR_HAVE_SSE2 and <emmintrin.h>
#include "Raster/TriangleSetup.hpp"

namespace sr {

// Pixel rectangle [x0, x1) x [y0, y1) the fill may touch. Clipping spans to it never changes
// which pixels inside it are covered.
struct Scissor {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
inline Scissor fullScissor(const FrameBuffer& fb) { return {0, 0, fb.width(), fb.height()}; }

// Walks one FixedEdge down the pixel rows, yielding at each row the index of the first pixel
// whose centre is at or right of the edge. Exact DDA with an error term, after Hecker
// ("Perspective Texture Mapping, Part 2: Rasterization", Game Developer, June 1995):
//   x(row) = x0 + (Yc - y0) dx / dy, Yc = row centre; we want i = ceil((x(row) - 128) / 256)
//   = ceil(N / D) with N = (x0 - 128) dy + (Yc - y0) dx and D = 256 dy. Keep i and the error
//   e = i D - N in [0, D); one row down adds 256 dx = q D + r (0 <= r < D) to N, so i += q and
//   e -= r, borrowing one more pixel when e goes negative. The prestep to the first row is a
//   direct division, so rows above the scissor cost nothing. |N| < 2^47: int64 is exact.
class EdgeWalker {
public:
    EdgeWalker() = default;
    EdgeWalker(const FixedEdge& e, int row) {
        assert(e.dy > 0);
        denom_ = std::int64_t(kSubPixelScale) * e.dy;
        const std::int64_t n = (std::int64_t(e.x0) - kSubPixelScale / 2) * e.dy +
                               (pixelCentreFixed(row) - e.y0) * std::int64_t(e.dx);
        x_ = ceilDiv(n, denom_);
        error_ = x_ * denom_ - n;
        step_ = floorDiv(e.dx, e.dy);                        // floor(256 dx / 256 dy)
        stepError_ = std::int64_t(kSubPixelScale) * (e.dx - step_ * std::int64_t(e.dy)); // in [0, D)
    }
    // First pixel column at or right of the edge on the current row (may lie outside the screen).
    std::int64_t x() const { return x_; }
    void nextRow() {
        x_ += step_;
        error_ -= stepError_;
        if (error_ < 0) {
            ++x_;
            error_ += denom_;
        }
    }

private:
    std::int64_t x_ = 0, error_ = 0, denom_ = 1, step_ = 0, stepError_ = 0;
};

// Calls visit(y, x0, x1) for every non-empty span [x0, x1) of row y covered by the triangle and
// inside the scissor, top row first, in increasing y. The rule (D3D10 top-left, proven equal to
// the edge-function rule in Tests/Raster/TriangleCoverageTests.cpp): row j is covered when its
// centre is in [yTop, yBottom); its span starts at the first centre >= the left edge's x (a
// centre ON a left edge is in) and ends before the first centre >= the right edge's x (a centre
// on a right edge is out). A horizontal top edge is the top row's span itself (in); a
// horizontal bottom edge lies on the excluded yBottom row (out).
template <class Visit>
void forEachSpan(const TriangleSetup& t, const Scissor& s, Visit&& visit) {
    const int rowBegin = std::max(t.firstRow, s.y0);
    const int rowEnd = std::min(t.endRow, s.y1);
    if (rowBegin >= rowEnd || t.maxX < s.x0 || t.minX >= s.x1) return;
    const int midRow = std::clamp(t.midRow, rowBegin, rowEnd);

    // Walk the two parts of the triangle: rows above the middle vertex against the upper short
    // edge, then the rest against the lower one; the long edge runs through both.
    EdgeWalker longWalk(t.longEdge, rowBegin);
    for (int part = 0; part < 2; ++part) {
        const int from = part == 0 ? rowBegin : midRow;
        const int to = part == 0 ? midRow : rowEnd;
        if (from >= to) continue;
        EdgeWalker shortWalk(part == 0 ? t.upperEdge : t.lowerEdge, from);
        const EdgeWalker& left = t.longEdgeOnLeft ? longWalk : shortWalk;
        const EdgeWalker& right = t.longEdgeOnLeft ? shortWalk : longWalk;
        for (int y = from; y < to; ++y) {
            const int x0 = int(std::clamp<std::int64_t>(left.x(), s.x0, s.x1));
            const int x1 = int(std::clamp<std::int64_t>(right.x(), s.x0, s.x1));
            if (x0 < x1) visit(y, x0, x1);
            longWalk.nextRow();
            shortWalk.nextRow();
        }
    }
}

// What the span loop hands the per-pixel shader: position, depth and, when kVaryings > 0,
// 1/w and the perspective-correct varyings (v/w divided by 1/w at this pixel centre).
template <int kVaryings>
struct Fragment {
    int x = 0, y = 0;
    float z = 0.0f;
    float invW = 0.0f;                     // only set when kVaryings > 0
    std::array<float, kVaryings> varyings; // the first kVaryings varyings of the setup
};

// Depth policy of a fill, chosen at compile time. Depth is reversed-Z float, test GREATER
// (strict: on an exact tie the fragment already in the buffer stays).
// Precision: z_ndc = near / distance (infinite far plane) is stored as float, whose relative
// spacing is 2^-24 at every magnitude, so two depths are distinguishable whenever their
// distances differ by more than ~2^-23 relatively, near or far alike (Reed, "Depth Precision
// Visualized", 2015). The screen-linear plane evaluation adds a few ulps on top.
enum class DepthMode { Off, Test, TestWrite };

// The span loop: fills the covered pixels of `t` inside the scissor. Per pixel, in order:
// depth test (if enabled), depth write (TestWrite), colour = shader(fragment). kVaryings
// (<= t.varyingCount) varyings are interpolated as kPersp says (TriangleSetup.hpp; Affine needs a
// setup made with perspectiveCorrect = false); with kVaryings == 0 no divide runs at all.
// Attributes at a span start are evaluated from the plane equation in double (never accumulated
// from row to row); along the span pixel k gets start + k * gradient in float (one multiply-add
// per attribute, and no error build-up on long spans).
// Shader: any callable `Pixel(const Fragment<kVaryings>&)`, inlined: no virtual call per pixel.
template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp = PerspectiveMode::Exact, class Shader>
void fillTriangle(const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, Shader&& shader) {
    static_assert(kVaryings >= 0 && kVaryings <= kMaxVaryings, "too many varyings");
    assert(kVaryings <= t.varyingCount);
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= fb.width() && s.y1 <= fb.height());
    constexpr int kPlanes = kVaryings > 0 ? kPlaneVarying0 + kVaryings : 1;
    constexpr int kSpan = kPersp == PerspectiveMode::Span16 ? 16 : 8;

    forEachSpan(t, s, [&](int y, int x0, int x1) {
        // Plane values at the centre of the span's first pixel (double, once per span).
        const double dx = (x0 + 0.5) - t.originX, dy = (y + 0.5) - t.originY;
        // Sized for z and 1/w at least, so code that names kPlaneInvW compiles in range for every
        // instantiation (only the first kPlanes entries are used).
        constexpr int kArray = kPlanes > kPlaneVarying0 ? kPlanes : kPlaneVarying0;
        float start[kArray] = {};
        for (int k = 0; k < kPlanes; ++k) start[k] = float(t.value[k] + t.ddx[k] * dx + t.ddy[k] * dy);

        float gradient[kArray] = {}; // per-pixel gradients in locals: stores to the buffers can't alias them
        for (int k = 0; k < kPlanes; ++k) gradient[k] = t.ddxStep[k];
        Pixel* colour = fb.colorRow(y);
        float* depth = fb.depthRow(y);
        Fragment<kVaryings> f;
        f.y = y;
        // Span subdivision (Span16/Span8): segments of kSpan pixels aligned to the span start;
        // exact varyings at a segment's first pixel and at the next segment's first pixel (or the
        // span's last pixel), linear in between: one divide per kSpan pixels.
        [[maybe_unused]] float segValue[kVaryings > 0 ? kVaryings : 1] = {};
        [[maybe_unused]] float segSlope[kVaryings > 0 ? kVaryings : 1] = {};
        [[maybe_unused]] int segStart = x0, segEnd = x0;
        [[maybe_unused]] auto exactAt = [&](int px, int k) {
            const float at = float(px - x0);
            const int p = kPlaneVarying0 + k;
            return (start[p] + gradient[p] * at) / (start[kPlaneInvW] + gradient[kPlaneInvW] * at);
        };
        float step = 0.0f; // pixel index along the span, exact in float
        for (int x = x0; x < x1; ++x, step += 1.0f) {
            f.z = start[kPlaneZ] + gradient[kPlaneZ] * step;
            if constexpr (kDepth != DepthMode::Off) {
                if (!(f.z > depth[x])) continue;
                if constexpr (kDepth == DepthMode::TestWrite) depth[x] = f.z;
            }
            f.x = x;
            if constexpr (kVaryings > 0) {
                f.invW = start[kPlaneInvW] + gradient[kPlaneInvW] * step;
                if constexpr (kPersp == PerspectiveMode::Exact) {
                    const float w = 1.0f / f.invW;
                    for (int k = 0; k < kVaryings; ++k) {
                        const int p = kPlaneVarying0 + k;
                        f.varyings[std::size_t(k)] = (start[p] + gradient[p] * step) * w;
                    }
                } else if constexpr (kPersp == PerspectiveMode::Affine) {
                    for (int k = 0; k < kVaryings; ++k) {
                        const int p = kPlaneVarying0 + k;
                        f.varyings[std::size_t(k)] = start[p] + gradient[p] * step;
                    }
                } else {
                    static_assert(kPersp == PerspectiveMode::Span16 || kPersp == PerspectiveMode::Span8);
                    if (x >= segEnd) { // first visited pixel of a new segment
                        segStart = x0 + ((x - x0) / kSpan) * kSpan;
                        segEnd = std::min(x1, segStart + kSpan);
                        const int last = std::min(segStart + kSpan, x1 - 1);
                        for (int k = 0; k < kVaryings; ++k) {
                            segValue[k] = exactAt(segStart, k);
                            segSlope[k] = last > segStart ? (exactAt(last, k) - segValue[k]) / float(last - segStart) : 0.0f;
                        }
                    }
                    const float i = float(x - segStart);
                    for (int k = 0; k < kVaryings; ++k) f.varyings[std::size_t(k)] = segValue[k] + segSlope[k] * i;
                }
            }
            colour[x] = shader(static_cast<const Fragment<kVaryings>&>(f));
        }
    });
}

template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp = PerspectiveMode::Exact, class Shader>
void fillTriangle(const TriangleSetup& t, FrameBuffer& fb, Shader&& shader) {
    fillTriangle<kDepth, kVaryings, kPersp>(t, fb, fullScissor(fb), shader);
}

// Four fragments in structure-of-arrays form, for programs that shade with SIMD (fragment4).
template <int kVaryings>
struct FragmentBatch {
    int count = 0;
    int x[4] = {}, y[4] = {};
    alignas(16) float invW[4] = {};
    alignas(16) float v[kVaryings > 0 ? kVaryings : 1][4] = {};
};

#if SR_HAVE_SSE2
// The first kPlanes plane values at the centre of pixel (x0, y), the start of a span of the SIMD
// loops: fillTriangle's very expression (value + ddx dx + ddy dy in double, rounded to float),
// two planes per double register with the same IEEE multiplies and adds in the same order.
template <int kPlanes>
inline void spanStartPlanes(const TriangleSetup& t, int y, int x0, float out[kPlanes]) {
    const double dx = (x0 + 0.5) - t.originX, dy = (y + 0.5) - t.originY;
    const __m128d dxD = _mm_set1_pd(dx), dyD = _mm_set1_pd(dy);
    int k = 0;
    for (; k + 1 < kPlanes; k += 2) {
        const __m128d v = _mm_add_pd(_mm_add_pd(_mm_loadu_pd(t.value + k), _mm_mul_pd(_mm_loadu_pd(t.ddx + k), dxD)),
                                     _mm_mul_pd(_mm_loadu_pd(t.ddy + k), dyD));
        _mm_storel_pi(reinterpret_cast<__m64*>(out + k), _mm_cvtpd_ps(v)); // round to nearest, as float(double)
    }
    for (; k < kPlanes; ++k) out[k] = float(t.value[k] + t.ddx[k] * dx + t.ddy[k] * dy);
}

// fillTriangle for a program with fragment4 (Exact and Affine interpolation), four pixels per
// step: pixels x, x+1, x+2, x+3 of a span get z, 1/w and the varyings from the same float
// operations as fillTriangle's (start + gradient * step, then * (1 / (1/w)) for Exact: SSE
// mulps/addps/divps round like their scalar forms, and there is no FMA), so every value is
// bit-identical to the one-pixel loop. The depth test is a lane mask (strict GREATER, written
// for the passing lanes only); groups with no passing lane are skipped; the passing lanes are
// shaded with one fragment4 call and only they are stored. Lanes past the span's end repeat its
// last pixel (step clamped), so fragment4 never sees values extrapolated off the triangle.
// `shaded` counts the passing fragments, as the one-pixel loop's shader does.
template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp, class Program>
void fillTriangle4(const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, Program& program,
                   std::uint64_t& shaded) {
    static_assert(kVaryings > 0 && kVaryings <= kMaxVaryings, "fillTriangle4 interpolates varyings");
    static_assert(kPersp == PerspectiveMode::Exact || kPersp == PerspectiveMode::Affine, "no span subdivision here");
    assert(kVaryings <= t.varyingCount);
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= fb.width() && s.y1 <= fb.height());
    constexpr int kPlanes = kPlaneVarying0 + kVaryings;
    FragmentBatch<kVaryings> batch;
    batch.count = 4;
    __m128 gradient[kPlanes]; // per-pixel steps: per triangle
    for (int k = 0; k < kPlanes; ++k) gradient[k] = _mm_set1_ps(t.ddxStep[k]);
    forEachSpan(t, s, [&](int y, int x0, int x1) {
        alignas(16) float first[kPlanes];
        spanStartPlanes<kPlanes>(t, y, x0, first);
        __m128 start[kPlanes];
        for (int k = 0; k < kPlanes; ++k) start[k] = _mm_set1_ps(first[k]);
        Pixel* colour = fb.colorRow(y);
        float* depth = fb.depthRow(y);
        for (int i = 0; i < 4; ++i) batch.y[i] = y;
        const __m128 lastStep = _mm_set1_ps(float(x1 - 1 - x0));
        const __m128 laneOffsets = _mm_setr_ps(0.0f, 1.0f, 2.0f, 3.0f);
        for (int x = x0; x < x1; x += 4) {
            const int n = std::min(4, x1 - x); // lanes inside the span
            const int inside = (1 << n) - 1;
            // Pixel index along the span (whole numbers, exact in float), clamped to the last pixel.
            const __m128 step = _mm_min_ps(_mm_add_ps(_mm_set1_ps(float(x - x0)), laneOffsets), lastStep);
            const __m128 z = _mm_add_ps(start[kPlaneZ], _mm_mul_ps(gradient[kPlaneZ], step));
            int pass = inside;
            if constexpr (kDepth != DepthMode::Off) {
                const __m128 stored = n == 4 ? _mm_loadu_ps(depth + x)
                                             : _mm_setr_ps(depth[x], depth[x + std::min(1, n - 1)],
                                                           depth[x + std::min(2, n - 1)], depth[x + std::min(3, n - 1)]);
                pass &= _mm_movemask_ps(_mm_cmpgt_ps(z, stored));
                if (pass == 0) continue;
                if constexpr (kDepth == DepthMode::TestWrite) {
                    if (pass == 0xF) {
                        _mm_storeu_ps(depth + x, z);
                    } else {
                        alignas(16) float zs[4];
                        _mm_store_ps(zs, z);
                        for (int i = 0; i < 4; ++i)
                            if (pass & (1 << i)) depth[x + i] = zs[i];
                    }
                }
            }
            shaded += std::uint64_t((0x4332322132212110ull >> (4 * pass)) & 0xFu); // popcount of 4 bits
            const __m128 invW = _mm_add_ps(start[kPlaneInvW], _mm_mul_ps(gradient[kPlaneInvW], step));
            _mm_store_ps(batch.invW, invW);
            if constexpr (kPersp == PerspectiveMode::Exact) {
                const __m128 w = _mm_div_ps(_mm_set1_ps(1.0f), invW);
                for (int k = 0; k < kVaryings; ++k) {
                    const int p = kPlaneVarying0 + k;
                    _mm_store_ps(batch.v[k], _mm_mul_ps(_mm_add_ps(start[p], _mm_mul_ps(gradient[p], step)), w));
                }
            } else {
                for (int k = 0; k < kVaryings; ++k) {
                    const int p = kPlaneVarying0 + k;
                    _mm_store_ps(batch.v[k], _mm_add_ps(start[p], _mm_mul_ps(gradient[p], step)));
                }
            }
            for (int i = 0; i < 4; ++i) batch.x[i] = x + std::min(i, n - 1);
            alignas(16) Pixel out[4];
            program.fragment4(static_cast<const FragmentBatch<kVaryings>&>(batch), out);
            if (pass == 0xF) {
                _mm_storeu_si128(reinterpret_cast<__m128i*>(colour + x), _mm_load_si128(reinterpret_cast<const __m128i*>(out)));
            } else {
                for (int i = 0; i < 4; ++i)
                    if (pass & (1 << i)) colour[x + i] = out[i];
            }
        }
    });
}
#endif

#if SR_HAVE_AVX2
// Eight fragments for fragment8 (AVX2): lane i is pixel (x[i], y[i]) with its 1/w and varyings.
// The lanes are not necessarily neighbours (see fillTriangle8); unused lanes repeat a used one.
// No initialisers: the fill writes every member before each fragment8 call (zeroing it cost a
// `rep stos` per eight pixels).
template <int kVaryings>
struct FragmentBatch8 {
    alignas(32) int x[8];
    alignas(32) int y[8];
    alignas(32) float invW[8];
    alignas(32) float v[kVaryings > 0 ? kVaryings : 1][8];
};

namespace detail {
// Left-packing permutations for _mm256_permutevar8x32: entry m lists the set bits of m in
// ascending order (then zeros), so the lanes that passed the depth test move to the front.
struct PackTable8 {
    alignas(32) int lanes[256][8];
    constexpr PackTable8() : lanes{} {
        for (int m = 0; m < 256; ++m) {
            int n = 0;
            for (int i = 0; i < 8; ++i)
                if (m & (1 << i)) lanes[m][n++] = i;
        }
    }
};
inline constexpr PackTable8 kPackTable8{};

// The fragments of one triangle waiting to be shaded: up to 15 (a full group of 8 is shaded as
// soon as it exists), each with its pixel, 1/w and varyings in lane-major arrays.
template <int kVaryings>
struct FragmentQueue8 {
    int count = 0;
    alignas(32) int x[16] = {};
    alignas(32) int y[16] = {};
    alignas(32) float invW[16] = {};
    alignas(32) float v[kVaryings][16] = {};
};

// One span of fillTriangle8 (a functor rather than a lambda: GCC does not give a lambda its
// enclosing function's target("avx2")).
template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp, class Program>
struct Span8 {
    static constexpr int kPlanes = kPlaneVarying0 + kVaryings;
    const TriangleSetup& t;
    FrameBuffer& fb;
    Program& program;
    std::uint64_t& shaded;
    FragmentQueue8<kVaryings>& queue;
    const __m256* gradient;

    // Shades the queue's first eight fragments (lanes past `used` repeat lane used - 1, so the
    // program sees only real fragments) and stores the first `used` colours at their pixels.
    SR_TARGET_AVX2 void shadeQueued(int used) const {
        FragmentBatch8<kVaryings> batch;
        const __m256i clampIndex = _mm256_min_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32(used - 1));
        const auto pick = [&](const float* from, float* to) SR_TARGET_AVX2 {
            _mm256_store_ps(to, _mm256_permutevar8x32_ps(_mm256_load_ps(from), clampIndex));
        };
        _mm256_store_si256(reinterpret_cast<__m256i*>(batch.x),
                           _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(queue.x)), clampIndex));
        _mm256_store_si256(reinterpret_cast<__m256i*>(batch.y),
                           _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(queue.y)), clampIndex));
        pick(queue.invW, batch.invW);
        for (int j = 0; j < kVaryings; ++j) pick(queue.v[j], batch.v[j]);
        alignas(32) Pixel out[8];
        program.fragment8(static_cast<const FragmentBatch8<kVaryings>&>(batch), out);
        for (int i = 0; i < used; ++i) fb.colorRow(batch.y[i])[batch.x[i]] = out[i];
    }

    SR_TARGET_AVX2 void operator()(int y, int x0, int x1) const {
        alignas(16) float first[kPlanes];
        spanStartPlanes<kPlanes>(t, y, x0, first);
        __m256 start[kPlanes];
        for (int k = 0; k < kPlanes; ++k) start[k] = _mm256_broadcast_ss(first + k);
        Pixel* colour = fb.colorRow(y);
        float* depth = fb.depthRow(y);
        const __m256 lastStep = _mm256_set1_ps(float(x1 - 1 - x0));
        const __m256 laneOffsets = _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f);
        const __m256i laneIndex = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        const __m256i row = _mm256_set1_epi32(y);
        const int rowWidth = fb.width();
        for (int x = x0; x < x1; x += 8) {
            const int n = std::min(8, x1 - x);
            // Lanes inside the span, as a vector mask: masked loads and stores never touch the others.
            const __m256i insideV = _mm256_cmpgt_epi32(_mm256_set1_epi32(n), laneIndex);
            const __m256 step = _mm256_min_ps(_mm256_add_ps(_mm256_set1_ps(float(x - x0)), laneOffsets), lastStep);
            const __m256 z = _mm256_add_ps(start[kPlaneZ], _mm256_mul_ps(gradient[kPlaneZ], step));
            __m256i passV = insideV;
            __m256 stored = _mm256_setzero_ps();
            // Plain loads and stores whenever all eight pixels are in this row (masked ones are
            // slow on some CPUs): pixels past the span's end are read and written back unchanged,
            // and they belong to this row, i.e. to this lane's band.
            const bool inRow = x + 8 <= rowWidth;
            if constexpr (kDepth != DepthMode::Off) {
                stored = inRow ? _mm256_loadu_ps(depth + x) : _mm256_maskload_ps(depth + x, insideV);
                passV = _mm256_and_si256(passV, _mm256_castps_si256(_mm256_cmp_ps(z, stored, _CMP_GT_OQ)));
            }
            const int pass = _mm256_movemask_ps(_mm256_castsi256_ps(passV));
            if (pass == 0) continue;
            if constexpr (kDepth == DepthMode::TestWrite) {
                if (inRow) _mm256_storeu_ps(depth + x, _mm256_blendv_ps(stored, z, _mm256_castsi256_ps(passV)));
                else _mm256_maskstore_ps(depth + x, passV, z);
            }
            const int passed = int(((0x4332322132212110ull >> (4 * (pass & 0xF))) & 0xFu) +
                                   ((0x4332322132212110ull >> (4 * (pass >> 4))) & 0xFu));
            shaded += std::uint64_t(passed);
            const __m256 invW = _mm256_add_ps(start[kPlaneInvW], _mm256_mul_ps(gradient[kPlaneInvW], step));
            __m256 values[kVaryings];
            if constexpr (kPersp == PerspectiveMode::Exact) {
                const __m256 w = _mm256_div_ps(_mm256_set1_ps(1.0f), invW);
                for (int j = 0; j < kVaryings; ++j) {
                    const int p = kPlaneVarying0 + j;
                    values[j] = _mm256_mul_ps(_mm256_add_ps(start[p], _mm256_mul_ps(gradient[p], step)), w);
                }
            } else {
                for (int j = 0; j < kVaryings; ++j) {
                    const int p = kPlaneVarying0 + j;
                    values[j] = _mm256_add_ps(start[p], _mm256_mul_ps(gradient[p], step));
                }
            }
            const __m256i columns = _mm256_add_epi32(_mm256_set1_epi32(x), laneIndex);
            if (pass == 0xFF) {
                // A whole group: shaded at once and stored with one vector store.
                FragmentBatch8<kVaryings> batch;
                _mm256_store_si256(reinterpret_cast<__m256i*>(batch.x), columns);
                _mm256_store_si256(reinterpret_cast<__m256i*>(batch.y), row);
                _mm256_store_ps(batch.invW, invW);
                for (int j = 0; j < kVaryings; ++j) _mm256_store_ps(batch.v[j], values[j]);
                alignas(32) Pixel out[8];
                program.fragment8(static_cast<const FragmentBatch8<kVaryings>&>(batch), out);
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(colour + x), _mm256_load_si256(reinterpret_cast<const __m256i*>(out)));
                continue;
            }
            // A partial group: its passing lanes join the queue (packed to the front), which is
            // shaded eight at a time. The pixels of one triangle are distinct, so the order in
            // which they are stored does not matter; the queue is emptied before the next triangle.
            const __m256i pack = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackTable8.lanes[pass]));
            const int at = queue.count;
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(queue.x + at), _mm256_permutevar8x32_epi32(columns, pack));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(queue.y + at), row);
            _mm256_storeu_ps(queue.invW + at, _mm256_permutevar8x32_ps(invW, pack));
            for (int j = 0; j < kVaryings; ++j) _mm256_storeu_ps(queue.v[j] + at, _mm256_permutevar8x32_ps(values[j], pack));
            queue.count = at + passed;
            if (queue.count >= 8) {
                shadeQueued(8);
                // Move the rest (fewer than 8) to the front.
                queue.count -= 8;
                const auto down = [](auto* lanes) SR_TARGET_AVX2 {
                    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), _mm256_loadu_si256(reinterpret_cast<const __m256i*>(lanes + 8)));
                };
                down(queue.x);
                down(queue.y);
                down(queue.invW);
                for (int j = 0; j < kVaryings; ++j) down(queue.v[j]);
            }
        }
    }
};
} // namespace detail

// fillTriangle4 with eight pixels per step (AVX2: the same operations, so the same bits) for a
// program with fragment8(const FragmentBatch8<kVaryings>&, Pixel out[8]). A group whose eight
// pixels all pass the depth test is shaded at once; the passing pixels of the other groups are
// packed into a queue and shaded eight at a time (whatever is left at the end of the triangle,
// with repeated lanes), so the shader rarely runs on lanes that are thrown away.
// Precondition: the CPU has AVX2 (cpuHasAvx2()).
template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp, class Program>
SR_TARGET_AVX2 void fillTriangle8(const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, Program& program,
                                  std::uint64_t& shaded) {
    static_assert(kVaryings > 0 && kVaryings <= kMaxVaryings, "fillTriangle8 interpolates varyings");
    static_assert(kPersp == PerspectiveMode::Exact || kPersp == PerspectiveMode::Affine, "no span subdivision here");
    assert(kVaryings <= t.varyingCount);
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= fb.width() && s.y1 <= fb.height());
    constexpr int kPlanes = kPlaneVarying0 + kVaryings;
    // One queue per thread, reused by every triangle (only `count` is reset): zeroing ~700
    // bytes per triangle showed up in profiles of small-triangle scenes. Lanes past `count` hold
    // earlier triangles' values, which are loaded but never used.
    static thread_local detail::FragmentQueue8<kVaryings> queue;
    queue.count = 0;
    __m256 gradient[kPlanes];
    for (int k = 0; k < kPlanes; ++k) gradient[k] = _mm256_set1_ps(t.ddxStep[k]);
    const detail::Span8<kDepth, kVaryings, kPersp, Program> span{t, fb, program, shaded, queue, gradient};
    forEachSpan(t, s, span);
    if (queue.count > 0) span.shadeQueued(queue.count);
}
#endif

} // namespace sr
