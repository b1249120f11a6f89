// Fly camera (see Camera.hpp): basis from yaw/pitch, guarded movement, view and projection.
#include "Raster/Geometry/Camera.hpp"

#include <cmath>

#include "Math/Transform.hpp"

namespace sr {

namespace {


float clampCoordinate(double v) {
    const double m = Camera::kMaxCoordinate;
    return float(v < -m ? -m : (v > m ? m : v));
}

} // namespace

float wrapAngle(float radians) {
    if (!std::isfinite(radians))
        return 0.0f;
    // remainder() is exact and lands in [-pi, pi]; float rounding can only reach -kPi at the
    // open end, which is the same direction as +kPi.
    float r = float(std::remainder(double(radians), 2.0 * kPiD));
    if (r <= -kPi)
        r = kPi;
    if (r > kPi)
        r = kPi;
    return r;
}

Camera::Camera(Vec3 position, float yaw, float pitch) {
    setPosition(position);
    setYawPitch(yaw, pitch);
}

Vec3 Camera::forward() const {
    const double cy = std::cos(double(yaw_)), sy = std::sin(double(yaw_));
    const double cp = std::cos(double(pitch_)), sp = std::sin(double(pitch_));
    return {float(-sy * cp), float(sp), float(-cy * cp)};
}

Vec3 Camera::right() const {
    const double cy = std::cos(double(yaw_)), sy = std::sin(double(yaw_));
    return {float(cy), 0.0f, float(-sy)};
}

Vec3 Camera::up() const {
    // cross(right, forward) worked out: (sin(yaw) sin(pitch), cos(pitch), cos(yaw) sin(pitch)).
    const double cy = std::cos(double(yaw_)), sy = std::sin(double(yaw_));
    const double cp = std::cos(double(pitch_)), sp = std::sin(double(pitch_));
    return {float(sy * sp), float(cp), float(cy * sp)};
}

void Camera::moveAlong(Vec3 d, float amount) {
    if (!std::isfinite(amount))
        return;
    const double a = amount;
    position_ = {clampCoordinate(double(position_.x) + double(d.x) * a),
                 clampCoordinate(double(position_.y) + double(d.y) * a),
                 clampCoordinate(double(position_.z) + double(d.z) * a)};
}

void Camera::moveForward(float amount) { moveAlong(forward(), amount); }
void Camera::moveRight(float amount) { moveAlong(right(), amount); }
void Camera::moveUp(float amount) { moveAlong({0.0f, 1.0f, 0.0f}, amount); }

void Camera::turn(float yawDelta, float pitchDelta) {
    // Each delta is applied on its own, so a NaN yaw delta does not block a valid pitch one.
    if (std::isfinite(yawDelta))
        yaw_ = wrapAngle(float(std::remainder(double(yaw_) + double(yawDelta), 2.0 * kPiD)));
    if (std::isfinite(pitchDelta))
        pitch_ = float(std::fmax(-double(kMaxPitch), std::fmin(double(kMaxPitch), double(pitch_) + pitchDelta)));
}

void Camera::setPosition(Vec3 p) {
    if (!isFinite(p))
        return;
    position_ = {clampCoordinate(p.x), clampCoordinate(p.y), clampCoordinate(p.z)};
}

void Camera::setYawPitch(float yaw, float pitch) {
    if (std::isfinite(yaw))
        yaw_ = wrapAngle(yaw);
    if (std::isfinite(pitch))
        pitch_ = clamp(pitch, -kMaxPitch, kMaxPitch);
}

void Camera::setFovY(float radians) {
    if (std::isnan(radians))
        return;
    fovY_ = clamp(radians, kMinFovY, kMaxFovY);
}

void Camera::setNearFar(float nearZ, float farZ) {
    if (!std::isnan(nearZ))
        near_ = clamp(nearZ, kMinNear, kMaxCoordinate);
    far_ = (farZ > near_) ? farZ : kInfinity; // NaN compares false -> infinite
}

Mat4 Camera::view() const {
    // Rows right, up, -forward; translation -R * eye (the inverse of the camera's rigid frame).
    const Vec3 r = right(), u = up(), f = forward();
    const Vec3 e = position_;
    Mat4 v{};
    const float rows[3][3] = {{r.x, r.y, r.z}, {u.x, u.y, u.z}, {-f.x, -f.y, -f.z}};
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col)
            v.m[col * 4 + row] = rows[row][col];
        // Dot product in double: exact enough for kMaxCoordinate-sized eyes, never overflows.
        v.m[12 + row] = float(-(double(rows[row][0]) * e.x + double(rows[row][1]) * e.y +
                                double(rows[row][2]) * e.z));
        v.m[row * 4 + 3] = 0.0f;
    }
    v.m[15] = 1.0f;
    return v;
}

Mat4 Camera::projection(float aspect) const {
    if (!(aspect > 0.0f) || !std::isfinite(aspect))
        aspect = 1.0f;
    if (infiniteFar())
        return perspectiveInfinite(fovY_, aspect, near_);
    return perspective(fovY_, aspect, near_, far_);
}

} // namespace sr
