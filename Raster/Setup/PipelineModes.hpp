// The pipeline's mode enums (perspective, depth, partial pipelines), apart from the loops that run them.
#pragma once

#include <optional>
#include <string_view>

namespace sr {

// How varyings are interpolated across the screen (a quality knob, measured by the report):
//  - Exact: (v/w) / (1/w) at every pixel centre (Hecker 1995): correct everywhere.
//  - Affine: v itself is linear in screen space (no divide at all; PlayStation-style warping).
// Quake's span subdivision (span16 / span8: exact every 16 / 8 pixels, linear in between) was
// retired: with the vector kernels exact costs within a few percent of affine, so the middle
// settings bought nothing (docs/PERFORMANCE.md has the measurement).
enum class PerspectiveMode { Exact, Affine };

const char* perspectiveModeName(PerspectiveMode mode);
std::optional<PerspectiveMode> parsePerspectiveMode(std::string_view text); // exact|affine
// True for the names of retired modes (span16, span8), so the command line can say so.
bool isRetiredPerspectiveMode(std::string_view text);

// Depth policy of a fill, chosen at compile time. Depth is reversed-Z float, test GREATER
// (strict: on an exact tie the fragment already in the buffer stays).
// Precision: z_ndc = near / distance (infinite far plane) is stored as float, whose relative
// spacing is 2^-24 at every magnitude, so two depths are distinguishable whenever their
// distances differ by more than ~2^-23 relatively, near or far alike (Reed, "Depth Precision
// Visualized", 2015). The screen-linear plane evaluation adds a few ulps on top.
enum class DepthMode { Off, Test, TestWrite };

// Where a draw stops: the bench command times partial pipelines to split a frame's time into
// stages (geometry = vertex shader + clip + divide + cull; binning, in a draw spread over several
// threads by bins (Binning.hpp), else the same as Geometry; setup; fill = span loop + shading).
enum class PipelineStop { Geometry, Bin, Setup, Fill };

} // namespace sr
