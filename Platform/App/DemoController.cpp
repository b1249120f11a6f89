// Actions -> camera and toggles: the fly camera's frame-time-scaled motion and the mode cycles.
#include "Platform/App/DemoController.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "Raster/Texture/TextureLod.hpp" // kMaxAnisotropy

namespace sr::app {

namespace {

// Cycles an enum whose values are 0 .. count-1.
template <typename E>
E next(E value, int count) {
    return E((int(value) + 1) % count);
}

} // namespace

Camera cameraFromSetup(const CameraSetup& setup) {
    // forward() = (-sin(yaw) cos(pitch), sin(pitch), -cos(yaw) cos(pitch)) (Raster/Geometry/Camera.hpp),
    // so yaw = atan2(-f.x, -f.z) and pitch = asin(f.y) for the unit direction f.
    const Vec3 f = normalize(setup.target - setup.eye);
    float yaw = 0.0f, pitch = 0.0f;
    if (isFinite(f) && length(f) > 0.5f) {
        yaw = std::atan2(-f.x, -f.z);
        pitch = std::asin(std::clamp(f.y, -1.0f, 1.0f));
    }
    Camera camera(setup.eye, yaw, pitch);
    camera.setFovY(radians(float(setup.fovDegrees)));
    camera.setNearFar(float(setup.nearZ), std::isinf(setup.farZ) ? Camera::kInfinity : float(setup.farZ));
    return camera;
}

CameraSetup setupFromCamera(const Camera& camera) {
    CameraSetup c;
    c.eye = camera.position();
    c.target = camera.position() + camera.forward();
    c.up = {0.0f, 1.0f, 0.0f};
    c.fovDegrees = double(camera.fovY()) * (180.0 / kPiD);
    c.nearZ = camera.nearZ();
    c.farZ = camera.infiniteFar() ? std::numeric_limits<double>::infinity() : double(camera.farZ());
    return c;
}

namespace {

// Same position, orientation, field of view and planes: the camera has not moved.
bool samePose(const Camera& a, const Camera& b) {
    return a.position() == b.position() && a.yaw() == b.yaw() && a.pitch() == b.pitch() && a.fovY() == b.fovY() &&
           a.nearZ() == b.nearZ() && a.farZ() == b.farZ();
}

} // namespace

const char* cullLabel(CullMode mode) {
    switch (mode) {
    case CullMode::None: return "cull none";
    case CullMode::CW: return "cull CW";
    case CullMode::CCW: return "cull CCW";
    }
    return "cull ?";
}

DemoController::DemoController(const Camera& home, const RenderSettings& settings, Vec3 toLight, MotionTuning tuning)
    : home_(home), start_(home), camera_(home), settings_(settings), toLight_(toLight), tuning_(tuning) {}

DemoController::DemoController(const CameraSetup& home, const RenderSettings& settings, Vec3 toLight, MotionTuning tuning)
    : DemoController(cameraFromSetup(home), settings, toLight, tuning) {
    homeSetup_ = home;
    startSetup_ = home;
}

void DemoController::cycleCamera() {
    if (cameras_.empty()) return;
    cameraIndex_ = cameraIndex_ + 1 >= int(cameras_.size()) ? -1 : cameraIndex_ + 1;
    if (cameraIndex_ < 0) {
        home_ = start_;
        homeSetup_ = startSetup_;
    } else {
        // Until the camera moves, the view is exactly the file's camera (its up and planes too).
        homeSetup_ = cameras_[std::size_t(cameraIndex_)];
        home_ = cameraFromSetup(*homeSetup_);
    }
    camera_ = home_;
}

CameraSetup DemoController::cameraSetup() const {
    if (homeSetup_ && samePose(camera_, home_)) return *homeSetup_;
    return setupFromCamera(camera_);
}

Action DemoController::keyDown(Key key, bool repeat) {
    if (key == Key::Unknown || key == Key::Count)
        return Action::None;
    held_[std::size_t(key)] = true;
    if (repeat)
        return Action::None; // toggles flip once per press, not at the auto-repeat rate
    const Action action = actionForKey(key);
    // A quality chosen by hand holds: --quality auto stops following the budget (U resumes).
    if (action == Action::CycleShading || action == Action::ToggleColour || action == Action::CycleFilter ||
        action == Action::CyclePerspective || action == Action::CycleAntialiasing)
        autoOn_ = false;
    switch (action) {
    case Action::CycleCull: settings_.cull = next(settings_.cull, 3); break;
    case Action::CycleShading: settings_.shading = next(settings_.shading, physical_ ? 5 : 4); break; // pbr: glTF only
    case Action::ToggleColour:
        settings_.colour = settings_.colour == ColorMode::Linear ? ColorMode::Gamma : ColorMode::Linear;
        break;
    case Action::CycleFilter:
        // nearest -> bilinear -> trilinear -> trilinear with 16 anisotropic taps -> nearest.
        if (settings_.filter == TextureFilter::Trilinear && settings_.aniso == 1) {
            settings_.aniso = kMaxAnisotropy;
        } else {
            settings_.filter = next(settings_.filter, 3);
            settings_.aniso = 1;
        }
        settings_.filterFromFile = false; // the user's choice from now on, over any glTF sampler
        break;
    case Action::CyclePerspective: settings_.perspective = next(settings_.perspective, 2); break;
    case Action::CycleAntialiasing: cycleAntialiasing(); break;
    case Action::ToggleWireframe: settings_.wireframe = !settings_.wireframe; break;
    case Action::ToggleOutline: settings_.outline.pickCentre = !settings_.outline.pickCentre; break;
    case Action::ToggleShadows: settings_.shadows.on = !settings_.shadows.on; break;
    case Action::ToggleDepthView: depthView_ = !depthView_; break;
    case Action::ResetView: resetView(); break;
    case Action::CycleCamera: cycleCamera(); break;
    case Action::ToggleHelp: help_ = !help_; break;
    case Action::ToggleSkyLight: ibl_ = ibl_ ? nullptr : sceneIbl_; break;
    case Action::ToggleAutoQuality:
        if (!autoSettings_.empty())
            autoOn_ = !autoOn_;
        break;
    case Action::TogglePlay:
        if (animated_)
            playing_ = !playing_;
        break;
    case Action::StepBack:
    case Action::StepForward:
        if (animated_) {
            playing_ = false;
            advanceAnimation(action == Action::StepForward ? kAnimationStep : -kAnimationStep);
        }
        break;
    case Action::None:
    case Action::Quit:
    case Action::CycleVariant:
    case Action::Screenshot: break; // the platform's
    }
    return action;
}

void DemoController::keyUp(Key key) {
    if (key != Key::Unknown && key != Key::Count)
        held_[std::size_t(key)] = false;
}

void DemoController::releaseAllKeys() { held_.fill(false); }

void DemoController::mouseDrag(int dx, int dy) {
    // Dragging right turns right (negative yaw); dragging down looks down.
    camera_.turn(-float(dx) * tuning_.mouseRadiansPerPixel, -float(dy) * tuning_.mouseRadiansPerPixel);
}

void DemoController::setAutoQuality(const QualityProbe& probe, double budgetMs, bool textured) {
    autoSettings_ = probe.settings;
    autoTextured_ = textured;
    autoSelector_ = AutoQualitySelector(probe.points, budgetMs);
    autoOn_ = !autoSettings_.empty();
    applyAutoSetting(autoSelector_.current());
}

void DemoController::applyAutoSetting(int index) {
    if (index < 0 || std::size_t(index) >= autoSettings_.size())
        return;
    const RenderSettings& s = autoSettings_[std::size_t(index)];
    settings_.antiAliasing = s.antiAliasing;
    settings_.filter = s.filter;
    settings_.aniso = s.aniso;
    settings_.filterFromFile = false;
    settings_.shading = s.shading;
    settings_.perspective = s.perspective;
    settings_.colour = s.colour;
}

void DemoController::frameRendered(double renderMs) {
    if (!autoOn_)
        return;
    const int before = autoSelector_.current();
    const int now = autoSelector_.update(renderMs);
    if (now != before)
        applyAutoSetting(now);
}

void DemoController::setAnimation(double duration, double start, int clip) {
    animated_ = true;
    playing_ = true;
    animDuration_ = std::isfinite(duration) && duration > 0.0 ? duration : 0.0;
    animClip_ = clip;
    animTime_ = 0.0;
    advanceAnimation(std::isfinite(start) ? start : 0.0);
}

void DemoController::advanceAnimation(double dt) {
    if (!animated_)
        return;
    animTime_ += dt;
    if (animDuration_ > 0.0)
        animTime_ -= std::floor(animTime_ / animDuration_) * animDuration_; // into [0, duration)
    else
        animTime_ = 0.0;
}

void DemoController::update(double dtSeconds) {
    // Clamp the step: a NaN, negative or huge frame time (a breakpoint, a dragged window)
    // integrates at most maxStep.
    const double dt = std::isfinite(dtSeconds) ? std::clamp(dtSeconds, 0.0, tuning_.maxStep) : 0.0;
    if (dt <= 0.0)
        return;
    if (playing_)
        advanceAnimation(dt);
    const float speed = tuning_.moveSpeed * (held(Key::Shift) ? tuning_.fastFactor : 1.0f);
    const float step = float(double(speed) * dt);
    const float turnStep = float(double(tuning_.turnSpeed) * dt);

    // Turn first, then move along the new basis (the order only matters within one step).
    const float yaw = axis(Key::Left, Key::Right); // positive yaw turns left
    const float pitch = axis(Key::Up, Key::Down);
    if (yaw != 0.0f || pitch != 0.0f)
        camera_.turn(yaw * turnStep, pitch * turnStep);
    if (const float f = axis(Key::W, Key::S); f != 0.0f)
        camera_.moveForward(f * step);
    if (const float r = axis(Key::D, Key::A); r != 0.0f)
        camera_.moveRight(r * step);
    if (const float u = axis(Key::E, Key::Q); u != 0.0f)
        camera_.moveUp(u * step);
}

void DemoController::cycleAntialiasing() {
    // off -> FXAA -> MSAA 2 -> 4 -> 8 -> SSAA 4 -> 16 -> off.
    static constexpr AntiAliasing kCycle[] = {AntiAliasing::none(),          AntiAliasing::fxaa(), *AntiAliasing::multisample(2),
                                              *AntiAliasing::multisample(4), *AntiAliasing::multisample(8),
                                              *AntiAliasing::supersample(4), *AntiAliasing::supersample(16)};
    constexpr int n = int(sizeof kCycle / sizeof kCycle[0]);
    int at = 0;
    for (int i = 0; i < n; ++i)
        if (kCycle[i] == settings_.antiAliasing) at = i;
    settings_.antiAliasing = kCycle[(at + 1) % n];
}

std::string DemoController::modeSummary() const {
    std::string s = cullLabel(settings_.cull);
    s += " | ";
    s += shadingModeName(settings_.shading);
    s += settings_.colour == ColorMode::Linear ? " linear | " : " | ";
    s += filterName(settings_.filter);
    if (settings_.aniso > 1) s += " aniso " + std::to_string(settings_.aniso);
    s += " | ";
    s += perspectiveModeName(settings_.perspective);
    const AntiAliasing aa = settings_.antiAliasing;
    s += aa.multisampled()   ? " | msaa " + std::to_string(aa.samples())
         : aa.postFiltered() ? std::string(" | fxaa")
                             : " | ssaa " + std::to_string(aa.ssaaSamples());
    if (cameraIndex_ >= 0)
        s += " | camera " + std::to_string(cameraIndex_);
    if (settings_.wireframe)
        s += " | wireframe";
    if (settings_.shadows.on)
        s += " | shadows";
    if (sceneIbl_)
        s += ibl_ ? " | sky light" : " | sky light off";
    if (settings_.outline.pickCentre)
        s += aa.multisampled() ? " | outline (not with msaa)" : " | outline";
    if (depthView_)
        s += " | depth view";
    if (!autoSettings_.empty()) {
        char a[64];
        const int k = autoSelector_.current();
        if (autoOn_ && k >= 0)
            std::snprintf(a, sizeof a, " | auto %.1f ms: err %.4f", autoSelector_.budgetMs(), autoSelector_.points()[std::size_t(k)].error);
        else
            std::snprintf(a, sizeof a, " | auto held");
        s += a;
    }
    if (animated_) {
        char t[48];
        std::snprintf(t, sizeof t, " | t %.2f s%s", animTime_, playing_ ? "" : " paused");
        s += t;
    }
    if (help_)
        s += " | help"; // scripts can tell the overlay is up (it hides part of the picture)
    return s;
}

} // namespace sr::app
