// SSIM with separable Gaussian statistics (ImageMetrics.hpp).
#include "Platform/App/ImageMetrics.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

namespace sr::app {
namespace {

// One channel of a pixel: 0 red, 1 green, 2 blue.
int channel(Pixel p, int c) { return c == 0 ? int(pixelR(p)) : c == 1 ? int(pixelG(p)) : int(pixelB(p)); }

// The normalised Gaussian of sigma 1.5 over 2 r + 1 taps.
std::vector<double> gaussian(int r) {
    std::vector<double> w(std::size_t(2 * r + 1));
    double sum = 0.0;
    for (int i = -r; i <= r; ++i) sum += w[std::size_t(i + r)] = std::exp(-double(i * i) / (2.0 * 1.5 * 1.5));
    for (double& v : w) v /= sum;
    return w;
}

} // namespace

double structuralSimilarity(const FrameBuffer& reference, const FrameBuffer& test) {
    assert(reference.width() == test.width() && reference.height() == test.height());
    const int w = reference.width(), h = test.height();
    if (w <= 0 || h <= 0) return 1.0;
    const int r = std::min(5, (std::min(w, h) - 1) / 2);
    const std::vector<double> g = gaussian(r);
    const double c1 = (0.01 * 255.0) * (0.01 * 255.0), c2 = (0.03 * 255.0) * (0.03 * 255.0);
    const int outW = w - 2 * r, outH = h - 2 * r;
    // Per channel: the five products x, y, x^2, y^2, xy filtered along rows into `rows` (only the
    // columns whose window fits), then along columns at each output pixel.
    std::vector<std::array<double, 5>> rows(std::size_t(outW) * std::size_t(h));
    double total = 0.0;
    for (int c = 0; c < 3; ++c) {
        for (int y = 0; y < h; ++y) {
            const Pixel* a = reference.colorRow(y);
            const Pixel* b = test.colorRow(y);
            for (int x = 0; x < outW; ++x) {
                std::array<double, 5> s{};
                for (int k = 0; k <= 2 * r; ++k) {
                    const double wk = g[std::size_t(k)];
                    const double px = channel(a[x + k], c), py = channel(b[x + k], c);
                    s[0] += wk * px;
                    s[1] += wk * py;
                    s[2] += wk * px * px;
                    s[3] += wk * py * py;
                    s[4] += wk * px * py;
                }
                rows[std::size_t(y) * std::size_t(outW) + std::size_t(x)] = s;
            }
        }
        double sum = 0.0;
        for (int y = 0; y < outH; ++y)
            for (int x = 0; x < outW; ++x) {
                std::array<double, 5> s{};
                for (int k = 0; k <= 2 * r; ++k) {
                    const std::array<double, 5>& v = rows[std::size_t(y + k) * std::size_t(outW) + std::size_t(x)];
                    for (int i = 0; i < 5; ++i) s[std::size_t(i)] += g[std::size_t(k)] * v[std::size_t(i)];
                }
                const double mx = s[0], my = s[1];
                const double vx = s[2] - mx * mx, vy = s[3] - my * my, cxy = s[4] - mx * my;
                sum += (2.0 * mx * my + c1) * (2.0 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
            }
        total += sum / (double(outW) * double(outH));
    }
    return total / 3.0;
}

} // namespace sr::app
