// Scanline fill: exact fixed-point edge walking, top-left spans, depth test and a templated span loop.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>

#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Setup/FixedPoint.hpp"
#include "Raster/Setup/PipelineModes.hpp" // DepthMode, PerspectiveMode
#include "Raster/Setup/Scissor.hpp"
#include "Raster/Setup/TriangleSetup.hpp"

namespace sr {

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
// the edge-function rule in Tests/Fill/TriangleCoverageTests.cpp): row j is covered when its
// centre is in [yTop, yBottom); its span starts at the first centre >= the left edge's x (a
// centre ON a left edge is in) and ends before the first centre >= the right edge's x (a centre
// on a right edge is out). A horizontal top edge is the top row's span itself (in); a
// horizontal bottom edge lies on the excluded yBottom row (out).
// `t` is a TriangleSetup or a SpanCoverage (its coverage fields alone).
template <class Coverage, class Visit>
void forEachSpan(const Coverage& t, const Scissor& s, Visit&& visit) {
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

// The coverage fields of a TriangleSetup on their own (what forEachSpan reads).
struct SpanCoverage {
    FixedEdge longEdge, upperEdge, lowerEdge;
    bool longEdgeOnLeft = true;
    int firstRow = 0, midRow = 0, endRow = 0;
    int minX = 0, maxX = 0; // conservative column bounds (for scissor rejection only)
};

// The coverage of the sample at offset (ox, oy) from every pixel centre (1/256 pixel, |o| < 128):
// pixel (x, y)'s sample is covered exactly when its centre is covered by the triangle moved by
// -(ox, oy), so the edges move and the rows are recomputed; all of it stays exact (integers).
// With (0, 0) it is the setup's own coverage.
inline SpanCoverage sampleCoverage(const TriangleSetup& t, Fixed ox, Fixed oy) {
    SpanCoverage c;
    auto moved = [&](FixedEdge e) {
        e.x0 -= ox;
        e.y0 -= oy;
        return e;
    };
    c.longEdge = moved(t.longEdge);
    c.upperEdge = moved(t.upperEdge);
    c.lowerEdge = moved(t.lowerEdge);
    c.longEdgeOnLeft = t.longEdgeOnLeft;
    const std::int64_t yTop = c.longEdge.y0, yBottom = std::int64_t(c.longEdge.y0) + c.longEdge.dy;
    const std::int64_t yMid = c.lowerEdge.y0;
    c.firstRow = int(firstCentreAtOrAfter(yTop, 1));
    c.midRow = int(firstCentreAtOrAfter(yMid, 1));
    c.endRow = int(firstCentreAtOrAfter(yBottom, 1));
    c.minX = t.minX - 1;
    c.maxX = t.maxX + 1;
    return c;
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

// The span loop: fills the covered pixels of `t` inside the scissor. Per pixel, in order:
// depth test (if enabled), depth write (TestWrite), colour = shader(fragment). kVaryings
// (<= t.varyingCount) varyings are interpolated as kPersp says (PipelineModes.hpp; Affine needs a
// setup made with perspectiveCorrect = false); with kVaryings == 0 no divide runs at all.
// Attributes at a span start are evaluated from the plane equation in double (never accumulated
// from row to row). Along the span, depth and 1/w of pixel k are start + k * ddx evaluated in
// double and rounded once: their relative error stays within a few 2^-24 however long the span
// and however much they shrink along it (a float start + k * gradient would lose |k gradient| *
// 2^-24 to cancellation: 8.6% on an 8000-pixel span ending near a vanishing line). The other
// varyings get start + k * gradient in float (one multiply-add each).
// Shader: any callable `Pixel(const Fragment<kVaryings>&)`, inlined: no virtual call per pixel.
// One span of fillTriangle: pixels [x0, x1) of row y (all covered by `t`), in order.
template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp, class Shader>
void fillSpan(const TriangleSetup& t, FrameBuffer& fb, int y, int x0, int x1, Shader& shader) {
    constexpr int kPlanes = kVaryings > 0 ? kPlaneVarying0 + kVaryings : 1;
    // Plane values at the centre of the span's first pixel (double, once per span).
    const double dx = (x0 + 0.5) - t.originX, dy = (y + 0.5) - t.originY;
    // Sized for z and 1/w at least, so code that names kPlaneInvW compiles in range for every
    // instantiation (only the first kPlanes entries are used).
    constexpr int kArray = kPlanes > kPlaneVarying0 ? kPlanes : kPlaneVarying0;
    float start[kArray] = {};
    double startD[kPlaneVarying0] = {}; // depth and 1/w (when interpolated), unrounded
    for (int k = 0; k < kPlanes; ++k) {
        const double v = t.value[k] + t.ddx[k] * dx + t.ddy[k] * dy;
        start[k] = float(v);
        if (k < kPlaneVarying0) startD[k] = v;
    }

    float gradient[kArray] = {}; // per-pixel gradients in locals: stores to the buffers can't alias them
    for (int k = 0; k < kPlanes; ++k) gradient[k] = t.ddxStep[k];
    Pixel* colour = fb.colorRow(y);
    float* depth = fb.depthRow(y);
    Fragment<kVaryings> f;
    f.y = y;
    float step = 0.0f; // pixel index along the span, exact in float
    for (int x = x0; x < x1; ++x, step += 1.0f) {
        f.z = float(startD[kPlaneZ] + t.ddx[kPlaneZ] * double(step));
        if constexpr (kDepth != DepthMode::Off) {
            if (!(f.z > depth[x])) continue;
            if constexpr (kDepth == DepthMode::TestWrite) depth[x] = f.z;
        }
        f.x = x;
        if constexpr (kVaryings > 0) {
            f.invW = float(startD[kPlaneInvW] + t.ddx[kPlaneInvW] * double(step));
            if constexpr (kPersp == PerspectiveMode::Exact) {
                const float w = 1.0f / f.invW;
                for (int k = 0; k < kVaryings; ++k) {
                    const int p = kPlaneVarying0 + k;
                    f.varyings[std::size_t(k)] = (start[p] + gradient[p] * step) * w;
                }
            } else {
                static_assert(kPersp == PerspectiveMode::Affine);
                for (int k = 0; k < kVaryings; ++k) {
                    const int p = kPlaneVarying0 + k;
                    f.varyings[std::size_t(k)] = start[p] + gradient[p] * step;
                }
            }
        }
        colour[x] = shader(static_cast<const Fragment<kVaryings>&>(f));
    }
}

template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp = PerspectiveMode::Exact, class Shader>
void fillTriangle(const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, Shader&& shader) {
    static_assert(kVaryings >= 0 && kVaryings <= kMaxVaryings, "too many varyings");
    assert(kVaryings <= t.varyingCount);
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= fb.width() && s.y1 <= fb.height());
    forEachSpan(t, s, [&](int y, int x0, int x1) { fillSpan<kDepth, kVaryings, kPersp>(t, fb, y, x0, x1, shader); });
}

template <DepthMode kDepth, int kVaryings, PerspectiveMode kPersp = PerspectiveMode::Exact, class Shader>
void fillTriangle(const TriangleSetup& t, FrameBuffer& fb, Shader&& shader) {
    fillTriangle<kDepth, kVaryings, kPersp>(t, fb, fullScissor(fb), shader);
}

} // namespace sr
