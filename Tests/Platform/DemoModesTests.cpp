// Tests of the demo's mode toggles (cull, shading, filter, perspective, wireframe, depth view,
// help), the title text and frame statistics, the depth view's grey mapping and screenshot names.
#include "TestFramework.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "Platform/App/DemoController.hpp"
#include "Platform/App/DepthView.hpp"
#include "Platform/App/FrameStats.hpp"
#include "Raster/Shade/Ibl.hpp"

using namespace sr;
using namespace sr::app;

namespace {

DemoController makeController() { return DemoController(Camera{}, RenderSettings{}, Vec3{0.0f, 1.0f, 0.0f}); }

} // namespace

TEST_CASE("C cycles the cull mode none -> CW -> CCW -> none and the summary shows it", "[platform]") {
    DemoController c = makeController();
    CHECK(c.settings().cull == CullMode::None);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | ssaa 1");
    CHECK(c.keyDown(Key::C) == Action::CycleCull);
    CHECK(c.settings().cull == CullMode::CW);
    CHECK(c.modeSummary().rfind("cull CW |", 0) == 0);
    c.keyUp(Key::C);
    c.keyDown(Key::C);
    CHECK(c.settings().cull == CullMode::CCW);
    CHECK(c.modeSummary().rfind("cull CCW |", 0) == 0);
    c.keyDown(Key::C);
    CHECK(c.settings().cull == CullMode::None);
}

TEST_CASE("a glTF scene's shading cycle includes pbr; G toggles linear light", "[platform][pbr]") {
    DemoController c = makeController();
    c.setPhysicalLights(true);
    // From phong, the controller's start.
    const ShadingMode shading[] = {ShadingMode::Pbr, ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud,
                                   ShadingMode::Phong, ShadingMode::Pbr};
    for (const ShadingMode m : shading) {
        c.keyDown(Key::M);
        CHECK(c.settings().shading == m);
    }
    const ColorMode start = c.settings().colour;
    c.keyDown(Key::G);
    CHECK(c.settings().colour != start);
    CHECK((c.modeSummary().find(" linear |") != std::string::npos) == (c.settings().colour == ColorMode::Linear));
    c.keyDown(Key::G);
    CHECK(c.settings().colour == start);
}

TEST_CASE("auto-repeat does not flip a toggle again", "[platform]") {
    DemoController c = makeController();
    c.keyDown(Key::C);
    CHECK(c.keyDown(Key::C, /*repeat=*/true) == Action::None);
    CHECK(c.keyDown(Key::C, /*repeat=*/true) == Action::None);
    CHECK(c.settings().cull == CullMode::CW);
}

TEST_CASE("shading, filter, perspective and anti-aliasing cycle through every mode", "[platform]") {
    DemoController c = makeController();
    const ShadingMode shading[] = {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong};
    for (const ShadingMode m : shading) {
        c.keyDown(Key::M);
        CHECK(c.settings().shading == m);
    }
    // bilinear -> trilinear -> trilinear with 16 anisotropic taps -> nearest -> bilinear.
    const std::pair<TextureFilter, int> filters[] = {{TextureFilter::Trilinear, 1}, {TextureFilter::Trilinear, 16},
                                                     {TextureFilter::Nearest, 1}, {TextureFilter::Bilinear, 1}};
    for (const auto& [f, aniso] : filters) {
        c.keyDown(Key::T);
        CHECK(c.settings().filter == f);
        CHECK(c.settings().aniso == aniso);
        if (aniso > 1) CHECK(c.modeSummary() == "cull none | phong | trilinear aniso 16 | exact | ssaa 1");
    }
    const PerspectiveMode modes[] = {PerspectiveMode::Affine, PerspectiveMode::Exact};
    for (const PerspectiveMode p : modes) {
        c.keyDown(Key::P);
        CHECK(c.settings().perspective == p);
    }
    // off -> FXAA -> MSAA 2, 4, 8 -> SSAA 4, 16 -> off: one kind at a time.
    const AntiAliasing cycle[] = {AntiAliasing::fxaa(),          *AntiAliasing::multisample(2), *AntiAliasing::multisample(4),
                                  *AntiAliasing::multisample(8), *AntiAliasing::supersample(4), *AntiAliasing::supersample(16),
                                  AntiAliasing::none()};
    for (const AntiAliasing aa : cycle) {
        CHECK(c.keyDown(Key::N) == Action::CycleAntialiasing);
        CHECK(c.settings().antiAliasing == aa);
    }
    c.keyDown(Key::N);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | fxaa");
    c.keyDown(Key::N);
    c.keyDown(Key::N);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | msaa 4");
    for (int i = 0; i < 2; ++i) c.keyDown(Key::N);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | ssaa 4");
    for (int i = 0; i < 2; ++i) c.keyDown(Key::N);
    c.keyDown(Key::M);
    c.keyDown(Key::P);
    CHECK(c.modeSummary() == "cull none | unlit | bilinear | affine | ssaa 1");
}

