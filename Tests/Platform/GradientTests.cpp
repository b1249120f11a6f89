// Tests of the first-light gradient: corner colours, pixel-centre sampling, animation, 0x0 safety.
#include "TestFramework.hpp"

#include "Platform/Demo/Gradient.hpp"

#include <cstdlib>
#include <set>

using namespace sr;
using namespace sr::demo;

namespace {

// Largest per-channel difference between two packed pixels.
int channelDistance(Pixel a, Pixel b) {
    const int dr = std::abs(int(pixelR(a)) - int(pixelR(b)));
    const int dg = std::abs(int(pixelG(a)) - int(pixelG(b)));
    const int db = std::abs(int(pixelB(a)) - int(pixelB(b)));
    return std::max(dr, std::max(dg, db));
}

} // namespace

TEST_CASE("gradient colours stay in range and opaque", "[platform]") {
    for (double t : {0.0, 1.0, 2.5, 5.99, 6.0, 1e6, -3.0}) {
        const GradientCorners c = gradientCorners(t);
        for (const Color& k : {c.topLeft, c.topRight, c.bottomLeft, c.bottomRight}) {
            CHECK(k.r >= 0.0f);
            CHECK(k.r <= 1.0f);
            CHECK(k.g >= 0.0f);
            CHECK(k.g <= 1.0f);
            CHECK(k.b >= 0.0f);
            CHECK(k.b <= 1.0f);
            CHECK(k.a == 1.0f);
        }
    }
}

TEST_CASE("gradientColor hits the corners at (0,0), (1,0), (0,1), (1,1)", "[platform]") {
    const GradientCorners c = gradientCorners(1.25);
    const auto same = [](Color a, Color b) {
        return a.r == Approx(b.r) && a.g == Approx(b.g) && a.b == Approx(b.b) && a.a == Approx(b.a);
    };
    CHECK(same(gradientColor(c, 0, 0), c.topLeft));
    CHECK(same(gradientColor(c, 1, 0), c.topRight));
    CHECK(same(gradientColor(c, 0, 1), c.bottomLeft));
    CHECK(same(gradientColor(c, 1, 1), c.bottomRight));
}

TEST_CASE("the animation is periodic and actually moves", "[platform]") {
    const GradientCorners a = gradientCorners(0.5);
    const GradientCorners b = gradientCorners(0.5 + kGradientPeriodSeconds);
    CHECK(a.topLeft.r == Approx(b.topLeft.r).margin(1e-5));
    CHECK(a.bottomRight.g == Approx(b.bottomRight.g).margin(1e-5));
    const GradientCorners later = gradientCorners(0.5 + kGradientPeriodSeconds / 4);
    CHECK(std::abs(later.topLeft.r - a.topLeft.r) + std::abs(later.topLeft.g - a.topLeft.g) > 0.1f);
}

TEST_CASE("renderGradient samples pixel centres", "[platform]") {
    FrameBuffer fb(64, 32);
    fb.clear(0);
    const double t = 2.0;
    renderGradient(fb, t);
    const GradientCorners c = gradientCorners(t);
    for (int y : {0, 7, 31}) {
        for (int x : {0, 13, 63}) {
            const float u = (float(x) + 0.5f) / 64.0f;
            const float v = (float(y) + 0.5f) / 32.0f;
            INFO("pixel " << x << "," << y);
            // Row-then-column blending may round differently from gradientColor by 1 step.
            CHECK(channelDistance(fb.pixel(x, y), packBgra8(gradientColor(c, u, v))) <= 1);
            CHECK((fb.pixel(x, y) >> 24) == 0xFFu); // X byte opaque
        }
    }
}

TEST_CASE("the gradient is not a flat colour", "[platform]") {
    FrameBuffer fb(320, 180);
    renderGradient(fb, 0.0);
    std::set<Pixel> distinct;
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x)
            distinct.insert(fb.pixel(x, y));
    CHECK(distinct.size() > 100);
    CHECK(channelDistance(fb.pixel(0, 0), fb.pixel(319, 179)) > 64);
}

TEST_CASE("renderGradient handles 0x0 and 1x1 framebuffers", "[platform]") {
    FrameBuffer empty;
    REQUIRE(empty.resize(0, 0));
    renderGradient(empty, 1.0); // nothing to draw, nothing written
    CHECK(empty.empty());

    FrameBuffer one(1, 1);
    renderGradient(one, 1.0);
    const GradientCorners c = gradientCorners(1.0);
    CHECK(channelDistance(one.pixel(0, 0), packBgra8(gradientColor(c, 0.5f, 0.5f))) <= 1);

    // Shrinking to 0x0 and growing back keeps working (a minimise / restore cycle).
    FrameBuffer fb(8, 8);
    REQUIRE(fb.resize(0, 0));
    renderGradient(fb, 0.0);
    REQUIRE(fb.resize(8, 8));
    renderGradient(fb, 0.0);
    CHECK((fb.pixel(7, 7) >> 24) == 0xFFu);
}
