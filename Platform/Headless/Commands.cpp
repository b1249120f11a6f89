// `softraster render` and `softraster bench` (their arguments: CommandArgs.cpp), and the dispatch to them and to report.
#include "Platform/Headless/Commands.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <thread>

#include "Platform/Headless/CommandArgs.hpp"
#include "Platform/Headless/Flight.hpp"
#include "Platform/Headless/ImageCompare.hpp"
#include "Platform/Headless/Json.hpp"
#include "Platform/Headless/Timing.hpp"
#include "Raster/Frame/ShadowPass.hpp"
#include "Resources/Image.hpp"

namespace sr::headless {
namespace {

// Window-space depth in the reference renderer's convention (GL: 0 = near, 1 = far and
// background): our reversed-Z z_ndc = n/(f-n) (f/d - 1) and GL's (z_ndc+1)/2 = f/(f-n) (1 - n/d)
// add up to exactly 1, so the GL value is 1 - z.
std::vector<float> referenceDepth(const FrameBuffer& fb) {
    std::vector<float> d(std::size_t(fb.width()) * std::size_t(fb.height()));
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = 1.0f - fb.depthData()[i];
    return d;
}

int writeOutputs(const CommandArgs& a, const FrameBuffer& fb, Streams io) {
    if (!a.out.empty()) {
        const Status s = writeImage(a.out, toImage(fb));
        if (!s) {
            io.err << "softraster: " << s.error() << "\n";
            return kExitFailure;
        }
        io.out << a.out << "\n";
    }
    if (!a.depthOut.empty()) {
        const std::vector<float> depth = referenceDepth(fb);
        const Status s = writePfm(a.depthOut, fb.width(), fb.height(), depth.data());
        if (!s) {
            io.err << "softraster: " << s.error() << "\n";
            return kExitFailure;
        }
        if (!a.quiet) io.err << "softraster: wrote depth " << a.depthOut << "\n";
    }
    return kExitOk;
}

} // namespace

int runRender(const std::vector<std::string>& args, Streams io) {
    auto parsed = parseCommandArgs(Subcommand::Render, args, io.err);
    if (!parsed) return parsed.exitCode;
    CommandArgs& a = *parsed.args;
    if (a.help) {
        io.out << usage(Subcommand::Render);
        return kExitOk;
    }
    if (a.out.empty()) a.out = "softraster.png";
    auto prepared = prepareScene(a, io.err);
    if (!prepared) return kExitFailure;
    PreparedScene& p = *prepared;
    app::renderFrame(p.context, p.scene, p.view, p.settings);
    return writeOutputs(a, p.framebuffer, io);
}

int runBench(const std::vector<std::string>& args, Streams io) {
    auto parsed = parseCommandArgs(Subcommand::Bench, args, io.err);
    if (!parsed) return parsed.exitCode;
    CommandArgs& a = *parsed.args;
    if (a.help) {
        io.out << usage(Subcommand::Bench);
        return kExitOk;
    }
    auto prepared = prepareScene(a, io.err);
    if (!prepared) return kExitFailure;
    PreparedScene& p = *prepared;
    if (a.flightSeed) {
        std::ostringstream discard;
        const int rc = runFlight(a, p, *a.flightSeed, Streams{discard, io.err, false});
        if (rc != kExitOk) return rc;
        if (const int wrc = writeOutputs(a, p.framebuffer, Streams{discard, io.err, false}); wrc != kExitOk) return wrc;
        io.out << discard.str().substr(0, discard.str().find('\n') + 1); // the JSON line, last on stdout
        return kExitOk;
    }
    RenderSettings settings = p.settings;

    // Whole frames: clear + every draw, as a real program renders them; an animated scene with
    // --time-step posed first, each frame at the next time.
    const bool animating = p.scene.animation && a.timeStep > 0.0;
    const int clip = a.scene.animation.value_or(-1);
    double now = a.scene.time.value_or(0.0);
    auto frame = [&] {
        if (animating) {
            app::poseScene(p.scene, now, clip);
            now += a.timeStep;
            if (!p.scene.lights.empty()) p.view.lighting.lights = p.scene.lights; // animated lights (KHR_animation_pointer)
        }
        app::renderFrame(p.context, p.scene, p.view, settings);
    };
    p.context.stats = {};
    const TimingSummary full = summarise(timeFrames(a.warmup, a.frames, frame));
    const double resolveMs = p.context.stats.resolveMs / double(a.warmup + a.frames); // mean per frame
    p.context.stats = {};
    frame(); // one more frame for the counters and the output image
    const RenderStats counters = p.context.stats;
    std::int64_t covered = 0;
    for (int i = 0, n = p.framebuffer.width() * p.framebuffer.height(); i < n; ++i)
        covered += p.framebuffer.depthData()[i] != FrameBuffer::kFarDepth;

    // Per-stage breakdown by difference of partial pipelines (no timers inside the hot loops):
    // clear only; + vertex/clip/cull; + binning (several threads); + setup; the full frame above.
    const int stageFrames = std::max(5, a.frames / 4);
    const TimingSummary clearOnly =
        summarise(timeFrames(1, stageFrames, [&] { p.framebuffer.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth); }));
    settings.stopAfter = PipelineStop::Geometry;
    const TimingSummary geometry = summarise(timeFrames(1, stageFrames, frame));
    // Binning: only draws spread over several threads are binned (Raster/Setup/Binning.hpp).
    const bool bins = p.threadsUsed > 1;
    TimingSummary binned = geometry;
    if (bins) {
        settings.stopAfter = PipelineStop::Bin;
        binned = summarise(timeFrames(1, stageFrames, frame));
    }
    settings.stopAfter = PipelineStop::Setup;
    const TimingSummary setup = summarise(timeFrames(1, stageFrames, frame));
    settings.stopAfter = PipelineStop::Fill;
    // The sky (a pass of its own after the draws): the full frame without it, the difference.
    TimingSummary noSky = full;
    if (p.scene.scene.sky.on()) {
        const Sky sky = p.scene.scene.sky;
        p.scene.scene.sky = Sky{};
        noSky = summarise(timeFrames(1, stageFrames, frame));
        p.scene.scene.sky = sky;
    }
    // The shadow pass (the lights' depth-only maps; only with --shadows), timed on its own: the
    // full frame runs it first, the partial pipelines do not.
    TimingSummary shadowPass{};
    if (settings.shadows.on) {
        SceneShadows maps;
        shadowPass = summarise(timeFrames(1, stageFrames, [&] {
            renderShadowMaps(p.context, p.scene.scene, p.view, settings.shadows, maps);
        }));
    }
    // Posing alone (morph targets, skins, node transforms into the meshes).
    TimingSummary animate{};
    if (animating) animate = summarise(timeFrames(1, stageFrames, [&] { app::poseScene(p.scene, now += a.timeStep, clip); }));
    frame(); // leave the full image in the framebuffer for --out