TEST_CASE("wireframe, depth view and help toggle; Quit, Screenshot and the variant key are left to the platform", "[platform]") {
    DemoController c = makeController();
    c.keyDown(Key::L);
    CHECK(c.settings().wireframe);
    c.keyDown(Key::Z);
    CHECK(c.depthView());
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | ssaa 1 | wireframe | depth view");
    c.keyDown(Key::L);
    c.keyDown(Key::Z);
    CHECK_FALSE(c.settings().wireframe);
    CHECK_FALSE(c.depthView());
    CHECK_FALSE(c.helpVisible());
    CHECK(c.keyDown(Key::F1) == Action::ToggleHelp);
    CHECK(c.helpVisible());
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | ssaa 1 | help");
    CHECK(c.keyDown(Key::Escape) == Action::Quit);
    CHECK(c.keyDown(Key::F12) == Action::Screenshot);
    // K (the next material variant) reloads the model: the platform's, the settings unchanged.
    const std::string before = c.modeSummary();
    CHECK(c.keyDown(Key::K) == Action::CycleVariant);
    CHECK(c.modeSummary() == before);
    CHECK(c.keyDown(Key::Unknown) == Action::None);
    CHECK(c.keyDown(Key::W) == Action::None);
}

TEST_CASE("H toggles the shadows; the title says so", "[platform]") {
    DemoController c = makeController();
    CHECK_FALSE(c.settings().shadows.on);
    CHECK(c.keyDown(Key::H) == Action::ToggleShadows);
    CHECK(c.settings().shadows.on);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | ssaa 1 | shadows");
    c.keyDown(Key::H);
    CHECK_FALSE(c.settings().shadows.on);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | ssaa 1");
}

TEST_CASE("O toggles the selection outline; the title says so, and that MSAA does not draw it", "[platform]") {
    DemoController c = makeController();
    CHECK_FALSE(c.settings().outline.pickCentre);
    CHECK(c.keyDown(Key::O) == Action::ToggleOutline);
    CHECK(c.settings().outline.pickCentre);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | ssaa 1 | outline");
    c.keyDown(Key::N); // FXAA: a post-filter, the outline is drawn
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | fxaa | outline");
    c.keyDown(Key::N); // MSAA 2
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | msaa 2 | outline (not with msaa)");
    c.keyDown(Key::O);
    CHECK_FALSE(c.settings().outline.pickCentre);
    CHECK(c.modeSummary() == "cull none | phong | bilinear | exact | msaa 2");
}

TEST_CASE("an animated scene plays at real time and loops; Space pauses; ',' and '.' step; the title shows the time",
          "[platform][animation]") {
    DemoController c = makeController();
    CHECK_FALSE(c.animated());
    CHECK(c.modeSummary().find(" | t ") == std::string::npos); // nothing animates: no time shown
    c.keyDown(Key::Space);                                      // and the keys change nothing
    c.keyUp(Key::Space);
    c.keyDown(Key::Period);
    c.keyUp(Key::Period);
    CHECK(c.animationTime() == 0.0);
    CHECK_FALSE(c.animationPlaying());
    c.setAnimation(2.0, 0.5, 1);
    CHECK(c.animated());
    CHECK(c.animationClip() == 1);
    CHECK(c.animationPlaying());
    CHECK(c.animationTime() == 0.5);
    CHECK(c.modeSummary().find(" | t 0.50 s") != std::string::npos);
    c.update(0.1);
    CHECK(c.animationTime() == Approx(0.6));
    for (int i = 0; i < 15; ++i) c.update(0.1); // 2.1 s: looped over the 2 s clip
    CHECK(c.animationTime() == Approx(0.1).margin(1e-9));
    CHECK(c.keyDown(Key::Space) == Action::TogglePlay);
    c.keyUp(Key::Space);
    CHECK_FALSE(c.animationPlaying());
    CHECK(c.modeSummary().find(" paused") != std::string::npos);
    const double paused = c.animationTime();
    c.update(0.1);
    CHECK(c.animationTime() == paused); // paused: time stands still
    CHECK(c.keyDown(Key::Period) == Action::StepForward);
    c.keyUp(Key::Period);
    CHECK(c.animationTime() == Approx(paused + DemoController::kAnimationStep));
    c.keyDown(Key::Comma);
    c.keyUp(Key::Comma);
    c.keyDown(Key::Comma);
    c.keyUp(Key::Comma);
    CHECK(c.animationTime() == Approx(paused - DemoController::kAnimationStep));
    for (int i = 0; i < 3; ++i) { // below 0: wraps to the clip's end
        c.keyDown(Key::Comma);
        c.keyUp(Key::Comma);
    }
    CHECK(c.animationTime() == Approx(2.0 + paused - 4 * DemoController::kAnimationStep));
    c.keyDown(Key::Space); // plays again
    CHECK(c.animationPlaying());
}

