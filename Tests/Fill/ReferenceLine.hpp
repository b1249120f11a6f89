// Reference line drawer for tests: Line.hpp's rule read literally, in exact rationals, slow.
#pragma once

#include <set>
#include <utility>

#include "Raster/Fill/ScanlineFill.hpp"

namespace sr::ref {

using PixelSet = std::set<std::pair<int, int>>; // (x, y)

// The pixels inside the scissor that the rule of Line.hpp lights for the segment a-b, any float
// endpoints (nothing for NaN or infinities). Rule 5: with all four coordinates inside the guard
// band (|v| <= 16384) the whole segment's snapped ends; otherwise the ends of its exact clip to
// the scissor grown by one pixel, snapped exactly. Then rules 2-3 in int64 for those ends. Every
// step is exact (arbitrary-precision integers and rationals written here, sharing nothing with
// Raster/Geometry/LineClip), and nothing is ever rounded.
PixelSet linePixels(const Scissor& s, float ax, float ay, float bx, float by);

} // namespace sr::ref
