// LaneBalance: which render lane fills which band of rows, weighted by how fast each lane has been.
#pragma once

#include <array>
#include <cstdint>

namespace sr {

// Most lanes a pattern can share (RenderContext's kMaxRenderThreads).
inline constexpr int kMaxBalancedLanes = 64;

// A split draw cuts the target into bands of rows (LaneBands in Pipeline.hpp). Band b belongs to
// lane owners[b % period]: a pattern of `period` bands repeated down the target, lane l owning
// weights[l] of each period, spread out so that a model in one part of the screen still reaches
// every lane. Equal weights give the plain interleave, band b to lane b % lanes.
struct BandPattern {
    static constexpr int kBandsPerLane = 8; // period = 8 bands per lane (16 for two lanes)
    int lanes = 1, period = 1;
    std::array<std::uint8_t, kBandsPerLane * kMaxBalancedLanes> owners{};
    int ownerOfBand(int band) const { return owners[std::size_t(band % period)]; }
};

// The pattern of `weights` (lanes entries, each >= 1, summing to kBandsPerLane * lanes): slot i
// goes to the lane furthest behind its share of slots 0..i (weights[l] * (i + 1) / period minus
// the slots it has), ties to the lower lane.
BandPattern spreadBands(const int* weights, int lanes);

// The weights of the lanes' bands, adapted to their speed. The lanes of these 2-vCPU VMs do not
// run at the same speed (one vCPU 1.5x slower than the other in a plain FMA loop, which one
// changing by the minute), and a split draw waits for its slowest lane: each draw reports each lane's own
// busy time (record), and once enough time has been seen the weights move towards equal busy
// times, smoothed, so one noisy draw does not move them. Which lane fills which row never changes
// the image or the counters (Pipeline.hpp), only how long the draw takes.
class LaneBalance {
public:
    // Equal weights over `lanes`, adapting.
    void reset(int lanes);
    // Fixed weights (no adaptation): tests, and measurements of a given split.
    void fix(const int* weights, int lanes);

    const BandPattern& pattern() const { return pattern_; }
    int weight(int lane) const { return weights_[std::size_t(lane)]; }

    // One split draw: busySeconds[l] is lane l's time in the draw's raster job (its own work,
    // not its wait for the others).
    void record(const double* busySeconds);

    // Busy time gathered before the weights are revisited, and the smoothing: the new share is
    // kKeep * old + (1 - kKeep) * measured.
    static constexpr double kWindowSeconds = 2e-3;
    static constexpr double kKeep = 0.5;

private:
    void apply(bool force); // weights_ from share_ (unless within the hysteresis), then the pattern

    int lanes_ = 1;
    bool adaptive_ = true;
    std::array<double, kMaxBalancedLanes> share_{}; // smoothed fraction of the bands per lane
    std::array<double, kMaxBalancedLanes> busy_{};  // busy seconds since the last revision
    std::array<int, kMaxBalancedLanes> weights_{};
    BandPattern pattern_;
};

} // namespace sr
