// Image error metrics: mean absolute error, and MSE over the colour channels -> PSNR = 10 log10(255^2 / MSE).
#include "Platform/Headless/ImageCompare.hpp"

#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace sr::headless {

ImageError compareImages(const FrameBuffer& reference, const FrameBuffer& test) {
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
    return e;
}

} // namespace sr::headless
