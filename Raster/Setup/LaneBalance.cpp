// LaneBalance: the band pattern and its adaptation (see LaneBalance.hpp).
#include "Raster/Setup/LaneBalance.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace sr {

BandPattern spreadBands(const int* weights, int lanes) {
    assert(lanes >= 1 && lanes <= kMaxBalancedLanes);
    BandPattern p;
    p.lanes = lanes;
    p.period = BandPattern::kBandsPerLane * lanes;
    std::array<int, kMaxBalancedLanes> given{};
    for (int i = 0; i < p.period; ++i) {
        // deficit of lane l after slot i, in 1 / period units: weights[l] * (i + 1) - period * given[l]
        int best = 0;
        long bestDeficit = 0;
        for (int l = 0; l < lanes; ++l) {
            const long deficit = long(weights[l]) * (i + 1) - long(p.period) * given[std::size_t(l)];
            if (l == 0 || deficit > bestDeficit) {
                best = l;
                bestDeficit = deficit;
            }
        }
        p.owners[std::size_t(i)] = std::uint8_t(best);
        ++given[std::size_t(best)];
    }
    for (int b = 0; b < BandPattern::kMaxBands; ++b) p.bandOwners[std::size_t(b)] = p.owners[std::size_t(b % p.period)];
    return p;
}

void LaneBalance::reset(int lanes) {
    lanes_ = std::clamp(lanes, 1, kMaxBalancedLanes);
    adaptive_ = true;
    for (int l = 0; l < lanes_; ++l) share_[std::size_t(l)] = 1.0 / lanes_;
    busy_.fill(0.0);
    apply(true);
}

void LaneBalance::fix(const int* weights, int lanes) {
    lanes_ = std::clamp(lanes, 1, kMaxBalancedLanes);
    adaptive_ = false;
    busy_.fill(0.0);
    for (int l = 0; l < lanes_; ++l) weights_[std::size_t(l)] = weights[l];
    pattern_ = spreadBands(weights_.data(), lanes_);
}

void LaneBalance::record(const double* busySeconds) {
    if (!adaptive_ || lanes_ < 2) return;
    double total = 0.0;
    for (int l = 0; l < lanes_; ++l) {
        busy_[std::size_t(l)] += std::max(busySeconds[l], 0.0);
        total += busy_[std::size_t(l)];
    }
    if (!(total >= kWindowSeconds)) return;
    // Lane l filled weights_[l] bands of each period in busy_[l] seconds: its speed in bands per
    // second. The shares that would have made the busy times equal are the speeds' fractions.
    std::array<double, kMaxBalancedLanes> speed{};
    double speedSum = 0.0;
    const double least = total * 1e-3; // a lane that did (almost) nothing counts as very fast, not infinitely
    for (int l = 0; l < lanes_; ++l) {
        speed[std::size_t(l)] = weights_[std::size_t(l)] / std::max(busy_[std::size_t(l)], least);
        speedSum += speed[std::size_t(l)];
    }
    for (int l = 0; l < lanes_; ++l)
        share_[std::size_t(l)] = kKeep * share_[std::size_t(l)] + (1.0 - kKeep) * speed[std::size_t(l)] / speedSum;
    busy_.fill(0.0);
    apply(false);
}

void LaneBalance::apply(bool force) {
    // Largest remainder over period - lanes slots after one slot each (every lane keeps a band),
    // with a hysteresis: the weights stay unless some lane's share is more than 0.6 of a band
    // away from its weight (noise of a few percent does not flip a band back and forth).
    const int period = BandPattern::kBandsPerLane * lanes_;
    if (!force) {
        bool far = false;
        for (int l = 0; l < lanes_; ++l)
            far = far || std::fabs(share_[std::size_t(l)] * period - weights_[std::size_t(l)]) > 0.6;
        if (!far) return;
    }
    const int spare = period - lanes_;
    std::array<double, kMaxBalancedLanes> remainder{};
    int given = 0;
    for (int l = 0; l < lanes_; ++l) {
        const double want = std::max(share_[std::size_t(l)] * period - 1.0, 0.0);
        const int whole = std::min(int(want), spare - given);
        weights_[std::size_t(l)] = 1 + whole;
        remainder[std::size_t(l)] = want - whole;
        given += whole;
    }
    while (given < spare) {
        int best = 0;
        for (int l = 1; l < lanes_; ++l)
            if (remainder[std::size_t(l)] > remainder[std::size_t(best)]) best = l;
        ++weights_[std::size_t(best)];
        remainder[std::size_t(best)] = -1.0;
        ++given;
    }
    pattern_ = spreadBands(weights_.data(), lanes_);
}

} // namespace sr
