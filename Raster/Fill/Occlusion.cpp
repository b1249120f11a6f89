#include "Raster/Fill/Occlusion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sr {

float nearestDepthBound(const TriangleSetup& t, int x0, int x1, int y0, int y1) {
    const FixedEdge& l = t.longEdge;
    auto zAt = [&t](std::int64_t x, std::int64_t y) {
        return t.planeAt(kPlaneZ, double(x) / kSubPixelScale, double(y) / kSubPixelScale);
    };
    const double zMax = std::max({zAt(l.x0, l.y0), zAt(t.lowerEdge.x0, t.lowerEdge.y0),
                                  zAt(std::int64_t(l.x0) + l.dx, std::int64_t(l.y0) + l.dy)});
    const double reachX = std::max(std::fabs(x0 - t.originX), std::fabs(x1 - t.originX)) + 2.0;
    const double reachY = std::max(std::fabs(y0 - t.originY), std::fabs(y1 - t.originY)) + 2.0;
    const double slack = (std::fabs(t.value[kPlaneZ]) + std::fabs(t.ddx[kPlaneZ]) * 2.0 * reachX +
                          std::fabs(t.ddy[kPlaneZ]) * reachY) * 0x1p-44;
    return float(zMax + slack);
}

bool hiddenInFrame(const TriangleSetup& t, const FrameBuffer& fb, const Scissor& s) {
    if (t.maxX - t.minX >= 32 || t.endRow - t.firstRow > 32) return false;
    const int x0 = std::max(t.minX, s.x0), x1 = std::min(t.maxX + 1, s.x1);
    const int y0 = std::max(t.firstRow, s.y0), y1 = std::min(t.endRow, s.y1);
    if (x0 >= x1 || y0 >= y1) return false;
    if (!(fb.depthRow(y0)[x0] >= float(t.value[kPlaneZ]))) return false;
    const float bound = nearestDepthBound(t, x0, x1, y0, y1);
    if (!(bound == bound)) return false;
    for (int y = y0; y < y1; ++y) {
        const float* depth = fb.depthRow(y);
        for (int x = x0; x < x1; ++x)
            if (!(depth[x] >= bound)) return false;
    }
    return true;
}

} // namespace sr
