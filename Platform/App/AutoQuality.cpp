// --quality auto's choice rules over measured points (AutoQuality.hpp).
#include "Platform/App/AutoQuality.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "Platform/App/ImageMetrics.hpp"
#include "Raster/Texture/TextureLod.hpp" // kMaxAnisotropy

namespace sr::app {
namespace {

// a before b: the lower `first` key, then the lower `second`, then the earlier index.
bool ahead(double a1, double a2, double b1, double b2) { return a1 < b1 || (a1 == b1 && a2 < b2); }

} // namespace

int chooseForBudget(const std::vector<QualityPoint>& points, double budgetMs) {
    int best = -1, fastest = -1;
    for (int i = 0; i < int(points.size()); ++i) {
        const QualityPoint& p = points[std::size_t(i)];
        if (fastest < 0 || ahead(p.ms, p.error, points[std::size_t(fastest)].ms, points[std::size_t(fastest)].error)) fastest = i;
        if (!(p.ms <= budgetMs)) continue;
        if (best < 0 || ahead(p.error, p.ms, points[std::size_t(best)].error, points[std::size_t(best)].ms)) best = i;
    }
    return best >= 0 ? best : fastest;
}

int chooseForError(const std::vector<QualityPoint>& points, double maxError) {
    int best = -1, accurate = -1;
    for (int i = 0; i < int(points.size()); ++i) {
        const QualityPoint& p = points[std::size_t(i)];
        if (accurate < 0 || ahead(p.error, p.ms, points[std::size_t(accurate)].error, points[std::size_t(accurate)].ms)) accurate = i;
        if (!(p.error <= maxError)) continue;
        if (best < 0 || ahead(p.ms, p.error, points[std::size_t(best)].ms, points[std::size_t(best)].error)) best = i;
    }
    return best >= 0 ? best : accurate;
}

std::string shadingLabel(const RenderSettings& r) {
    return std::string(shadingModeName(r.shading)) + (r.shading == ShadingMode::Pbr && r.colour == ColorMode::Gamma ? " gamma" : "");
}

std::string settingLabel(const RenderSettings& r, bool textured) {
    const AntiAliasing aa = r.antiAliasing;
    std::string l = aa.multisampled()   ? "msaa" + std::to_string(aa.samples())
                    : aa.postFiltered() ? std::string("fxaa")
                                        : "ssaa" + std::to_string(aa.ssaaSamples());
    if (textured) l += " " + std::string(filterName(r.filter)) + (r.aniso > 1 ? " aniso" + std::to_string(r.aniso) : "");
    return l + " " + shadingLabel(r) + " " + perspectiveModeName(r.perspective);
}

QualityProbe probeQuality(RenderContext& ctx, LoadedScene& scene, const CameraSetup& camera, const FrameView& view,
                          const SceneOptions& options, const RenderSettings& baseIn, bool textured) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const bool physical = scene.physical;
    RenderSettings base = baseIn;
    base.perspective = PerspectiveMode::Exact;
    base.filterFromFile = false;
    base.shading = physical ? ShadingMode::Pbr : ShadingMode::Phong;
    base.colour = physical ? ColorMode::Linear : ColorMode::Gamma;
    QualityProbe probe;
    // Per anti-aliasing mode, the texture and shading rungs: Gouraud with the cheapest filter,
    // then the scene's model with bilinear, trilinear and 16 anisotropic taps (untextured: Gouraud
    // and the model); MSAA 8 only with the most accurate rest. 18 candidates with the truth, so
    // that the probe of the built-in scene stays within 2 s.
    struct Rung {
        TextureFilter filter;
        int aniso;
        ShadingMode shading;
    };
    const Rung texturedRungs[] = {{TextureFilter::Bilinear, 1, ShadingMode::Gouraud},
                                  {TextureFilter::Bilinear, 1, base.shading},
                                  {TextureFilter::Trilinear, 1, base.shading},
                                  {TextureFilter::Trilinear, kMaxAnisotropy, base.shading}};
    const Rung plainRungs[] = {{TextureFilter::Trilinear, 1, ShadingMode::Gouraud}, {TextureFilter::Trilinear, 1, base.shading}};
    const Rung* rungs = textured ? texturedRungs : plainRungs;
    const int rungCount = textured ? 4 : 2;
    const int w = ctx.target().width(), h = ctx.target().height();
    const auto fits = [&](AntiAliasing aa) {
        const int g = aa.gridSide();
        return msaaFits(w, h, aa.msaaSamples()) && w <= FrameBuffer::kMaxDimension / g && h <= FrameBuffer::kMaxDimension / g;
    };
    const auto add = [&](AntiAliasing aa, const Rung& r) {
        RenderSettings s = base;
        s.antiAliasing = aa;
        s.filter = r.filter;
        s.aniso = r.aniso;
        s.shading = r.shading;
        if (fits(aa)) probe.settings.push_back(s);
    };
    for (AntiAliasing aa : {AntiAliasing::none(), AntiAliasing::fxaa(), *AntiAliasing::multisample(4), *AntiAliasing::supersample(4)})
        for (int k = 0; k < rungCount; ++k) add(aa, rungs[k]);
    add(*AntiAliasing::multisample(8), rungs[rungCount - 1]);
    RenderSettings truthSettings = base; // the ground truth: a candidate too (error 0)
    truthSettings.antiAliasing = *AntiAliasing::supersample(16);
    truthSettings.filter = TextureFilter::Trilinear;
    truthSettings.aniso = kMaxAnisotropy;
    if (fits(truthSettings.antiAliasing)) probe.settings.push_back(truthSettings);
    // Errors at half size: the truth first.
    const int pw = std::max(16, w / 2), ph = std::max(16, h / 2);
    FrameBuffer small(pw, ph);
    RenderContext smallContext(small);
    smallContext.setThreads(ctx.threads());
    const FrameView smallView = makeFrameView(camera, pw, ph, options.light, scene.lights, physical, scene.ibl.get());
    renderFrame(smallContext, scene, smallView, truthSettings);
    const FrameBuffer truth = small;
    std::optional<AntiAliasing> warmed; // the anti-aliasing whose buffers the last frames used
    for (std::size_t k = 0; k < probe.settings.size(); ++k) {
        const RenderSettings& s = probe.settings[k];
        QualityPoint q;
        const bool isTruth = k + 1 == probe.settings.size() && fits(truthSettings.antiAliasing);
        if (!isTruth) { // the truth's error is 0
            renderFrame(smallContext, scene, smallView, s);
            q.error = 1.0 - structuralSimilarity(truth, small);
        }
        // One frame to warm up (the first of each anti-aliasing mode: its buffers), then up to
        // three timed ones while they take under 40 ms in all. A warm-up frame of over 100 ms is
        // the measurement itself (its buffers' first use is a small part of it).
        const auto frame = [&] { renderFrame(ctx, scene, view, s); };
        std::vector<double> ms;
        double spent = 0.0;
        if (!(warmed && *warmed == s.antiAliasing)) {
            const auto t0 = Clock::now();
            frame();
            const double first = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            if (first > 100.0) {
                ms.push_back(first);
                spent = first;
            }
        }
        warmed = s.antiAliasing;
        while (ms.size() < 3 && (ms.empty() || spent < 40.0)) {
            const auto t0 = Clock::now();
            frame();
            ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
            spent += ms.back();
        }
        std::sort(ms.begin(), ms.end());
        q.ms = ms.size() == 2 ? 0.5 * (ms[0] + ms[1]) : ms[ms.size() / 2];
        probe.points.push_back(q);
    }
    probe.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return probe;
}