    auto positive = [](double v) { return std::max(v, 0.0); };
    const double pixels = double(a.scene.width) * double(a.scene.height);
    std::string j = "{\"renderer\":\"softraster\"";
    j += ",\"width\":" + std::to_string(a.scene.width) + ",\"height\":" + std::to_string(a.scene.height);
    j += ",\"triangles\":" + std::to_string(p.scene.scene.triangleCount());
    j += ",\"frames\":" + std::to_string(a.frames) + ",\"warmup\":" + std::to_string(a.warmup);
    j += ",\"threads\":" + std::to_string(p.threadsUsed);
    j += ",\"ms_per_frame_median\":" + jsonNumber(full.median);
    j += ",\"ms_per_frame_min\":" + jsonNumber(full.min);
    j += ",\"ms_per_frame_mean\":" + jsonNumber(full.mean);
    j += ",\"mpix_per_s\":" + jsonNumber(full.median > 0 ? pixels / (full.median * 1000.0) : 0.0);
    j += ",\"stages_ms\":{\"clear\":" + jsonNumber(clearOnly.median);
    j += ",\"transform_clip_cull\":" + jsonNumber(positive(geometry.median - clearOnly.median - animate.median));
    if (bins) j += ",\"binning\":" + jsonNumber(positive(binned.median - geometry.median));
    j += ",\"setup\":" + jsonNumber(positive(setup.median - binned.median));
    const bool resolves = settings.antiAliasing.samples() > 1 || settings.antiAliasing.postFiltered(); // FXAA: its pass
    j += ",\"fill_shade\":" + jsonNumber(positive(noSky.median - setup.median - shadowPass.median - (resolves ? resolveMs : 0.0)));
    if (resolves) j += ",\"resolve\":" + jsonNumber(resolveMs);
    if (settings.shadows.on) j += ",\"shadow_pass\":" + jsonNumber(shadowPass.median);
    if (p.scene.scene.sky.on()) j += ",\"sky\":" + jsonNumber(positive(full.median - noSky.median));
    if (animating) j += ",\"animate\":" + jsonNumber(animate.median);
    j += "}";
    j += ",\"counters\":{\"vertices_transformed\":" + std::to_string(counters.verticesTransformed);
    j += ",\"triangles_in\":" + std::to_string(counters.trianglesIn);
    j += ",\"trivially_rejected\":" + std::to_string(counters.trivialRejected);
    j += ",\"clipped\":" + std::to_string(counters.clipped);
    j += ",\"culled\":" + std::to_string(counters.culled);
    j += ",\"rasterized\":" + std::to_string(counters.rasterized);
    j += ",\"triangles_set_up\":" + std::to_string(counters.setupsBuilt);
    j += ",\"pixels_shaded\":" + std::to_string(counters.fragmentsShaded);
    j += ",\"pixels_covered\":" + std::to_string(covered);
    j += ",\"triangles_sorted\":" + std::to_string(counters.trianglesSorted);
    j += ",\"overdraw\":" + jsonNumber(covered > 0 ? double(counters.fragmentsShaded) / double(covered) : 0.0) + "}";
    j += ",\"shading\":\"" + std::string(shadingModeName(settings.shading)) + "\"";
    j += ",\"cull\":\"" + std::string(cullModeName(settings.cull)) + "\"";
    j += ",\"filter\":\"" + std::string(filterName(settings.filter)) + "\"";
    j += ",\"aniso\":" + std::to_string(settings.aniso);
    j += ",\"persp\":\"" + std::string(perspectiveModeName(settings.perspective)) + "\"";
    j += ",\"isa\":\"" + std::string(isaName(settings.isa)) + "\"";
    j += ",\"ssaa\":" + std::to_string(settings.antiAliasing.ssaaSamples());
    j += ",\"msaa\":" + std::to_string(settings.antiAliasing.msaaSamples());
    j += std::string(",\"fxaa\":") + (settings.antiAliasing.postFiltered() ? "true" : "false");
    j += ",\"textured\":" + std::string(p.textured ? "true" : "false");
    if (p.autoQuality) {
        j += ",\"quality_auto\":{\"setting\":\"" + p.autoQuality->label + "\",\"probe_ms\":" + jsonNumber(p.autoQuality->ms) +
             ",\"error\":" + jsonNumber(p.autoQuality->error) + ",\"candidates\":" + std::to_string(p.autoQuality->candidates) +
             ",\"probe_s\":" + jsonNumber(p.autoQuality->probeSeconds);
        // What it chose from, in probe order: each candidate's probed time and error.
        j += ",\"probed\":[";
        for (std::size_t k = 0; k < p.autoProbe.points.size(); ++k)
            j += std::string(k ? "," : "") + "{\"setting\":\"" + app::settingLabel(p.autoProbe.settings[k], p.textured) +
                 "\",\"ms\":" + jsonNumber(p.autoProbe.points[k].ms) + ",\"error\":" + jsonNumber(p.autoProbe.points[k].error) + "}";
        j += "]}";
    }
    if (!p.scene.builtIn)
        j += ",\"load_ms\":" + jsonNumber(p.scene.loadMs) + ",\"load\":{\"triangles\":" + std::to_string(p.scene.loadedTriangles) +
             ",\"texels\":" + std::to_string(p.scene.loadedTexels) + "}";
    j += ",\"hardware_threads\":" + std::to_string(std::thread::hardware_concurrency()) + "}";

