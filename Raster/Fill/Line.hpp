// DDA line drawer: clipped, fixed-point, direction-independent, optional colour and depth test.
#pragma once

#include <cstdint>
#include <optional>

#include "Raster/Fill/ScanlineFill.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Frame/Msaa.hpp"

namespace sr {

// A line endpoint in screen space (pixels, y down; same space as ScreenVertex).
struct LineVertex {
    float x = 0.0f, y = 0.0f;
    float z = 0.0f;          // reversed-Z depth in [0, 1], used by the depth test
    Pixel colour = 0xFFFFFFFFu;
};

struct LineOptions {
    // Interpolate the endpoint colours linearly in screen space; otherwise every pixel gets the
    // colour of the first endpoint passed to drawLine (the "provoking" vertex).
    bool interpolateColour = false;
    // Depth test GREATER-OR-EQUAL against the z-buffer (z interpolated linearly in screen space
    // along the major axis). >= rather than the triangles' strict > so that a wireframe overlay
    // drawn over the same geometry's fill, at the same depth, stays visible.
    bool depthTest = false;
    bool depthWrite = false; // write z of drawn pixels (only meaningful with depthTest)
};

// THE LINE RULE (documented once, relied on by the tests):
//  1. Endpoints are snapped to the 1/256 grid like triangle vertices. The major axis is x when
//     |dx| >= |dy| (after snapping), else y. Below, "column" means a pixel index along the
//     major axis and "row" one along the minor axis.
//  2. The line draws exactly one pixel in every column from the column containing one endpoint
//     to the column containing the other, both included (pixel i contains [i, i + 1)). So
//     steps = columns - 1 = floor(x_max) - floor(x_min), the DDA's max(|dx|, |dy|) up to the
//     sub-pixel parts. A zero-length line draws the one pixel containing its point.
//  3. In column i the pixel drawn is the row containing the exact line point at
//     x = clamp(i + 0.5, x_min, x_max): the column centre, or the endpoint itself in an end
//     column whose centre the segment does not reach. Consecutive evaluation points are at most
//     one pixel apart, so the line is 8-connected; every endpoint's column is drawn.
//  4. The rule depends only on the unordered pair {A, B} and is evaluated in exact integer
//     arithmetic (an error-term DDA), so A->B and B->A draw the same pixels. The endpoints are
//     put in a canonical order before anything else (clipping included) to keep it so.
//  5. Clipping: the segment is clipped (Liang-Barsky) to the scissor grown by one pixel before
//     stepping: fully outside draws nothing, and at most one scissor-width (or height) of
//     columns is ever visited. When both endpoints are inside the guard band the clip (in
//     double) only narrows the columns visited and the pixels are exactly those of rule 2-3
//     restricted to the scissor. When an endpoint is beyond the guard band (e.g. +-1e9, or up
//     to +-3.4e38), the segment is replaced by its visible part: both ends of the exact clipped
//     segment (a + t (b - a) for the exact t where it enters and leaves the grown scissor, an
//     end inside it staying itself) are snapped as in rule 1, floor(256 v + 1/2) of their exact
//     coordinates, and the pixels are those of rule 2-3 for that snapped segment, restricted to
//     the scissor. Clipping and snapping are exact integer arithmetic on the floats' binary
//     values (LineClip.hpp), so the result is the infinite-precision one for every finite input.
//  6. Any NaN or infinite coordinate: nothing is drawn.

// Setup record of a line: canonical snapped endpoints and the prestepped DDA (one per line).
struct LineSetup {
    bool yMajor = false;      // columns run along y (rows along x)
    bool reversed = false;    // canonical order is B -> A
    std::int64_t majorA = 0, minorA = 0, majorB = 0, minorB = 0; // snapped, majorA <= majorB
    std::int64_t firstColumn = 0, lastColumn = 0; // columns to visit (already scissored)
    std::int64_t columnA = 0, columnB = 0;        // end columns of the whole line
    // Attributes at the canonical endpoints (after clipping): depth and colour channels.
    float zA = 0.0f, zB = 0.0f;
    float colourA[3] = {}, colourB[3] = {};
    Pixel flatColour = 0;
};

// Builds the line record, or nullopt when nothing can be drawn (non-finite input, fully outside
// the scissor).
std::optional<LineSetup> setupLine(const LineVertex& a, const LineVertex& b, const Scissor& s);

// Calls plot(x, y, t) for every pixel of the line inside the scissor, where t in [0, 1] is the
// canonical-order parameter of the evaluation point (0 at majorA, 1 at majorB).
template <class Plot>
void forEachLinePixel(const LineSetup& l, const Scissor& s, Plot&& plot);

// Draws the line a-b into fb (colour, optional depth test/write) following the rule above.
void drawLine(FrameBuffer& fb, const LineVertex& a, const LineVertex& b,
              const LineOptions& options = {});

// `width` (>= 1) parallel lines a-b, offset along the minor axis by whole or half pixels (exact
// on the 1/256 snapping grid) and centred on a-b: a line `width` pixels wide, for a target
// supersampled width x width that is resolved back to one pixel. Into a multisampled target
// (`msaa` not null) one line, whose pixels cover all their samples.
void drawWideLine(FrameBuffer& fb, MsaaBuffer* msaa, const LineVertex& a, const LineVertex& b,
                  const LineOptions& options, int width);

// The same line into a multisampled target: the pixels of the rule above, each covering all of
// its samples (depth tested per sample, with the line's depth at the pixel), so that after the
// resolve the line looks as it does without multisampling.
void drawLine(MsaaBuffer& target, const LineVertex& a, const LineVertex& b, const LineOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Row of column c at the fixed-point major coordinate m (clamped to the segment): the exact
// floor((minorA + (m - majorA) dMinor / dMajor) / 256).
inline std::int64_t lineRowAt(const LineSetup& l, std::int64_t m) {
    const std::int64_t dM = l.majorB - l.majorA, dN = l.minorB - l.minorA;
    if (dM == 0) return floorDiv(l.minorA, kSubPixelScale);
    return floorDiv(l.minorA * dM + (m - l.majorA) * dN, std::int64_t(kSubPixelScale) * dM);
}

template <class Plot>
void forEachLinePixel(const LineSetup& l, const Scissor& s, Plot&& plot) {
    const std::int64_t dM = l.majorB - l.majorA, dN = l.minorB - l.minorA;
    const std::int64_t minorLo = l.yMajor ? s.x0 : s.y0, minorHi = l.yMajor ? s.x1 : s.y1;
    const float tScale = dM > 0 ? float(kSubPixelScale) / float(dM) : 0.0f;
    const float tOffset = dM > 0 ? float(kSubPixelScale / 2 - l.majorA) / float(dM) : 0.0f;

    // Error-term DDA over the column centres (Bresenham's idea, exact for any slope |dN| <= dM):
    // row = floor(N / D) with N = minorA dM + (centre - majorA) dN, D = 256 dM, kept as
    // N = row D + e, 0 <= e < D; one column adds 256 dN = q D + r to N.
    const std::int64_t D = std::int64_t(kSubPixelScale) * (dM > 0 ? dM : 1);
    const std::int64_t S = std::int64_t(kSubPixelScale) * dN;
    const std::int64_t q = floorDiv(S, D), r = S - q * D;
    std::int64_t row = 0, e = 0;
    {
        const std::int64_t n = l.minorA * dM + (pixelCentreFixed(l.firstColumn) - l.majorA) * dN;
        row = floorDiv(n, D);
        e = n - row * D;
    }
    for (std::int64_t c = l.firstColumn; c <= l.lastColumn; ++c) {
        // End columns evaluate at the clamped point (rule 3), middle ones at the centre.
        std::int64_t r0 = row;
        float t = float(c) * tScale + tOffset;
        if (c == l.columnA || c == l.columnB) {
            const std::int64_t m = std::clamp(pixelCentreFixed(c), l.majorA, l.majorB);
            r0 = lineRowAt(l, m);
            t = dM > 0 ? float(m - l.majorA) / float(dM) : 0.0f;
        }
        if (r0 >= minorLo && r0 < minorHi) {
            if (l.yMajor) plot(int(r0), int(c), t);
            else plot(int(c), int(r0), t);
        }
        row += q;
        e += r;
        if (e >= D) {
            ++row;
            e -= D;
        }
    }
}

} // namespace sr
