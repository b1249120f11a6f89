// Tests of the demo's command-line parser (model, scene flags, --frames, --screenshot, --help,
// errors) and key -> action map.
#include "TestFramework.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <thread>
#include <vector>

#include "Platform/App/CommandLine.hpp"
#include "Platform/App/Input.hpp"
#include "Platform/App/SceneOptions.hpp"

using sr::app::parseCommandLine;

TEST_CASE("no arguments: run until closed", "[platform]") {
    const auto r = parseCommandLine({});
    REQUIRE(r.ok);
    CHECK_FALSE(r.options.frames.has_value());
    CHECK_FALSE(r.options.help);
    CHECK(r.error.empty());
}

TEST_CASE("--frames N and --frames=N", "[platform]") {
    auto r = parseCommandLine({"--frames", "5"});
    REQUIRE(r.ok);
    CHECK(r.options.frames == 5);

    r = parseCommandLine({"--frames=120"});
    REQUIRE(r.ok);
    CHECK(r.options.frames == 120);

    r = parseCommandLine({"--frames", "2000000000"});
    REQUIRE(r.ok);
    CHECK(r.options.frames == sr::app::kMaxDemoFrames);
}

TEST_CASE("--help, -h and /? ask for help", "[platform]") {
    for (const char* flag : {"--help", "-h", "/?"}) {
        const auto r = parseCommandLine({flag});
        REQUIRE(r.ok);
        CHECK(r.options.help);
    }
    const auto both = parseCommandLine({"--frames", "3", "--help"});
    REQUIRE(both.ok);
    CHECK(both.options.help);
    CHECK(both.options.frames == 3);
}

TEST_CASE("bad --frames values are rejected with the value in the message", "[platform]") {
    for (const char* bad : {"0", "-1", "+3", "abc", "12x", " 7", "3.5", "", "2000000001", "99999999999999999999"}) {
        INFO("value: '" << bad << "'");
        const auto r = parseCommandLine({"--frames", bad});
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("--frames") != std::string::npos);
        CHECK(r.error.find(std::string("'") + bad + "'") != std::string::npos);
    }
    const auto eq = parseCommandLine({"--frames=-4"});
    CHECK_FALSE(eq.ok);
}

