// Subcommand flags (on top of the shared scene flags), help texts and scene preparation.
#include "Platform/Headless/CommandArgs.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>

#include "Platform/App/AutoQuality.hpp"

namespace sr::headless {
namespace {

std::optional<int> parseCount(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || errno == ERANGE || v < 0 || v > kMaxTimedFrames) return std::nullopt;
    return int(v);
}

const char* name(Subcommand c) {
    switch (c) {
    case Subcommand::Render: return "render";
    case Subcommand::Bench: return "bench";
    case Subcommand::Report: return "report";
    case Subcommand::None: break;
    }
    return "";
}

} // namespace

std::string usage(Subcommand c) {
    switch (c) {
    case Subcommand::None:
        return "usage: softraster <command> [flags]   (softraster <command> --help for its flags)\n"
               "commands:\n"
               "  render   render a scene to an image (.ppm, .png or .bmp) and optionally its depth (.pfm)\n"
               "  bench    time frames of a scene and print one JSON line (stages, counters)\n"
               "  report   measure every quality setting's time and error; writes report.csv/.md/.svg\n"
               "  compare  the error of one image against another (PSNR, SSIM, ...) and its heat map\n"
               "Without --obj the built-in default scene is used.\n";
    case Subcommand::Render:
        return "usage: softraster render [scene flags] [--out FILE] [--depth-out FILE.pfm] [--quiet]\n"
               "  --out FILE            image to write; the extension picks the format: .ppm .png .bmp\n"
               "                        (default softraster.png); its path is printed on stdout\n"
               "  --depth-out FILE.pfm  depth as window-space [0,1] (0 = near, 1 = far/background, the\n"
               "                        OpenGL convention of the llvmpipe reference), rows bottom-up\n"
               "  --quiet               no diagnostics on stderr\n" +
               app::sceneFlagsHelp();
    case Subcommand::Bench:
        return "usage: softraster bench [scene flags] [--frames N] [--warmup N] [--time-step DT] [--flight SEED] [--out FILE] [--depth-out FILE] [--quiet]\n"
               "  --frames N            timed frames (default 100)\n"
               "  --warmup N            untimed frames first (default 5)\n"
               "  --time-step DT        animate: each frame DT seconds after the one before, from --time\n"
               "                        (default 0: the pose --time gives, or the rest pose); the JSON's\n"
               "                        stages_ms then has \"animate\" (posing the meshes, per frame)\n"
               "  --flight SEED         soak test: each frame from a new seeded random camera pose\n"
               "                        (including eye on a vertex, in a triangle's plane, inside the\n"
               "                        model, looking straight up/down, extreme near/far/fov); prints\n"
               "                        one JSON line with nan_pixels (non-finite depth values over all\n"
               "                        frames), rss_kb_frame_100, rss_kb_end, peak_kb_frame_100,\n"
               "                        peak_kb_end (Linux; -1 elsewhere) and the count of each pose\n"
               "  --out, --depth-out    also write the last frame (as render does)\n"
               "Prints one JSON line: size, triangles, frames, threads, ms_per_frame_median/min/mean,\n"
               "mpix_per_s, stages_ms (clear, transform_clip_cull, setup, fill_shade: from timing\n"
               "partial pipelines; resolve with SSAA/MSAA: its mean, timed around it) and counters (triangles in/rejected/clipped/culled/rasterized, pixels\n"
               "shaded/covered, overdraw). Vertex data is prepared once, before the timed frames.\n" +
               app::sceneFlagsHelp();
    case Subcommand::Report:
        return "usage: softraster report --out-dir DIR [scene flags] [--frames N] [--warmup N] [--rounds N] [--quiet]\n"
               "  --out-dir DIR         where report.csv, report.md, report.svg and the error heat maps of the\n"
               "                        settings on the Pareto front (report-map-N.png) go (created)\n"
               "  --frames N            timed frames per setting and round (default 30)\n"
               "  --warmup N            untimed frames before each setting's timed ones (default 5)\n"
               "  --rounds N            interleaved timing rounds (default 3): median, min and max\n"
               "Renders the ground truth (16 samples per pixel, trilinear, phong, exact) and every\n"
               "combination of anti-aliasing (1 sample, --msaa 4, --ssaa 4) x texture filter x shading\n"
               "(flat, gouraud, phong) x perspective (affine, exact), and --msaa 8; records the time per frame and the error against\n"
               "the ground truth (mean abs error, PSNR, max abs error, share of differing pixels), the\n"
               "Pareto front and the --quality presets. The scene flags fix everything else; width and\n"
               "height at most 2048 (the ground truth renders 4x4 the size).\n" +
               app::sceneFlagsHelp();
    }
    return "";
}

