// The demo's platform-free logic: held keys and mouse drags -> the fly camera, key presses ->
// mode toggles, and the frame view / mode summary the window shows. Unit-tested natively.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "Platform/App/AutoQuality.hpp"
#include "Platform/App/Input.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "Raster/Frame/RenderSettings.hpp"
#include "Raster/Geometry/Camera.hpp"

namespace sr::app {

// How fast the camera flies and turns. Every rate is per SECOND and scaled by the frame time,
// so the demo feels the same at 30 and at 300 fps.
struct MotionTuning {
    float moveSpeed = 2.5f;                  // world units per second
    float fastFactor = 4.0f;                 // with Shift held
    float turnSpeed = radians(90.0f);        // arrow keys, radians per second
    float mouseRadiansPerPixel = radians(0.25f);
    // Longest frame time one update integrates: after a breakpoint or a stall of seconds the
    // camera moves one short step instead of jumping out of the scene.
    double maxStep = 0.1;
};

// The fly camera looking from setup.eye at setup.target (yaw/pitch from the direction; no roll:
// the fly camera's up is world +Y), with its field of view and near/far planes.
Camera cameraFromSetup(const CameraSetup& setup);

// The fly camera as a setup for makeFrameView, the one view builder of the demo and the headless
// command: eye = position, target = position + forward, up = world +Y, its field of view in
// degrees and its near/far planes (+infinity without a far plane).
CameraSetup setupFromCamera(const Camera& camera);

// Short name of the cull mode, as the title bar shows it (perspective modes: perspectiveModeName).
const char* cullLabel(CullMode mode); // "cull none", "cull CW", "cull CCW"

class DemoController {
public:
    DemoController(const Camera& home, const RenderSettings& settings, Vec3 toLight, MotionTuning tuning = {});
    // Starts at the camera the flags resolve to (resolveCamera): until the camera moves, every
    // frame's view is makeFrameView of exactly this setup, so the demo's first frames are the
    // headless command's image of the same flags, bit for bit.
    DemoController(const CameraSetup& home, const RenderSettings& settings, Vec3 toLight, MotionTuning tuning = {});

    // --- Input (already translated by the platform layer) -----------------------------------
    // A key went down (repeat = auto-repeat of a held key) or up. Returns the press's action;
    // the controller has already applied every action except Quit and Screenshot, which need
    // the platform (and are only reported, once per press: auto-repeat reports None).
    Action keyDown(Key key, bool repeat = false);
    void keyUp(Key key);
    // Forget every held key (the window lost the focus: no key-up will come).
    void releaseAllKeys();
    bool held(Key key) const { return held_[std::size_t(key)]; }
    // A drag by (dx, dy) pixels (x right, y down): turns by the distance, not by time.
    void mouseDrag(int dx, int dy);

    // Integrates the held keys over dtSeconds (clamped to [0, tuning.maxStep]; NaN = 0).
    void update(double dtSeconds);

    // --- State ------------------------------------------------------------------------------
    const Camera& camera() const { return camera_; }
    Camera& camera() { return camera_; }
    const RenderSettings& settings() const { return settings_; }
    bool depthView() const { return depthView_; }
    bool helpVisible() const { return help_; }
    const MotionTuning& tuning() const { return tuning_; }
    void resetView() { camera_ = home_; }
    // The model's own cameras (LoadedScene::cameras), which V cycles through after the starting
    // view. The selected one becomes the view R returns to; -1 = the starting view.
    void setCameras(std::vector<CameraSetup> cameras) { cameras_ = std::move(cameras); }
    // The scene's own lights (LoadedScene::lights); none: the one directional light toLight.
    void setLights(std::vector<Light> lights) { lights_ = std::move(lights); }
    // The lights' units (LoadedScene::physical: a glTF scene's).
    void setPhysicalLights(bool physical) { physical_ = physical; }
    // The sky's light (LoadedScene::ibl), or null.
    // The scene's sky light (a reload's too: turned off with I, it stays off).
    void setImageLight(const ImageLight* ibl) {
        ibl_ = sceneIbl_ && !ibl_ ? nullptr : ibl;
        sceneIbl_ = ibl;
    }
    bool skyLightOn() const { return ibl_ != nullptr; }
    int cameraIndex() const { return cameraIndex_; }
    // A glTF file's animation (LoadedScene::animation): played from `start` seconds at real time,
    // looping over `duration` (the longest clip; 0: a pose that does not move), clip `clip` alone
    // or every clip (< 0). Space pauses and plays, ',' and '.' pause and step kAnimationStep.
    void setAnimation(double duration, double start, int clip);
    bool animated() const { return animated_; }
    bool animationPlaying() const { return animated_ && playing_; }
    double animationTime() const { return animTime_; }
    int animationClip() const { return animClip_; }
    static constexpr double kAnimationStep = 1.0 / 30.0;
    // --quality auto: the probe's settings (AutoQuality.hpp) and the frame-time budget. The
    // setting follows the budget (AutoQualitySelector) as frames are rendered; U holds it and
    // follows again.
    void setAutoQuality(const QualityProbe& probe, double budgetMs, bool textured);
    bool autoQuality() const { return autoOn_; }
    // A frame took renderMs to render: under auto, the setting of the next one.
    void frameRendered(double renderMs);

    // The camera as a setup for the one view builder (makeFrameView): the starting setup while
    // the camera is where it started, else eye = position, target = position + forward, up = +Y.
    CameraSetup cameraSetup() const;
    FrameView frameView(int width, int height) const { return makeFrameView(cameraSetup(), width, height, toLight_, lights_, physical_, ibl_); }

    // "cull none | phong | bilinear | exact | ssaa 4" (or "| msaa 4" while multisampling; + " | wireframe",
    // " | depth view", " | help"; an animated scene " | t 1.23 s", " paused" when paused; under
    // --quality auto " | auto 16.7 ms: err 0.0234", " | auto held" after U).
    std::string modeSummary() const;

private:
    void cycleAntialiasing();
    void cycleCamera();
    Camera home_;
    std::optional<CameraSetup> homeSetup_; // the exact starting setup, when constructed from one
    std::optional<CameraSetup> startSetup_; // the flags' setup, restored after the last camera
    Camera start_;                          // the flags' fly camera
    std::vector<CameraSetup> cameras_;
    int cameraIndex_ = -1;
    Camera camera_;
    RenderSettings settings_;
    Vec3 toLight_;
    std::vector<Light> lights_;
    bool physical_ = false;
    const ImageLight* ibl_ = nullptr;      // what the frame is lit by (null: the lights alone)
    const ImageLight* sceneIbl_ = nullptr; // the scene's (ToggleSkyLight flips ibl_ between it and null)
    MotionTuning tuning_;
    bool depthView_ = false;
    bool help_ = false;
    std::vector<RenderSettings> autoSettings_;
    AutoQualitySelector autoSelector_;
    bool autoOn_ = false, autoTextured_ = false;
    void applyAutoSetting(int index);
    bool animated_ = false, playing_ = true;
    double animTime_ = 0.0, animDuration_ = 0.0;
    int animClip_ = -1;
    void advanceAnimation(double dt);
    std::array<bool, std::size_t(kKeyCount)> held_{};

    float axis(Key positive, Key negative) const { return float(held(positive)) - float(held(negative)); }
};

} // namespace sr::app