TEST_CASE("--frames without a value, or twice, is an error", "[platform]") {
    auto r = parseCommandLine({"--frames"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("needs a value") != std::string::npos);

    r = parseCommandLine({"--frames", "2", "--frames=3"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("twice") != std::string::npos);
}

TEST_CASE("unknown arguments are named in the error", "[platform]") {
    for (const char* bad : {"--frame", "--FRAMES", "-x", "--help=1", "--frames5", "--screenshots"}) {
        INFO("argument: " << bad);
        const auto r = parseCommandLine({bad});
        CHECK_FALSE(r.ok);
        CHECK(r.error.find(std::string("'") + bad + "'") != std::string::npos);
    }
    CHECK_FALSE(parseCommandLine({""}).ok);
    // A non-ASCII argument (UTF-8) is reported, not mangled.
    const auto r = parseCommandLine({"--f\xC3\xA9"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("--f\xC3\xA9") != std::string::npos);
}

TEST_CASE("usage text names the program and every flag", "[platform]") {
    const std::string text = sr::app::usageText("SoftRaster.exe");
    CHECK(text.find("SoftRaster.exe") != std::string::npos);
    CHECK(text.find("--frames N") != std::string::npos);
    CHECK(text.find("--help") != std::string::npos);
    CHECK(text.find("--screenshot PATH") != std::string::npos);
    CHECK(text.find("--cull MODE") != std::string::npos); // the shared scene flags
    CHECK(text.find("F12") != std::string::npos);         // and the keys
    CHECK(text.back() == '\n');
}

TEST_CASE("a positional argument is the model; scene flags are shared with the headless command", "[platform]") {
    auto r = parseCommandLine({"models/t\xC3\xA9" "apot.obj", "--width", "640", "--height=480", "--cull", "cw",
                               "--shading", "flat", "--filter", "trilinear", "--wireframe"});
    REQUIRE(r.ok);
    CHECK(r.options.scene.obj == "models/t\xC3\xA9" "apot.obj");
    CHECK(r.options.sizeGiven);
    CHECK(r.options.scene.width == 640);
    CHECK(r.options.scene.height == 480);
    CHECK(r.options.scene.cull == sr::CullMode::CW);
    CHECK(r.options.scene.shading == sr::ShadingMode::Flat);
    CHECK(r.options.scene.filter == sr::TextureFilter::Trilinear);
    CHECK(r.options.scene.wireframe);

    r = parseCommandLine({});
    REQUIRE(r.ok);
    CHECK_FALSE(r.options.sizeGiven);
    CHECK(r.options.scene.obj.empty());

    r = parseCommandLine({"a.obj", "b.obj"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("'b.obj'") != std::string::npos);
}

TEST_CASE("--screenshot PATH and --screenshot=PATH", "[platform]") {
    auto r = parseCommandLine({"--frames", "3", "--screenshot", "out dir/shot.png"});
    REQUIRE(r.ok);
    CHECK(r.options.screenshot == "out dir/shot.png");
    r = parseCommandLine({"--screenshot=a.bmp"});
    REQUIRE(r.ok);
    CHECK(r.options.screenshot == "a.bmp");
    CHECK_FALSE(parseCommandLine({"--screenshot"}).ok);
    CHECK_FALSE(parseCommandLine({"--screenshot="}).ok);
}

TEST_CASE("bad scene flags and combinations are errors naming the value", "[platform]") {
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--width", "0"}, {"--height", "99999"}, {"--cull", "back"}, {"--shading", "x"},
          {"--width"}, {"--eye", "1,2"}}) {
        INFO(args[0]);
        const auto r = parseCommandLine(args);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find(args[0]) != std::string::npos);
    }
    const auto r = parseCommandLine({"--near", "5", "--far", "1"});
    CHECK_FALSE(r.ok);
    CHECK(r.error.find("--far") != std::string::npos);
}

TEST_CASE("Escape quits, toggle keys map to their actions, movement keys have no press action", "[platform]") {
    using sr::app::Action;
    using sr::app::Key;
    CHECK(sr::app::actionForKey(Key::Escape) == Action::Quit);
    CHECK(sr::app::actionForKey(Key::Unknown) == Action::None);
    STATIC_REQUIRE(sr::app::actionForKey(Key::Escape) == Action::Quit);
    CHECK(sr::app::actionForKey(Key::C) == Action::CycleCull);
    CHECK(sr::app::actionForKey(Key::F12) == Action::Screenshot);
    CHECK(sr::app::actionForKey(Key::W) == Action::None);
    CHECK(sr::app::actionForKey(Key::Shift) == Action::None);
}

TEST_CASE("the demo renders on every hardware thread unless --threads says otherwise", "[platform]") {
    const int all = sr::app::defaultDemoThreads();
    CHECK(all >= 1);
    CHECK(all == std::max(1, std::min(int(std::thread::hardware_concurrency()), sr::app::kMaxThreads)));
    CHECK(parseCommandLine({}).options.scene.threads == all);
    CHECK(parseCommandLine({"--threads", "1"}).options.scene.threads == 1);
    CHECK(parseCommandLine({"--threads=3"}).options.scene.threads == 3);
    CHECK(parseCommandLine({"--threads", "0"}).options.scene.threads == 0);
}

TEST_CASE("the demo starts at the balanced quality preset; --quality and explicit flags change it", "[platform]") {
    using sr::app::Quality;
    const auto plain = parseCommandLine({});
    REQUIRE(plain.ok);
    CHECK(plain.options.scene.quality == Quality::Balanced);
    CHECK(plain.options.scene.antiAliasing == sr::app::qualitySettings(Quality::Balanced).antiAliasing);
    CHECK(plain.options.scene.antiAliasing.ssaaSamples() == 4);
    const auto fast = parseCommandLine({"--quality", "fast"});
    REQUIRE(fast.ok);
    CHECK(fast.options.scene.antiAliasing.ssaaSamples() == 1);
    CHECK(fast.options.scene.filter == sr::TextureFilter::Bilinear);
    CHECK(fast.options.scene.shading == sr::ShadingMode::Gouraud);
    CHECK(fast.options.scene.perspective == sr::PerspectiveMode::Exact);
    // An explicit knob without --quality keeps the balanced preset for the others.
    const auto one = parseCommandLine({"--ssaa", "1", "--filter", "nearest"});
    REQUIRE(one.ok);
    CHECK(one.options.scene.antiAliasing.ssaaSamples() == 1);
    CHECK(one.options.scene.filter == sr::TextureFilter::Nearest);
    CHECK(plain.options.scene.filter == sr::TextureFilter::Trilinear);
    CHECK(one.options.scene.shading == sr::ShadingMode::Phong);
    // A window too large for its sample target is not an error (it renders without SSAA).
    CHECK(parseCommandLine({"--width", "8000"}).ok);
    CHECK_FALSE(parseCommandLine({"--width", "8000", "--ssaa", "4"}).ok);
    CHECK(sr::app::actionForKey(sr::app::Key::N) == sr::app::Action::CycleAntialiasing);
}

TEST_CASE("anti-aliasing: one value; --ssaa and --msaa replace a preset's, 1 turns off only its own mode", "[platform]") {
    using sr::AntiAliasing;
    const auto aaOf = [](std::vector<std::string> args) {
        const auto r = parseCommandLine(args);
        REQUIRE(r.ok);
        return r.options.scene.antiAliasing;
    };
    CHECK(aaOf({"--msaa", "4"}) == *AntiAliasing::multisample(4)); // replaces balanced's SSAA 4
    CHECK(aaOf({"--quality", "accurate", "--msaa", "8"}) == *AntiAliasing::multisample(8));
    CHECK(aaOf({"--msaa", "2", "--quality", "accurate"}) == *AntiAliasing::multisample(2)); // explicit wins
    CHECK(aaOf({"--ssaa", "16", "--msaa", "1"}) == *AntiAliasing::supersample(16));
    CHECK(aaOf({"--msaa", "1", "--ssaa", "16"}) == *AntiAliasing::supersample(16));
    CHECK(aaOf({"--msaa", "8", "--ssaa", "1"}) == *AntiAliasing::multisample(8));
    CHECK(aaOf({"--msaa", "8", "--msaa", "1"}) == AntiAliasing::none());
    CHECK(aaOf({"--ssaa", "1"}) == AntiAliasing::none());
    const auto both = parseCommandLine({"--ssaa", "16", "--msaa", "2"});
    CHECK_FALSE(both.ok);
    CHECK(both.error.find("--ssaa 16 and --msaa 2: choose one way of anti-aliasing") != std::string::npos);
    CHECK_FALSE(parseCommandLine({"--msaa", "3"}).ok);
    CHECK_FALSE(parseCommandLine({"--ssaa", "2"}).ok);
    // --fxaa: a mode of its own, over any preset's, refused beside another mode's samples.
    CHECK(aaOf({"--fxaa"}) == AntiAliasing::fxaa());
    CHECK(aaOf({"--quality", "accurate", "--fxaa"}) == AntiAliasing::fxaa());
    CHECK(aaOf({"--fxaa", "--quality", "balanced"}) == AntiAliasing::fxaa());
    CHECK(aaOf({"--fxaa", "--msaa", "1"}) == AntiAliasing::fxaa());
    CHECK(aaOf({"--ssaa", "1", "--fxaa"}) == AntiAliasing::fxaa());
    const auto fxaaMsaa = parseCommandLine({"--fxaa", "--msaa", "4"});
    CHECK_FALSE(fxaaMsaa.ok);
    CHECK(fxaaMsaa.error.find("--fxaa and --msaa 4: choose one way of anti-aliasing") != std::string::npos);
    const auto ssaaFxaa = parseCommandLine({"--ssaa", "4", "--fxaa"});
    CHECK_FALSE(ssaaFxaa.ok);
    CHECK(ssaaFxaa.error.find("--fxaa and --ssaa 4: choose one way of anti-aliasing") != std::string::npos);
    CHECK_FALSE(parseCommandLine({"--fxaa=1"}).ok);
}

TEST_CASE("--aniso: 1, 2, 4, 8 or 16 trilinear taps; it brings the trilinear filter; accurate's own; refused with another filter",
          "[platform][aniso]") {
    const auto opts = [](std::vector<std::string> args) {
        const auto r = parseCommandLine(args);
        REQUIRE(r.ok);
        return r.options.scene;
    };
    CHECK(opts({}).aniso == 1);
    const auto a8 = opts({"--aniso", "8"});
    CHECK(a8.aniso == 8);
    CHECK(a8.filter == sr::TextureFilter::Trilinear);
    CHECK(opts({"--aniso", "4", "--quality", "fast"}).filter == sr::TextureFilter::Trilinear); // explicit wins
    CHECK(opts({"--quality", "accurate"}).aniso == 16);
    CHECK(opts({"--quality", "accurate", "--aniso", "2"}).aniso == 2);
    CHECK(opts({"--quality", "accurate", "--filter", "bilinear"}).aniso == 1); // the preset's taps go with its filter
    CHECK(opts({"--quality", "balanced"}).aniso == 1);
    CHECK(opts({"--aniso", "1", "--filter", "nearest"}).filter == sr::TextureFilter::Nearest);
    for (const std::vector<std::string>& bad : {std::vector<std::string>{"--aniso", "3"}, {"--aniso", "32"}, {"--aniso", "x"},
                                               {"--aniso", "0"}}) {
        CAPTURE(bad);
        const auto r = parseCommandLine(bad);
        CHECK_FALSE(r.ok);
        CHECK(r.error.find("bad value for --aniso") != std::string::npos);
    }
    const auto mixed = parseCommandLine({"--filter", "bilinear", "--aniso", "4"});
    CHECK_FALSE(mixed.ok);
    CHECK(mixed.error.find("--aniso 4 takes trilinear taps: not with --filter bilinear") != std::string::npos);
    const auto affine = parseCommandLine({"--aniso", "4", "--persp", "affine"});
    CHECK_FALSE(affine.ok);
    CHECK(affine.error.find("not with --persp affine") != std::string::npos);
}

TEST_CASE("the demo starts with shadows in the built-in scene, without in a model; --shadows and --no-shadows win", "[platform]") {
    CHECK(parseCommandLine({}).options.scene.shadows.on);
    CHECK_FALSE(parseCommandLine({"--no-shadows"}).options.scene.shadows.on);
    CHECK_FALSE(parseCommandLine({"model.obj"}).options.scene.shadows.on);
    CHECK_FALSE(parseCommandLine({"--model", "model.obj"}).options.scene.shadows.on);
    CHECK(parseCommandLine({"model.obj", "--shadows"}).options.scene.shadows.on);
    CHECK_FALSE(parseCommandLine({"--shadows", "--no-shadows"}).options.scene.shadows.on); // the last one wins
    // The other shadow flags are no on / off choice: the default stays.
    CHECK(parseCommandLine({"--shadow-size", "1024"}).options.scene.shadows.on);
    CHECK_FALSE(parseCommandLine({"model.obj", "--shadow-pcf", "5"}).options.scene.shadows.on);
}

TEST_CASE("--isa picks the span kernels; an unknown or unavailable one is refused", "[platform]") {
    CHECK(parseCommandLine({}).options.scene.isa == sr::bestIsa());
    const auto scalar = parseCommandLine({"--isa", "scalar"});
    REQUIRE(scalar.ok);
    CHECK(scalar.options.scene.isa == sr::Isa::Scalar);
    const auto bad = parseCommandLine({"--isa", "neon"});
    CHECK_FALSE(bad.ok);
    CHECK(bad.error.find("--isa") != std::string::npos);
    for (sr::Isa isa : sr::kAllIsas) {
        const auto r = parseCommandLine({"--isa", sr::isaName(isa)});
        CHECK(r.ok == sr::isaAvailable(isa));
        if (!r.ok) CHECK(r.error.find("not available") != std::string::npos);
    }
}

TEST_CASE("the demo takes --quality auto with a frame-time budget, not an error bound", "[platform][auto]") {
    const auto r = parseCommandLine({"--quality", "auto", "--budget-ms", "8"});
    CHECK(r.error.empty());
    CHECK(r.options.scene.autoQuality);
    CHECK(*r.options.scene.budgetMs == 8.0);
    CHECK(parseCommandLine({"--quality", "auto", "--max-error", "0.01"}).error.find("--max-error is the headless command's") != std::string::npos);
    CHECK(parseCommandLine({"--budget-ms", "5"}).error.find("give it too") != std::string::npos);
}

TEST_CASE("scene flags: one table names, parses and documents each; every flag in the help is parsed and every parsed flag is in the help",
          "[platform][flags]") {
    const std::vector<std::string> names = sr::app::sceneFlagNames();
    const std::string help = sr::app::sceneFlagsHelp();
    REQUIRE(names.size() >= 40);
    // The help's flags: each "--word" token.
    std::vector<std::string> documented;
    for (std::size_t at = help.find("--"); at != std::string::npos; at = help.find("--", at + 2)) {
        std::size_t end = at + 2;
        while (end < help.size() && (std::isalnum(static_cast<unsigned char>(help[end])) || help[end] == '-')) ++end;
        documented.push_back(help.substr(at, end - at));
    }
    for (const std::string& name : names) {
        INFO(name);
        CHECK(std::find(documented.begin(), documented.end(), name) != documented.end());
        // Recognised: with a value where it takes one, "--flag=value" refused where it takes none.
        sr::app::SceneOptions o;
        std::string error;
        std::size_t i = 0;
        const std::vector<std::string> alone{name};
        const sr::app::FlagResult r = sr::app::parseSceneFlag(alone, i, o, error);
        CHECK(r != sr::app::FlagResult::NotMine);
        if (r == sr::app::FlagResult::Consumed) { // a switch
            i = 0;
            const std::vector<std::string> withValue{name + "=1"};
            CHECK(sr::app::parseSceneFlag(withValue, i, o, error) == sr::app::FlagResult::Error);
            CHECK(error == name + " takes no value");
        } else {
            CHECK(error == "missing value for " + name);
        }
    }
    for (const std::string& flag : documented) {
        INFO(flag);
        CHECK(std::find(names.begin(), names.end(), flag) != names.end());
    }
    // Not a scene flag: left to the caller.
    sr::app::SceneOptions o;
    std::string error;
    std::size_t i = 0;
    CHECK(sr::app::parseSceneFlag({"--frames"}, i, o, error) == sr::app::FlagResult::NotMine);
}
