// The multisampled fill's coverage and depth stage (MsaaFill.hpp): which samples of which pixels
// a triangle covers, which of them pass the depth test, and the pixels to shade.
#include "Raster/Fill/MsaaFill.hpp"
#include "Raster/Fill/Kernels/KernelConfig.hpp"
#include "Raster/Fill/Occlusion.hpp"
#include "Raster/Fill/Prefetch.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#if SR_KERNELS_X86
#include <immintrin.h>
#endif
#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define SR_MSAA_SSE2 1
#else
#define SR_MSAA_SSE2 0
#endif

namespace sr {
namespace {

// The centroid of the samples in a coverage mask, as an offset from the pixel centre in pixels
// (the mean of their pattern offsets; (0, 0) for an empty mask).
struct Centroid {
    double dx = 0.0, dy = 0.0;
};
template <int kN>
const Centroid* centroidTable() {
    static const auto table = [] {
        std::vector<Centroid> t(std::size_t(1) << kN);
        const SampleOffset* pattern = msaaPattern(kN);
        for (unsigned mask = 1; mask < t.size(); ++mask) {
            double sx = 0.0, sy = 0.0;
            int count = 0;
            for (int k = 0; k < kN; ++k) {
                if (!(mask & (1u << k))) continue;
                sx += pattern[k].x;
                sy += pattern[k].y;
                ++count;
            }
            t[mask] = {sx / (count * double(kSubPixelScale)), sy / (count * double(kSubPixelScale))};
        }
        return t;
    }();
    return table.data();
}

// Samples per 64-byte cache line (colour and depth samples are 4 bytes each).
constexpr std::size_t kLine = 64 / sizeof(float);
static_assert(sizeof(Pixel) == sizeof(float), "a colour and a depth sample are the same size");

// Append a row or run record by storing its fields in place: a braced `push_back({...})` would
// build the record on the stack with narrow stores and copy it with one wide load, which cannot
// be forwarded from them and so waits behind every older store (the sample writes and their
// cache misses included).
void addRow(MsaaScratch& scratch, int y, int lo, int hi, std::size_t offset) {
    MsaaScratch::Row& row = scratch.rows.emplace_back();
    row.y = y;
    row.lo = lo;
    row.hi = hi;
    row.offset = offset;
}
void addRun(MsaaScratch& scratch, int y, int x0, int x1, std::size_t passedAt, double dx, double dy) {
    SpanRun& run = scratch.runs.emplace_back();
    run.y = y;
    run.x0 = x0;
    run.x1 = x1;
    run.passedAt = std::uint32_t(passedAt);
    run.dx = dx;
    run.dy = dy;
}

// Room for `count` masks in the scratch rows.
void reserveMasks(MsaaScratch& scratch, std::size_t count) {
    if (scratch.covered.size() < count) {
        scratch.covered.resize(2 * count);
        scratch.passed.resize(2 * count);
    }
}

#if SR_MSAA_SSE2
// All ones in the 32-bit lanes whose bit is set in `bits` (0..15).
inline __m128i laneMask(unsigned bits) {
    return _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(int(bits)), _mm_setr_epi32(1, 2, 4, 8)), _mm_setr_epi32(1, 2, 4, 8));
}
#endif

// The depth test of one row's covered samples, pixels [lo, hi) with masks covered[x - lo]:
// writes passed[x - lo]. Depth of sample k: the plane at the sample point of pixel `lo` in
// double, then + (x - lo) ddx in double, rounded once to float (so every path gets the same
// floats: the stored depths do not depend on how coverage was found).
// `decided(x, pass, cover)` is called for every pixel of the row, left to right, once its
// passing samples are known (RunList: the pixels to shade, listed in the same pass).
template <int kN, DepthMode kDepth, bool kVector, class Decided>
void depthTestRow(const TriangleSetup& t, const SampleOffset* pattern, float* depth, int y, int lo, int hi,
                  const std::uint8_t* covered, std::uint8_t* passed, Decided&& decided) {
    if constexpr (kDepth == DepthMode::Off) {
        (void)t, (void)pattern, (void)depth, (void)y;
        for (int x = lo; x < hi; ++x) {
            passed[x - lo] = covered[x - lo];
            decided(x, covered[x - lo], covered[x - lo]);
        }
    } else {
        const double ddx = t.ddx[kPlaneZ];
        double zStart[kN];
        for (int k = 0; k < kN; ++k)
            zStart[k] = t.planeAt(kPlaneZ, lo + 0.5 + double(pattern[k].x) / kSubPixelScale,
                                  y + 0.5 + double(pattern[k].y) / kSubPixelScale);
        for (int x = lo; x < hi; ++x) {
            const unsigned cover = covered[x - lo];
            if (cover == 0) {
                passed[x - lo] = 0;
                decided(x, 0u, 0u);
                continue;
            }
            float* stored = depth + std::size_t(x) * kN;
            const double step = double(x - lo);
            unsigned pass = 0;
#if SR_MSAA_SSE2
            if constexpr (kVector && kN >= 4) {
                // Four samples at a time: the same double multiply and add, rounded once to
                // float (cvtpd2ps rounds as the scalar conversion does), compared, kept by lane.
                const __m128d slope = _mm_set1_pd(ddx), steps = _mm_set1_pd(step);
                for (int g = 0; g < kN / 4; ++g) {
                    const __m128 low = _mm_cvtpd_ps(_mm_add_pd(_mm_loadu_pd(zStart + 4 * g), _mm_mul_pd(slope, steps)));
                    const __m128 high = _mm_cvtpd_ps(_mm_add_pd(_mm_loadu_pd(zStart + 4 * g + 2), _mm_mul_pd(slope, steps)));
                    const __m128 z = _mm_movelh_ps(low, high);
                    const __m128 old = _mm_loadu_ps(stored + 4 * g);
                    const unsigned nearer = unsigned(_mm_movemask_ps(_mm_cmpgt_ps(z, old)));
                    const unsigned ok = nearer & (cover >> (4 * g)) & 0xFu;
                    if constexpr (kDepth == DepthMode::TestWrite) {
                        if (ok != 0) {
                            const __m128 keep = _mm_castsi128_ps(laneMask(ok));
                            _mm_storeu_ps(stored + 4 * g, _mm_or_ps(_mm_and_ps(keep, z), _mm_andnot_ps(keep, old)));
                        }
                    }
                    pass |= ok << (4 * g);
                }
                passed[x - lo] = std::uint8_t(pass);
                decided(x, pass, cover);
                continue;
            }
#endif
            for (int k = 0; k < kN; ++k) {
                const float z = float(zStart[k] + ddx * step);
                const bool ok = (cover >> k & 1u) && z > stored[k];
                if constexpr (kDepth == DepthMode::TestWrite) stored[k] = ok ? z : stored[k];
                pass |= unsigned(ok) << k;
            }
            passed[x - lo] = std::uint8_t(pass);
            decided(x, pass, cover);
        }
    }
}

