// SoftRaster.exe entry point: command line, scene loading, DPI awareness, and the never-blocking
// message loop (with --frames / --screenshot for scripts).
#include "Platform/App/CommandLine.hpp"
#include "Platform/App/DemoController.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "Platform/Win32/Console.hpp"
#include "Platform/Win32/Dpi.hpp"
#include "Platform/Win32/MainWindow.hpp"
#include "Platform/Win32/Win32Include.hpp"

#include <algorithm>

namespace {

constexpr int kDefaultClientWidth = 960; // at 96 DPI; scaled by the monitor's DPI
constexpr int kDefaultClientHeight = 540;

// An error for the user: stderr (scripts, consoles) and a message box (Explorer users).
void reportError(const std::string& message) {
    sr::win32::writeStderr(message);
    sr::win32::showMessageBox(message, /*isError=*/true);
}

// Pumps every pending message. Returns false once WM_QUIT arrives (exitCode is then its value).
bool pumpMessages(int& exitCode) {
    MSG msg;
    while (PeekMessageW(&msg, nullptr, 0, 0, PM_REMOVE)) {
        if (msg.message == WM_QUIT) {
            exitCode = int(msg.wParam);
            return false;
        }
        TranslateMessage(&msg);
        DispatchMessageW(&msg);
    }
    return true;
}

// Renders as fast as messages allow; sleeps in WaitMessage while there is nothing to draw
// (minimised / 0 x 0), so a hidden demo costs no CPU. With --frames N it stops after N rendered
// frames (exit code 0 like a user close); --screenshot saves the last frame before that, or the
// first frame when the demo runs until closed.
int runMessageLoop(sr::win32::MainWindow& window, const sr::app::DemoOptions& options) {
    using namespace sr;
    int exitCode = app::kExitOk;
    const long long maxFrames = options.frames.value_or(0);
    long long frames = 0;
    for (;;) {
        if (window.exists() && window.idle())
            WaitMessage();
        if (!pumpMessages(exitCode))
            return exitCode;
        if (!window.exists() || window.idle())
            continue;
        window.renderFrame();
        ++frames;
        const bool last = maxFrames > 0 && frames >= maxFrames;
        if (options.screenshot && (last || (maxFrames == 0 && frames == 1))) {
            const Status saved = window.saveFrame(*options.screenshot);
            if (!saved) {
                win32::writeStderr("SoftRaster: could not save the screenshot: " + saved.error() + "\n");
                if (last) {
                    window.close();
                    pumpMessages(exitCode);
                    return app::kExitFailure;
                }
            } else {
                win32::writeStdout("SoftRaster: saved " + *options.screenshot + "\n");
            }
        }
        if (last)
            window.close(); // WM_DESTROY posts WM_QUIT(0)
    }
}

} // namespace