TEST_CASE("frame statistics average over the period", "[platform]") {
    FrameStats s(0.25);
    CHECK_FALSE(s.hasAverage());
    int ready = 0;
    for (int i = 0; i < 100; ++i) ready += s.addFrame(0.01) ? 1 : 0; // 1 s at 100 fps
    CHECK(ready == 4);
    CHECK(std::fabs(s.fps() - 100.0) < 1.0);
    CHECK(std::fabs(s.msPerFrame() - 10.0) < 0.1);
    CHECK_FALSE(s.addFrame(std::nan(""))); // ignored time, still a frame
    CHECK(s.totalFrames() == 101);
}

TEST_CASE("the title shows fps, ms, threads, triangles with separators and the modes", "[platform]") {
    FrameStats s(0.1);
    CHECK(windowTitle(s, 1, 12, "cull none").rfind("SoftRaster", 0) == 0);
    CHECK(windowTitle(s, 1, 12, "x").find("-- fps") != std::string::npos);
    CHECK(windowTitle(s, 1, 12, "x").find("frame 0 ") != std::string::npos);
    CHECK(windowTitle(s, 1, 12, "x").find("\xE2\x80\x94 1 thread \xE2\x80\x94 12 tris") != std::string::npos);
    s.addFrame(0.007);
    s.addFrame(0.007);
    for (int i = 0; i < 14; ++i) s.addFrame(0.007);
    const std::string t = windowTitle(s, 2, 3212, "cull none | phong | bilinear | exact", "saved a.png");
    CHECK(t == "SoftRaster \xE2\x80\x94 143 fps 7.0 ms \xE2\x80\x94 frame 16 \xE2\x80\x94 2 threads \xE2\x80\x94 3,212 tris \xE2\x80\x94 cull none | phong | "
               "bilinear | exact \xE2\x80\x94 saved a.png");
    CHECK(withThousands(0) == "0");
    CHECK(withThousands(999) == "999");
    CHECK(withThousands(1000) == "1,000");
    CHECK(withThousands(1234567) == "1,234,567");
}

TEST_CASE("depth view: background black, nearest white, grey falls with distance", "[platform]") {
    FrameBuffer fb(4, 1);
    fb.clear(packBgra(10, 20, 30), 0.0f);
    // Reversed-Z with an infinite far plane: d = near / distance (near = 0.1).
    float* d = fb.depthData();
    d[1] = 0.1f / 1.0f;  // 1 unit away
    d[2] = 0.1f / 10.0f; // 10 units
    d[3] = std::numeric_limits<float>::quiet_NaN();
    depthToGrey(fb);
    CHECK(fb.pixel(0, 0) == packBgra(0, 0, 0));
    CHECK(fb.pixel(1, 0) == packBgra(255, 255, 255));
    CHECK(fb.pixel(2, 0) == packBgra(40, 40, 40));
    CHECK(fb.pixel(3, 0) == packBgra(0, 0, 0));

    // Log scale: the geometric middle distance is the middle grey.
    FrameBuffer g(3, 1);
    g.clear(0, 0.0f);
    g.depthData()[0] = 1.0f;
    g.depthData()[1] = 0.1f;
    g.depthData()[2] = 0.01f;
    depthToGrey(g);
    CHECK(std::abs(int(pixelR(g.pixel(1, 0))) - (40 + 215 / 2)) <= 1);

    // One depth only, and an empty framebuffer.
    FrameBuffer one(2, 2);
    one.clear(0, 0.5f);
    depthToGrey(one);
    CHECK(one.pixel(1, 1) == packBgra(255, 255, 255));
    FrameBuffer empty;
    depthToGrey(empty);
    CHECK(empty.empty());
}

