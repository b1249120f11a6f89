// Frame-time averaging and the title-bar text.
#include "Platform/App/FrameStats.hpp"

#include <cmath>
#include <cstdio>

namespace sr::app {

bool FrameStats::addFrame(double seconds) {
    accumulated_ += (std::isfinite(seconds) && seconds > 0.0) ? seconds : 0.0;
    ++frames_;
    ++totalFrames_;
    if (accumulated_ < period_)
        return false;
    fps_ = double(frames_) / accumulated_;
    ms_ = 1000.0 * accumulated_ / double(frames_);
    hasAverage_ = true;
    accumulated_ = 0.0;
    frames_ = 0;
    return true;
}

std::string withThousands(std::uint64_t value) {
    std::string digits = std::to_string(value);
    std::string out;
    const std::size_t n = digits.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (i > 0 && (n - i) % 3 == 0)
            out += ',';
        out += digits[i];
    }
    return out;
}

std::string windowTitle(const FrameStats& stats, int threads, std::uint64_t triangles, const std::string& modes,
                        const std::string& status) {
    static const char* const kDash = " \xE2\x80\x94 "; // U+2014 EM DASH, UTF-8
    char perf[64];
    if (stats.hasAverage())
        std::snprintf(perf, sizeof perf, "%.0f fps %.1f ms", stats.fps(), stats.msPerFrame());
    else
        std::snprintf(perf, sizeof perf, "-- fps");
    std::string title = "SoftRaster";
    title += kDash;
    title += perf;
    title += kDash;
    title += "frame " + withThousands(stats.totalFrames());
    title += kDash;
    title += std::to_string(threads) + (threads == 1 ? " thread" : " threads");
    title += kDash;
    title += withThousands(triangles) + " tris";
    title += kDash;
    title += modes;
    if (!status.empty()) {
        title += kDash;
        title += status;
    }
    return title;
}

} // namespace sr::app