AutoQualitySelector::AutoQualitySelector(std::vector<QualityPoint> points, double budgetMs, int holdFrames)
    : points_(std::move(points)), budgetMs_(budgetMs), holdFrames_(std::max(holdFrames, 1)) {
    current_ = chooseForBudget(points_, budgetMs_);
}

int AutoQualitySelector::update(double frameMs) {
    if (current_ < 0 || !(frameMs > 0.0) || !std::isfinite(frameMs)) return current_;
    const double probed = points_[std::size_t(current_)].ms;
    if (probed > 0.0) ratio_ += 0.25 * (frameMs / probed - ratio_);
    std::vector<QualityPoint> predicted = points_;
    for (QualityPoint& p : predicted) p.ms *= ratio_;
    // Over the budget: the best that fits it; within it: a dearer setting only with 10% to spare.
    int want = current_;
    if (predicted[std::size_t(current_)].ms > budgetMs_) {
        want = chooseForBudget(predicted, budgetMs_);
    } else {
        const int up = chooseForBudget(predicted, 0.9 * budgetMs_);
        if (up >= 0 && predicted[std::size_t(up)].error < predicted[std::size_t(current_)].error) want = up;
    }
    if (want == current_) {
        pending_ = -1;
        held_ = 0;
    } else if (want == pending_) {
        if (++held_ >= holdFrames_) {
            current_ = want;
            pending_ = -1;
            held_ = 0;
        }
    } else {
        pending_ = want;
        held_ = 1;
        if (holdFrames_ <= 1) {
            current_ = want;
            pending_ = -1;
            held_ = 0;
        }
    }
    return current_;
}

} // namespace sr::app
