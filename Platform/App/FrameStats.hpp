// Frame statistics for the title bar: FPS and ms per frame averaged over a short period, the
// frames drawn so far, and the title text itself
// ("SoftRaster — 143 fps 7.0 ms — frame 1,024 — 3,212 tris — cull none | phong | ...").
#pragma once

#include <cstdint>
#include <string>

namespace sr::app {

// Averages frame times over `period` seconds, so the title changes a few times per second
// instead of flickering every frame.
class FrameStats {
public:
    explicit FrameStats(double periodSeconds = 0.25) : period_(periodSeconds) {}

    // Adds one frame that took `seconds` (non-finite or negative counts as 0). Returns true when
    // a period is complete and fps() / msPerFrame() hold a new average.
    bool addFrame(double seconds);

    bool hasAverage() const { return hasAverage_; }
    // Every frame added since construction (scripts read it from the title: rendering goes on).
    std::uint64_t totalFrames() const { return totalFrames_; }
    double fps() const { return fps_; }
    double msPerFrame() const { return ms_; }

private:
    double period_;
    double accumulated_ = 0.0;
    long long frames_ = 0;
    std::uint64_t totalFrames_ = 0;
    bool hasAverage_ = false;
    double fps_ = 0.0;
    double ms_ = 0.0;
};

// 3212 -> "3,212".
std::string withThousands(std::uint64_t value);

// The window title (UTF-8): "SoftRaster — F fps M ms — frame N — R threads — T tris — modes" and,
// when not empty, " — status" ("1 thread" for one). Without an average yet the FPS part reads
// "-- fps". N is stats.totalFrames() with thousands separators. The modes come right after
// "tris — " (scripts read them there), so the thread count, which no key changes, stands before.
std::string windowTitle(const FrameStats& stats, int threads, std::uint64_t triangles, const std::string& modes,
                        const std::string& status = {});

} // namespace sr::app