// Lists row y's pixels to shade: runs of pixels whose centre is covered (pixels [c0, c1)),
// shaded at the centre, and every other pixel with a sample that passed on its own, at the
// centroid of its covered samples.
template <int kN>
void listRuns(MsaaScratch& scratch, int y, int lo, int hi, int c0, int c1, const std::uint8_t* covered,
              const std::uint8_t* passed) {
    const Centroid* centroids = centroidTable<kN>();
    const std::size_t at = std::size_t(passed - scratch.passed.data()); // pixel lo's mask
    c0 = std::max(c0, lo);
    c1 = std::min(c1, hi);
    for (int x = lo; x < hi;) {
        if (passed[x - lo] == 0) {
            ++x;
        } else if (x >= c0 && x < c1) {
            const int from = x;
            while (x < c1 && passed[x - lo] != 0) ++x;
            addRun(scratch, y, from, x, at + std::size_t(from - lo), 0.0, 0.0);
        } else {
            const Centroid& m = centroids[covered[x - lo]];
            addRun(scratch, y, x, x + 1, at + std::size_t(x - lo), m.dx, m.dy);
            ++x;
        }
    }
}

// listRuns' list built pixel by pixel, left to right, as the depth test decides each pixel (the
// Auto method: one pass over the row instead of two; the Reference method keeps listRuns, and
// the test compares them).
template <int kN>
struct RunList {
    MsaaScratch& scratch;
    const Centroid* centroids = centroidTable<kN>();
    int y = 0, lo = 0, c0 = 0, c1 = 0;
    std::size_t at = 0; // where pixel lo's mask is in scratch.passed
    int from = -1;      // the open run's first pixel (-1: none)

    // Row `row`'s pixels [lo, hi), their masks of passing samples at `passed` (in scratch.passed).
    RunList(MsaaScratch& s, int row, int first, int hi, int centre0, int centre1, const std::uint8_t* passed)
        : scratch(s), y(row), lo(first), c0(std::max(centre0, first)), c1(std::min(centre1, hi)),
          at(std::size_t(passed - s.passed.data())) {}
    void operator()(int x, unsigned pass, unsigned cover) {
        if (pass != 0 && x >= c0 && x < c1) {
            if (from < 0) from = x;
            return;
        }
        close(x);
        if (pass != 0) {
            const Centroid& m = centroids[cover];
            addRun(scratch, y, x, x + 1, at + std::size_t(x - lo), m.dx, m.dy);
        }
    }
    void close(int x) {
        if (from < 0) return;
        addRun(scratch, y, from, x, at + std::size_t(from - lo), 0.0, 0.0);
        from = -1;
    }
};

// The row's depth test and its pixels to shade: in one pass (Auto, kVector) or the depth test
// then listRuns (Reference).
template <int kN, DepthMode kDepth, bool kVector>
void testAndListRow(const TriangleSetup& t, const SampleOffset* pattern, float* depth, MsaaScratch& scratch, int y,
                    int lo, int hi, int c0, int c1, const std::uint8_t* covered, std::uint8_t* passed) {
    if constexpr (kVector) {
        RunList<kN> runs(scratch, y, lo, hi, c0, c1, passed);
        depthTestRow<kN, kDepth, true>(t, pattern, depth, y, lo, hi, covered, passed, runs);
        runs.close(hi);
    } else {
        depthTestRow<kN, kDepth, false>(t, pattern, depth, y, lo, hi, covered, passed, [](int, unsigned, unsigned) {});
        listRuns<kN>(scratch, y, lo, hi, c0, c1, covered, passed);
    }
}

