// Homogeneous-space triangle clipper (Blinn & Newell 1978 planes, Sutherland-Hodgman 1974 passes).
#include "Raster/Geometry/Clipper.hpp"

#include <cassert>
#include <cmath>
#include <utility>

#include "Raster/Setup/RasterLimits.hpp"

namespace sr {

static_assert(kClipGuardBand < kGuardBand, "the clipper's band must sit inside the rasterizer's");

namespace {

bool finitePosition(const ClipVertex& v) { return isFinite(v.position); }

// View-volume planes used only for trivial rejection: the visible screen x, y = +-w.
enum ViewBit : unsigned {
    kViewLeft = 1u << kClipPlaneCount,
    kViewRight = 1u << (kClipPlaneCount + 1),
    kViewBottom = 1u << (kClipPlaneCount + 2),
    kViewTop = 1u << (kClipPlaneCount + 3),
};

} // namespace

Clipper::Clipper(const ClipParams& params) : params_(params) {
    assert(params.varyingCount >= 0 && params.varyingCount <= kMaxVaryings);
    // Symmetric NDC guard band: x_ndc in [-g, g] maps to screen x in [W - G, G], inside [-G, G].
    if (params.viewportWidth > 0)
        gx_ = 2.0 * double(kClipGuardBand) / double(params.viewportWidth) - 1.0;
    if (params.viewportHeight > 0)
        gy_ = 2.0 * double(kClipGuardBand) / double(params.viewportHeight) - 1.0;
}

double Clipper::distance(int plane, const Vec4& p) const {
    const double x = p.x, y = p.y, z = p.z, w = p.w;
    switch (plane) {
    case kPlaneNear: return w - z;
    case kPlaneMinW: return w - double(kClipMinW);
    case kPlaneFar: return z;
    case kPlaneLeft: return x + gx_ * w;
    case kPlaneRight: return gx_ * w - x;
    case kPlaneBottom: return y + gy_ * w;
    case kPlaneTop: return gy_ * w - y;
    default: assert(false && "bad clip plane"); return 0.0;
    }
}

unsigned Clipper::outcode(const Vec4& p) const {
    unsigned code = 0;
    for (int plane = 0; plane < kClipPlaneCount; ++plane) {
        if (plane == kPlaneFar && !params_.clipFar)
            continue;
        if (distance(plane, p) < 0.0)
            code |= 1u << plane;
    }
    return code;
}

unsigned Clipper::viewOutcode(const Vec4& p) const {
    const double x = p.x, y = p.y, w = p.w;
    unsigned code = outcode(p) & ((1u << kPlaneNear) | (1u << kPlaneMinW) | (1u << kPlaneFar));
    if (x < -w) code |= kViewLeft;
    if (x > w) code |= kViewRight;
    if (y < -w) code |= kViewBottom;
    if (y > w) code |= kViewTop;
    return code;
}

ClipClass Clipper::classify(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c) const {
    if (!finitePosition(a) || !finitePosition(b) || !finitePosition(c))
        return ClipClass::Reject;
    if (params_.viewportWidth <= 0 || params_.viewportHeight <= 0)
        return ClipClass::Reject;
    // Trivial reject: all three outside the same view-volume plane. Each plane is a half-space
    // of 4D clip space, so the whole triangle is outside it too (whatever the signs of w).
    if (viewOutcode(a.position) & viewOutcode(b.position) & viewOutcode(c.position))
        return ClipClass::Reject;
    // Trivial accept: every vertex inside every clip plane (near, w > 0, far if enabled,
    // guard band). The view-volume sides are left to the rasterizer's scissor.
    if ((outcode(a.position) | outcode(b.position) | outcode(c.position)) == 0)
        return ClipClass::Accept;
    return ClipClass::Clip;
}

ClipVertex Clipper::intersect(int plane, const ClipVertex& inside, double dInside, const ClipVertex& outside,
                              double dOutside) const {
    // Always parameterised from the inside vertex towards the outside one: the edge shared by
    // two triangles is the same (inside, outside) pair in both, so the cut is bit-identical no
    // matter which triangle is being clipped or in which order it lists the edge.
    assert(dInside > 0.0 && dOutside < 0.0);
    const double t = dInside / (dInside - dOutside); // in (0, 1)
    ClipVertex v;
    for (int i = 0; i < 4; ++i) {
        const double a = inside.position[i];
        const double b = outside.position[i];
        v.position[i] = float(a + t * (b - a));
    }
    // Varyings are linear in clip space: the same parameter interpolates them.
    for (int i = 0; i < params_.varyingCount; ++i) {
        const double a = inside.varyings[std::size_t(i)];
        const double b = outside.varyings[std::size_t(i)];
        v.varyings[std::size_t(i)] = float(a + t * (b - a));
    }
    // Put the new vertex exactly on the plane (the rounded lerp may miss it by an ulp).
    Vec4& p = v.position;
    switch (plane) {
    case kPlaneNear: p.z = p.w; break;
    case kPlaneMinW: p.w = kClipMinW; break;
    case kPlaneFar: p.z = 0.0f; break;
    case kPlaneLeft: p.x = float(-gx_ * double(p.w)); break;
    case kPlaneRight: p.x = float(gx_ * double(p.w)); break;
    case kPlaneBottom: p.y = float(-gy_ * double(p.w)); break;
    case kPlaneTop: p.y = float(gy_ * double(p.w)); break;
    default: assert(false && "bad clip plane"); break;
    }
    // Keep the planes already applied satisfied despite rounding: both ends of the edge are
    // inside them, so these clamps move the vertex by at most an ulp or so.
    if (plane > kPlaneMinW && p.w < kClipMinW)
        p.w = kClipMinW;
    if (plane > kPlaneNear && p.z > p.w)
        p.z = p.w;
    if (plane > kPlaneFar && params_.clipFar && p.z < 0.0f)
        p.z = 0.0f;
    return v;
}

int Clipper::clipAgainst(int plane, const ClipVertex* in, int inCount, ClipVertex* out) const {
    // Sutherland & Hodgman, "Reentrant polygon clipping" (CACM 1974): walk the edges (S, E),
    // emitting E when inside and the crossing point when the edge changes side. A vertex
    // exactly on the plane (d == 0) counts as inside and no crossing is emitted next to it, so
    // the output has no duplicated vertices.
    std::array<double, kMaxClipVertices> d;
    bool anyOutside = false;
    for (int i = 0; i < inCount; ++i) {
        d[std::size_t(i)] = distance(plane, in[i].position);
        anyOutside |= d[std::size_t(i)] < 0.0;
    }
    if (!anyOutside)
        return -1; // the pass would be the identity: the caller keeps `in`
    int n = 0;
    for (int i = 0; i < inCount; ++i) {
        const int s = (i + inCount - 1) % inCount;
        const double ds = d[std::size_t(s)], de = d[std::size_t(i)];
        if (de >= 0.0) {
            if (ds < 0.0 && de > 0.0)
                out[n++] = intersect(plane, in[i], de, in[s], ds);
            out[n++] = in[i];
        } else if (ds > 0.0) {
            out[n++] = intersect(plane, in[s], ds, in[i], de);
        }
        assert(n <= kMaxClipVertices);
    }
    return n;
}

int Clipper::clip(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, ClippedPolygon& out) {
    out.count = 0;
    if (!finitePosition(a) || !finitePosition(b) || !finitePosition(c)) {
        ++stats_.nonFinite;
        return 0;
    }
    switch (classify(a, b, c)) {
    case ClipClass::Reject:
        ++stats_.trivialRejected;
        return 0;
    case ClipClass::Accept:
        ++stats_.trivialAccepted;
        out.vertices[0] = a;
        out.vertices[1] = b;
        out.vertices[2] = c;
        out.count = 3;
        return 3;
    case ClipClass::Clip: break;
    }

    ++stats_.clipped;
    // Ping-pong between the output polygon and a scratch buffer, one plane at a time in the
    // fixed order of ClipPlane; a plane no vertex is outside of costs one distance per vertex.
    std::array<ClipVertex, kMaxClipVertices> scratch;
    ClipVertex* src = scratch.data();
    ClipVertex* dst = out.vertices.data();
    src[0] = a;
    src[1] = b;
    src[2] = c;
    int n = 3;
    for (int plane = 0; plane < kClipPlaneCount && n >= 3; ++plane) {
        if (plane == kPlaneFar && !params_.clipFar)
            continue;
        const int m = clipAgainst(plane, src, n, dst);
        if (m < 0)
            continue; // no vertex outside this plane
        n = m;
        std::swap(src, dst);
    }
    if (n < 3) {
        ++stats_.clippedAway;
        return 0;
    }
    if (src != out.vertices.data())
        for (int i = 0; i < n; ++i)
            out.vertices[std::size_t(i)] = src[i];
    out.count = n;
    return n;
}

int clipTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, const ClipParams& params,
                 ClippedPolygon& out, ClipStats* stats) {
    Clipper clipper(params);
    const int n = clipper.clip(a, b, c, out);
    if (stats) {
        const ClipStats& s = clipper.stats();
        stats->trivialAccepted += s.trivialAccepted;
        stats->trivialRejected += s.trivialRejected;
        stats->clipped += s.clipped;
        stats->clippedAway += s.clippedAway;
        stats->nonFinite += s.nonFinite;
    }
    return n;
}

} // namespace sr
