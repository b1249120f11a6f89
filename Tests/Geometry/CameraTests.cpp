// Tests of the fly camera: angle limits, orthonormal basis, movement, NaN safety, view/projection.
#include "TestFramework.hpp"

#include <cmath>
#include <limits>

#include "Math/Mat4.hpp"
#include "Raster/Geometry/Camera.hpp"

using namespace sr;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// M * v computed from the column-major storage directly (no dependency on Mat4's operator).
Vec4 mul(const Mat4& m, Vec4 v) {
    Vec4 r;
    for (int row = 0; row < 4; ++row)
        r[row] = m.m[0 * 4 + row] * v.x + m.m[1 * 4 + row] * v.y + m.m[2 * 4 + row] * v.z + m.m[3 * 4 + row] * v.w;
    return r;
}

void checkBasis(const Camera& cam) {
    const Vec3 f = cam.forward(), r = cam.right(), u = cam.up();
    CHECK(length(f) == Approx(1.0f).epsilon(1e-6));
    CHECK(length(r) == Approx(1.0f).epsilon(1e-6));
    CHECK(length(u) == Approx(1.0f).epsilon(1e-6));
    CHECK(std::fabs(dot(f, r)) < 1e-6f);
    CHECK(std::fabs(dot(f, u)) < 1e-6f);
    CHECK(std::fabs(dot(r, u)) < 1e-6f);
    const Vec3 c = cross(r, u); // right-handed: right x up = backward = -forward
    CHECK(c.x == Approx(-f.x).margin(1e-6));
    CHECK(c.y == Approx(-f.y).margin(1e-6));
    CHECK(c.z == Approx(-f.z).margin(1e-6));
    CHECK(r.y == 0.0f); // no roll: right stays horizontal
}

bool sameState(const Camera& a, const Camera& b) {
    return a.position() == b.position() && a.yaw() == b.yaw() && a.pitch() == b.pitch();
}

} // namespace

TEST_CASE("default camera looks down -Z with +Y up", "[pipeline][camera]") {
    const Camera cam;
    CHECK(cam.forward() == Vec3(0, 0, -1));
    CHECK(cam.right() == Vec3(1, 0, 0));
    CHECK(cam.up() == Vec3(0, 1, 0));
    CHECK(cam.infiniteFar());
}

TEST_CASE("positive yaw turns left, positive pitch looks up", "[pipeline][camera]") {
    Camera cam;
    cam.turn(kPi / 2, 0);
    CHECK(cam.forward().x == Approx(-1.0f));
    CHECK(cam.forward().z == Approx(0.0f).margin(1e-7));
    Camera up;
    up.turn(0, 0.5f);
    CHECK(up.forward().y == Approx(std::sin(0.5f)));
}

