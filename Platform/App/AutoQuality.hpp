// --quality auto: choosing a setting from measured (time, error) points, by a frame-time budget or an error bound.
#pragma once

#include <string>
#include <vector>

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Frame/RenderContext.hpp"

namespace sr::app {

// One setting as measured: its frame time and its error against the ground truth (1 - SSIM: 0
// for the truth itself, larger is worse).
struct QualityPoint {
    double ms = 0.0;
    double error = 0.0;
};

// The point to draw within a frame-time budget: the most accurate (lowest error) whose time is at
// most budgetMs; among equally accurate ones the faster, then the first. When none fits: the
// fastest (then the more accurate). -1 for no points.
int chooseForBudget(const std::vector<QualityPoint>& points, double budgetMs);

// The cheapest point whose error is at most maxError: the lowest time; among equally fast ones the
// more accurate, then the first. When none is accurate enough: the most accurate (then the
// faster). -1 for no points.
int chooseForError(const std::vector<QualityPoint>& points, double maxError);

// The shading model, and "pbr gamma" for pbr on display values (its truth is in linear light).
std::string shadingLabel(const RenderSettings& settings);
// A setting as the report, the probe and the demo's title name it: "ssaa4 trilinear phong exact",
// "msaa4 ..."; the filter only for a textured scene.
std::string settingLabel(const RenderSettings& settings, bool textured);

// The probe's candidates, measured.
struct QualityProbe {
    std::vector<RenderSettings> settings;
    std::vector<QualityPoint> points;
    double seconds = 0.0; // how long the probe took
};

// Probes the candidates (1 sample, FXAA, MSAA 4, SSAA 4 x {Gouraud with bilinear, the scene's own
// model with bilinear, trilinear or trilinear with 16 anisotropic taps} (untextured: Gouraud or the
// model), MSAA 8 with the model and the best filter, exact perspective; and the ground truth
// itself, SSAA 16, trilinear with 16 taps, the scene's model): each one's frame time through ctx
// at its target's size (after a first frame of each anti-aliasing mode, the median of up to 3
// while they take under 40 ms together; a first frame of over 100 ms alone), and its error as
// 1 - SSIM against the truth (0 for the truth itself), both rendered at half the width and height
// (at least 16; SSIM is the costly part). `base` gives every other field
// (cull, ISA, sky, shadows, ...); `view` is the frame's view, `camera` and `options` make the
// half-size one.
QualityProbe probeQuality(RenderContext& ctx, LoadedScene& scene, const CameraSetup& camera, const FrameView& view,
                          const SceneOptions& options, const RenderSettings& base, bool textured);

// Keeps a frame-time budget while the scene's load changes, from the probe's points: each frame
// drawn at the current setting updates how much slower or faster than in the probe frames are
// now (an average over the last frames), every point's time is predicted by that factor, and the
// choice follows chooseForBudget, with hysteresis: a dearer setting is taken only when its
// predicted time is within 90% of the budget, and any change only after the same choice held for
// `holdFrames` frames in a row, so a budget sitting between two settings does not alternate.
class AutoQualitySelector {
public:
    AutoQualitySelector() = default;
    AutoQualitySelector(std::vector<QualityPoint> points, double budgetMs, int holdFrames = 15);
    int current() const { return current_; }
    double budgetMs() const { return budgetMs_; }
    const std::vector<QualityPoint>& points() const { return points_; }
    // A frame drawn at current() took frameMs: returns the setting for the next frame.
    int update(double frameMs);

private:
    std::vector<QualityPoint> points_;
    double budgetMs_ = 1000.0 / 60.0;
    int holdFrames_ = 15;
    int current_ = -1;
    int pending_ = -1, held_ = 0;
    double ratio_ = 1.0; // frame time now / in the probe, averaged
};

} // namespace sr::app
