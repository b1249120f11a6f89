// Tests of the demo's platform-free controller: frame-time-scaled flying and turning, the step
// clamp, key toggles and their cycles, the camera taken from eye/target, and the frame view.
#include "TestFramework.hpp"

#include <cmath>
#include <limits>

#include "Platform/App/DemoController.hpp"

using namespace sr;
using namespace sr::app;

namespace {

DemoController makeController(MotionTuning tuning = {}) {
    CameraSetup setup;
    setup.eye = {0.0f, 2.2f, 7.0f};
    setup.target = {0.0f, 0.8f, 0.0f};
    setup.up = {0.0f, 1.0f, 0.0f};
    setup.nearZ = 0.1;
    setup.farZ = std::numeric_limits<double>::infinity();
    return DemoController(cameraFromSetup(setup), RenderSettings{}, Vec3{1.0f, 1.0f, 1.0f}, tuning);
}

float distance(Vec3 a, Vec3 b) { return length(a - b); }

// Holds `key` for `frames` frames of `dt` seconds each; returns the camera position.
Vec3 flyFrames(Key key, int frames, double dt) {
    DemoController c = makeController();
    c.keyDown(key);
    for (int i = 0; i < frames; ++i)
        c.update(dt);
    return c.camera().position();
}

} // namespace

TEST_CASE("the fly camera starts at the eye looking at the target", "[platform]") {
    const DemoController c = makeController();
    const Vec3 expected = normalize(Vec3{0.0f, 0.8f, 0.0f} - Vec3{0.0f, 2.2f, 7.0f});
    CHECK(distance(c.camera().position(), {0.0f, 2.2f, 7.0f}) < 1e-6f);
    CHECK(distance(c.camera().forward(), expected) < 1e-5f);
    CHECK(c.camera().infiniteFar());

    // Any direction, including straight down the axes and steeply down.
    for (const Vec3 dir : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 0, 1}, Vec3{0.3f, -0.9f, 0.1f}}) {
        CameraSetup s;
        s.eye = {1.0f, 2.0f, 3.0f};
        s.target = s.eye + dir;
        const Camera cam = cameraFromSetup(s);
        CHECK(distance(cam.forward(), normalize(dir)) < 1e-5f);
    }
}

TEST_CASE("the frame view matches makeFrameView for the starting camera", "[platform]") {
    const DemoController c = makeController();
    CameraSetup setup;
    setup.eye = {0.0f, 2.2f, 7.0f};
    setup.target = {0.0f, 0.8f, 0.0f};
    setup.up = {0.0f, 1.0f, 0.0f};
    setup.nearZ = 0.1;
    setup.farZ = std::numeric_limits<double>::infinity();
    const FrameView ours = c.frameView(640, 480);
    const FrameView ref = makeFrameView(setup, 640, 480, {1.0f, 1.0f, 1.0f}, {});
    for (int r = 0; r < 4; ++r)
        for (int col = 0; col < 4; ++col) {
            INFO("element " << r << "," << col);
            CHECK(std::fabs(ours.viewProj(r, col) - ref.viewProj(r, col)) < 1e-4f);
        }
    CHECK_FALSE(ours.finiteFar);
    REQUIRE(ours.lighting.lights.size() == 1);
    CHECK(std::fabs(length(ours.lighting.lights[0].toLight) - 1.0f) < 1e-6f);
    // A minimised 0 x 0 window still gets a finite matrix.
    const FrameView empty = c.frameView(0, 0);
    for (int r = 0; r < 4; ++r)
        for (int col = 0; col < 4; ++col) CHECK(std::isfinite(empty.viewProj(r, col)));
}