TEST_CASE("pitch clamps short of +-90 degrees and yaw wraps to (-pi, pi]", "[pipeline][camera]") {
    Camera cam;
    cam.turn(0, 10.0f);
    CHECK(cam.pitch() == Camera::kMaxPitch);
    CHECK(cam.pitch() < kPi / 2);
    checkBasis(cam);
    cam.turn(0, -100.0f);
    CHECK(cam.pitch() == -Camera::kMaxPitch);
    checkBasis(cam);

    for (float delta : {3.0f * kPi, -3.0f * kPi, 7.5f, -100.25f, 1e5f, kPi, -kPi, 1e30f, -1e30f}) {
        Camera c;
        c.turn(delta, 0);
        INFO("delta " << delta);
        CHECK(c.yaw() > -kPi);
        CHECK(c.yaw() <= kPi);
        checkBasis(c);
        if (std::fabs(delta) > 1e6f)
            continue; // finite and in range is all one can ask of a 1e30 radian turn
        // Same direction as the unwrapped angle (computed in double).
        CHECK(c.forward().x == Approx(float(-std::sin(double(delta)))).margin(1e-6));
        CHECK(c.forward().z == Approx(float(-std::cos(double(delta)))).margin(1e-6));
    }
    // (-pi, pi] in real numbers: float kPi is slightly MORE than pi, so it wraps to the float
    // just above -pi, and -kPi (slightly less than -pi) to the float just below +pi.
    for (float a : {kPi, -kPi, 0.0f, 1.0f, -1.0f, 3.1415925f, -3.1415925f, 2.0f * kPi, 1e20f}) {
        const float r = wrapAngle(a);
        INFO("angle " << a << " -> " << r);
        CHECK(r > -kPi);
        CHECK(r <= kPi);
        if (std::fabs(a) < 1e6f)
            CHECK(std::cos(r) == Approx(float(std::cos(double(a)))).margin(1e-6));
        if (std::fabs(a) < 3.1415926f)
            CHECK(r == a); // already in range: unchanged
    }
    CHECK(wrapAngle(kNaN) == 0.0f);
    CHECK(wrapAngle(kInf) == 0.0f);

    // Many small turns accumulate and keep wrapping.
    Camera spin;
    for (int i = 0; i < 1000; ++i)
        spin.turn(0.1f, 0);
    CHECK(spin.yaw() > -kPi);
    CHECK(spin.yaw() <= kPi);
    CHECK(spin.yaw() == Approx(float(std::remainder(100.0, 2.0 * 3.14159265358979323846))).margin(1e-3));
}

TEST_CASE("forward, right and up stay orthonormal", "[pipeline][camera]") {
    for (float yaw = -3.1f; yaw <= 3.2f; yaw += 0.37f) {
        for (float pitch = -1.6f; pitch <= 1.6f; pitch += 0.29f) {
            Camera cam({1, 2, 3}, yaw, pitch);
            INFO("yaw " << yaw << " pitch " << pitch);
            checkBasis(cam);
        }
    }
}

TEST_CASE("moving by d moves the eye by d along the basis", "[pipeline][camera]") {
    Camera cam({1.5f, -2.0f, 4.0f}, 0.7f, -0.3f);
    const float d = 2.5f;
    Vec3 before = cam.position();
    cam.moveForward(d);
    Vec3 delta = cam.position() - before;
    CHECK(length(delta) == Approx(d).epsilon(1e-6));
    CHECK(delta.x == Approx(cam.forward().x * d).margin(1e-6));
    CHECK(delta.y == Approx(cam.forward().y * d).margin(1e-6));
    CHECK(delta.z == Approx(cam.forward().z * d).margin(1e-6));

    before = cam.position();
    cam.moveRight(-d);
    delta = cam.position() - before;
    CHECK(delta.x == Approx(-cam.right().x * d).margin(1e-6));
    CHECK(delta.y == 0.0f);
    CHECK(delta.z == Approx(-cam.right().z * d).margin(1e-6));

    before = cam.position();
    cam.moveUp(d);
    CHECK(cam.position().x == before.x);
    CHECK(cam.position().y == Approx(before.y + d));
    CHECK(cam.position().z == before.z);

    before = cam.position();
    cam.moveForward(0.0f); // zero-length moves are no-ops
    cam.moveRight(-0.0f);
    CHECK(cam.position() == before);
}