#if SR_KERNELS_X86
// The sample points' offsets from the pixel centre, in pixels (depthTestRow's
// double(pattern[k].x) / kSubPixelScale), for loading four at a time.
template <int kN>
struct SamplePoints {
    alignas(32) double x[kN < 4 ? 4 : kN], y[kN < 4 ? 4 : kN]; // (2 samples: the last two 0, unused)
};
template <int kN>
const SamplePoints<kN>& samplePoints() {
    static const SamplePoints<kN> points = [] {
        SamplePoints<kN> p;
        const SampleOffset* pattern = msaaPattern(kN);
        for (int k = 0; k < kN; ++k) {
            p.x[k] = double(pattern[k].x) / kSubPixelScale;
            p.y[k] = double(pattern[k].y) / kSubPixelScale;
        }
        return p;
    }();
    return points;
}

// testAndListRow's one pass with AVX2 (draws whose kernels are AVX2 or AVX-512), 2, 4 or 8
// samples with a depth test: the samples' depth planes at the row's first pixel four (two)
// doubles per step, and each pixel's depths as one `start + step * ddx` per four (two) samples,
// with planeAt's and depthTestRow's double operations lane by lane, rounded once to float: the
// same floats.
SR_BEGIN_TARGET(SR_TARGET_STRING_AVX2)
template <int kN, DepthMode kDepth>
void testAndListRowAvx2(const TriangleSetup& t, float* depth, MsaaScratch& scratch, int y, int lo, int hi, int c0,
                        int c1, const std::uint8_t* covered, std::uint8_t* passed) {
    static_assert((kN == 2 || kN % 4 == 0) && kDepth != DepthMode::Off, "2, 4 or 8 samples, a depth test");
    constexpr int kGroups = (kN + 3) / 4;
    const SamplePoints<kN>& points = samplePoints<kN>();
    const __m256d ddx = _mm256_set1_pd(t.ddx[kPlaneZ]);
    if constexpr (kN == 2) { // two doubles
        const __m128d slope = _mm256_castpd256_pd128(ddx);
        const __m128d dx = _mm_sub_pd(_mm_add_pd(_mm_set1_pd(lo + 0.5), _mm_load_pd(points.x)), _mm_set1_pd(t.originX));
        const __m128d dy = _mm_sub_pd(_mm_add_pd(_mm_set1_pd(y + 0.5), _mm_load_pd(points.y)), _mm_set1_pd(t.originY));
        const __m128d zStart = _mm_add_pd(_mm_add_pd(_mm_set1_pd(t.value[kPlaneZ]), _mm_mul_pd(slope, dx)),
                                          _mm_mul_pd(_mm_set1_pd(t.ddy[kPlaneZ]), dy));
        RunList<kN> runs(scratch, y, lo, hi, c0, c1, passed);
        for (int x = lo; x < hi; ++x) {
            const unsigned cover = covered[x - lo];
            unsigned pass = 0;
            if (cover != 0) {
                double* stored = reinterpret_cast<double*>(depth + std::size_t(x) * kN); // the pixel's two floats
                const __m128 z = _mm_cvtpd_ps(_mm_add_pd(zStart, _mm_mul_pd(slope, _mm_set1_pd(double(x - lo))))); // (upper 0)
                const __m128 old = _mm_castpd_ps(_mm_load_sd(stored));
                pass = unsigned(_mm_movemask_ps(_mm_cmpgt_ps(z, old))) & cover;
                if constexpr (kDepth == DepthMode::TestWrite)
                    if (pass != 0) _mm_store_sd(stored, _mm_castps_pd(_mm_blendv_ps(old, z, _mm_castsi128_ps(laneMask(pass)))));
            }
            passed[x - lo] = std::uint8_t(pass);
            runs(x, pass, cover);
        }
        runs.close(hi);
        return;
    }
    const __m256d rowX = _mm256_set1_pd(lo + 0.5), rowY = _mm256_set1_pd(y + 0.5);
    __m256d zStart[kGroups];
    for (int g = 0; g < kGroups; ++g) {
        const __m256d dx = _mm256_sub_pd(_mm256_add_pd(rowX, _mm256_load_pd(points.x + 4 * g)), _mm256_set1_pd(t.originX));
        const __m256d dy = _mm256_sub_pd(_mm256_add_pd(rowY, _mm256_load_pd(points.y + 4 * g)), _mm256_set1_pd(t.originY));
        zStart[g] = _mm256_add_pd(_mm256_add_pd(_mm256_set1_pd(t.value[kPlaneZ]), _mm256_mul_pd(ddx, dx)),
                                  _mm256_mul_pd(_mm256_set1_pd(t.ddy[kPlaneZ]), dy));
    }
    RunList<kN> runs(scratch, y, lo, hi, c0, c1, passed);
    for (int x = lo; x < hi; ++x) {
        const unsigned cover = covered[x - lo];
        if (cover == 0) {
            passed[x - lo] = 0;
            runs(x, 0u, 0u);
            continue;
        }
        float* stored = depth + std::size_t(x) * kN;
        const __m256d steps = _mm256_set1_pd(double(x - lo));
        unsigned pass = 0;
        if constexpr (kN == 4) {
            const __m128 z = _mm256_cvtpd_ps(_mm256_add_pd(zStart[0], _mm256_mul_pd(ddx, steps)));
            const __m128 old = _mm_loadu_ps(stored);
            pass = unsigned(_mm_movemask_ps(_mm_cmpgt_ps(z, old))) & cover;
            if constexpr (kDepth == DepthMode::TestWrite)
                if (pass != 0) _mm_storeu_ps(stored, _mm_blendv_ps(old, z, _mm_castsi128_ps(laneMask(pass))));
        } else if constexpr (kN == 8) {
            const __m256 z = _mm256_set_m128(_mm256_cvtpd_ps(_mm256_add_pd(zStart[1], _mm256_mul_pd(ddx, steps))),
                                             _mm256_cvtpd_ps(_mm256_add_pd(zStart[0], _mm256_mul_pd(ddx, steps))));
            const __m256 old = _mm256_loadu_ps(stored);
            pass = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(z, old, _CMP_GT_OQ))) & cover;
            if constexpr (kDepth == DepthMode::TestWrite) {
                if (pass != 0) {
                    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
                    const __m256i keep = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(pass)), bit), bit);
                    _mm256_storeu_ps(stored, _mm256_blendv_ps(old, z, _mm256_castsi256_ps(keep)));
                }
            }
        }
        passed[x - lo] = std::uint8_t(pass);
        runs(x, pass, cover);
    }
    runs.close(hi);
}
SR_END_TARGET
#endif

