// Back-face culling: screen-space winding on the 1/256-pixel snapped grid, and the cull modes.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "Raster/Geometry/Vertex.hpp"

namespace sr {

// Which winding (as the viewer sees the image) to discard. Front faces are CCW by convention,
// so back-face culling is CullMode::CW.
enum class CullMode { None, CW, CCW };

// "none", "cw", "ccw".
const char* cullModeName(CullMode mode);
// Parses "none", "cw" or "ccw" (ASCII case-insensitive); anything else is std::nullopt.
std::optional<CullMode> parseCullMode(std::string_view text);

enum class Winding { CCW, CW, Degenerate };

// Twice the signed screen area, (x1-x0)(y2-y0) - (x2-x0)(y1-y0), of the triangle snapped to
// the rasterizer's fixed-point grid (kSubPixelBits = 8: units of 1/256 pixel, so the result is
// in 1/65536 pixel^2), computed exactly in int64. Snapping is the rasterizer's snapToFixed
// (FixedPoint.hpp: nearest, ties towards +inf). Screen y is down, so a negative area
// is a CCW (front-facing) triangle.
// Precondition: x, y finite and inside the guard band |x|, |y| <= kGuardBand (what the clipper
// guarantees); outside it only the sign (-1, 0 or 1) is returned, computed from the unsnapped
// coordinates in double (no overflow), and a non-finite coordinate gives 0.
std::int64_t snappedArea2(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2);

// Winding on screen from the sign of snappedArea2: CCW (< 0), CW (> 0), Degenerate (== 0).
Winding screenWinding(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2);

// True when the triangle is to be dropped before setup: its winding is the culled one, or it
// is degenerate (zero area on the snapped grid covers no sample; dropped in every mode,
// including None, and the rasterizer would drop it anyway). Decided on the same snapped grid
// as the rasterizer, so the two always agree on zero-area triangles.
bool isCulled(CullMode mode, const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2);

} // namespace sr
