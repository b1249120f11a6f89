// Homogeneous-space triangle clipper: trivial accept/reject, then Sutherland-Hodgman per plane.
#pragma once

#include <array>
#include <cstdint>

#include "Raster/Geometry/Vertex.hpp"

namespace sr {

// Per-draw clipping parameters.
struct ClipParams {
    int viewportWidth = 0;   // pixels; a 0 (or negative) dimension rejects every triangle
    int viewportHeight = 0;
    bool clipFar = false;    // clip against z >= 0 (a projection with a finite far plane)
    int varyingCount = 0;    // varyings [0, varyingCount) are interpolated; the rest stay 0
};

// Counters for statistics (how often each path was taken). Plain numbers, reset by the owner.
struct ClipStats {
    std::uint64_t trivialAccepted = 0; // no clipping needed: vertices copied through
    std::uint64_t trivialRejected = 0; // all three vertices outside one plane (or empty viewport)
    std::uint64_t clipped = 0;         // went through Sutherland-Hodgman
    std::uint64_t clippedAway = 0;     // ... and nothing was left (subset of `clipped`)
    std::uint64_t nonFinite = 0;       // dropped: a position component was NaN or Inf
};

// The clip planes, in the fixed order the clipper applies them. Each plane is a half-space
// d(v) >= 0 of homogeneous clip space (Blinn & Newell, "Clipping using homogeneous
// coordinates", SIGGRAPH 1978):
//   Near    d = w - z                 (reversed-Z: the near plane is z = w, z_ndc = 1)
//   MinW    d = w - kClipMinW         (w > 0 strictly: nothing with w <= 0 reaches the divide)
//   Far     d = z                     (only with ClipParams::clipFar)
//   Left    d = x + gx * w            (guard band, screen x >= -kClipGuardBand pixels)
//   Right   d = gx * w - x            (guard band, screen x <= +kClipGuardBand pixels)
//   Bottom  d = y + gy * w            (guard band, screen y <= +kClipGuardBand pixels)
//   Top     d = gy * w - y            (guard band, screen y >= -kClipGuardBand pixels)
// with gx = 2 * kClipGuardBand / width - 1 and gy likewise: the symmetric NDC band whose
// screen image [W - G, G] lies inside [-G, G].
enum ClipPlane : int { kPlaneNear, kPlaneMinW, kPlaneFar, kPlaneLeft, kPlaneRight, kPlaneBottom, kPlaneTop,
                       kClipPlaneCount };

// Smallest w a clipped vertex keeps (the MinW plane). Any real perspective projection has
// w >= near on the visible side, so this plane only bites for hand-made clip coordinates.
inline constexpr float kClipMinW = 1e-12f;

// Guard band the clipper keeps screen positions inside, in pixels: the rasterizer's limit
// (RasterLimits.hpp, 16384) minus 256 pixels, so float rounding in the divide and viewport (a
// few ulps, far below one pixel at this magnitude) can never push a vertex past the limit.
inline constexpr float kClipGuardBand = 16128.0f;

// Worst case: 3 vertices + 1 per plane (each plane cut adds at most one vertex to a convex
// polygon) -> 10 vertices -> 8 fan triangles.
inline constexpr int kMaxClipVertices = 3 + kClipPlaneCount;
inline constexpr int kMaxClipTriangles = kMaxClipVertices - 2;

// A convex clipped polygon, vertices in the input's winding order.
struct ClippedPolygon {
    std::array<ClipVertex, kMaxClipVertices> vertices;
    int count = 0;

    // Fan triangulation: triangle i (0 <= i < triangleCount()) is vertices
    // {0, i + 1, i + 2}; it keeps the winding of the polygon (and so of the input triangle).
    int triangleCount() const { return count >= 3 ? count - 2 : 0; }
    std::array<int, 3> triangle(int i) const { return {0, i + 1, i + 2}; }
};

// What a triangle needs (decided from its three vertices only).
enum class ClipClass {
    Reject,  // non-finite position, empty viewport, or all vertices outside one plane
    Accept,  // every vertex inside every clip plane: draw as is, no clipping
    Clip,    // straddles a clip plane: run clip()
};

// Per-vertex clip code (Clipper::vertexCode): bits 0..kClipPlaneCount-1 are the clip planes
// (ClipPlane) the position is outside of; the next four the view-volume sides x, y = +-w
// (trivial rejection only); kCodeNonFinite marks a NaN/Inf component. A triangle is then
// classified from the AND / OR of its three cached codes (Cohen-Sutherland outcodes, as in
// Foley et al., "Computer Graphics: Principles and Practice", 3.12.3), instead of recomputing
// three outcodes per triangle: each vertex is shared by ~6 triangles in a closed mesh.
inline constexpr unsigned kCodeClipMask = (1u << kClipPlaneCount) - 1u;
inline constexpr unsigned kCodeViewMask = 0xFu << kClipPlaneCount;
inline constexpr unsigned kCodeNonFinite = 1u << (kClipPlaneCount + 4);

// Clips triangles for one viewport. Construct once per draw (it precomputes the guard-band
// factors); clip() updates the statistics counters.
//
// Guarantees for every vertex clip() outputs: finite position, w >= kClipMinW (so w > 0),
// z <= w (in front of, or exactly on, the near plane; z >= 0 too with clipFar), and a screen
// position (toScreen) inside [-kClipGuardBand, kClipGuardBand]^2 up to float rounding.
// An edge shared by two triangles is clipped to bit-identical vertices in both: each cut is
// computed from the inside vertex towards the outside one, whichever triangle it belongs to.
class Clipper {
public:
    explicit Clipper(const ClipParams& params);

