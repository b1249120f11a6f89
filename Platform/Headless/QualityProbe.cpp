// --quality auto: each candidate timed at the scene's size and compared with the truth at half size, then the choice.
#include "Platform/Headless/QualityProbe.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <vector>

#include "Platform/App/AutoQuality.hpp"
#include "Platform/Headless/ImageCompare.hpp"
#include "Platform/Headless/Timing.hpp"

namespace sr::headless {

std::string shadingLabel(const RenderSettings& r) {
    return std::string(shadingModeName(r.shading)) + (r.shading == ShadingMode::Pbr && r.colour == ColorMode::Gamma ? " gamma" : "");
}

std::string settingLabel(const RenderSettings& r, bool textured) {
    const AntiAliasing aa = r.antiAliasing;
    std::string l = aa.multisampled() ? "msaa" + std::to_string(aa.samples()) : "ssaa" + std::to_string(aa.ssaaSamples());
    if (textured) l += " " + std::string(filterName(r.filter));
    return l + " " + shadingLabel(r) + " " + perspectiveModeName(r.perspective);
}

QualityChoice probeQuality(PreparedScene& p) {
    const auto start = std::chrono::steady_clock::now();
    const bool physical = p.scene.physical;
    RenderSettings base = p.settings;
    base.perspective = PerspectiveMode::Exact;
    base.filterFromFile = false;
    base.shading = physical ? ShadingMode::Pbr : ShadingMode::Phong;
    base.colour = physical ? ColorMode::Linear : ColorMode::Gamma;
    std::vector<RenderSettings> candidates;
    const std::vector<TextureFilter> filters =
        p.textured ? std::vector<TextureFilter>{TextureFilter::Bilinear, TextureFilter::Trilinear} : std::vector<TextureFilter>{TextureFilter::Trilinear};
    const int w = p.framebuffer.width(), h = p.framebuffer.height();
    const auto fits = [&](AntiAliasing aa) {
        const int g = aa.gridSide();
        return msaaFits(w, h, aa.msaaSamples()) && w <= FrameBuffer::kMaxDimension / g && h <= FrameBuffer::kMaxDimension / g;
    };
    for (AntiAliasing aa : {AntiAliasing::none(), *AntiAliasing::multisample(4), *AntiAliasing::supersample(4), *AntiAliasing::multisample(8)})
        for (TextureFilter f : filters)
            for (ShadingMode m : {ShadingMode::Gouraud, base.shading}) {
                RenderSettings s = base;
                s.antiAliasing = aa;
                s.filter = f;
                s.shading = m;
                if (fits(aa)) candidates.push_back(s);
            }
    RenderSettings truthSettings = base; // the ground truth: a candidate too (error 0)
    truthSettings.antiAliasing = *AntiAliasing::supersample(16);
    truthSettings.filter = TextureFilter::Trilinear;
    if (fits(truthSettings.antiAliasing)) candidates.push_back(truthSettings);
    // Errors at half size: the truth first.
    const int pw = std::max(16, p.framebuffer.width() / 2), ph = std::max(16, p.framebuffer.height() / 2);
    FrameBuffer small(pw, ph);
    RenderContext smallContext(small);
    smallContext.setThreads(p.context.threads());
    FrameView smallView = app::makeFrameView(p.camera, pw, ph, p.options.light, p.scene.lights, physical, p.scene.ibl.get());
    app::renderFrame(smallContext, p.scene, smallView, truthSettings);
    const FrameBuffer truth = small;
    std::vector<app::QualityPoint> points;
    std::optional<AntiAliasing> warmed; // the anti-aliasing whose buffers the last frames used
    for (const RenderSettings& s : candidates) {
        app::renderFrame(smallContext, p.scene, smallView, s);
        app::QualityPoint q;
        q.error = 1.0 - structuralSimilarity(truth, small);
        // One frame to warm up (the first of each anti-aliasing mode: its buffers), then up to
        // three timed ones while they take under 60 ms in all.
        const auto frame = [&] { app::renderFrame(p.context, p.scene, p.view, s); };
        if (!(warmed && *warmed == s.antiAliasing)) frame();
        warmed = s.antiAliasing;
        std::vector<double> ms;
        double spent = 0.0;
        while (ms.size() < 3 && (ms.empty() || spent < 60.0)) {
            ms.push_back(timeFrames(0, 1, frame).front());
            spent += ms.back();
        }
        q.ms = summarise(ms).median;
        points.push_back(q);
    }
    const app::SceneOptions& o = p.options;
    const int k = o.maxError ? app::chooseForError(points, *o.maxError) : app::chooseForBudget(points, o.budgetMs.value_or(1000.0 / 60.0));
    QualityChoice c;
    c.settings = candidates[std::size_t(k)];
    c.label = settingLabel(c.settings, p.textured);
    c.ms = points[std::size_t(k)].ms;
    c.error = points[std::size_t(k)].error;
    c.candidates = int(candidates.size());
    c.probeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return c;
}

} // namespace sr::headless