ParsedArgs parseCommandArgs(Subcommand command, const std::vector<std::string>& args, std::ostream& err) {
    ParsedArgs result;
    CommandArgs a;
    if (command == Subcommand::Report) a.frames = 30;
    const std::string prefix = std::string("softraster ") + name(command) + ": ";
    auto fail = [&](const std::string& message) {
        err << prefix << message << "\n";
        result.exitCode = 2;
        return result;
    };
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string error;
        switch (app::parseSceneFlag(args, i, a.scene, error)) {
        case app::FlagResult::Consumed: continue;
        case app::FlagResult::Error: return fail(error);
        case app::FlagResult::NotMine: break;
        }
        std::string flag = args[i];
        std::optional<std::string> value;
        if (const auto eq = flag.find('='); flag.rfind("--", 0) == 0 && eq != std::string::npos) {
            value = flag.substr(eq + 1);
            flag = flag.substr(0, eq);
        }
        auto need = [&]() -> std::optional<std::string> {
            if (value) return value;
            if (i + 1 >= args.size()) return std::nullopt;
            return args[++i];
        };
        const bool render = command == Subcommand::Render, bench = command == Subcommand::Bench,
                   report = command == Subcommand::Report;
        if (flag == "--help" || flag == "-h") {
            a.help = true;
        } else if (flag == "--quiet") {
            a.quiet = true;
        } else if ((render || bench) && (flag == "--out" || flag == "--depth-out")) {
            const auto v = need();
            if (!v || v->empty()) return fail("missing value for " + flag);
            (flag == "--out" ? a.out : a.depthOut) = *v;
        } else if (report && flag == "--out-dir") {
            const auto v = need();
            if (!v || v->empty()) return fail("missing value for --out-dir");
            a.outDir = *v;
        } else if ((bench || report) && (flag == "--frames" || flag == "--warmup")) {
            const auto v = need();
            if (!v) return fail("missing value for " + flag);
            const auto n = parseCount(*v);
            if (!n || (flag == "--frames" && *n < 1))
                return fail("bad value for " + flag + ": '" + *v + "' (expected an integer from " +
                            (flag == "--frames" ? "1" : "0") + " to " + std::to_string(kMaxTimedFrames) + ")");
            (flag == "--frames" ? a.frames : a.warmup) = *n;
        } else if (report && flag == "--rounds") {
            const auto v = need();
            if (!v) return fail("missing value for --rounds");
            const auto n = parseCount(*v);
            if (!n || *n < 1 || *n > 1000)
                return fail("bad value for --rounds: '" + *v + "' (expected an integer from 1 to 1000)");
            a.rounds = *n;
        } else if (bench && flag == "--time-step") {
            const auto v = need();
            if (!v) return fail("missing value for --time-step");
            char* end = nullptr;
            const double dt = std::strtod(v->c_str(), &end);
            if (v->empty() || end != v->c_str() + v->size() || !std::isfinite(dt) || dt < 0.0 || dt > 1e6)
                return fail("bad value for --time-step: '" + *v + "' (expected seconds from 0)");
            a.timeStep = dt;
        } else if (bench && flag == "--flight") {
            const auto v = need();
            if (!v) return fail("missing value for --flight");
            char* end = nullptr;
            errno = 0;
            const unsigned long long seed = std::strtoull(v->c_str(), &end, 10);
            if (v->empty() || (*v)[0] == '-' || end != v->c_str() + v->size() || errno == ERANGE || seed > 0xFFFFFFFFull)
                return fail("bad value for --flight: '" + *v + "' (expected a seed from 0 to 4294967295)");
            a.flightSeed = std::uint32_t(seed);
        } else if (flag.rfind("-", 0) == 0) {
            return fail("unknown flag '" + args[i] + "' (see softraster " + name(command) + " --help)");
        } else {
            return fail("unexpected argument '" + args[i] + "' (see softraster " + name(command) + " --help)");
        }
    }
    if (!a.help) {
        if (command == Subcommand::Report && a.outDir.empty()) return fail("--out-dir DIR is required");
        if (command == Subcommand::Report && a.scene.autoQuality) return fail("--quality auto chooses one setting: report measures them all");
        if (const auto problem = app::validateSceneOptions(a.scene)) return fail(*problem);
    }
    result.args = std::move(a);
    return result;
}

