// Image error metrics: mean absolute error, MSE -> PSNR = 10 log10(255^2 / MSE), SSIM (separable Gaussian statistics), the heat map.
#include "Platform/Headless/ImageCompare.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

namespace sr::headless {
namespace {

// One channel of a pixel: 0 red, 1 green, 2 blue.
int channel(Pixel p, int c) { return c == 0 ? int(pixelR(p)) : c == 1 ? int(pixelG(p)) : int(pixelB(p)); }

} // namespace

ImageError compareImages(const FrameBuffer& reference, const FrameBuffer& test, bool withSsim) {
    assert(reference.width() == test.width() && reference.height() == test.height());
    ImageError e;
    double sumSq = 0.0, sumAbs = 0.0;
    const std::int64_t n = std::int64_t(reference.width()) * reference.height();
    for (int y = 0; y < reference.height(); ++y) {
        const Pixel* a = reference.colorRow(y);
        const Pixel* b = test.colorRow(y);
        for (int x = 0; x < reference.width(); ++x) {
            const int dr = std::abs(int(pixelR(a[x])) - int(pixelR(b[x])));
            const int dg = std::abs(int(pixelG(a[x])) - int(pixelG(b[x])));
            const int db = std::abs(int(pixelB(a[x])) - int(pixelB(b[x])));
            const int m = std::max(dr, std::max(dg, db));
            e.maxAbs = std::max(e.maxAbs, m);
            e.differing += m > 0;
            sumSq += double(dr * dr + dg * dg + db * db);
            sumAbs += double(dr + dg + db);
        }
    }
    e.differingShare = n > 0 ? double(e.differing) / double(n) : 0.0;
    e.meanAbs = n > 0 ? sumAbs / (3.0 * double(n)) : 0.0;
    const double mse = n > 0 ? sumSq / (3.0 * double(n)) : 0.0;
    e.psnrDb = mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
    if (withSsim) e.ssim = e.differing == 0 ? 1.0 : app::structuralSimilarity(reference, test);
    return e;
}

Image errorHeatMap(const FrameBuffer& reference, const FrameBuffer& test) {
    assert(reference.width() == test.width() && reference.height() == test.height());
    // The ramp's stops at t = 0, 0.25, 0.5, 0.75, 1: black, blue, magenta, orange, white.
    static const double kStops[5][3] = {{0, 0, 0}, {0.1, 0.1, 0.9}, {0.8, 0.1, 0.8}, {1.0, 0.55, 0.0}, {1, 1, 1}};
    Image out;
    out.width = reference.width();
    out.height = reference.height();
    out.rgba.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
    for (int y = 0; y < out.height; ++y) {
        const Pixel* a = reference.colorRow(y);
        const Pixel* b = test.colorRow(y);
        for (int x = 0; x < out.width; ++x) {
            int d = 0;
            for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(channel(a[x], c) - channel(b[x], c)));
            const double t = std::min(1.0, std::sqrt(double(d) / 64.0)) * 4.0;
            const int i = std::min(int(t), 3);
            const double f = t - double(i);
            std::uint8_t* p = &out.rgba[(std::size_t(y) * std::size_t(out.width) + std::size_t(x)) * 4];
            for (int c = 0; c < 3; ++c)
                p[c] = std::uint8_t(std::lround(255.0 * (kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c]))));
            p[3] = 255;
        }
    }
    return out;
}

FrameBuffer frameOf(const Image& image) {
    FrameBuffer fb(image.width, image.height);
    for (int y = 0; y < image.height; ++y) {
        Pixel* row = fb.colorRow(y);
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = &image.rgba[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 4];
            row[x] = packBgra(p[0], p[1], p[2]);
        }
    }
    return fb;
}

} // namespace sr::headless