TEST_CASE("NaN and infinite deltas are ignored; huge ones stay finite", "[pipeline][camera]") {
    Camera cam({1, 2, 3}, 0.5f, 0.25f);
    const Camera saved = cam;
    cam.turn(kNaN, kNaN);
    cam.turn(kInf, -kInf);
    cam.moveForward(kNaN);
    cam.moveRight(kInf);
    cam.moveUp(-kInf);
    cam.setPosition({kNaN, 0, 0});
    cam.setYawPitch(kNaN, kInf);
    CHECK(sameState(cam, saved));

    // A NaN yaw delta does not block a valid pitch delta.
    cam.turn(kNaN, 0.1f);
    CHECK(cam.yaw() == saved.yaw());
    CHECK(cam.pitch() == Approx(0.35f));

    cam.turn(1e30f, 1e30f);
    cam.moveForward(3e38f);
    cam.moveRight(-3e38f);
    cam.moveUp(3e38f);
    cam.moveUp(3e38f);
    CHECK(isFinite(cam.position()));
    CHECK(std::fabs(cam.position().y) <= Camera::kMaxCoordinate);
    CHECK(std::isfinite(cam.yaw()));
    CHECK(cam.pitch() == Camera::kMaxPitch);
    checkBasis(cam);
    CHECK(isFinite(cam.view()));

    cam.setFovY(kNaN);
    CHECK(std::isfinite(cam.fovY()));
    cam.setFovY(100.0f);
    CHECK(cam.fovY() == Camera::kMaxFovY);
    cam.setNearFar(kNaN, kNaN);
    CHECK(cam.infiniteFar());
    CHECK(cam.nearZ() > 0.0f);
    CHECK(isFinite(cam.projection(kNaN)));
    CHECK(isFinite(cam.projection(0.0f)));
}

TEST_CASE("view maps the eye to the origin and forward to -Z", "[pipeline][camera]") {
    for (float yaw : {0.0f, 0.8f, -2.5f, kPi}) {
        for (float pitch : {0.0f, 0.6f, -1.2f, Camera::kMaxPitch}) {
            const Camera cam({3.0f, -7.0f, 12.5f}, yaw, pitch);
            const Mat4 v = cam.view();
            INFO("yaw " << yaw << " pitch " << pitch);
            const Vec3 e = cam.position();
            const Vec4 eye = mul(v, {e, 1.0f});
            CHECK(eye.x == Approx(0.0f).margin(1e-5));
            CHECK(eye.y == Approx(0.0f).margin(1e-5));
            CHECK(eye.z == Approx(0.0f).margin(1e-5));
            CHECK(eye.w == 1.0f);
            const Vec4 f = mul(v, {cam.forward(), 0.0f});
            CHECK(f.x == Approx(0.0f).margin(1e-6));
            CHECK(f.y == Approx(0.0f).margin(1e-6));
            CHECK(f.z == Approx(-1.0f));
            const Vec4 u = mul(v, {cam.up(), 0.0f});
            CHECK(u.y == Approx(1.0f));
            const Vec4 r = mul(v, {cam.right(), 0.0f});
            CHECK(r.x == Approx(1.0f));
            // A point ahead of the eye lands ahead in view space.
            const Vec4 ahead = mul(v, {e + cam.forward() * 5.0f, 1.0f});
            CHECK(ahead.z == Approx(-5.0f).epsilon(1e-5));
        }
    }
}

TEST_CASE("projection puts the near plane at depth 1 and the far plane at 0", "[pipeline][camera]") {
    Camera cam({0, 1, 0}, 0.3f, 0.2f);
    cam.setNearFar(0.5f, 100.0f);
    const Mat4 pv = cam.projection(16.0f / 9.0f) * cam.view();
    const Vec4 nearPt = mul(pv, {cam.position() + cam.forward() * 0.5f, 1.0f});
    CHECK(nearPt.z / nearPt.w == Approx(1.0f).epsilon(1e-5));
    const Vec4 farPt = mul(pv, {cam.position() + cam.forward() * 100.0f, 1.0f});
    CHECK(farPt.z / farPt.w == Approx(0.0f).margin(1e-5));

    cam.setNearFar(0.5f, Camera::kInfinity);
    const Mat4 pvi = cam.projection(1.0f) * cam.view();
    const Vec4 farAway = mul(pvi, {cam.position() + cam.forward() * 1e6f, 1.0f});
    CHECK(farAway.z / farAway.w > 0.0f);
    CHECK(farAway.z / farAway.w < 1e-6f);
    const Vec4 n2 = mul(pvi, {cam.position() + cam.forward() * 0.5f, 1.0f});
    CHECK(n2.z / n2.w == Approx(1.0f).epsilon(1e-5));
}