    // Trivial accept / reject test (cheap; no clipping). The reference for classifyCodes.
    ClipClass classify(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c) const;

    // The clip code of one position (see kCodeClipMask): computed once per vertex.
    unsigned vertexCode(const Vec4& p) const {
        if (!isFinite(p)) return kCodeNonFinite;
        // The same double distances as distance() (exact signs for float inputs).
        const double x = p.x, y = p.y, z = p.z, w = p.w;
        unsigned code = 0;
        code |= unsigned(w - z < 0.0) << kPlaneNear;
        code |= unsigned(w - double(kClipMinW) < 0.0) << kPlaneMinW;
        code |= unsigned(params_.clipFar && z < 0.0) << kPlaneFar;
        code |= unsigned(x + gx_ * w < 0.0) << kPlaneLeft;
        code |= unsigned(gx_ * w - x < 0.0) << kPlaneRight;
        code |= unsigned(y + gy_ * w < 0.0) << kPlaneBottom;
        code |= unsigned(gy_ * w - y < 0.0) << kPlaneTop;
        code |= unsigned(x < -w) << kClipPlaneCount;
        code |= unsigned(x > w) << (kClipPlaneCount + 1);
        code |= unsigned(y < -w) << (kClipPlaneCount + 2);
        code |= unsigned(y > w) << (kClipPlaneCount + 3);
        return code;
    }
    // classify() from the three vertices' cached codes; equal to classify() on the vertices.
    ClipClass classifyCodes(unsigned c0, unsigned c1, unsigned c2) const {
        constexpr unsigned kRejectMask =
            (1u << kPlaneNear) | (1u << kPlaneMinW) | (1u << kPlaneFar) | kCodeViewMask;
        if ((c0 | c1 | c2) & kCodeNonFinite) return ClipClass::Reject;
        if (params_.viewportWidth <= 0 || params_.viewportHeight <= 0) return ClipClass::Reject;
        if (c0 & c1 & c2 & kRejectMask) return ClipClass::Reject;
        if (((c0 | c1 | c2) & kCodeClipMask) == 0) return ClipClass::Accept;
        return ClipClass::Clip;
    }

    // Clips triangle (a, b, c) to the clip volume. Returns the number of polygon vertices
    // written to `out` (0 = nothing left to draw, else 3..kMaxClipVertices); out.count is set
    // to the same number. A trivially accepted triangle is copied through unchanged.
    int clip(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, ClippedPolygon& out);

    const ClipParams& params() const { return params_; }
    const ClipStats& stats() const { return stats_; }
    void resetStats() { stats_ = {}; }

    // Guard-band factors (NDC half-extent of the band) for this viewport.
    double guardX() const { return gx_; }
    double guardY() const { return gy_; }

private:
    // Signed distance of a position to one plane (>= 0: inside). Double, so the sign is exact
    // for every float input (products of floats by gx/gy are rounded once, consistently).
    double distance(int plane, const Vec4& p) const;
    // Bit mask of the clip planes the position is outside of.
    unsigned outcode(const Vec4& p) const;
    // Bit mask of the view-volume planes (near, MinW, far if enabled, x/y = +-w) it is outside.
    unsigned viewOutcode(const Vec4& p) const;
    // One Sutherland-Hodgman pass of `in` against `plane` into `out`; returns out's count, or
    // -1 without writing `out` when no vertex is outside (the pass would be the identity).
    int clipAgainst(int plane, const ClipVertex* in, int inCount, ClipVertex* out) const;
    // The point where edge (inside, outside) crosses `plane`, position and varyings.
    ClipVertex intersect(int plane, const ClipVertex& inside, double dInside, const ClipVertex& outside,
                         double dOutside) const;

    ClipParams params_;
    double gx_ = 1.0;
    double gy_ = 1.0;
    ClipStats stats_;
};

// Convenience for one-off calls (tests, tools): builds a Clipper, clips, adds to *stats.
int clipTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, const ClipParams& params,
                 ClippedPolygon& out, ClipStats* stats = nullptr);

} // namespace sr