// testAndListRow, or its AVX2 pass where the draw's ISA has AVX2 (kWide) and it applies.
template <int kN, DepthMode kDepth, bool kVector, bool kWide>
void testAndListRowFor(const TriangleSetup& t, const SampleOffset* pattern, float* depth, MsaaScratch& scratch, int y,
                       int lo, int hi, int c0, int c1, const std::uint8_t* covered, std::uint8_t* passed) {
#if SR_KERNELS_X86
    if constexpr (kWide && kN >= 2 && kDepth != DepthMode::Off) {
        (void)pattern;
        testAndListRowAvx2<kN, kDepth>(t, depth, scratch, y, lo, hi, c0, c1, covered, passed);
        return;
    }
#endif
    testAndListRow<kN, kDepth, kVector>(t, pattern, depth, scratch, y, lo, hi, c0, c1, covered, passed);
}

// --- Large triangles: exact edge walks, one per sample and one for the centre ------------------
template <int kN, DepthMode kDepth, bool kVector, bool kWide>
void coverByWalks(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, int rowBegin, int rowEnd,
                  MsaaScratch& scratch) {
    constexpr int n = kN;
    const SampleOffset* pattern = msaaPattern(n);
    // The span of every sample (and of the centre, entry n) on every row.
    const int stride = 2 * (n + 1);
    scratch.spans.assign(std::size_t(rowEnd - rowBegin) * std::size_t(stride), 0); // [0, 0): empty
    for (int k = 0; k <= n; ++k) {
        const SpanCoverage c = k < n ? sampleCoverage(t, pattern[k].x, pattern[k].y) : sampleCoverage(t, 0, 0);
        const Scissor rows{s.x0, rowBegin, s.x1, rowEnd};
        forEachSpan(c, rows, [&](int y, int x0, int x1) {
            int* span = scratch.spans.data() + std::size_t(y - rowBegin) * std::size_t(stride) + 2 * k;
            span[0] = x0;
            span[1] = x1;
        });
    }
    std::size_t used = 0;
    for (int y = rowBegin; y < rowEnd; ++y) {
        const int* spans = scratch.spans.data() + std::size_t(y - rowBegin) * std::size_t(stride);
        int lo = s.x1, hi = s.x0;
        for (int k = 0; k < n; ++k) {
            if (spans[2 * k] >= spans[2 * k + 1]) continue;
            lo = std::min(lo, spans[2 * k]);
            hi = std::max(hi, spans[2 * k + 1]);
        }
        if (lo >= hi) continue;
        const std::size_t width = std::size_t(hi - lo);
        reserveMasks(scratch, used + width);
        std::uint8_t* covered = scratch.covered.data() + used;
        std::uint8_t* passed = scratch.passed.data() + used;
        addRow(scratch, y, lo, hi, used);
        used += width;
        // Every sample is covered in the spans' intersection [inner0, inner1); the few pixels
        // at either end are tested sample by sample.
        int inner0 = lo, inner1 = hi;
        for (int k = 0; k < n; ++k) {
            inner0 = std::max(inner0, spans[2 * k]);
            inner1 = std::min(inner1, spans[2 * k + 1]);
        }
        if (inner0 >= inner1) inner0 = inner1 = hi;
        auto maskAt = [&](int x) {
            unsigned mask = 0;
            for (int k = 0; k < n; ++k) mask |= unsigned(x >= spans[2 * k] && x < spans[2 * k + 1]) << k;
            return std::uint8_t(mask);
        };
        for (int x = lo; x < inner0; ++x) covered[x - lo] = maskAt(x);
        std::fill(covered + (inner0 - lo), covered + (inner1 - lo), std::uint8_t((1u << n) - 1u));
        for (int x = inner1; x < hi; ++x) covered[x - lo] = maskAt(x);
        target.prepareSpan(y, lo, hi); // a pending fast clear made real before the test
        testAndListRowFor<kN, kDepth, kVector, kWide>(t, pattern, target.depthRow(y), scratch, y, lo, hi, spans[2 * n],
                                                      spans[2 * n + 1], covered, passed);
    }
}

