// sr_shading_bench: time of the default scene per shading mode, specialised drawMesh pipelines vs the general one-pipeline path.
//
// Usage: sr_shading_bench [frames (default 60)] [width height (default 800 600)]
// Single-threaded (the renderer has no threads yet). Per mode: warm-up frames, then `frames`
// frames alternating specialised / general (so drift of the machine's speed hits both alike),
// each timed on its own; the table shows the medians and general / specialised.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "../GeneralRenderer.hpp"
#include "Platform/App/SceneSetup.hpp"

using namespace sr;

namespace {

double medianOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

} // namespace

int main(int argc, char** argv) {
    const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 60;
    app::SceneOptions options;
    if (argc > 3) {
        options.width = std::clamp(std::atoi(argv[2]), 1, FrameBuffer::kMaxDimension);
        options.height = std::clamp(std::atoi(argv[3]), 1, FrameBuffer::kMaxDimension);
    }
    constexpr int kWarmup = 5;

    auto loaded = app::loadScene(options);
    if (!loaded.ok()) {
        std::fprintf(stderr, "sr_shading_bench: %s\n", loaded.error().c_str());
        return 1;
    }
    loaded.value().scene = test::opaqueOnly(std::move(loaded.value().scene)); // the general renderer's scenes
    const app::LoadedScene& scene = loaded.value();
    const FrameView view = app::makeFrameView(app::resolveCamera(options, scene), options.width, options.height,
                                               options.light, scene.lights);
    FrameBuffer special(options.width, options.height), general(options.width, options.height);
    RenderContext cs(special), cg(general);

    std::printf("sr_shading_bench: default scene (%zu triangles), %dx%d, %d frames per path after %d warm-up, "
                "renderer threads 1 (machine: %u hardware threads)\n",
                scene.scene.triangleCount(), options.width, options.height, frames, kWarmup,
                std::thread::hardware_concurrency());
    std::printf("%-8s %10s %16s %14s %8s %10s\n", "mode", "varyings", "specialised ms", "general ms", "speed-up",
                "same img");
    using Clock = std::chrono::steady_clock;
    // Untextured/textured, vs 14 in the general path (Gouraud: six RGB terms under the built-in
    // scene's coloured fill light).
    const char* varyings[] = {"0/2", "0/2", "6/8", "6/8"};
    int m = 0;
    for (ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong}) {
        RenderSettings settings = app::makeRenderSettings(options);
        settings.shading = mode;
        auto drawSpecial = [&] { app::renderFrame(cs, scene, view, settings); };
        auto drawGeneral = [&] {
            general.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
            test::renderSceneGeneral(cg, scene.scene, view, settings,
                                     scene.textureOverride ? &*scene.textureOverride : nullptr);
        };
        for (int i = 0; i < kWarmup; ++i) {
            drawSpecial();
            drawGeneral();
        }
        std::vector<double> ts, tg;
        for (int i = 0; i < frames; ++i) {
            // Alternate which path goes first, so neither always runs on the other's cache state.
            const bool specialFirst = i % 2 == 0;
            auto t0 = Clock::now();
            specialFirst ? drawSpecial() : drawGeneral();
            auto t1 = Clock::now();
            specialFirst ? drawGeneral() : drawSpecial();
            auto t2 = Clock::now();
            const double first = std::chrono::duration<double, std::milli>(t1 - t0).count();
            const double second = std::chrono::duration<double, std::milli>(t2 - t1).count();
            ts.push_back(specialFirst ? first : second);
            tg.push_back(specialFirst ? second : first);
        }
        long differing = 0;
        for (int y = 0; y < special.height(); ++y)
            for (int x = 0; x < special.width(); ++x) differing += special.pixel(x, y) != general.pixel(x, y);
        const double ms = medianOf(ts), mg = medianOf(tg);
        std::printf("%-8s %7s/10 %16.2f %14.2f %7.2fx %10s\n", shadingModeName(mode), varyings[m++], ms, mg, mg / ms,
                    differing == 0 ? "yes" : "NO");
    }
    return 0;
}
