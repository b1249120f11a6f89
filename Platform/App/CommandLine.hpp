// Command-line parsing of the demo program: [model.obj] [scene / quality flags] [--frames N]
// [--screenshot PATH] [--help]. Platform-free and unit-tested.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Platform/App/SceneOptions.hpp"

namespace sr::app {

// Process exit codes shared by every front end.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1; // a model / file that cannot be loaded or written
inline constexpr int kExitUsage = 2;   // bad command line

struct DemoOptions {
    // The scene and quality flags shared with the headless command (SceneOptions.hpp);
    // scene.width / scene.height are the initial CLIENT size in pixels when sizeGiven.
    SceneOptions scene;
    bool sizeGiven = false; // --width or --height given (else the window picks a DPI-scaled size)
    // Exit with kExitOk after this many rendered frames; empty = run until closed.
    std::optional<long long> frames;
    // Save the last frame before exiting (with --frames), or the first frame (without).
    std::optional<std::string> screenshot;
    bool help = false;
};

// The demo's quality without --quality (docs/PERFORMANCE.md: interactive at 960 x 540 on 2 cores).
inline constexpr Quality kDefaultDemoQuality = Quality::Balanced;

// The demo's render threads without --threads: every hardware thread (1 when unknown).
int defaultDemoThreads();

// Either options or a one-line message naming the offending argument.
struct ParseResult {
    bool ok = false;
    DemoOptions options;
    std::string error;
};

// Largest accepted --frames value (about 1 year at 60 Hz: plenty, and far from overflow).
inline constexpr long long kMaxDemoFrames = 2'000'000'000LL;

// Parses the arguments that follow the program name (UTF-8). Accepts one positional model path
// (like --obj), every flag of parseSceneFlag, "--frames N" / "--frames=N" (1 <= N <=
// kMaxDemoFrames), "--screenshot PATH" / "--screenshot=PATH", "--help", "-h" and "/?". Anything else
// is an error, and so is a combination validateSceneOptions refuses.
ParseResult parseCommandLine(const std::vector<std::string>& args);

// The usage text shown by --help and after an error (lines end in '\n'): flags and keys.
std::string usageText(const std::string& programName);

} // namespace sr::app