// --- Small triangles: edge functions over the bounding box, a pixel's samples at once ----------
// (msaaSmallTriangle: every edge value, step and sample offset over the box is exact in int32.)

struct FixedPoint64 {
    std::int64_t x, y;
};

// Edge function of a -> b at p (the reference rasterizer's, Tests/Fill/ReferenceRasterizer.cpp):
// > 0 on the interior side of a clockwise (y-down) triangle.
std::int64_t edgeAt(FixedPoint64 a, FixedPoint64 b, FixedPoint64 p) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// D3D10's top-left rule for a clockwise edge a -> b: a left edge (interior at larger x) or a
// horizontal top edge (interior below) keeps the points exactly on it.
bool isTopLeft(FixedPoint64 a, FixedPoint64 b) {
    const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
    return dy < 0 || (dy == 0 && dx > 0);
}

// One edge of the triangle over the box: its biased value (>= 0 inside) at the centre of the
// box's first pixel, its steps one pixel right and one row down, and its offsets to each sample.
template <int kN>
struct BoxEdge {
    std::int32_t atOrigin = 0, stepX = 0, stepY = 0;
    std::int32_t sample[kN < 4 ? 4 : kN] = {}; // lanes past kN: 0 (masked off)
};

template <int kN>
BoxEdge<kN> boxEdge(FixedPoint64 a, FixedPoint64 b, FixedPoint64 origin, const SampleOffset* pattern) {
    BoxEdge<kN> e;
    const std::int64_t ax = -(b.y - a.y), by = b.x - a.x; // E(p) = ax * p.x + by * p.y + c
    e.atOrigin = std::int32_t(edgeAt(a, b, origin) + (isTopLeft(a, b) ? 0 : -1));
    e.stepX = std::int32_t(ax * kSubPixelScale);
    e.stepY = std::int32_t(by * kSubPixelScale);
    for (int k = 0; k < kN; ++k) e.sample[k] = std::int32_t(ax * pattern[k].x + by * pattern[k].y);
    return e;
}

// Bit k set when sample k of the pixel whose three edge values (at its centre) are e0, e1, e2
// is inside every edge.
template <int kN>
struct SampleMasks {
    static constexpr int kLanes = kN < 4 ? 4 : kN;
    static constexpr unsigned kAll = (1u << kN) - 1u;
#if SR_MSAA_SSE2
    __m128i offset[3][kLanes / 4];
    explicit SampleMasks(const BoxEdge<kN>* edges) {
        for (int i = 0; i < 3; ++i)
            for (int g = 0; g < kLanes / 4; ++g)
                offset[i][g] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(edges[i].sample + 4 * g));
    }
    unsigned operator()(std::int32_t e0, std::int32_t e1, std::int32_t e2) const {
        const __m128i v0 = _mm_set1_epi32(e0), v1 = _mm_set1_epi32(e1), v2 = _mm_set1_epi32(e2);
        unsigned outside = 0;
        for (int g = 0; g < kLanes / 4; ++g) {
            const __m128i any = _mm_or_si128(_mm_or_si128(_mm_add_epi32(v0, offset[0][g]), _mm_add_epi32(v1, offset[1][g])),
                                             _mm_add_epi32(v2, offset[2][g]));
            outside |= unsigned(_mm_movemask_ps(_mm_castsi128_ps(any))) << (4 * g); // a sign bit: some edge < 0
        }
        return ~outside & kAll;
    }
#else
    const BoxEdge<kN>* edges;
    explicit SampleMasks(const BoxEdge<kN>* e) : edges(e) {}
    unsigned operator()(std::int32_t e0, std::int32_t e1, std::int32_t e2) const {
        unsigned mask = 0;
        for (int k = 0; k < kN; ++k)
            mask |= unsigned((e0 + edges[0].sample[k]) >= 0 && (e1 + edges[1].sample[k]) >= 0 &&
                             (e2 + edges[2].sample[k]) >= 0)
                    << k;
        return mask;
    }
#endif
};

// The masks of a small triangle's whole box (`width` x `rows` pixels, edges at the first pixel's
// centre): row r's at masks + r * width (the covered samples of each pixel: SampleMasks' bits),
// bit i of any[r] set when pixel i of row r has a covered sample, of centre[r] when its centre
// is covered. `masks` has room for 7 bytes past the box (the wide pass writes whole groups).
template <int kN>
void coverBox(const BoxEdge<kN>* edges, int width, int rows, std::uint8_t* masks, std::uint32_t* any, std::uint32_t* centre) {
    const SampleMasks<kN> masksOf(edges);
    std::int32_t r0 = edges[0].atOrigin, r1 = edges[1].atOrigin, r2 = edges[2].atOrigin;
    for (int r = 0; r < rows; ++r, r0 += edges[0].stepY, r1 += edges[1].stepY, r2 += edges[2].stepY) {
        std::uint8_t* rowMasks = masks + std::size_t(r) * std::size_t(width);
        std::uint32_t anyBits = 0, centreBits = 0;
        std::int32_t e0 = r0, e1 = r1, e2 = r2;
        for (int i = 0; i < width; ++i, e0 += edges[0].stepX, e1 += edges[1].stepX, e2 += edges[2].stepX) {
            const unsigned mask = masksOf(e0, e1, e2);
            rowMasks[i] = std::uint8_t(mask);
            anyBits |= std::uint32_t(mask != 0) << i;
            centreBits |= std::uint32_t((e0 | e1 | e2) >= 0) << i;
        }
        any[r] = anyBits;
        centre[r] = centreBits;
    }
}

