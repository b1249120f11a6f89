// Back-face culling on the snapped fixed-point grid (see Cull.hpp).
#include "Raster/Geometry/Cull.hpp"

#include <cmath>

#include "Raster/Setup/FixedPoint.hpp"
#include "Raster/Setup/RasterLimits.hpp"

namespace sr {

const char* cullModeName(CullMode mode) {
    switch (mode) {
    case CullMode::None: return "none";
    case CullMode::CW: return "cw";
    case CullMode::CCW: return "ccw";
    }
    return "none";
}

std::optional<CullMode> parseCullMode(std::string_view text) {
    auto equalsLower = [](std::string_view a, std::string_view lower) {
        if (a.size() != lower.size())
            return false;
        for (std::size_t i = 0; i < a.size(); ++i) {
            char c = a[i];
            if (c >= 'A' && c <= 'Z')
                c = char(c - 'A' + 'a');
            if (c != lower[i])
                return false;
        }
        return true;
    };
    if (equalsLower(text, "none")) return CullMode::None;
    if (equalsLower(text, "cw")) return CullMode::CW;
    if (equalsLower(text, "ccw")) return CullMode::CCW;
    return std::nullopt;
}

std::int64_t snappedArea2(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2) {
    const float xs[3] = {v0.x, v1.x, v2.x};
    const float ys[3] = {v0.y, v1.y, v2.y};
    bool inBand = true;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(xs[i]) || !std::isfinite(ys[i]))
            return 0;
        inBand = inBand && std::fabs(xs[i]) <= kGuardBand && std::fabs(ys[i]) <= kGuardBand;
    }
    if (!inBand) {
        // Outside the contract: a sign from doubles (|x| < 2^128, products < 2^257: no overflow).
        const double a = (double(xs[1]) - xs[0]) * (double(ys[2]) - ys[0]) -
                         (double(xs[2]) - xs[0]) * (double(ys[1]) - ys[0]);
        return a > 0.0 ? 1 : (a < 0.0 ? -1 : 0);
    }
    // The rasterizer's own snapping (FixedPoint.hpp), so both see the same triangle.
    // |X| <= 2^22 on the grid: deltas <= 2^23, products <= 2^46, exact in int64.
    std::int64_t X[3], Y[3];
    for (int i = 0; i < 3; ++i) {
        X[i] = snapToFixed(xs[i]);
        Y[i] = snapToFixed(ys[i]);
    }
    return (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
}

Winding screenWinding(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2) {
    const std::int64_t a = snappedArea2(v0, v1, v2);
    return a < 0 ? Winding::CCW : (a > 0 ? Winding::CW : Winding::Degenerate);
}

bool isCulled(CullMode mode, const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2) {
    const Winding w = screenWinding(v0, v1, v2);
    if (w == Winding::Degenerate)
        return true;
    return (mode == CullMode::CW && w == Winding::CW) || (mode == CullMode::CCW && w == Winding::CCW);
}

} // namespace sr