int WINAPI wWinMain(HINSTANCE instance, HINSTANCE, PWSTR, int showCommand) {
    using namespace sr;
    const app::ParseResult parsed = app::parseCommandLine(win32::commandLineArguments());
    if (!parsed.ok) {
        reportError("SoftRaster: " + parsed.error + "\n" + app::usageText("SoftRaster.exe"));
        return app::kExitUsage;
    }
    app::DemoOptions options = parsed.options; // applySceneDefaults completes it
    if (options.help) {
        const std::string text = app::usageText("SoftRaster.exe");
        if (!win32::writeStdout(text))
            win32::showMessageBox(text, /*isError=*/false);
        return app::kExitOk;
    }

    // The scene (built-in or the OBJ) and the camera it asks for: a failure names the file.
    Result<app::LoadedScene> loaded = app::loadScene(options.scene);
    if (!loaded) {
        reportError("SoftRaster: cannot load the scene: " + loaded.error() + "\n");
        return app::kExitFailure;
    }
    app::LoadedScene& scene = loaded.value();
    for (const std::string& warning : scene.warnings)
        win32::writeStderr("SoftRaster: warning: " + warning + "\n");
    if (const auto problem = app::applySceneDefaults(options.scene, scene)) {
        reportError("SoftRaster: " + *problem + "\n");
        return app::kExitFailure;
    }

    // The fly camera starts at the resolved eye / target; a model's speed follows its size
    // (half its bounding radius per second), the built-in scene's is the tuned default.
    const app::CameraSetup setup = app::resolveCamera(options.scene, scene);
    app::MotionTuning tuning;
    if (!scene.builtIn)
        tuning.moveSpeed = float(std::max(scene.radius * 0.5, 1e-3));
    app::DemoController controller(setup, app::makeRenderSettings(options.scene),
                                    options.scene.light, tuning);
    controller.setCameras(scene.cameras); // V cycles through the model's own cameras
    controller.setLights(scene.lights);
    controller.setPhysicalLights(scene.physical);
    controller.setImageLight(scene.ibl.get());
    if (scene.animation) // plays from --time (or 0), every clip or --animation N's
        controller.setAnimation(scene.animation->duration(options.scene.animation.value_or(-1)), options.scene.time.value_or(0.0),
                                options.scene.animation.value_or(-1));

    if (options.scene.autoQuality) {
        // --quality auto: the probe at the size the window will have (its default when no size
        // was given), before the window exists; the budget defaults to the display's refresh.
        const int w = options.sizeGiven ? options.scene.width : kDefaultClientWidth;
        const int h = options.sizeGiven ? options.scene.height : kDefaultClientHeight;
        FrameBuffer probeFrame(w, h);
        RenderContext probeContext(probeFrame);
        probeContext.setThreads(ThreadPool::threadsWorthStarting(options.scene.threads));
        const FrameView view = app::makeFrameView(setup, w, h, options.scene.light, scene.lights, scene.physical, scene.ibl.get());
        bool textured = scene.textureOverride.has_value();
        for (const SceneDraw& d : scene.scene.draws) textured |= d.texture >= 0;
        const app::QualityProbe probe = app::probeQuality(probeContext, scene, setup, view, options.scene,
                                                          app::makeRenderSettings(options.scene), textured);
        double budget = 1000.0 / 60.0;
        if (HDC screen = GetDC(nullptr)) {
            const int hz = GetDeviceCaps(screen, VREFRESH); // 0 or 1: the hardware default, unknown
            ReleaseDC(nullptr, screen);
            if (hz >= 24) budget = 1000.0 / hz;
        }
        controller.setAutoQuality(probe, options.scene.budgetMs.value_or(budget), textured);
    }

    win32::enableDpiAwareness(); // before any window exists
    win32::MainWindow window(scene, controller);
    window.setThreads(ThreadPool::threadsWorthStarting(options.scene.threads)); // more would take turns on the CPUs
    // K: the model's material variants in turn, then its own materials again; each a reload of
    // the file with --variant set (the geometry, cameras and lights are the same).
    if (!scene.variants.empty()) {
        std::size_t shown = 0; // 0: the file's own materials; k: variant k - 1
        for (std::size_t k = 0; k < scene.variants.size(); ++k)
            if (scene.variants[k] == options.scene.variant) shown = k + 1;
        window.setVariantCycler(
            [&options, &scene, &controller, &window, shown]() mutable -> std::string {
                const std::size_t next = (shown + 1) % (scene.variants.size() + 1);
                app::SceneOptions o = options.scene;
                o.variant = next == 0 ? std::string() : scene.variants[next - 1];
                Result<app::LoadedScene> reloaded = app::loadScene(o);
                if (!reloaded) return "variant: " + reloaded.error();
                if (const auto problem = app::applySceneDefaults(o, reloaded.value())) return "variant: " + *problem;
                scene = std::move(reloaded.value());
                controller.setImageLight(scene.ibl.get());
                shown = next;
                window.setVariantName(o.variant);
                return o.variant.empty() ? std::string("the model's own materials") : "material variant " + o.variant;
            },
            options.scene.variant);
    }
    const bool created = options.sizeGiven
                             ? window.create(instance, showCommand, options.scene.width, options.scene.height, false)
                             : window.create(instance, showCommand, kDefaultClientWidth, kDefaultClientHeight, true);
    if (!created) {
        reportError("SoftRaster: could not create the window (error " + std::to_string(GetLastError()) + ")\n");
        return app::kExitFailure;
    }
    return runMessageLoop(window, options);
}
