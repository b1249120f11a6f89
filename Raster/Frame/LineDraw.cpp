// drawWorldLines: clip-space transform, homogeneous segment clipping, the DDA line drawer.
#include "Raster/Frame/LineDraw.hpp"

#include <algorithm>
#include <cmath>

#include "Raster/Fill/Line.hpp"
#include "Raster/Geometry/Clipper.hpp" // kClipMinW
#include "Raster/Geometry/Viewport.hpp"

namespace sr {
namespace {

// The clip-space end of a segment, and its signed distances to the planes it is clipped against
// (inside >= 0): near (w - z), MinW (w - kClipMinW), far (z; only with a far plane).
struct ClipEnd {
    double x, y, z, w;
};

ClipEnd toClip(const FrameView& view, Vec3 p) {
    const Vec4 c = view.viewProj * Vec4(p, 1.0f);
    return {c.x, c.y, c.z, c.w};
}

bool finiteEnd(const ClipEnd& e) {
    return std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z) && std::isfinite(e.w);
}

// Liang-Barsky on the plane distances: the parameter range [t0, t1] of a + t (b - a) inside
// every plane, or false when none is.
bool clipSegment(const ClipEnd& a, const ClipEnd& b, bool clipFar, double& t0, double& t1) {
    t0 = 0.0;
    t1 = 1.0;
    const double minW = double(kClipMinW);
    const double da[3] = {a.w - a.z, a.w - minW, a.z}, db[3] = {b.w - b.z, b.w - minW, b.z};
    for (int p = 0; p < (clipFar ? 3 : 2); ++p) {
        if (da[p] < 0.0 && db[p] < 0.0) return false;
        if (da[p] < 0.0) t0 = std::max(t0, da[p] / (da[p] - db[p]));
        else if (db[p] < 0.0) t1 = std::min(t1, da[p] / (da[p] - db[p]));
    }
    return t0 <= t1;
}

// The point a + t (b - a) (a and b exactly at t = 0 and 1) on the screen.
ScreenVertex toScreenAt(const ClipEnd& a, const ClipEnd& b, double t, int width, int height) {
    const auto at = [t](double p, double q) { return t == 1.0 ? float(q) : float(p + (q - p) * t); };
    ClipVertex v;
    v.position = Vec4(at(a.x, b.x), at(a.y, b.y), at(a.z, b.z), at(a.w, b.w));
    return toScreen(v, width, height, 0);
}

} // namespace

void drawWorldLines(RenderContext& ctx, const FrameView& view, const std::vector<Vec3>& positions,
                    const std::vector<std::uint32_t>& indices, bool points, Pixel colour, int width) {
    FrameBuffer& fb = ctx.target();
    MsaaBuffer* msaa = ctx.multisampleTarget();
    const int w = fb.width(), h = fb.height();
    if (w <= 0 || h <= 0) return;
    LineOptions options;
    options.depthTest = true;
    options.depthWrite = true;
    width = std::max(width, 1);
    const auto draw = [&](const ScreenVertex& a, const ScreenVertex& b) {
        const LineVertex la{a.x, a.y, a.z, colour}, lb{b.x, b.y, b.z, colour};
        if (!points || msaa) {
            drawWideLine(fb, msaa, la, lb, options, width); // as the wireframe's edges (Line.hpp)
            return;
        }
        // A point: the k x k block (k = width) of the output pixel that contains it.
        if (!(std::fabs(a.x) < 1e9f && std::fabs(a.y) < 1e9f)) return; // far outside the target
        const float x0 = std::floor(a.x / float(width)) * float(width), y0 = std::floor(a.y / float(width)) * float(width);
        for (int i = 0; i < width; ++i)
            for (int j = 0; j < width; ++j) {
                const float x = x0 + float(i) + 0.5f, y = y0 + float(j) + 0.5f;
                drawLine(fb, LineVertex{x, y, a.z, colour}, LineVertex{x, y, a.z, colour}, options);
            }
    };
    const std::size_t step = points ? 1 : 2;
    for (std::size_t i = 0; i + step - 1 < indices.size(); i += step) {
        if (indices[i] >= positions.size() || indices[i + step - 1] >= positions.size()) continue;
        const ClipEnd a = toClip(view, positions[indices[i]]);
        const ClipEnd b = points ? a : toClip(view, positions[indices[i + 1]]);
        if (!finiteEnd(a) || !finiteEnd(b)) continue;
        double t0 = 0.0, t1 = 1.0;
        if (!clipSegment(a, b, view.finiteFar, t0, t1)) continue;
        draw(toScreenAt(a, b, t0, w, h), toScreenAt(a, b, t1, w, h));
    }
}

} // namespace sr
