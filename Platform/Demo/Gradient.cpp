// The first-light picture: corner colours cycle through hues; pixels blend them bilinearly.
#include "Platform/Demo/Gradient.hpp"

#include <cmath>

namespace sr::demo {

namespace {

// A fully saturated hue for phase in [0, 1): cosine ramps for R, G, B a third of a turn apart
// (a smooth stand-in for HSV that never goes dark), kept in [0.1, 0.9].
Color hue(double phase) {
    constexpr double kTwoPi = 6.283185307179586;
    const auto channel = [phase](double offset) {
        return float(0.5 + 0.4 * std::cos(kTwoPi * (phase + offset)));
    };
    return Color{channel(0.0), channel(-1.0 / 3.0), channel(-2.0 / 3.0), 1.0f};
}

} // namespace

GradientCorners gradientCorners(double timeSeconds) {
    // Reduce the time to a phase in [0, 1) in double first: float time loses precision in hours.
    double phase = std::fmod(timeSeconds / kGradientPeriodSeconds, 1.0);
    if (phase < 0.0)
        phase += 1.0;
    return GradientCorners{hue(phase), hue(phase + 0.25), hue(phase + 0.75), hue(phase + 0.5)};
}

Color gradientColor(const GradientCorners& c, float u, float v) {
    return lerp(lerp(c.topLeft, c.topRight, u), lerp(c.bottomLeft, c.bottomRight, u), v);
}

void renderGradient(FrameBuffer& fb, double timeSeconds) {
    const int w = fb.width();
    const int h = fb.height();
    if (fb.empty())
        return;
    const GradientCorners c = gradientCorners(timeSeconds);
    const float invW = 1.0f / float(w);
    const float invH = 1.0f / float(h);
    // Per row: blend the left and right edge colours once; per pixel: one lerp across the row.
    for (int y = 0; y < h; ++y) {
        const float v = (float(y) + 0.5f) * invH;
        const Color left = lerp(c.topLeft, c.bottomLeft, v);
        const Color right = lerp(c.topRight, c.bottomRight, v);
        Pixel* row = fb.colorRow(y);
        for (int x = 0; x < w; ++x) {
            const float u = (float(x) + 0.5f) * invW;
            row[x] = packBgra8(lerp(left, right, u));
        }
    }
}

} // namespace sr::demo
