// `softraster report`: time and error of every quality setting, as CSV, Markdown and an SVG plot.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "Platform/App/AutoQuality.hpp"
#include "Platform/Headless/CommandArgs.hpp"
#include "Platform/Headless/Commands.hpp"
#include "Platform/Headless/ImageCompare.hpp"
#include "Platform/Headless/Timing.hpp"
#include "Raster/Frame/Resolve.hpp"
#include "Raster/Texture/TextureLod.hpp" // kMaxAnisotropy
#include "Resources/FileIO.hpp"
#include "Resources/Image.hpp"

namespace sr::headless {
namespace {

struct Setting {
    RenderSettings settings;
    bool truth = false;                   // the ground truth (SSAA 16 with the most accurate rest)
    std::optional<app::Quality> preset;  // the --quality preset this combination is, if any
    unsigned dropped = 0;                 // PbrLobe bits drawn without: the materials as if they had not those extensions
};

// The material extensions a rung may drop, each with its name in the report.
constexpr std::pair<unsigned, const char*> kDroppable[] = {
    {kLobeClearcoat, "clearcoat"}, {kLobeSheen, "sheen"}, {kLobeDielectricSpecular, "specular"}};

// The droppable extensions the scene's draws use (PbrLobe bits).
unsigned sceneLobes(const Scene& scene) {
    unsigned lobes = 0;
    for (const SceneDraw& d : scene.draws) {
        if (!d.pbr) continue;
        if (d.pbr->clearcoat > 0.0f) lobes |= kLobeClearcoat;
        if (d.pbr->sheenColor.x > 0.0f || d.pbr->sheenColor.y > 0.0f || d.pbr->sheenColor.z > 0.0f) lobes |= kLobeSheen;
        if (hasDielectricSpecular(*d.pbr) || d.maps.has(MapSlot::Specular) || d.maps.has(MapSlot::SpecularColour))
            lobes |= kLobeDielectricSpecular;
    }
    return lobes;
}

// The draws as if their materials had not the extensions in `dropped`: no coat (its factor 0,
// its maps gone), no sheen (black, its maps gone), the dielectric of appendix B (F0 0.04,
// weight 1, no specular maps).
std::vector<SceneDraw> withoutLobes(std::vector<SceneDraw> draws, unsigned dropped) {
    for (SceneDraw& d : draws) {
        if (!d.pbr) continue;
        if (dropped & kLobeClearcoat) {
            d.pbr->clearcoat = 0.0f;
            for (const MapSlot s : {MapSlot::Clearcoat, MapSlot::ClearcoatRoughness, MapSlot::ClearcoatNormal}) d.maps[s] = -1;
        }
        if (dropped & kLobeSheen) {
            d.pbr->sheenColor = Vec3{0.0f, 0.0f, 0.0f};
            d.maps[MapSlot::SheenColour] = d.maps[MapSlot::SheenRoughness] = -1;
        }
        if (dropped & kLobeDielectricSpecular) {
            d.pbr->dielectricF0 = d.pbr->specularColorF0 = Vec3{0.04f, 0.04f, 0.04f};
            d.pbr->specularWeight = 1.0f;
            d.maps[MapSlot::Specular] = d.maps[MapSlot::SpecularColour] = -1;
        }
    }
    return draws;
}

// " without clearcoat", " without clearcoat and specular", ...: what a rung drops ("" for none).
std::string droppedLabel(unsigned dropped) {
    std::string without;
    for (const auto& [bit, name] : kDroppable)
        if (dropped & bit) without += std::string(without.empty() ? " without " : " and ") + name;
    return without;
}

// "pbr", "pbr without clearcoat", ...: the shading column.
std::string shadingOf(const Setting& s) { return app::shadingLabel(s.settings) + droppedLabel(s.dropped); }

struct Row {
    Setting setting;
    TimingSummary time;        // median / min over the rounds' per-round medians
    double maxMs = 0.0;        // max over the rounds
    ImageError error;    // against the ground truth
};

// The ground truth: 16 samples per pixel (4x4, each shaded), exact perspective, trilinear
// mipmaps with 16 anisotropic taps, per-pixel (Phong) lighting. Then every combination of
// anti-aliasing (1 sample, FXAA, MSAA 4 or SSAA 4) x texture filter (bilinear, trilinear,
// trilinear with 16 anisotropic taps) x shading (Gouraud, Phong), exact perspective, and MSAA 8
// with the truth's other settings. A scene without textures skips the filter (it changes nothing
// there); unlit is left out (it drops the lighting: another picture, not an approximation of this
// one). Nearest, affine and flat are not rungs: they save too little (docs/PERFORMANCE.md:
// nearest 0.89-1.03x bilinear, affine 0.94-1.02x exact, flat 0.84-0.96x Gouraud).
// A physical (glTF) scene's truth is its own material model, pbr in linear light; Phong and
// Gouraud are then rungs of the shading sweep, and pbr on display values (gamma) one more setting,
// and so, at one sample, is pbr without each material extension the scene has (`lobes`:
// sceneLobes), and without all of them where it has more than one.
std::vector<Setting> settingsToMeasure(RenderSettings base, bool textured, bool physical, unsigned lobes) {
    base.perspective = PerspectiveMode::Exact;
    base.filter = TextureFilter::Trilinear;
    base.aniso = kMaxAnisotropy;
    base.filterFromFile = false; // the report measures each filter itself
    base.shading = physical ? ShadingMode::Pbr : ShadingMode::Phong;
    base.colour = physical ? ColorMode::Linear : ColorMode::Gamma;
    base.antiAliasing = *AntiAliasing::supersample(16);
    std::vector<Setting> out{{base, true, {}}};
    struct Filter {
        TextureFilter filter;
        int aniso;
    };
    std::vector<Filter> filters{{TextureFilter::Trilinear, 1}};
    if (textured) filters = {{TextureFilter::Bilinear, 1}, {TextureFilter::Trilinear, 1}, {TextureFilter::Trilinear, kMaxAnisotropy}};
    for (AntiAliasing aa : {AntiAliasing::none(), AntiAliasing::fxaa(), *AntiAliasing::multisample(4), *AntiAliasing::supersample(4)})
        for (Filter f : filters)
            for (ShadingMode m : {ShadingMode::Gouraud, ShadingMode::Phong, ShadingMode::Pbr}) {
                if (m == ShadingMode::Pbr && !physical) continue;
                Setting s{base, false, {}};
                s.settings.antiAliasing = aa;
                s.settings.filter = f.filter;
                s.settings.aniso = f.aniso;
                s.settings.shading = m;
                out.push_back(s);
            }
    Setting msaa8{base, false, {}};
    msaa8.settings.antiAliasing = *AntiAliasing::multisample(8);
    out.push_back(msaa8);
    if (physical) { // the truth's model on display values, one sample
        Setting gamma{base, false, {}};
        gamma.settings.antiAliasing = AntiAliasing::none();
        gamma.settings.colour = ColorMode::Gamma;
        out.push_back(gamma);
        int kinds = 0;
        for (const auto& [bit, name] : kDroppable) {
            if (!(lobes & bit)) continue;
            ++kinds;
            Setting without{base, false, {}, bit};
            without.settings.antiAliasing = AntiAliasing::none();
            out.push_back(without);
        }
        if (kinds > 1) {
            Setting none{base, false, {}, lobes};
            none.settings.antiAliasing = AntiAliasing::none();
            out.push_back(none);
        }
    }
    // Mark the presets (untextured scenes: the filter does not count).
    for (app::Quality q : {app::Quality::Fast, app::Quality::Balanced, app::Quality::Accurate}) {
        const app::QualitySettings qs = app::qualitySettings(q, physical);
        for (Setting& s : out)
            if (s.dropped == 0 && s.settings.antiAliasing == qs.antiAliasing && s.settings.shading == qs.shading &&
                s.settings.colour == base.colour &&
                s.settings.perspective == qs.perspective &&
                (!textured || (s.settings.filter == qs.filter && s.settings.aniso == qs.aniso))) {
                s.preset = q;
                break;
            }
    }
    return out;
}

std::string fmt(double v, int decimals = 3) {
    if (std::isinf(v)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

std::string label(const Setting& s, bool textured) { return app::settingLabel(s.settings, textured) + droppedLabel(s.dropped); }

// Points on the Pareto front: no other point is both faster and at least as accurate (mean
// absolute error against the ground truth).
std::vector<bool> paretoFront(const std::vector<Row>& rows) {
    std::vector<bool> front(rows.size(), true);
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < rows.size(); ++j) {
            if (i == j) continue;
            const bool faster = rows[j].time.median <= rows[i].time.median;
            const bool better = rows[j].error.meanAbs <= rows[i].error.meanAbs;
            const bool strictly = rows[j].time.median < rows[i].time.median || rows[j].error.meanAbs < rows[i].error.meanAbs;
            if (faster && better && strictly) front[i] = false;
        }
    return front;
}

// Mean absolute error against the ground truth (0 at the top) against time per frame; the front
// and the presets labelled, every other combination a grey dot.
std::string svgPlot(const std::vector<Row>& rows, const std::vector<bool>& front, bool textured,
                    const std::string& title) {
    const double W = 900, H = 560, left = 90, right = 60, top = 62, bottom = 60;
    double tMin = 1e300, tMax = 0, eMin = 1e300, eMax = 0;
    for (const Row& r : rows) {
        tMin = std::min(tMin, r.time.median);
        tMax = std::max(tMax, r.time.median);
        eMax = std::max(eMax, r.error.meanAbs);
        if (r.error.meanAbs > 0) eMin = std::min(eMin, r.error.meanAbs);
    }
    if (eMax <= 0) eMax = eMin = 1;
    // Error on a log axis too (it spans three or four decades); an error of 0 (the ground truth)
    // is drawn on the top line, labelled 0.
    const double yTop = std::log10(eMin / 2), yBottom = std::log10(eMax * 1.3);
    if (tMax <= tMin) tMax = tMin + 1;
    // Time on a log axis: the ground truth costs an order of magnitude more than the rest.
    const double lMin = std::log10(std::max(tMin, 1e-3) / 1.15), lMax = std::log10(tMax * 1.15);
    auto X = [&](double t) { return left + (std::log10(std::max(t, 1e-3)) - lMin) / (lMax - lMin) * (W - left - right); };
    auto Y = [&](double e) {
        const double l = e > 0 ? std::log10(e) : yTop;
        return top + (l - yTop) / (yBottom - yTop) * (H - top - bottom);
    };
    std::ostringstream s;
    s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
    s << "<text x='" << W / 2 << "' y='22' text-anchor='middle' font-size='15'>" << title << "</text>\n";
    s << "<line x1='" << left << "' y1='" << H - bottom << "' x2='" << W - right << "' y2='" << H - bottom
      << "' stroke='black'/>\n<line x1='" << left << "' y1='" << top << "' x2='" << left << "' y2='" << H - bottom
      << "' stroke='black'/>\n";
    for (int k = 0; k <= 4; ++k) {
        const double t = std::pow(10.0, lMin + (lMax - lMin) * k / 4);
        const double e = k == 0 ? 0.0 : std::pow(10.0, yTop + (yBottom - yTop) * k / 4);
        s << "<text x='" << X(t) << "' y='" << H - bottom + 18 << "' text-anchor='middle'>" << fmt(t, 2) << "</text>\n";
        s << "<text x='" << left - 8 << "' y='" << Y(e) + 4 << "' text-anchor='end'>" << fmt(e, 3) << "</text>\n";
    }
    s << "<text x='" << (left + W - right) / 2 << "' y='" << H - 15
      << "' text-anchor='middle'>ms per frame (median of the rounds, log scale)</text>\n";
    s << "<text transform='translate(18," << (top + H - bottom) / 2 << ") rotate(-90)' text-anchor='middle'>"
      << "mean abs error vs SSAA 16 ground truth (levels, log scale; 0 at top)</text>\n";
    // The Pareto front as a line through its points, fastest first.
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (front[i]) idx.push_back(i);
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return rows[a].time.median < rows[b].time.median; });
    s << "<polyline fill='none' stroke='#2a7' stroke-width='2' points='";
    for (std::size_t i : idx) s << X(rows[i].time.median) << "," << Y(rows[i].error.meanAbs) << " ";
    s << "'/>\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        const double x = X(r.time.median), y = Y(r.error.meanAbs);
        const bool named = front[i] || r.setting.preset;
        s << "<circle cx='" << x << "' cy='" << y << "' r='" << (named ? 5 : 3) << "' fill='"
          << (r.setting.preset ? "#c33" : front[i] ? "#2a7" : "#aaa") << "'/>\n";
        // Labels to the right of their point, or to its left near the right edge.
        const bool leftOf = x > W - right - 220;
        if (named)
            s << "<text x='" << (leftOf ? x - 8 : x + 8) << "' y='" << y - 6 << "' text-anchor='"
              << (leftOf ? "end" : "start") << "'>" << label(r.setting, textured)
              << (r.setting.preset ? std::string(" [") + app::qualityName(*r.setting.preset) + "]" : "") << "</text>\n";
    }
    s << "<text x='" << W / 2 << "' y='42' text-anchor='middle'>green: Pareto front; red: the --quality presets; "
      << "grey: the other combinations</text>\n</svg>\n";
    return s.str();
}

