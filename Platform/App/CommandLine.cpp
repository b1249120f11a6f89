// Command-line parsing of the demo program: strict, with messages that name the bad value.
#include "Platform/App/CommandLine.hpp"

#include <algorithm>
#include <cctype>
#include <thread>

#include "Platform/App/Input.hpp"

namespace sr::app {

namespace {

// Parses a whole string as a decimal integer in [1, kMaxDemoFrames]; no sign, no spaces, no suffix.
std::optional<long long> parseFrameCount(const std::string& text) {
    if (text.empty() || text.size() > 10)
        return std::nullopt;
    long long value = 0;
    for (const char c : text) {
        if (!std::isdigit(static_cast<unsigned char>(c)))
            return std::nullopt;
        value = value * 10 + (c - '0');
    }
    if (value < 1 || value > kMaxDemoFrames)
        return std::nullopt;
    return value;
}

ParseResult failure(std::string message) {
    ParseResult r;
    r.error = std::move(message);
    return r;
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// "--name VALUE" or "--name=VALUE": the value (advancing i past it), or nullopt when arg is
// another flag. A missing value is reported through `missing`.
std::optional<std::string> valueOf(const std::vector<std::string>& args, std::size_t& i, const std::string& name,
                                   bool& missing) {
    const std::string& arg = args[i];
    if (arg == name) {
        if (i + 1 >= args.size()) {
            missing = true;
            return std::nullopt;
        }
        return args[++i];
    }
    if (startsWith(arg, (name + "=").c_str()))
        return arg.substr(name.size() + 1);
    return std::nullopt;
}

} // namespace

ParseResult parseCommandLine(const std::vector<std::string>& args) {
    ParseResult result;
    DemoOptions& o = result.options;
    bool modelGiven = false, threadsGiven = false, shadowsGiven = false;
    // The demo shows the gradient sky unless --sky none or --skybox DIR say otherwise (the
    // headless command keeps the black background, as the reference renderer draws it).
    o.scene.sky = Sky::Kind::Gradient;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--help" || arg == "-h" || arg == "/?") {
            o.help = true;
            continue;
        }
        if (arg.empty())
            return failure("empty argument");

        bool missing = false;
        if (const auto value = valueOf(args, i, "--frames", missing); value || missing) {
            if (missing)
                return failure("--frames needs a value: --frames N (N >= 1)");
            if (o.frames)
                return failure("--frames given twice");
            const std::optional<long long> n = parseFrameCount(*value);
            if (!n)
                return failure("bad value for --frames: '" + *value + "' (expected an integer from 1 to " +
                               std::to_string(kMaxDemoFrames) + ")");
            o.frames = n;
            continue;
        }
        if (const auto value = valueOf(args, i, "--screenshot", missing); value || missing) {
            if (missing || value->empty())
                return failure("--screenshot needs a file path: --screenshot PATH (.png, .bmp or .ppm)");
            o.screenshot = *value;
            continue;
        }

        // A positional argument is the model (the same as --model PATH): .obj, .gltf or .glb.
        if (arg[0] != '-' && arg != "/?") {
            if (modelGiven || !o.scene.obj.empty())
                return failure("more than one model given: '" + arg + "'");
            o.scene.obj = arg;
            modelGiven = true;
            continue;
        }

        std::string error;
        const bool sizeFlag = startsWith(arg, "--width") || startsWith(arg, "--height");
        const bool threadsFlag = startsWith(arg, "--threads");
        const bool shadowsFlag = arg == "--shadows" || arg == "--no-shadows";
        switch (parseSceneFlag(args, i, o.scene, error)) {
        case FlagResult::Consumed:
            o.sizeGiven |= sizeFlag;
            threadsGiven |= threadsFlag;
            shadowsGiven |= shadowsFlag;
            continue;
        case FlagResult::Error: return failure(error);
        case FlagResult::NotMine: break;
        }
        return failure("unknown argument: '" + arg + "'");
    }
    if (const auto problem = validateSceneOptions(o.scene))
        return failure(*problem);
    if (o.scene.maxError)
        return failure("--max-error is the headless command's: the demo's --quality auto keeps a frame time (--budget-ms MS)");
    // The demo renders on every hardware thread unless --threads says otherwise (the headless
    // command keeps 1, as the reference renderer does).
    if (!threadsGiven) o.scene.threads = defaultDemoThreads();
    // The demo starts at the balanced quality preset unless --quality names another (the headless
    // command keeps the plain defaults: 1 sample, bilinear, phong, exact). A window too large
    // for its sample target is drawn without supersampling (renderSceneFrame).
    if (!o.scene.quality) applyQuality(o.scene, kDefaultDemoQuality);
    // The built-in scene starts with shadows on; a model without them (its shadow pass grows
    // with its triangles: H, or --shadows, turns them on), unless --shadows / --no-shadows say.
    if (!shadowsGiven) o.scene.shadows.on = o.scene.obj.empty();
    result.ok = true;
    return result;
}

int defaultDemoThreads() {
    const unsigned hardware = std::thread::hardware_concurrency(); // 0 when unknown
    return std::clamp(int(hardware), 1, kMaxThreads);
}

std::string usageText(const std::string& programName) {
    std::string text = "Usage: " + programName +
                       " [MODEL] [--width W --height H] [scene and quality flags] [--frames N]\n"
                       "       [--screenshot PATH] [--help]\n"
                       "  MODEL                the model to fly around: .obj, .gltf or .glb (default: the\n"
                       "                       built-in scene)\n"
                       "  --width W --height H initial client size in pixels (default 960 x 540 at 96 DPI)\n"
                       "  --frames N           exit with code 0 after N rendered frames (for scripts and tests)\n"
                       "  --screenshot PATH    save the last frame before exiting (or the first frame\n"
                       "                       without --frames) as PNG / BMP / PPM (by extension)\n"
                       "  --help               show this text\n"
                       "  (the demo renders on every hardware thread by default: --threads N overrides;\n"
                       "  it starts at --quality balanced: 4 samples per pixel, trilinear, phong, exact,\n"
                       "  and with --sky gradient; the built-in scene with --shadows, a model without)\n";
    text += sceneFlagsHelp();
    text += "keys:\n";
    for (const KeyHelp& k : kKeyHelp) {
        std::string keys = "  " + std::string(k.keys);
        keys.resize(22, ' ');
        text += keys + k.what + "\n";
    }
    return text;
}

} // namespace sr::app
