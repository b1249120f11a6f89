// DDA line drawer: canonical ordering, Liang-Barsky clipping, snapping and the framebuffer writer.
#include "Raster/Fill/Line.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "Raster/Geometry/LineClip.hpp"

namespace sr {

namespace {

bool finite(const LineVertex& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

bool inGuardBand(const LineVertex& v) {
    return std::fabs(v.x) <= kGuardBand && std::fabs(v.y) <= kGuardBand;
}

// Where a clipped segment end lies: parameter t and, when a boundary moved it, which one.
struct ClipEnd {
    double t;
    int axis = -1; // -1: not clipped, 0: x = bound, 1: y = bound
    double bound = 0.0;
};

// Liang-Barsky (1984): clips the parameter range [t0, t1] of p(t) = a + t d against
// lo <= p <= hi on one axis. Returns false when the segment is entirely outside.
bool clipAxis(int axis, double a, double d, double lo, double hi, ClipEnd& t0, ClipEnd& t1) {
    const double p[2] = {-d, d};
    const double q[2] = {a - lo, hi - a};
    const double bound[2] = {lo, hi};
    for (int k = 0; k < 2; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0) return false; // parallel to and outside this boundary
            continue;
        }
        const double t = q[k] / p[k];
        if (p[k] < 0.0 && t > t0.t) t0 = {t, axis, bound[k]};
        if (p[k] > 0.0 && t < t1.t) t1 = {t, axis, bound[k]};
    }
    return t0.t <= t1.t;
}

// The clipped point, computed ON the boundary that clipped it (x = bound exactly, y from the
// slope), not as a + t d. Only for endpoints inside the guard band, where double is far more
// precise than the one-column margin the result is used with (beyond it, LineClip is exact).
void clippedPoint(const ClipEnd& c, double ax, double ay, double dx, double dy, double& x, double& y) {
    if (c.axis == 0) {
        x = c.bound;
        y = ay + (c.bound - ax) * (dy / dx);
    } else if (c.axis == 1) {
        y = c.bound;
        x = ax + (c.bound - ay) * (dx / dy);
    } else {
        x = ax + c.t * dx; // t is exactly 0 or 1 here
        y = ay + c.t * dy;
    }
}

void unpack(Pixel p, float out[3]) {
    out[0] = float(pixelR(p));
    out[1] = float(pixelG(p));
    out[2] = float(pixelB(p));
}

} // namespace

std::optional<LineSetup> setupLine(const LineVertex& inA, const LineVertex& inB, const Scissor& s) {
    if (!finite(inA) || !finite(inB) || s.x0 >= s.x1 || s.y0 >= s.y1) return std::nullopt;

    // --- Canonical order first (rule 4): lexicographic on (x, y), so everything below is a
    // function of the unordered pair {A, B} ---------------------------------------------------
    LineSetup l;
    l.flatColour = inA.colour;
    const bool swap = (inB.x < inA.x) || (inB.x == inA.x && inB.y < inA.y);
    LineVertex a = swap ? inB : inA, b = swap ? inA : inB;
    l.reversed = swap;

    // --- Clip to the scissor grown by one pixel (rule 5) -------------------------------------
    float za = a.z, zb = b.z;
    unpack(a.colour, l.colourA);
    unpack(b.colour, l.colourB);
    std::int64_t fxA = 0, fyA = 0, fxB = 0, fyB = 0; // snapped endpoints of the segment to step
    // Columns the visible part can light, per axis (x, y): [narrow[k][0], narrow[k][1]].
    constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
    constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
    std::int64_t narrow[2][2] = {{kMin, kMax}, {kMin, kMax}};
    if (inGuardBand(a) && inGuardBand(b)) {
        // Both endpoints snap as they are; the clip, in double (errors far below a pixel at
        // this range), only narrows the columns visited, with one column to spare each side.
        const double ax = a.x, ay = a.y, dx = double(b.x) - ax, dy = double(b.y) - ay;
        ClipEnd t0{0.0}, t1{1.0};
        if (!clipAxis(0, ax, dx, s.x0 - 1.0, s.x1 + 1.0, t0, t1)) return std::nullopt;
        if (!clipAxis(1, ay, dy, s.y0 - 1.0, s.y1 + 1.0, t0, t1)) return std::nullopt;
        double cx0, cy0, cx1, cy1;
        clippedPoint(t0, ax, ay, dx, dy, cx0, cy0);
        clippedPoint(t1, ax, ay, dx, dy, cx1, cy1);
        fxA = snapToFixed(a.x);
        fyA = snapToFixed(a.y);
        fxB = snapToFixed(b.x);
        fyB = snapToFixed(b.y);
        narrow[0][0] = std::int64_t(std::floor(std::min(cx0, cx1))) - 1;
        narrow[0][1] = std::int64_t(std::floor(std::max(cx0, cx1))) + 1;
        narrow[1][0] = std::int64_t(std::floor(std::min(cy0, cy1))) - 1;
        narrow[1][1] = std::int64_t(std::floor(std::max(cy0, cy1))) + 1;
    } else {
        // An endpoint beyond the guard band: the segment is replaced by its visible part, clipped
        // and snapped exactly (any finite float, up to 3.4e38), attributes interpolated to match.
        const ClipBox box{std::int64_t(s.x0) - 1, std::int64_t(s.y0) - 1, std::int64_t(s.x1) + 1,
                          std::int64_t(s.y1) + 1};
        const std::optional<ExactClip> c = clipSegmentExact(a.x, a.y, b.x, b.y, box);
        if (!c) return std::nullopt;
        fxA = c->x0;
        fyA = c->y0;
        fxB = c->x1;
        fyB = c->y1;
        float ca[3], cb[3];
        for (int k = 0; k < 3; ++k) {
            ca[k] = float(l.colourA[k] + c->t0 * (l.colourB[k] - l.colourA[k]));
            cb[k] = float(l.colourA[k] + c->t1 * (l.colourB[k] - l.colourA[k]));
        }
        std::copy(ca, ca + 3, l.colourA);
        std::copy(cb, cb + 3, l.colourB);
        const double z0 = za + c->t0 * (double(zb) - za), z1 = za + c->t1 * (double(zb) - za);
        za = float(z0);
        zb = float(z1);
        // The ends are the visible part's own: the end columns need no narrowing.
    }

    // --- Pick the major axis, order along it ---------------------------------------------------
    l.yMajor = std::llabs(fyB - fyA) > std::llabs(fxB - fxA);
    l.majorA = l.yMajor ? fyA : fxA;
    l.minorA = l.yMajor ? fxA : fyA;
    l.majorB = l.yMajor ? fyB : fxB;
    l.minorB = l.yMajor ? fxB : fyB;
    l.zA = za;
    l.zB = zb;
    if (l.majorB < l.majorA) { // only possible for y-major; still a function of the pair
        std::swap(l.majorA, l.majorB);
        std::swap(l.minorA, l.minorB);
        std::swap(l.zA, l.zB);
        for (int k = 0; k < 3; ++k) std::swap(l.colourA[k], l.colourB[k]);
        l.reversed = !l.reversed;
    }

    // --- Columns: the whole line's end columns, narrowed to the visible part and scissor -------
    l.columnA = floorDiv(l.majorA, kSubPixelScale);
    l.columnB = floorDiv(l.majorB, kSubPixelScale);
    const std::int64_t lo = l.yMajor ? s.y0 : s.x0, hi = (l.yMajor ? s.y1 : s.x1) - 1;
    l.firstColumn = std::max({l.columnA, lo, narrow[l.yMajor][0]});
    l.lastColumn = std::min({l.columnB, hi, narrow[l.yMajor][1]});
    if (l.firstColumn > l.lastColumn) return std::nullopt;
    return l;
}