TEST_CASE("an absurd near plane is clamped to Camera::kMinNear by the demo camera and the headless builder alike",
          "[platform]") {
    // 1e-46 is below the smallest float (zero depth everywhere: a blank image) and 1e-40 subnormal;
    // both paths must build the projection of near = kMinNear, not of the absurd value.
    for (double nearZ : {1e-46, 1e-40, 1e-9}) {
        INFO("near " << nearZ);
        CameraSetup setup;
        setup.eye = {0.0f, 2.2f, 7.0f};
        setup.target = {0.0f, 0.8f, 0.0f};
        setup.up = {0.0f, 1.0f, 0.0f};
        setup.farZ = std::numeric_limits<double>::infinity();
        CameraSetup clamped = setup;
        clamped.nearZ = double(Camera::kMinNear);
        setup.nearZ = nearZ;
        const FrameView headless = makeFrameView(setup, 640, 480, {1.0f, 1.0f, 1.0f}, {});
        const FrameView expected = makeFrameView(clamped, 640, 480, {1.0f, 1.0f, 1.0f}, {});
        const Camera camera = cameraFromSetup(setup);
        CHECK(camera.nearZ() == Camera::kMinNear);
        for (int r = 0; r < 4; ++r)
            for (int col = 0; col < 4; ++col) CHECK(headless.viewProj(r, col) == expected.viewProj(r, col));
        // The reversed-Z depth of a point 1e4 away is a normal float, not zero or subnormal.
        const Vec4 p = headless.viewProj * Vec4(0.0f, 0.8f, 7.0f - 1e4f, 1.0f);
        CHECK(std::fabs(p.z / p.w) >= std::numeric_limits<float>::min());
    }
    // A far plane the clamped near passes becomes infinite, as Camera::setNearFar does.
    CameraSetup tiny;
    tiny.eye = {0.0f, 0.0f, 1.0f};
    tiny.target = {0.0f, 0.0f, 0.0f};
    tiny.up = {0.0f, 1.0f, 0.0f};
    tiny.nearZ = 1e-12;
    tiny.farZ = 1e-7;
    CHECK_FALSE(makeFrameView(tiny, 64, 64, {1.0f, 1.0f, 1.0f}, {}).finiteFar);
    CHECK(cameraFromSetup(tiny).farZ() == Camera::kInfinity);
}

TEST_CASE("movement is scaled by frame time: 30 fps and 300 fps fly the same distance", "[platform]") {
    for (const Key key : {Key::W, Key::S, Key::A, Key::D, Key::Q, Key::E}) {
        INFO("key " << int(key));
        const Vec3 at30 = flyFrames(key, 30, 1.0 / 30.0);
        const Vec3 at300 = flyFrames(key, 300, 1.0 / 300.0);
        const Vec3 oneStep = flyFrames(key, 1, 0.1);     // 1 frame of N * dt ...
        const Vec3 tenSteps = flyFrames(key, 10, 0.01);  // ... vs N frames of dt
        CHECK(distance(at30, at300) < 1e-3f);
        CHECK(distance(oneStep, tenSteps) < 1e-4f);
        // One second at the default speed flies 2.5 units.
        CHECK(std::fabs(distance(at30, {0.0f, 2.2f, 7.0f}) - 2.5f) < 1e-3f);
    }
}

TEST_CASE("W flies along the view direction, S back, Shift is faster", "[platform]") {
    DemoController c = makeController();
    const Vec3 start = c.camera().position();
    const Vec3 forward = c.camera().forward();
    c.keyDown(Key::W);
    c.update(0.1);
    CHECK(distance(c.camera().position(), start + forward * 0.25f) < 1e-5f);
    c.keyDown(Key::Shift);
    c.update(0.1);
    CHECK(distance(c.camera().position(), start + forward * 1.25f) < 1e-4f);
    c.keyUp(Key::Shift);
    c.keyUp(Key::W);
    c.update(0.1);
    CHECK(distance(c.camera().position(), start + forward * 1.25f) < 1e-4f); // released: stays
    // W and S together cancel.
    c.keyDown(Key::W);
    c.keyDown(Key::S);
    c.update(0.1);
    CHECK(distance(c.camera().position(), start + forward * 1.25f) < 1e-4f);
    c.releaseAllKeys();
    CHECK_FALSE(c.held(Key::W));
    CHECK_FALSE(c.held(Key::S));
}