Status writeText(const std::string& path, const std::string& text) { return writeFileBytes(path, text.data(), text.size()); }

} // namespace

int runReport(const std::vector<std::string>& args, Streams io) {
    auto parsed = parseCommandArgs(Subcommand::Report, args, io.err);
    if (!parsed) return parsed.exitCode;
    CommandArgs& a = *parsed.args;
    if (a.help) {
        io.out << usage(Subcommand::Report);
        return kExitOk;
    }
    if (const int f = AntiAliasing::supersample(16)->gridSide();
        a.scene.width > FrameBuffer::kMaxDimension / f || a.scene.height > FrameBuffer::kMaxDimension / f) {
        io.err << "softraster report: the ground truth renders 16 samples per pixel (4x4): width and height at most "
               << FrameBuffer::kMaxDimension / f << "\n";
        return kExitUsage;
    }
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::u8path(a.outDir), ec);
    if (ec) {
        io.err << "softraster report: cannot create " << a.outDir << ": " << ec.message() << "\n";
        return kExitFailure;
    }
    auto prepared = prepareScene(a, io.err);
    if (!prepared) return kExitFailure;
    PreparedScene& p = *prepared;
    const bool textured = p.textured;

    const std::vector<Setting> settings = settingsToMeasure(p.settings, textured, p.scene.physical, sceneLobes(p.scene.scene));
    // A rung that drops extensions draws the scene's draws made without them (swapped in for it).
    std::vector<std::pair<unsigned, std::vector<SceneDraw>>> reduced;
    for (const Setting& s : settings)
        if (s.dropped) reduced.emplace_back(s.dropped, withoutLobes(p.scene.scene.draws, s.dropped));
    const auto render = [&](const Setting& s) {
        std::vector<SceneDraw>* swapped = nullptr;
        for (auto& [dropped, draws] : reduced)
            if (dropped == s.dropped) swapped = &draws;
        if (swapped) std::swap(p.scene.scene.draws, *swapped);
        app::renderFrame(p.context, p.scene, p.view, s.settings);
        if (swapped) std::swap(p.scene.scene.draws, *swapped);
    };
    // Images first (the error does not depend on timing), the ground truth first of all.
    std::vector<ImageError> errors(settings.size());
    FrameBuffer truth;
    for (std::size_t k = 0; k < settings.size(); ++k) {
        render(settings[k]);
        if (k == 0) truth = p.framebuffer;
        errors[k] = compareImages(truth, p.framebuffer, true);
    }
    // Timing: rounds, each timing every setting once in turn (interleaved, so a slow spell of a
    // shared machine hits every setting alike); per setting the median, min and max of its
    // per-round medians.
    std::vector<std::vector<double>> perRound(settings.size());
    for (int round = 0; round < a.rounds; ++round)
        for (std::size_t k = 0; k < settings.size(); ++k) {
            if (!a.quiet) {
                io.err << (io.progress ? "\r" : "") << "softraster report: round " << (round + 1) << "/" << a.rounds
                       << " [" << (k + 1) << "/" << settings.size() << "] " << label(settings[k], textured)
                       << (io.progress ? "          " : "\n");
                io.err.flush();
            }
            auto frame = [&] { render(settings[k]); };
            perRound[k].push_back(summarise(timeFrames(a.warmup, a.frames, frame)).median);
        }
    if (!a.quiet && io.progress) io.err << "\n";
    std::vector<Row> rows;
    for (std::size_t k = 0; k < settings.size(); ++k) {
        Row row{settings[k], summarise(perRound[k]), 0.0, errors[k]};
        row.maxMs = *std::max_element(perRound[k].begin(), perRound[k].end());
        rows.push_back(row);
    }

    const std::vector<bool> front = paretoFront(rows);
    const std::string scene = a.scene.obj.empty() ? std::string("built-in scene") : a.scene.obj;
    const std::string machine = std::to_string(std::thread::hardware_concurrency()) + " hardware threads, " +
                                std::to_string(p.threadsUsed) + " render thread" + (p.threadsUsed == 1 ? "" : "s") +
                                ", span kernels " + isaName(p.settings.isa);
    std::ostringstream csv, md;
    csv << "ssaa,msaa,fxaa,filter,shading,persp,ms_median,ms_min,ms_max,mean_abs,psnr_db,ssim,max_abs,differing_share,pareto,preset,"
           "truth\n";
    md << "# SoftRaster quality report\n\n"
       << "Scene: " << scene << ", " << a.scene.width << "x" << a.scene.height << ", "
       << p.scene.scene.triangleCount() << " triangles, cull " << cullModeName(p.settings.cull)
       << (textured ? ", textured" : ", untextured (the texture filter changes nothing and is not varied)") << ". "
       << "Machine: " << machine << ". Time: " << a.rounds << " interleaved rounds, each the median of " << a.frames
       << " frames after " << a.warmup << " warm-up frames per setting; the table gives the median of the rounds "
       << "and their min and max.\n\n"
       << "**Error is measured against the ground truth**: the image with 16 samples per pixel (4x4 supersampling, "
          "each sample shaded) and the most accurate other settings (trilinear filtering, exact perspective, and the "
          "scene's own material model: "
       << (p.scene.physical ? "the glTF metallic-roughness BRDF in linear light" : "Phong shading on display values")
       << "). Mean abs error is per colour channel in levels (0-255); PSNR over R, G, B; SSIM the structural "
          "similarity of Wang et al. 2004 (11x11 Gaussian window, sigma 1.5, per channel, averaged; 1 = the truth). Every "
          "combination of anti-aliasing (1 sample; FXAA: 1 sample, its edges filtered; MSAA 4: coverage and depth per "
          "sample, shaded once per pixel; SSAA 4: 2x2 samples, each shaded) x texture filter (bilinear, trilinear) x "
          "shading (Gouraud, Phong, and pbr in glTF) is measured with exact perspective, and MSAA 8 with "
          "the ground truth's other settings (nearest, affine and flat save too little: they are not measured); a glTF "
          "scene adds pbr on display values and, at one sample, pbr without each material extension it has (clearcoat, "
          "sheen, specular: its materials as if the file had not the extension); the Pareto front (no other combination both "
          "faster and at most as wrong) is marked, and so are the `--quality` presets.\n\n"
       << "| ssaa | msaa | fxaa | filter | shading | persp | ms/frame median [min, max] | mean abs | PSNR dB | SSIM | max abs | "
          "differing pixels | Pareto | preset |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        const RenderSettings& st = r.setting.settings;
        const std::string filter =
            textured ? std::string(filterName(st.filter)) + (st.aniso > 1 ? "+aniso" + std::to_string(st.aniso) : "") : "-";
        const std::string preset = r.setting.preset ? app::qualityName(*r.setting.preset) : "";
        csv << st.antiAliasing.ssaaSamples() << "," << st.antiAliasing.msaaSamples() << ","
            << (st.antiAliasing.postFiltered() ? 1 : 0) << "," << filter << ","
            << shadingOf(r.setting) << "," << perspectiveModeName(st.perspective) << "," << fmt(r.time.median) << ","
            << fmt(r.time.min) << "," << fmt(r.maxMs) << "," << fmt(r.error.meanAbs, 4)
            << "," << fmt(r.error.psnrDb, 2) << "," << fmt(r.error.ssim, 6) << "," << r.error.maxAbs << ","
            << fmt(r.error.differingShare, 5) << ","
            << (front[i] ? 1 : 0) << "," << preset << "," << (r.setting.truth ? 1 : 0) << "\n";
        md << "| " << st.antiAliasing.ssaaSamples() << (r.setting.truth ? " (ground truth)" : "") << " | "
           << st.antiAliasing.msaaSamples() << " | " << (st.antiAliasing.postFiltered() ? "yes" : "") << " | " << filter << " | "
           << shadingOf(r.setting) << " | " << perspectiveModeName(st.perspective) << " | " << fmt(r.time.median)
           << " [" << fmt(r.time.min) << ", " << fmt(r.maxMs) << "] | " << fmt(r.error.meanAbs, 4) << " | "
           << fmt(r.error.psnrDb, 2) << " | " << fmt(r.error.ssim, 6) << " | " << r.error.maxAbs << " | "
           << fmt(100.0 * r.error.differingShare, 2)
           << "% | " << (front[i] ? "yes" : "") << " | " << preset << " |\n";
    }
    md << "\nPlot: `report.svg` (mean abs error against time, the Pareto front and the presets labelled). Depth format "
          "(reversed-Z float32) and sub-pixel precision (8 bits) are fixed by design and have no setting.\n";
    // Where each setting on the front is wrong: its heat map against the truth (rendered again:
    // the images are deterministic).
    const std::string base = a.outDir + "/report";
    md << "\n## Where the error is\n\nPer pixel the largest channel difference d from the ground truth, black (0) "
          "through blue, magenta, orange to white (64 or more), at sqrt(d / 64) (`softraster compare A B --map` draws the "
          "same for any two images):\n\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!front[i] || rows[i].setting.truth) continue;
        render(rows[i].setting);
        const std::string name = "report-map-" + std::to_string(i) + ".png";
        const Status s = writeImage(a.outDir + "/" + name, errorHeatMap(truth, p.framebuffer));
        if (!s) {
            io.err << "softraster report: " << s.error() << "\n";
            return kExitFailure;
        }
        io.out << a.outDir << "/" << name << "\n";
        md << "- " << label(rows[i].setting, textured) << " (" << fmt(rows[i].time.median) << " ms, mean abs "
           << fmt(rows[i].error.meanAbs, 4) << ", SSIM " << fmt(rows[i].error.ssim, 6) << "):\n  ![" << label(rows[i].setting, textured)
           << "](" << name << ")\n";
    }
    for (const auto& [path, text] :
         {std::pair<std::string, std::string>{base + ".csv", csv.str()},
          {base + ".md", md.str()},
          {base + ".svg", svgPlot(rows, front, textured, "SoftRaster: error vs the SSAA 16 ground truth, " + scene)}}) {
        const Status s = writeText(path, text);
        if (!s) {
            io.err << "softraster report: " << s.error() << "\n";
            return kExitFailure;
        }
        io.out << path << "\n";
    }
    return kExitOk;
}

} // namespace sr::headless