    // The image (if asked) goes first so that stdout's last line is the JSON.
    CommandArgs imageArgs = a;
    std::ostringstream discard;
    Streams quietIo{discard, io.err, false};
    if (const int rc = writeOutputs(imageArgs, p.framebuffer, quietIo); rc != kExitOk) return rc;
    io.out << j << "\n";
    return kExitOk;
}

int runCompare(const std::vector<std::string>& args, Streams io) {
    static const char* const kUsage =
        "usage: softraster compare A B [--map OUT.png] [--quiet]\n"
        "  A, B                  two images of one size (.png .ppm .bmp .tga .jpg), A the reference\n"
        "  --map OUT.png         write the error heat map: per pixel the largest channel difference d,\n"
        "                        black (0) through blue, magenta, orange to white (d >= 64), at sqrt(d / 64)\n"
        "  --quiet               no diagnostics on stderr\n"
        "Prints one JSON line: width, height, mean_abs (levels per channel), psnr_db, max_abs,\n"
        "differing_pixels, differing_share, ssim (Wang et al. 2004: 11x11 Gaussian window of sigma 1.5,\n"
        "per R, G, B channel, averaged; 1 = identical).\n";
    std::vector<std::string> files;
    std::string map;
    bool quiet = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--help" || args[i] == "-h") {
            io.out << kUsage;
            return kExitOk;
        }
        if (args[i] == "--quiet") {
            quiet = true;
        } else if (args[i] == "--map" || args[i].rfind("--map=", 0) == 0) {
            if (args[i] == "--map") {
                if (i + 1 >= args.size() || args[i + 1].empty()) {
                    io.err << "softraster compare: missing value for --map\n";
                    return kExitUsage;
                }
                map = args[++i];
            } else {
                map = args[i].substr(6);
            }
        } else if (args[i].rfind("-", 0) == 0 && args[i].size() > 1) {
            io.err << "softraster compare: unknown flag '" << args[i] << "' (see softraster compare --help)\n";
            return kExitUsage;
        } else {
            files.push_back(args[i]);
        }
    }
    if (files.size() != 2) {
        io.err << "softraster compare: expected two images, got " << files.size() << " (see softraster compare --help)\n";
        return kExitUsage;
    }
    Image images[2];
    for (int k = 0; k < 2; ++k) {
        auto img = loadImage(files[std::size_t(k)]);
        if (!img) {
            io.err << "softraster compare: " << img.error() << "\n";
            return kExitFailure;
        }
        images[k] = std::move(img).value();
    }
    if (images[0].width != images[1].width || images[0].height != images[1].height) {
        io.err << "softraster compare: " << files[0] << " is " << images[0].width << "x" << images[0].height << ", " << files[1]
               << " is " << images[1].width << "x" << images[1].height << ": the images must be the same size\n";
        return kExitFailure;
    }
    const FrameBuffer a = frameOf(images[0]), b = frameOf(images[1]);
    const ImageError e = compareImages(a, b, true);
    if (!map.empty()) {
        const Status s = writeImage(map, errorHeatMap(a, b));
        if (!s) {
            io.err << "softraster compare: " << s.error() << "\n";
            return kExitFailure;
        }
        if (!quiet) io.err << "softraster compare: wrote the error map " << map << "\n";
    }
    std::string j = "{\"width\":" + std::to_string(images[0].width) + ",\"height\":" + std::to_string(images[0].height);
    j += ",\"mean_abs\":" + jsonNumber(e.meanAbs) + ",\"psnr_db\":" + jsonNumber(e.psnrDb);
    j += ",\"max_abs\":" + std::to_string(e.maxAbs) + ",\"differing_pixels\":" + std::to_string(e.differing);
    char ssim[32];
    std::snprintf(ssim, sizeof ssim, "%.6f", e.ssim); // finer than jsonNumber: near 1 the digits matter
    j += ",\"differing_share\":" + jsonNumber(e.differingShare) + ",\"ssim\":" + ssim + "}";
    io.out << j << "\n";
    return kExitOk;
}

int runHeadless(const std::vector<std::string>& args, Streams io) {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        (args.empty() ? io.err : io.out) << usage(Subcommand::None);
        return args.empty() ? kExitUsage : kExitOk;
    }
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (args[0] == "render") return runRender(rest, io);
    if (args[0] == "bench") return runBench(rest, io);
    if (args[0] == "report") return runReport(rest, io);
    if (args[0] == "compare") return runCompare(rest, io);
    io.err << "softraster: unknown command '" << args[0] << "' (expected render, bench, report or compare; see --help)\n";
    return kExitUsage;
}

} // namespace sr::headless