TEST_CASE("a huge, negative or NaN frame time moves at most one clamped step", "[platform]") {
    const Vec3 start{0.0f, 2.2f, 7.0f};
    const float maxMove = 2.5f * float(MotionTuning{}.maxStep);
    CHECK(std::fabs(distance(flyFrames(Key::W, 1, 30.0), start) - maxMove) < 1e-5f); // a breakpoint
    CHECK(std::fabs(distance(flyFrames(Key::W, 1, 1e300), start) - maxMove) < 1e-5f);
    CHECK(distance(flyFrames(Key::W, 1, -1.0), start) == 0.0f);
    CHECK(distance(flyFrames(Key::W, 1, std::nan("")), start) == 0.0f);
    CHECK(distance(flyFrames(Key::W, 1, INFINITY), start) == 0.0f);
}

TEST_CASE("arrow keys turn by time, mouse drags by distance", "[platform]") {
    DemoController c = makeController();
    const float yaw0 = c.camera().yaw(), pitch0 = c.camera().pitch();
    c.keyDown(Key::Left);
    for (int i = 0; i < 10; ++i) c.update(0.05); // 0.5 s at 90 deg/s
    CHECK(std::fabs(c.camera().yaw() - (yaw0 + radians(45.0f))) < 1e-4f);
    c.keyUp(Key::Left);
    c.keyDown(Key::Up);
    c.update(0.1);
    CHECK(std::fabs(c.camera().pitch() - (pitch0 + radians(9.0f))) < 1e-4f);
    c.keyUp(Key::Up);

    DemoController m = makeController();
    m.mouseDrag(100, 0); // drag right: turn right (negative yaw)
    CHECK(std::fabs(m.camera().yaw() - (yaw0 - 100 * MotionTuning{}.mouseRadiansPerPixel)) < 1e-5f);
    m.mouseDrag(0, 40); // drag down: look down
    CHECK(m.camera().pitch() < pitch0);
    // Pitch never passes the camera's limit.
    m.mouseDrag(0, 100000);
    CHECK(m.camera().pitch() >= -Camera::kMaxPitch);
}

TEST_CASE("R resets the view", "[platform]") {
    DemoController c = makeController();
    const Vec3 start = c.camera().position();
    c.keyDown(Key::D);
    c.keyDown(Key::Right);
    c.update(0.1);
    CHECK(distance(c.camera().position(), start) > 0.1f);
    CHECK(c.keyDown(Key::R) == Action::ResetView);
    CHECK(distance(c.camera().position(), start) == 0.0f);
}

TEST_CASE("one view builder: the demo's starting view is makeFrameView of the flags' camera, bit for bit",
          "[platform]") {
    // A camera the fly camera's yaw/pitch cannot represent exactly (an arbitrary direction).
    CameraSetup setup;
    setup.eye = {0.4f, 0.3f, 2.2f};
    setup.target = {0.0f, 0.05f, 0.0f};
    setup.up = {0.0f, 1.0f, 0.0f};
    setup.fovDegrees = 60.0;
    setup.nearZ = 0.5;
    setup.farZ = 5.0;
    const Vec3 light{1.0f, 1.0f, 1.0f};
    DemoController c(setup, RenderSettings{}, light);
    const FrameView ref = makeFrameView(setup, 960, 540, light, {});
    const FrameView start = c.frameView(960, 540);
    CHECK(start.viewProj == ref.viewProj);
    CHECK(start.eye == ref.eye);
    CHECK(start.finiteFar == ref.finiteFar);
    REQUIRE(start.lighting.lights.size() == 1);
    CHECK(start.lighting.lights[0].toLight == ref.lighting.lights[0].toLight);
    // The float yaw/pitch camera alone would not give these bits.
    const FrameView viaYawPitch = makeFrameView(setupFromCamera(cameraFromSetup(setup)), 960, 540, light, {});
    CHECK_FALSE(viaYawPitch.viewProj == ref.viewProj);
    // Once it moves, the view follows the fly camera through the same builder; R brings the
    // starting view back exactly.
    c.keyDown(Key::W);
    c.update(0.1);
    c.keyUp(Key::W);
    CHECK_FALSE(c.frameView(960, 540).viewProj == ref.viewProj);
    CHECK(c.frameView(960, 540).viewProj == makeFrameView(setupFromCamera(c.camera()), 960, 540, light, {}).viewProj);
    c.keyDown(Key::R);
    CHECK(c.frameView(960, 540).viewProj == ref.viewProj);
}