#if SR_KERNELS_X86
// The narrowest box the wide pass takes: under 4 pixels it costs more than it saves (bunny
// 480x270, MSAA 4: instructions 1.039x with every box, 1.008x from 4 pixels; 1920x1080: 0.950x).
inline constexpr int kWideBox = 4;

// coverBox eight pixels at a time (AVX2, for draws whose kernels are AVX2 or AVX-512): per
// sample, SampleMasks' int32 sums lane by lane (a sign bit: some edge < 0), so the same bits.
SR_BEGIN_TARGET(SR_TARGET_STRING_AVX2)
template <int kN, int k = 0>
inline __m256i wideMasks(const __m256i (&offset)[3][kN], __m256i v0, __m256i v1, __m256i v2, __m256i bits) {
    if constexpr (k == kN) {
        return bits;
    } else {
        const __m256i outside = _mm256_or_si256(_mm256_or_si256(_mm256_add_epi32(v0, offset[0][k]), _mm256_add_epi32(v1, offset[1][k])),
                                                _mm256_add_epi32(v2, offset[2][k]));
        bits = _mm256_or_si256(bits, _mm256_andnot_si256(_mm256_srai_epi32(outside, 31), _mm256_set1_epi32(1 << k)));
        return wideMasks<kN, k + 1>(offset, v0, v1, v2, bits);
    }
}
template <int kN>
void coverBoxAvx2(const BoxEdge<kN>* edges, int width, int rows, std::uint8_t* masks, std::uint32_t* any, std::uint32_t* centre) {
    __m256i offset[3][kN], ramp[3], step[3];
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < kN; ++k) offset[i][k] = _mm256_set1_epi32(edges[i].sample[k]);
        ramp[i] = _mm256_mullo_epi32(_mm256_set1_epi32(edges[i].stepX), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        step[i] = _mm256_set1_epi32(8 * edges[i].stepX); // |stepX| <= 2^21 (msaaSmallTriangle)
    }
    std::int32_t r0 = edges[0].atOrigin, r1 = edges[1].atOrigin, r2 = edges[2].atOrigin;
    for (int r = 0; r < rows; ++r, r0 += edges[0].stepY, r1 += edges[1].stepY, r2 += edges[2].stepY) {
        std::uint8_t* rowMasks = masks + std::size_t(r) * std::size_t(width);
        __m256i v0 = _mm256_add_epi32(_mm256_set1_epi32(r0), ramp[0]), v1 = _mm256_add_epi32(_mm256_set1_epi32(r1), ramp[1]),
                v2 = _mm256_add_epi32(_mm256_set1_epi32(r2), ramp[2]);
        std::uint32_t anyBits = 0, centreBits = 0;
        for (int i = 0; i < width; i += 8) {
            const __m256i bits = wideMasks<kN>(offset, v0, v1, v2, _mm256_setzero_si256());
            const unsigned valid = width - i >= 8 ? 0xFFu : (1u << (width - i)) - 1u;
            const unsigned none = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(bits, _mm256_setzero_si256()))));
            const unsigned outside = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_or_si256(_mm256_or_si256(v0, v1), v2))));
            anyBits |= std::uint32_t(~none & valid) << i;
            centreBits |= std::uint32_t(~outside & valid) << i;
            const __m128i words = _mm_packs_epi32(_mm256_castsi256_si128(bits), _mm256_extracti128_si256(bits, 1)); // < 256
            _mm_storel_epi64(reinterpret_cast<__m128i*>(rowMasks + i), _mm_packus_epi16(words, words));
            v0 = _mm256_add_epi32(v0, step[0]);
            v1 = _mm256_add_epi32(v1, step[1]);
            v2 = _mm256_add_epi32(v2, step[2]);
        }
        any[r] = anyBits;
        centre[r] = centreBits;
    }
}
SR_END_TARGET
#endif

