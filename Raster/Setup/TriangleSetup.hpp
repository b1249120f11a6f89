// Triangle setup: snaps a screen triangle to fixed point and builds the one record the fill reads.
#pragma once

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>

#include "Raster/Geometry/Cull.hpp"
#include "Raster/Geometry/Vertex.hpp"
#include "Raster/Setup/FixedPoint.hpp"
#include "Raster/Setup/PipelineModes.hpp" // PerspectiveMode

namespace sr {

// One triangle edge in 1/256-pixel fixed point, always walked downwards (dy >= 0).
// The x of the edge at a fixed-point height Y is x0 + (Y - y0) * dx / dy, kept as an exact
// rational by the edge walker (ScanlineFill.hpp); nothing is rounded at setup.
struct FixedEdge {
    Fixed x0 = 0, y0 = 0; // start (upper vertex)
    Fixed dx = 0, dy = 0; // end - start, dy >= 0 (|dx|, dy < 2^24)
};

// Attribute planes. Slot 0 is depth z (interpolated linearly in screen space, as D3D does:
// z/w is affine in screen space), slot 1 is 1/w, slots 2.. are varying_i / w. The fill
// recovers perspective-correct varyings as (v/w) / (1/w) per pixel (Hecker, "Perspective
// Texture Mapping, Part 1", Game Developer, April 1995: u/z and 1/z are linear in screen space).
inline constexpr int kPlaneZ = 0;
inline constexpr int kPlaneInvW = 1;
inline constexpr int kPlaneVarying0 = 2;
inline constexpr int kMaxPlanes = kPlaneVarying0 + kMaxVaryings;

// Texture coordinates rebased per triangle: the first `count` varyings (a uv pair) are shifted
// by a whole number of periods before v/w is formed, so a triangle far from uv 0 interpolates
// as finely as one near it (float u at 16,384 keeps only 9 bits of fraction), and a mesh whose
// uvs are offset by whole periods renders bit-identically. The period is the texture's: 1 for
// Repeat, 2 for Mirror (an odd shift would mirror the image); 0 (Clamp, untextured) rebases
// nothing. The sampled colour is unchanged: the wrap is periodic.
struct VaryingRebase {
    int count = 0;
    double period = 0.0;
};

// The shift for one varying of a triangle: the largest multiple of `period` at or below the
// smallest of a0, a1, a2 (0 when period is 0, or a value or a shifted value is not finite).
inline double rebaseOffset(double a0, double a1, double a2, double period) {
    if (!(period > 0.0)) return 0.0;
    const double lowest = std::min(std::min(a0, a1), a2);
    const double offset = period * std::floor(lowest / period);
    return std::isfinite(offset) && std::isfinite(a0 - offset) && std::isfinite(a1 - offset) &&
                   std::isfinite(a2 - offset)
               ? offset
               : 0.0;
}

// The per-triangle record: everything the span loop needs, computed once.
struct TriangleSetup {
    // --- Coverage (exact fixed point) ------------------------------------------------------
    // Vertices sorted by y (top, mid, bottom). The long edge runs top -> bottom; the short
    // edges top -> mid (upper part) and mid -> bottom (lower part).
    FixedEdge longEdge;
    FixedEdge upperEdge;
    FixedEdge lowerEdge;
    bool longEdgeOnLeft = true; // true when the middle vertex lies right of the long edge
    // Pixel rows whose centre y is in [yTop, yBottom): [firstRow, endRow). Rows from midRow on
    // (centre y >= yMid) use lowerEdge, earlier rows upperEdge.
    int firstRow = 0, midRow = 0, endRow = 0;
    // Pixel-column bounds of the snapped triangle (inclusive), for scissor rejection.
    int minX = 0, maxX = 0;
    // Twice the signed area in (1/256 px)^2 for the vertices in INPUT order: > 0 is clockwise
    // on screen (y down), < 0 counter-clockwise (Math/Conventions.hpp). Never 0.
    std::int64_t doubleArea = 0;

    // --- Attribute planes a(x, y) = value + ddx * (x - originX) + ddy * (y - originY) -----
    // Origin = the first input vertex, snapped (pixels). Gradients come from the snapped
    // positions. The plane is kept in double: the fill evaluates it once per span start, where
    // float would lose ~|ddx| * distance * 2^-24 to cancellation on thin triangles (large
    // gradients far from the origin); along a span it steps with the float copy ddxStep.
    double originX = 0.0, originY = 0.0;
    int varyingCount = 0;
    double value[kMaxPlanes] = {};
    double ddx[kMaxPlanes] = {};
    double ddy[kMaxPlanes] = {};
    float ddxStep[kMaxPlanes] = {};