namespace {

// The colour of a line pixel at canonical parameter t (clamped to [0, 1] by the caller).
Pixel lineColour(const LineSetup& l, const LineOptions& o, float t) {
    if (!o.interpolateColour) return l.flatColour;
    std::uint8_t ch[3];
    for (int k = 0; k < 3; ++k) {
        const float v = l.colourA[k] + t * (l.colourB[k] - l.colourA[k]);
        ch[k] = std::uint8_t(std::clamp(v + 0.5f, 0.0f, 255.0f));
    }
    return packBgra(ch[0], ch[1], ch[2]);
}

} // namespace

void drawLine(FrameBuffer& fb, const LineVertex& a, const LineVertex& b, const LineOptions& o) {
    const Scissor s = fullScissor(fb);
    const std::optional<LineSetup> l = setupLine(a, b, s);
    if (!l) return;
    forEachLinePixel(*l, s, [&](int x, int y, float t) {
        t = std::clamp(t, 0.0f, 1.0f);
        if (o.depthTest) {
            const float z = l->zA + t * (l->zB - l->zA);
            float& d = fb.depthRow(y)[x];
            if (!(z >= d)) return;
            if (o.depthWrite) d = z;
        }
        fb.colorRow(y)[x] = lineColour(*l, o, t);
    });
}

void drawLine(MsaaBuffer& target, const LineVertex& a, const LineVertex& b, const LineOptions& o) {
    const Scissor s{0, 0, target.width(), target.height()};
    const std::optional<LineSetup> l = setupLine(a, b, s);
    if (!l) return;
    const int n = target.samples();
    forEachLinePixel(*l, s, [&](int x, int y, float t) {
        t = std::clamp(t, 0.0f, 1.0f);
        const float z = l->zA + t * (l->zB - l->zA);
        const Pixel c = lineColour(*l, o, t);
        target.prepareSpan(y, x, x + 1);
        Pixel* colour = target.colourRow(y) + std::size_t(x) * std::size_t(n);
        float* depth = target.depthRow(y) + std::size_t(x) * std::size_t(n);
        for (int k = 0; k < n; ++k) {
            if (o.depthTest) {
                if (!(z >= depth[k])) continue;
                if (o.depthWrite) depth[k] = z;
            }
            colour[k] = c;
        }
    });
}

void drawWideLine(FrameBuffer& fb, MsaaBuffer* msaa, const LineVertex& a, const LineVertex& b,
                  const LineOptions& options, int width) {
    if (msaa) {
        drawLine(*msaa, a, b, options);
        return;
    }
    const bool xMajor = std::fabs(b.x - a.x) >= std::fabs(b.y - a.y);
    for (int k = 0; k < width; ++k) {
        const float offset = float(k) - 0.5f * float(width - 1);
        const float dx = xMajor ? 0.0f : offset, dy = xMajor ? offset : 0.0f;
        LineVertex a2 = a, b2 = b;
        a2.x += dx;
        a2.y += dy;
        b2.x += dx;
        b2.y += dy;
        drawLine(fb, a2, b2, options);
    }
}

} // namespace sr