TEST_CASE("screenshot names carry the date, time and counter", "[platform]") {
    std::tm t{};
    t.tm_year = 2025 - 1900;
    t.tm_mon = 2;
    t.tm_mday = 7;
    t.tm_hour = 9;
    t.tm_min = 5;
    t.tm_sec = 3;
    CHECK(screenshotName(t, 12) == "SoftRaster-20250307-090503-12.png");
    FrameBuffer empty;
    const Status s = saveScreenshot(empty, "never-written.png");
    CHECK_FALSE(s.ok());
    CHECK(s.error().find("never-written.png") != std::string::npos);
}

TEST_CASE("--quality auto in the demo: the probe's setting applied, followed as frames come, held by U and by a hand-picked mode",
          "[platform][auto]") {
    DemoController c = makeController();
    QualityProbe probe;
    RenderSettings cheap, dear;
    cheap.antiAliasing = AntiAliasing::none();
    cheap.shading = ShadingMode::Gouraud;
    dear.antiAliasing = *AntiAliasing::supersample(4);
    dear.filter = TextureFilter::Trilinear;
    probe.settings = {cheap, dear};
    probe.points = {{4.0, 0.05}, {12.0, 0.01}};
    c.setAutoQuality(probe, 20.0, true);
    CHECK(c.autoQuality());
    CHECK(c.settings().antiAliasing.ssaaSamples() == 4); // 12 ms fits 20
    CHECK(c.modeSummary().find(" | auto 20.0 ms: err 0.0100") != std::string::npos);
    for (int f = 0; f < 40; ++f) c.frameRendered(30.0); // 2.5x dearer now: 30 > 20
    CHECK(c.settings().antiAliasing.ssaaSamples() == 1);
    CHECK(c.settings().shading == ShadingMode::Gouraud);
    // U holds the setting: the frames no longer move it.
    CHECK(c.keyDown(Key::U) == Action::ToggleAutoQuality);
    c.keyUp(Key::U);
    CHECK_FALSE(c.autoQuality());
    CHECK(c.modeSummary().find(" | auto held") != std::string::npos);
    for (int f = 0; f < 60; ++f) c.frameRendered(1.0);
    CHECK(c.settings().antiAliasing.ssaaSamples() == 1);
    c.keyDown(Key::U); // follows again: cheap frames, up to the dear setting
    c.keyUp(Key::U);
    for (int f = 0; f < 60; ++f) c.frameRendered(1.0);
    CHECK(c.settings().antiAliasing.ssaaSamples() == 4);
    // A mode picked by hand holds too.
    c.keyDown(Key::N);
    c.keyUp(Key::N);
    CHECK_FALSE(c.autoQuality());
}

TEST_CASE("I toggles the light from the sky of a scene that has one; the title says which", "[platform][pbr][ibl]") {
    DemoController c = makeController();
    // No sky light: the key changes nothing, the title does not mention it.
    CHECK(c.keyDown(Key::I) == Action::ToggleSkyLight);
    c.keyUp(Key::I);
    CHECK_FALSE(c.skyLightOn());
    CHECK(c.frameView(64, 48).ibl == nullptr);
    CHECK(c.modeSummary().find("sky light") == std::string::npos);
    // A scene lit by its sky: on at the start, off with I, on again.
    Sky sky;
    sky.kind = Sky::Kind::Gradient;
    const ImageLight ibl(sky);
    c.setImageLight(&ibl);
    CHECK(c.frameView(64, 48).ibl == &ibl);
    CHECK(c.modeSummary().find(" | sky light") != std::string::npos);
    CHECK(c.modeSummary().find("sky light off") == std::string::npos);
    c.keyDown(Key::I);
    c.keyUp(Key::I);
    CHECK_FALSE(c.skyLightOn());
    CHECK(c.frameView(64, 48).ibl == nullptr);
    CHECK(c.modeSummary().find(" | sky light off") != std::string::npos);
    // A reload while it is off (K: the scene's new sky light) keeps it off.
    const ImageLight reloaded(sky);
    c.setImageLight(&reloaded);
    CHECK(c.frameView(64, 48).ibl == nullptr);
    c.keyDown(Key::I);
    CHECK(c.frameView(64, 48).ibl == &reloaded);
}