    // Plane value at a screen point (pixels); for span starts, tests and one-off evaluations.
    double planeAt(int plane, double x, double y) const {
        return value[plane] + ddx[plane] * (x - originX) + ddy[plane] * (y - originY);
    }
};

// Snaps v0, v1, v2 (any winding) to the 1/256 grid and builds the record, or returns nullopt
// for a triangle that can cover nothing: zero area after snapping (collinear or coincident
// vertices), or a triangle that misses every pixel-centre row. Preconditions (asserted, and
// also rejected in release builds): finite coordinates within the guard band
// (|x|, |y| <= kGuardBand) and 0 <= varyingCount <= kMaxVaryings. Only the first
// varyingCount varyings are read. With perspectiveCorrect = false (PerspectiveMode::Affine) the
// varying planes hold v instead of v/w. `rebase` shifts the uv varyings (VaryingRebase).
std::optional<TriangleSetup> setupTriangle(const ScreenVertex& v0, const ScreenVertex& v1,
                                           const ScreenVertex& v2, int varyingCount,
                                           bool perspectiveCorrect = true, const VaryingRebase& rebase = {});

// What setupTriangleCulled decided.
enum class SetupOutcome {
    Ready,  // `out` holds the record: fill it
    Culled, // isCulled(cull, v0, v1, v2): the culled winding, or zero area on the snapped grid
    Empty,  // not culled, but covers no pixel-centre row (setupTriangle would give nullopt)
};

// Cull and setup in one pass: snaps once, decides the cull from the exact snapped doubleArea
// (the same grid and sign as isCulled, which stays the reference), and only then builds the
// edges and planes into `out` (a record the caller reuses: no copy, no optional). Returns
// Culled exactly when isCulled(cull, ...) is true, else what setupTriangle would give. Vertices
// outside the guard band (the clipper never outputs them) are Culled or Empty as isCulled says.
// keepRowless (multisampling: samples lie off the pixel centres) builds the whole record, and
// returns Ready, for a triangle that misses every pixel-centre row too (firstRow >= endRow).
SetupOutcome setupTriangleCulled(TriangleSetup& out, const ScreenVertex& v0, const ScreenVertex& v1,
                                 const ScreenVertex& v2, CullMode cull, int varyingCount,
                                 bool perspectiveCorrect = true, const VaryingRebase& rebase = {},
                                 bool keepRowless = false);

// A screen vertex's position snapped to the sub-pixel grid (snapToFixed), once per vertex for
// the triangles that share it (the vertex stage, for binning); x == kUnsnapped when the
// vertex lies outside the guard band (or is NaN), where a triangle's setup decides from the
// floats (isCulled).
struct SnappedVertex {
    Fixed x = 0, y = 0;
};
inline constexpr Fixed kUnsnapped = INT32_MIN;
// Whether setup can snap v: finite and within the guard band (false for NaN: every comparison
// with NaN is false).
inline bool inGuardBand(const ScreenVertex& v) { return std::fabs(v.x) <= kGuardBand && std::fabs(v.y) <= kGuardBand; }
inline SnappedVertex snapVertex(const ScreenVertex& v) {
    if (!inGuardBand(v)) return {kUnsnapped, 0};
    return {snapToFixed(v.x), snapToFixed(v.y)};
}

// The decision setupTriangleCulled makes before it builds anything (the same validity and cull),
// from the vertices' snapped positions (snapVertex, none kUnsnapped), with the snapped y extent
// [minY, maxY] (fixed point) of a Ready triangle: pixel-centre rows [firstCentreAtOrAfter(minY, 1),
// firstCentreAtOrAfter(maxY, 1)). Empty, as there, when no centre row is covered and
// !keepRowless. The pipeline bins triangles to its lanes with it, without reading the screen
// vertices. (The extent comes back through references: returned in a struct with the outcome,
// GCC built it on the stack with narrow stores and read it back with one wide load, which cannot
// be forwarded from them: a stall on every triangle binned.)
SetupOutcome screenSnapped(SnappedVertex p0, SnappedVertex p1, SnappedVertex p2, CullMode cull, bool keepRowless,
                           Fixed& minY, Fixed& maxY);

} // namespace sr
