// Tests of the double view and projection (lookAtD, perspectiveD) against their float twins
// lookAt, perspective and perspectiveInfinite: the same matrices to float precision.
#include "TestFramework.hpp"

#include <cmath>
#include <limits>

#include "Math/Conventions.hpp"
#include "Math/Transform.hpp"
#include "MathTestUtil.hpp"

using namespace sr;
using srtest::relErr;

namespace {

// Both matrices hold the same values once the double one is rounded to float: each element within
// 1e-5 of the double value, relative (an element that is 0 in double is 0 in float too).
void checkAgree(const Mat4& single, const Mat4d& twice) {
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            INFO("element (" << r << ", " << c << "): float " << single(r, c) << ", double " << twice.m[r][c]);
            CHECK(relErr(double(single(r, c)), twice.m[r][c]) <= 1e-5);
        }
}

struct ViewCase {
    Vec3 eye, target, up;
};

// Several cameras: the default one, oblique ones, an up that is neither unit nor orthogonal to the
// view, a view almost straight down, one far from the origin and one at millimetre scale.
const ViewCase kCameras[] = {
    {{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}},
    {{3.0f, -2.0f, 7.0f}, {0.5f, 1.0f, -4.0f}, {0.0f, 1.0f, 0.0f}},
    {{-6.5f, 4.25f, -1.5f}, {2.0f, 0.5f, 3.0f}, {0.2f, 3.0f, 0.1f}},
    {{0.0f, 10.0f, 0.001f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}},
    {{1.0e5f, 2.0e4f, -3.0e5f}, {1.0e5f + 10.0f, 2.0e4f - 3.0f, -3.0e5f + 7.0f}, {0.0f, 0.0f, 1.0f}},
    {{0.001f, 0.002f, 0.003f}, {-0.004f, 0.001f, -0.002f}, {1.0f, 1.0f, 0.0f}},
};

} // namespace

TEST_CASE("lookAtD is lookAt in double", "[math][transform][double]") {
    for (const ViewCase& c : kCameras) {
        INFO("eye " << c.eye.x << "," << c.eye.y << "," << c.eye.z << " target " << c.target.x << ","
                    << c.target.y << "," << c.target.z << " up " << c.up.x << "," << c.up.y << "," << c.up.z);
        checkAgree(lookAt(c.eye, c.target, c.up), lookAtD(c.eye, c.target, c.up));
    }
}

TEST_CASE("lookAtD's rotation is orthonormal and its last row (0, 0, 0, 1)", "[math][transform][double]") {
    for (const ViewCase& c : kCameras) {
        const Mat4d v = lookAtD(c.eye, c.target, c.up);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const double d = v.m[i][0] * v.m[j][0] + v.m[i][1] * v.m[j][1] + v.m[i][2] * v.m[j][2];
                CHECK(std::fabs(d - (i == j ? 1.0 : 0.0)) <= 1e-12);
            }
        CHECK(v.m[3][0] == 0.0);
        CHECK(v.m[3][1] == 0.0);
        CHECK(v.m[3][2] == 0.0);
        CHECK(v.m[3][3] == 1.0);
        // The eye maps to the view-space origin.
        for (int r = 0; r < 3; ++r) {
            const double o = v.m[r][0] * c.eye.x + v.m[r][1] * c.eye.y + v.m[r][2] * c.eye.z + v.m[r][3];
            CHECK(std::fabs(o) <= 1e-9 * (1.0 + std::fabs(v.m[r][3])));
        }
    }
}

TEST_CASE("perspectiveD is perspective and perspectiveInfinite in double", "[math][projection][double]") {
    struct Case {
        float fovDegrees, aspect, nearZ, farZ;
    };
    const float inf = std::numeric_limits<float>::infinity();
    const Case cases[] = {
        {60.0f, 16.0f / 9.0f, 0.1f, 100.0f}, {90.0f, 1.0f, 1.0f, 3.0f},   {45.0f, 0.25f, 0.01f, 1.0e4f},
        {0.01f, 2.0f, 1.0e-6f, 1.0e9f},      {179.0f, 1.5f, 0.5f, 0.75f}, {60.0f, 16.0f / 9.0f, 0.1f, inf},
        {30.0f, 4.0f / 3.0f, 1.0e-6f, inf},
    };
    for (const Case& k : cases) {
        INFO("fov " << k.fovDegrees << " aspect " << k.aspect << " near " << k.nearZ << " far " << k.farZ);
        const float fov = radians(k.fovDegrees);
        const Mat4d d = perspectiveD(double(fov), double(k.aspect), double(k.nearZ), double(k.farZ));
        checkAgree(perspective(fov, k.aspect, k.nearZ, k.farZ), d);
        if (std::isinf(k.farZ)) checkAgree(perspectiveInfinite(fov, k.aspect, k.nearZ), d);
    }
}
