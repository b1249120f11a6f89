// Fly camera: position + yaw/pitch, movement and turning by caller-given amounts, view/projection.
#pragma once

#include <limits>

#include "Math/Mat4.hpp"
#include "Math/Vec.hpp"

namespace sr {

// A first-person fly camera in the right-handed, +Y-up world (Math/Conventions.hpp).
//  - yaw: right-handed rotation about world +Y; yaw 0 looks down -Z, positive yaw turns LEFT
//    (towards -X). Wrapped to (-pi, pi].
//  - pitch: positive looks up; clamped to [-kMaxPitch, kMaxPitch] (short of +-90 degrees, so
//    forward is never parallel to world up and the basis stays well defined). No roll.
//  - forward() = (-sin(yaw) cos(pitch), sin(pitch), -cos(yaw) cos(pitch)),
//    right() = (cos(yaw), 0, -sin(yaw)) (horizontal), up() = cross(right, forward).
// Amounts are per call; the caller scales them by frame time.
// No NaN policy: a non-finite amount or delta is ignored (the call does nothing); finite but
// huge moves are clamped so every position component stays within +-kMaxCoordinate; the
// setters clamp their argument into the valid range and ignore NaN.
class Camera {
public:
    static constexpr float kMaxPitch = 89.5f * (kPi / 180.0f);
    static constexpr float kMaxCoordinate = 1e15f;
    // The near-plane distances every camera path uses: the command line refuses a --near outside
    // [kMinNear, kMaxCoordinate] (exit 2), setNearFar and the headless view builder clamp into it.
    // With near >= 1e-6 the reversed-Z depth near / distance of any point within kMaxCoordinate is a
    // normal float (>= 1e-21 > FLT_MIN); a near of 1e-40 would make it subnormal and 1e-46 zero
    // (a blank image).
    static constexpr float kMinNear = 1e-6f;
    static constexpr float kMinFovY = 1.0f * (kPi / 180.0f);
    static constexpr float kMaxFovY = 179.0f * (kPi / 180.0f);
    static constexpr float kInfinity = std::numeric_limits<float>::infinity();

    Camera() = default;
    Camera(Vec3 position, float yaw, float pitch);

    // --- Movement (along the current basis) -------------------------------------------------
    void moveForward(float amount); // along forward() (includes pitch: a fly camera)
    void moveRight(float amount);   // along right()
    void moveUp(float amount);      // along world +Y
    // Adds to yaw (wrapped) and pitch (clamped).
    void turn(float yawDelta, float pitchDelta);

    // --- Basis (unit, orthogonal, right-handed: cross(right, up) == -forward) ---------------
    Vec3 forward() const;
    Vec3 right() const;
    Vec3 up() const;

    // --- State ------------------------------------------------------------------------------
    Vec3 position() const { return position_; }
    float yaw() const { return yaw_; }
    float pitch() const { return pitch_; }
    float fovY() const { return fovY_; }
    float nearZ() const { return near_; }
    float farZ() const { return far_; }
    bool infiniteFar() const { return far_ == kInfinity; }

    void setPosition(Vec3 p);            // non-finite ignored; clamped to +-kMaxCoordinate
    void setYawPitch(float yaw, float pitch); // each ignored if non-finite; wrapped / clamped
    void setFovY(float radians);         // clamped to [kMinFovY, kMaxFovY]
    // near clamped into [kMinNear, kMaxCoordinate]; far > near, or +infinity for an infinite projection.
    // A far <= near (or NaN) makes the projection infinite.
    void setNearFar(float nearZ, float farZ);

    // --- Matrices ---------------------------------------------------------------------------
    // World -> view: the eye maps to the origin, forward() to -Z, up() to +Y, right() to +X.
    // Built directly from the basis (rows right, up, -forward), so it is exactly orthonormal
    // in its rotation part and never NaN.
    Mat4 view() const;
    // View -> clip, reversed-Z (Math/Transform.hpp perspective / perspectiveInfinite). A
    // non-finite or non-positive aspect is treated as 1 (a minimised 0x0 window).
    Mat4 projection(float aspect) const;

private:
    Vec3 position_{0.0f, 0.0f, 0.0f};
    float yaw_ = 0.0f;
    float pitch_ = 0.0f;
    float fovY_ = 60.0f * (kPi / 180.0f);
    float near_ = 0.1f;
    float far_ = kInfinity;

    void moveAlong(Vec3 direction, float amount);
};

// Wraps an angle (radians) to (-pi, pi] (float pi, kPi). Non-finite input returns 0.
float wrapAngle(float radians);

} // namespace sr
