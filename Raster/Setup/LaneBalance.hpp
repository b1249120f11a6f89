// LaneBalance: which render lane fills which band of rows, weighted by how fast each lane has been.
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>

namespace sr {

// Most lanes a pattern can share (RenderContext's kMaxRenderThreads).
inline constexpr int kMaxBalancedLanes = 64;

// A split draw cuts the target into bands of kBandRows rows (LaneBands in
// Raster/Fill/RasterizeTriangle.hpp). Band b belongs to lane owners[b % period]: a pattern of
// `period` bands repeated down the target, lane l owning weights[l] of each period, spread out
// so that a model in one part of the screen still reaches every lane. Equal weights give the
// plain interleave, band b to lane b % lanes.
struct BandPattern {
    // 32 rows: half as many triangles of a dense mesh cross a band edge (and are set up by two
    // lanes) as with 16, and a 2-lane period (16 bands, 512 rows) still spreads over a 600-row
    // target (docs/PERFORMANCE.md, Threads).
    static constexpr int kBandRows = 32;
    static constexpr int kMaxBands = 8192 / kBandRows; // FrameBuffer::kMaxDimension rows (asserted there)
    static constexpr int kBandsPerLane = 8;            // period = 8 bands per lane (16 for two lanes)
    int lanes = 1, period = 1;
    std::array<std::uint8_t, kBandsPerLane * kMaxBalancedLanes> owners{};
    // owners repeated down every band of the largest target: the owner of a band without the
    // division by `period` (binning asks for it several times per triangle).
    std::array<std::uint8_t, kMaxBands> bandOwners{};
    int ownerOfBand(int band) const {
        assert(band >= 0 && band < kMaxBands);
        return bandOwners[std::size_t(band)];
    }
};

// The pattern of `weights` (lanes entries, each >= 1, summing to kBandsPerLane * lanes): slot i
// goes to the lane furthest behind its share of slots 0..i (weights[l] * (i + 1) / period minus
// the slots it has), ties to the lower lane.
BandPattern spreadBands(const int* weights, int lanes);

// Lane `lane`'s part [begin, end) of `count` items (vertices, triangles) split over `lanes`
// lanes in proportion to `weights` (lanes entries, each >= 1; null: equal parts): the parts
// follow each other in lane order and together cover [0, count) exactly once.
struct ItemRange {
    std::size_t begin = 0, end = 0;
};
inline ItemRange weightedPart(std::size_t count, int lane, int lanes, const int* weights) {
    assert(lane >= 0 && lane < lanes);
    if (!weights)
        return {count * std::size_t(lane) / std::size_t(lanes), count * std::size_t(lane + 1) / std::size_t(lanes)};
    std::size_t before = 0, total = 0;
    for (int l = 0; l < lanes; ++l) {
        assert(weights[l] >= 1);
        if (l < lane) before += std::size_t(weights[l]);
        total += std::size_t(weights[l]);
    }
    const std::size_t through = before + std::size_t(weights[lane]);
    return {count * before / total, count * through / total};
}

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
    const int* weights() const { return weights_.data(); } // one per lane of pattern()

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
