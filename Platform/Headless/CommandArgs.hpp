// Argument parsing and scene preparation shared by the headless subcommands.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Platform/App/AutoQuality.hpp"
#include "Raster/Frame/RenderContext.hpp"

namespace sr::headless {

enum class Subcommand { None, Render, Bench, Report };

struct CommandArgs {
    app::SceneOptions scene;
    std::string out;      // render/bench: colour image (.ppm/.png/.bmp)
    std::string depthOut; // render/bench: depth PFM
    std::string outDir;   // report
    int frames = 100;     // bench default; report uses its own default
    int warmup = 5;
    int rounds = 3;       // report: interleaved timing rounds
    std::optional<std::uint32_t> flightSeed; // bench --flight SEED: the soak flight (Flight.hpp)
    double timeStep = 0.0; // bench --time-step DT: each frame (warm-up included) DT seconds after the last (--time: the first)
    bool quiet = false;
    bool help = false;
};

// Largest accepted --frames / --warmup of bench and report (timed frames; the demo's --frames,
// frames to run before exiting, has its own limit: kMaxDemoFrames).
inline constexpr int kMaxTimedFrames = 1000000;

struct ParsedArgs {
    std::optional<CommandArgs> args;
    int exitCode = 0; // when args is empty: 2 (usage error, already reported on err)
    explicit operator bool() const { return args.has_value(); }
};

// Parses a subcommand's arguments; errors are one line on `err` naming the flag and value.
ParsedArgs parseCommandArgs(Subcommand command, const std::vector<std::string>& args, std::ostream& err);

// The help text of a subcommand (None: the overview).
std::string usage(Subcommand command);

// A loaded scene with its framebuffer, context, view and settings, ready to render.
// What --quality auto chose (Platform/App/AutoQuality.hpp: the probe and the rules).
struct QualityChoice {
    RenderSettings settings;
    std::string label;
    double ms = 0.0;      // its median frame time in the probe (the scene's size and threads)
    double error = 0.0;   // 1 - SSIM against the ground truth, at half the size
    int candidates = 0;
    double probeSeconds = 0.0;
};

struct PreparedScene {
    app::LoadedScene scene;
    app::SceneOptions options; // the flags with the scene's own defaults applied (applySceneDefaults)
    app::CameraSetup camera;
    FrameView view;
    RenderSettings settings;
    FrameBuffer framebuffer;
    RenderContext context{framebuffer};
    int threadsUsed = 1;
    bool textured = false;
    std::optional<QualityChoice> autoQuality; // --quality auto's choice (then in `settings`)
    app::QualityProbe autoProbe;               // and what it chose from (a flight follows the budget with it)
};

// Loads the scene, resolves the camera (printed on err as flags, like the reference), builds
// the framebuffer. Errors (unreadable model/texture, a shading model the scene cannot have) are
// reported on err; returns null then.
std::unique_ptr<PreparedScene> prepareScene(const CommandArgs& args, std::ostream& err);

} // namespace sr::headless
