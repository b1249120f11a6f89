// --quality auto for the headless command: a short probe of the scene (each candidate's frame time and error) and the choice.
#pragma once

#include <string>

#include "Platform/Headless/CommandArgs.hpp"

namespace sr::headless {

// The shading model, and "pbr gamma" for pbr on display values (its truth is in linear light).
std::string shadingLabel(const RenderSettings& settings);

// A setting as the report and the probe name it: "ssaa4 trilinear phong exact", "msaa4 ...";
// the filter only for a textured scene; pbr on display values as "pbr gamma".
std::string settingLabel(const RenderSettings& settings, bool textured);

// Probes the candidates (1 sample, MSAA 4 and 8, SSAA 4 x bilinear or trilinear x Gouraud or the
// scene's own model, exact perspective, the filter only when textured; and the ground truth
// itself): each one's frame time at the scene's size (after a first frame of each anti-aliasing
// mode, the median of up to 3 while they take under 60 ms together), and its error as 1 - SSIM against
// the ground truth (SSAA 16, trilinear, the scene's model) rendered at half the width and height,
// at least 16 (SSIM is the costly part). Then chooses by p.options' budget or error bound
// (AutoQuality.hpp): the most accurate within --budget-ms (default 16.7), or the cheapest within
// --max-error. p.settings' other fields (cull, ISA, sky, shadows, ...) are kept.
QualityChoice probeQuality(PreparedScene& p);

} // namespace sr::headless
