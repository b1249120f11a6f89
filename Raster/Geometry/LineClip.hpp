// Exact line clipping for any finite float endpoints: the visible part of a segment and its snapped ends.
#pragma once

#include <cstdint>
#include <optional>

namespace sr {

// The visible part of a segment p(t) = a + t (b - a), t in [t0, t1] within [0, 1].
struct ExactClip {
    // Both ends snapped to the 1/256 grid like snapToFixed, floor(256 v + 1/2), of their EXACT
    // coordinates (no intermediate rounding): (x0, y0) = snap(p(t0)), (x1, y1) = snap(p(t1)).
    std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    // t0 and t1 rounded to double: for interpolating attributes only, never for coverage.
    double t0 = 0.0, t1 = 1.0;
};

// An axis-aligned closed box [x0, x1] x [y0, y1] in pixels (integer bounds, |bound| <= 2^31).
struct ClipBox {
    std::int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Liang-Barsky (1984) clipping of the segment a-b to the box, evaluated in exact integer
// arithmetic on the binary values of the float endpoints (any finite float, 2^-149 to 3.4e38),
// followed by exact snapping of the clipped ends. Returns nullopt when the segment misses the
// box (a segment that only touches it is kept: t0 == t1). Preconditions: a and b finite,
// box.x0 <= box.x1, box.y0 <= box.y1.
std::optional<ExactClip> clipSegmentExact(float ax, float ay, float bx, float by, const ClipBox& box);

} // namespace sr
