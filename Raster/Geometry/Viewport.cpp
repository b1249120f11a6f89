// Perspective divide and viewport transform (see Viewport.hpp).
#include "Raster/Geometry/Viewport.hpp"

#include <cassert>
#include <cstddef>

namespace sr {

ScreenVertex toScreen(const ClipVertex& v, int width, int height, int varyingCount) {
    assert(isFinite(v.position) && v.position.w > 0.0f && "clip before the divide");
    assert(varyingCount >= 0 && varyingCount <= kMaxVaryings);
    const Vec4& p = v.position;
    const float halfW = 0.5f * float(width);
    const float halfH = 0.5f * float(height);
    ScreenVertex s;
    s.x = (p.x / p.w + 1.0f) * halfW;
    s.y = (1.0f - p.y / p.w) * halfH;
    s.z = p.z / p.w;
    s.invW = 1.0f / p.w;
    for (int i = 0; i < varyingCount; ++i)
        s.varyings[std::size_t(i)] = v.varyings[std::size_t(i)];
    return s;
}

} // namespace sr
