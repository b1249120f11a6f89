// How a frame is anti-aliased: one value for the mode and its sample count.
#pragma once

#include <cstdint>
#include <optional>

#include "Raster/Frame/Msaa.hpp"    // validMsaa
#include "Raster/Frame/Resolve.hpp" // ssaaFactor

namespace sr {

enum class AaMode : std::uint8_t {
    None,        // one sample per pixel, at its centre
    Supersample, // SSAA: every sample shaded on a 2x2 or 4x4 grid, box-filtered (Resolve.hpp)
    Multisample, // MSAA: coverage and depth per sample, shaded once per pixel (Msaa.hpp)
    PostFilter,  // FXAA: one sample, the finished image's edges filtered (Fxaa.hpp)
};

// One sample, or supersampling with 4 or 16 samples, or multisampling with 2, 4 or 8, or one
// sample with FXAA. Only none(), supersample(n), multisample(n) and fxaa() make one, and the
// counted two check n (the one place the counts are validated), so a value cannot hold two
// modes or a count its mode lacks.
class AntiAliasing {
public:
    constexpr AntiAliasing() = default;
    static constexpr AntiAliasing none() { return {}; }
    // n = 1: none(); n not 1, 4 or 16: nullopt.
    static constexpr std::optional<AntiAliasing> supersample(int samples) {
        if (ssaaFactor(samples) == 0) return std::nullopt;
        return samples == 1 ? none() : AntiAliasing(AaMode::Supersample, samples);
    }
    // n = 1: none(); n not 1, 2, 4 or 8: nullopt.
    static constexpr std::optional<AntiAliasing> multisample(int samples) {
        if (!validMsaa(samples)) return std::nullopt;
        return samples == 1 ? none() : AntiAliasing(AaMode::Multisample, samples);
    }

    static constexpr AntiAliasing fxaa() { return AntiAliasing(AaMode::PostFilter, 1); }

    constexpr AaMode mode() const { return mode_; }
    constexpr int samples() const { return samples_; } // per pixel: 1 without anti-aliasing
    constexpr bool supersampled() const { return mode_ == AaMode::Supersample; }
    constexpr bool multisampled() const { return mode_ == AaMode::Multisample; }
    constexpr bool postFiltered() const { return mode_ == AaMode::PostFilter; }
    // The count of one mode, 1 when the other mode (or none) is on: --ssaa's and --msaa's values.
    constexpr int ssaaSamples() const { return supersampled() ? samples_ : 1; }
    constexpr int msaaSamples() const { return multisampled() ? samples_ : 1; }
    // The side of the supersampling grid: 1, 2 or 4 (lines and outlines are this many target
    // pixels wide, so that they keep their width after the resolve).
    constexpr int gridSide() const { return ssaaFactor(ssaaSamples()); }

    friend constexpr bool operator==(AntiAliasing a, AntiAliasing b) {
        return a.mode_ == b.mode_ && a.samples_ == b.samples_;
    }
    friend constexpr bool operator!=(AntiAliasing a, AntiAliasing b) { return !(a == b); }

private:
    constexpr AntiAliasing(AaMode mode, int samples) : mode_(mode), samples_(std::uint8_t(samples)) {}
    AaMode mode_ = AaMode::None;
    std::uint8_t samples_ = 1;
};

} // namespace sr