std::unique_ptr<PreparedScene> prepareScene(const CommandArgs& a, std::ostream& err) {
    auto loaded = app::loadScene(a.scene);
    if (!loaded) {
        err << "softraster: " << loaded.error() << "\n";
        return nullptr;
    }
    auto p = std::make_unique<PreparedScene>();
    p->scene = std::move(loaded.value());
    if (!a.quiet) {
        for (const std::string& w : p->scene.warnings) err << "softraster: warning: " << w << "\n";
        err << "softraster: " << p->scene.description << "\n";
    }
    p->options = a.scene;
    if (const auto problem = app::applySceneDefaults(p->options, p->scene)) {
        err << "softraster: " << *problem << "\n";
        return nullptr;
    }
    if (a.scene.time) {
        if (p->scene.animation) app::poseScene(p->scene, *a.scene.time, a.scene.animation.value_or(-1));
        else if (!a.quiet) err << "softraster: note: --time: " << a.scene.obj << " has no animation, skin or morph target\n";
    }
    p->camera = app::resolveCamera(p->options, p->scene);
    if (!a.quiet) err << "softraster: camera: " << app::cameraFlags(p->camera) << "\n";
    p->view = app::makeFrameView(p->camera, a.scene.width, a.scene.height, a.scene.light, p->scene.lights, p->scene.physical);
    p->view.ibl = p->scene.ibl.get();
    p->settings = app::makeRenderSettings(p->options);
    if (!p->framebuffer.resize(a.scene.width, a.scene.height)) {
        err << "softraster: cannot allocate a " << a.scene.width << "x" << a.scene.height << " framebuffer\n";
        return nullptr;
    }
    p->context.setTarget(p->framebuffer);
    // 0 (llvmpipe's "no extra thread") renders on the caller too; more threads than this process
    // may run on at once are not started (they would only take turns).
    const int worth = ThreadPool::threadsWorthStarting(a.scene.threads);
    if (worth < a.scene.threads && !a.quiet)
        err << "softraster: --threads " << a.scene.threads << ": this process may run on " << worth
            << " CPU" << (worth == 1 ? "" : "s") << " at once: rendering with " << worth << " thread" << (worth == 1 ? "" : "s") << "\n";
    p->context.setThreads(worth);
    p->threadsUsed = p->context.threads();
    if (a.scene.wireframe && p->threadsUsed > 1 && !a.quiet)
        err << "softraster: warning: --wireframe draws on one thread (its lines cross the thread bands)\n";
    for (const SceneDraw& d : p->scene.scene.draws) p->textured |= d.texture >= 0;
    p->textured |= p->scene.textureOverride.has_value();
    if (p->options.autoQuality) {
        const app::QualityProbe probe =
            app::probeQuality(p->context, p->scene, p->camera, p->view, p->options, p->settings, p->textured);
        const app::SceneOptions& o = p->options;
        const int k = o.maxError ? app::chooseForError(probe.points, *o.maxError)
                                 : app::chooseForBudget(probe.points, o.budgetMs.value_or(1000.0 / 60.0));
        QualityChoice c;
        c.settings = probe.settings[std::size_t(k)];
        c.label = app::settingLabel(c.settings, p->textured);
        c.ms = probe.points[std::size_t(k)].ms;
        c.error = probe.points[std::size_t(k)].error;
        c.candidates = int(probe.points.size());
        c.probeSeconds = probe.seconds;
        p->settings = c.settings;
        if (!a.quiet) {
            char line[320];
            std::snprintf(line, sizeof line, "quality auto (%s %g): %s: %.3f ms a frame, error %.5f (1 - SSIM); probed %d settings in %.2f s",
                          p->options.maxError ? "--max-error" : "--budget-ms",
                          p->options.maxError ? *p->options.maxError : p->options.budgetMs.value_or(1000.0 / 60.0), c.label.c_str(), c.ms,
                          c.error, c.candidates, c.probeSeconds);
            err << "softraster: " << line << "\n";
        }
        p->autoQuality = c;
        p->autoProbe = probe;
    }
    return p;
}

} // namespace sr::headless
