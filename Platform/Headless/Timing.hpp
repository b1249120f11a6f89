// Frame timing for bench and report: run frames, keep each frame's milliseconds, summarise.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace sr::headless {

struct TimingSummary {
    double median = 0.0, min = 0.0, mean = 0.0; // milliseconds per frame
};

inline TimingSummary summarise(std::vector<double> ms) {
    TimingSummary s;
    if (ms.empty()) return s;
    std::sort(ms.begin(), ms.end());
    const std::size_t n = ms.size();
    s.median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    s.min = ms.front();
    double sum = 0.0;
    for (double v : ms) sum += v;
    s.mean = sum / double(n);
    return s;
}

// Runs `warmup` untimed frames, then `frames` timed ones; returns each timed frame's ms.
template <class Frame>
std::vector<double> timeFrames(int warmup, int frames, Frame&& frame) {
    using Clock = std::chrono::steady_clock;
    for (int i = 0; i < warmup; ++i) frame();
    std::vector<double> ms;
    ms.reserve(std::size_t(std::max(frames, 0)));
    for (int i = 0; i < frames; ++i) {
        const auto t0 = Clock::now();
        frame();
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    return ms;
}

} // namespace sr::headless
