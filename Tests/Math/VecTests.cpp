// Tests of Vec2/3/4: operators, products, and length/normalize at the extremes.
#include "TestFramework.hpp"

#include <cmath>
#include <limits>

#include "Math/Vec.hpp"

using namespace sr;

TEST_CASE("cross product follows the right-hand rule", "[math][vec]") {
    CHECK(cross(Vec3(1, 0, 0), Vec3(0, 1, 0)) == Vec3(0, 0, 1));
    CHECK(cross(Vec3(0, 1, 0), Vec3(0, 0, 1)) == Vec3(1, 0, 0));
    CHECK(cross(Vec3(2, 3, 4), Vec3(5, 6, 7)) == Vec3(3 * 7 - 4 * 6, 4 * 5 - 2 * 7, 2 * 6 - 3 * 5));
}

TEST_CASE("normalize of zero, denormal and huge vectors", "[math][vec]") {
    CHECK(normalize(Vec3(0, 0, 0)) == Vec3(0, 0, 0));
    const float denorm = std::numeric_limits<float>::denorm_min() * 8.0f;
    const Vec3 d = normalize(Vec3(denorm, 0, denorm));
    CHECK(d.x == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(d.z == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    const Vec3 h = normalize(Vec3(1e30f, -1e30f, 0));
    CHECK(h.x == Approx(std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(h.y == Approx(-std::sqrt(0.5f)).epsilon(1e-6));
    CHECK(length(Vec3(3e30f, 4e30f, 0)) == Approx(5e30f).epsilon(1e-6));
}
