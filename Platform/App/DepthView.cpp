// Depth buffer -> grey (log scale) and screenshot naming / writing.
#include "Platform/App/DepthView.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "Resources/Image.hpp"

namespace sr::app {

void depthToGrey(FrameBuffer& fb) {
    if (fb.empty())
        return;
    const std::size_t count = std::size_t(fb.width()) * std::size_t(fb.height());
    const float* depth = fb.depthData();
    Pixel* colour = fb.colorData();

    // Range of the covered pixels (d > 0; NaN fails the comparison and counts as background).
    float dMin = 0.0f, dMax = 0.0f;
    bool any = false;
    for (std::size_t i = 0; i < count; ++i) {
        const float d = depth[i];
        if (!(d > 0.0f) || !std::isfinite(d))
            continue;
        dMin = any ? std::min(dMin, d) : d;
        dMax = any ? std::max(dMax, d) : d;
        any = true;
    }
    const double logMin = any ? std::log(double(dMin)) : 0.0;
    const double span = any ? std::log(double(dMax)) - logMin : 0.0;
    const double scale = span > 0.0 ? 215.0 / span : 0.0;

    for (std::size_t i = 0; i < count; ++i) {
        const float d = depth[i];
        if (!(d > 0.0f) || !std::isfinite(d)) {
            colour[i] = packBgra(0, 0, 0);
            continue;
        }
        const double g = span > 0.0 ? 40.0 + (std::log(double(d)) - logMin) * scale : 255.0;
        const auto v = std::uint8_t(std::clamp(std::lround(g), 0L, 255L));
        colour[i] = packBgra(v, v, v);
    }
}

std::string screenshotName(const std::tm& when, int counter) {
    char name[80];
    std::snprintf(name, sizeof name, "SoftRaster-%04d%02d%02d-%02d%02d%02d-%d.png", when.tm_year + 1900,
                  when.tm_mon + 1, when.tm_mday, when.tm_hour, when.tm_min, when.tm_sec, counter);
    return name;
}

Status saveScreenshot(const FrameBuffer& fb, const std::string& utf8Path) {
    if (fb.empty())
        return Status::failure(utf8Path + ": nothing to save (the window has no pixels)");
    return writeImage(utf8Path, toImage(fb));
}

} // namespace sr::app