// Pixels [x0, x1) x [rowBegin, rowEnd): the triangle's columns and rows inside the scissor, not
// empty; the triangle is small (msaaSmallTriangle: the int32 box).
template <int kN, DepthMode kDepth, bool kWide>
void coverByEdgeFunctions(const TriangleSetup& t, MsaaBuffer& target, int x0, int x1, int rowBegin, int rowEnd,
                          MsaaScratch& scratch) {
    assert(msaaSmallTriangle(t) && x0 < x1 && rowBegin < rowEnd);

    // The vertices (from the setup's edges), ordered clockwise.
    const FixedEdge& l = t.longEdge;
    FixedPoint64 a{l.x0, l.y0}, b{t.lowerEdge.x0, t.lowerEdge.y0}, c{std::int64_t(l.x0) + l.dx, std::int64_t(l.y0) + l.dy};
    if (edgeAt(a, b, c) < 0) std::swap(b, c);
    const SampleOffset* pattern = msaaPattern(kN);
    const FixedPoint64 origin{pixelCentreFixed(x0), pixelCentreFixed(rowBegin)};
    const BoxEdge<kN> edges[3] = {boxEdge<kN>(b, c, origin, pattern), boxEdge<kN>(c, a, origin, pattern),
                                  boxEdge<kN>(a, b, origin, pattern)};
    // The box's masks first, a whole box row each in the scratch rows (each row's record then
    // starts at its first covered pixel).
    const int boxWidth = x1 - x0, boxRows = rowEnd - rowBegin;
    reserveMasks(scratch, std::size_t(boxWidth) * std::size_t(boxRows) + 7); // (+7: coverBoxAvx2's last group)
    std::uint32_t anyOf[kMsaaSmallSide], centreOf[kMsaaSmallSide];
#if SR_KERNELS_X86
    if (kWide && boxWidth >= kWideBox) coverBoxAvx2<kN>(edges, boxWidth, boxRows, scratch.covered.data(), anyOf, centreOf);
    else coverBox<kN>(edges, boxWidth, boxRows, scratch.covered.data(), anyOf, centreOf);
#else
    static_assert(!kWide, "the wide pass exists on x86-64 only");
    coverBox<kN>(edges, boxWidth, boxRows, scratch.covered.data(), anyOf, centreOf);
#endif
    for (int y = rowBegin; y < rowEnd; ++y) {
        const std::uint32_t any = anyOf[y - rowBegin], centre = centreOf[y - rowBegin];
        if (any == 0) continue;
        const int lo = x0 + lowestSetBit(any), hi = x0 + highestSetBit(any) + 1;
        const int c0 = centre ? x0 + lowestSetBit(centre) : x1, c1 = centre ? x0 + highestSetBit(centre) + 1 : x0;
        const std::size_t offset = std::size_t(y - rowBegin) * std::size_t(boxWidth) + std::size_t(lo - x0);
        std::uint8_t* covered = scratch.covered.data() + offset;
        std::uint8_t* passed = scratch.passed.data() + offset;
        addRow(scratch, y, lo, hi, offset);
        target.prepareSpan(y, lo, hi); // a pending fast clear made real before the test
        const std::size_t listed = scratch.runs.size();
        testAndListRowFor<kN, kDepth, true, kWide>(t, pattern, target.depthRow(y), scratch, y, lo, hi, c0, c1, covered,
                                                   passed);
        if (scratch.runs.size() != listed) {
            // A sample passed: the row's colour is written after the shading; ask for its lines.
            Pixel* colour = target.colourRow(y);
            for (std::size_t i = std::size_t(lo) * kN, to = std::size_t(hi) * kN; i < to; i += kLine)
                prefetchForWrite(colour + i);
            prefetchForWrite(colour + std::size_t(hi) * kN - 1);
        }
    }
}

// Whether no sample of pixels [x0, x1) x [rowBegin, rowEnd) (a small triangle's box) can pass
// the depth test `z > stored` against triangle `t`: every stored depth there is at least
// nearestDepthBound. Then finding its coverage is skipped (with no back faces culled, about half
// of a closed mesh's triangles pass no sample); the answer is the same, as no sample would pass.
// Pending blocks of a fast clear hold their row's clear depth; a NaN anywhere keeps the triangle.
template <int kN>
bool hiddenBehind(const TriangleSetup& t, const MsaaBuffer& target, int x0, int x1, int rowBegin, int rowEnd) {
    const float bound = nearestDepthBound(t, x0, x1, rowBegin, rowEnd);
    if (!(bound == bound)) return false;
    for (int y = rowBegin; y < rowEnd; ++y) {
        const float* depth = target.depthRow(y);
        for (int b = x0 / kMsaaClearBlock; b * kMsaaClearBlock < x1; ++b) {
            if (target.pendingBlock(y, b)) {
                if (!(target.rowClearDepth(y) >= bound)) return false;
                continue;
            }
            std::size_t i = std::size_t(std::max(x0, b * kMsaaClearBlock)) * kN;
            const std::size_t end = std::size_t(std::min(x1, (b + 1) * kMsaaClearBlock)) * kN;
#if SR_MSAA_SSE2
            const __m128 least = _mm_set1_ps(bound);
            for (; i + 4 <= end; i += 4)
                if (_mm_movemask_ps(_mm_cmpge_ps(_mm_loadu_ps(depth + i), least)) != 0xF) return false;
#endif
            for (; i < end; ++i)
                if (!(depth[i] >= bound)) return false;
        }
    }
    return true;
}

template <int kN, DepthMode kDepth, bool kWide>
void coverSamples(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch,
                  MsaaCoverageMethod method) {
    scratch.rows.clear();
    scratch.runs.clear();
    int rowBegin = 0, rowEnd = 0;
    msaaRowRange(t, rowBegin, rowEnd);
    rowBegin = std::max(rowBegin, s.y0);
    rowEnd = std::min(rowEnd, s.y1);
    int boxX0 = 0, boxX1 = 0;
    msaaColumnRange(t, boxX0, boxX1);
    boxX0 = std::max(boxX0, s.x0);
    boxX1 = std::min(boxX1, s.x1);
    if (rowBegin >= rowEnd || boxX0 >= boxX1) return;

    // A small triangle's samples are a few short pieces of rows far apart in memory (a row of
    // samples is width * n * 4 bytes): ask for all of its depth lines now, so that their cache
    // misses overlap with each other and with the coverage below instead of stalling the depth
    // test one line at a time (a large triangle's rows stream well on their own). Its colour
    // lines too, unless coverByEdgeFunctions takes it: that asks for a row's colour lines once a
    // sample of the row has passed the depth test (with no culling, half of the bunny's
    // triangles pass none and never write a colour).
    // (Keep the loops inline: moved into a function of its own, GCC 12 at -O2 takes a function
    // that only prefetches for one without effects and drops every call to it.)
    const bool edgeFunctions = method == MsaaCoverageMethod::Auto && msaaSmallTriangle(t);
    if (boxX1 - boxX0 <= 64 && rowEnd - rowBegin <= 64) {
        for (int y = rowBegin; y < rowEnd; ++y) {
            const std::size_t from = std::size_t(boxX0) * kN, to = std::size_t(boxX1) * kN;
            for (std::size_t i = from; i < to; i += kLine) prefetchForWrite(target.depthRow(y) + i);
            prefetchForWrite(target.depthRow(y) + to - 1);
            if (edgeFunctions) continue;
            for (std::size_t i = from; i < to; i += kLine) prefetchForWrite(target.colourRow(y) + i);
            prefetchForWrite(target.colourRow(y) + to - 1);
        }
    }
    if constexpr (kDepth != DepthMode::Off)
        if (edgeFunctions && occlusionCandidate(t) && hiddenBehind<kN>(t, target, boxX0, boxX1, rowBegin, rowEnd)) return;
    if (edgeFunctions) coverByEdgeFunctions<kN, kDepth, kWide>(t, target, boxX0, boxX1, rowBegin, rowEnd, scratch);
    else if (method == MsaaCoverageMethod::Reference) coverByWalks<kN, kDepth, false, false>(t, target, s, rowBegin, rowEnd, scratch);
    else coverByWalks<kN, kDepth, true, kWide>(t, target, s, rowBegin, rowEnd, scratch);
}

template <int kN, DepthMode kDepth, MsaaCoverageMethod kMethod, bool kWide = false>
void coverStage(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, MsaaScratch& scratch) {
    assert(target.samples() == kN);
    coverSamples<kN, kDepth, kWide>(t, target, s, scratch, kMethod);
}

// Auto's small triangles with coverBoxAvx2 when the draw's ISA has AVX2 (Avx2, Avx512).
template <int kN, DepthMode kDepth>
auto coverStageFor(MsaaCoverageMethod method, Isa isa) {
    if (method == MsaaCoverageMethod::Reference) return coverStage<kN, kDepth, MsaaCoverageMethod::Reference>;
#if SR_KERNELS_X86
    if (isa == Isa::Avx2 || isa == Isa::Avx512) return coverStage<kN, kDepth, MsaaCoverageMethod::Auto, true>;
#else
    (void)isa;
#endif
    return coverStage<kN, kDepth, MsaaCoverageMethod::Auto>;
}

template <int kN>
std::uint64_t writeRow(Pixel* colourRow, const Pixel* shaded, const std::uint8_t* passed, int lo, int hi) {
    std::uint64_t count = 0;
    for (int x = lo; x < hi; ++x) {
        const unsigned pass = passed[x - lo];
        if (pass == 0) continue;
        ++count;
        const Pixel c = shaded[x];
        Pixel* samples = colourRow + std::size_t(x) * kN;
#if SR_MSAA_SSE2
        if constexpr (kN >= 4) {
            const __m128i colour = _mm_set1_epi32(int(c));
            for (int g = 0; g < kN / 4; ++g) {
                __m128i* at = reinterpret_cast<__m128i*>(samples + 4 * g);
                const __m128i keep = laneMask(pass >> (4 * g) & 0xFu);
                _mm_storeu_si128(at, _mm_or_si128(_mm_and_si128(keep, colour), _mm_andnot_si128(keep, _mm_loadu_si128(at))));
            }
            continue;
        }
#endif
        for (int k = 0; k < kN; ++k)
            if (pass >> k & 1u) samples[k] = c;
    }
    return count;
}

} // namespace

template <int kN>
MsaaStages stagesFor(DepthMode depth, MsaaCoverageMethod method, Isa isa) {
    MsaaStages stages;
    stages.samples = kN;
    stages.write = writeRow<kN>;
    switch (depth) {
    case DepthMode::Off: stages.cover = coverStageFor<kN, DepthMode::Off>(method, isa); break;
    case DepthMode::Test: stages.cover = coverStageFor<kN, DepthMode::Test>(method, isa); break;
    case DepthMode::TestWrite: stages.cover = coverStageFor<kN, DepthMode::TestWrite>(method, isa); break;
    }
    return stages;
}

MsaaStages msaaStages(int samples, DepthMode depth, MsaaCoverageMethod method, Isa isa) {
    assert(validMsaa(samples));
    assert(isaAvailable(isa));
    switch (samples) {
    case 2: return stagesFor<2>(depth, method, isa);
    case 4: return stagesFor<4>(depth, method, isa);
    case 8: return stagesFor<8>(depth, method, isa);
    default: return stagesFor<1>(depth, method, isa);
    }
}

void coverTriangleSamples(const TriangleSetup& t, MsaaBuffer& target, const Scissor& s, DepthMode depth,
                          MsaaScratch& scratch, MsaaCoverageMethod method, Isa isa) {
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= target.width() && s.y1 <= target.height());
    msaaStages(target.samples(), depth, method, isa).cover(t, target, s, scratch);
}

} // namespace sr
