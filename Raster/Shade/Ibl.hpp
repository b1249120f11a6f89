// Image-based light: the sky's diffuse irradiance (spherical harmonics) and split-sum specular, made once.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "Math/Vec.hpp"
#include "Raster/Frame/Sky.hpp"
#include "Raster/Shade/Brdf.hpp" // brdfRoughness, brdfMetallic, maxOf, minOf, selectOf, splatAs

namespace sr {

// The directional albedo of the GGX lobe (height-correlated Smith visibility, Schlick's F) by N.V
// (columns, 0 to 1) and perceptual roughness (rows, 0 to 1, clamped to kMinRoughness), as the
// split sum's scale a and bias b of F0 (the albedo is F0 a + b) and their sum E_ss = a + b, the
// albedo of a white metal: what single scattering keeps of the light (the rest is the energy
// that multiple scattering would return; brdfMultiScatter). Importance-sampled (4096 Hammersley
// GGX samples a cell), made once per process.
struct BrdfAlbedoTable {
    static constexpr int kSize = 32;
    std::array<float, std::size_t(kSize) * std::size_t(kSize)> a{}, b{}, ess{};
};
const BrdfAlbedoTable& brdfAlbedoTable();

// The light a sky sends onto a surface, prepared once when the sky is loaded (Karis, "Real
// Shading in Unreal Engine 4", 2013: the split-sum approximation; Ramamoorthi and Hanrahan,
// "An Efficient Representation for Irradiance Environment Maps", 2001):
//  - the irradiance E(n) = integral of L(l) max(n.l, 0) dl as nine spherical-harmonic
//    coefficients (bands 0-2, convolved with the cosine lobe), projected from the sky in linear
//    light on a latitude-longitude grid: a uniform sky of radiance 1 gives E = pi everywhere;
//  - the radiance for roughness 0, 0.2, ..., 1: level 0 the sky itself (each texel the mean of
//    4 x 4 directions, decoded from sRGB), the others prefiltered by GGX (importance-sampled
//    around R = N = V, weighted by N.L) from level 0, blended between levels by roughness;
//  - the BRDF's scale and bias (a, b) by N.V and roughness, with F0 a + b the directional albedo
//    of the GGX lobe with height-correlated Smith visibility and Schlick's F.
// The levels are octahedral maps (Engelhardt and Dachsbacher, "Octahedron Environment Maps",
// 2008), so a lookup is a few additions, divisions and one bilinear footprint, with no
// trigonometry: what the span kernels evaluate lane by lane (IblTerms.inl, one source for both).
// The sky is looked up as Sky::sample does (OpenGL's cube-map faces), so what a mirror reflects
// is the background the frame shows.
class ImageLight {
public:
    explicit ImageLight(const Sky& sky);
    ImageLight(const ImageLight&) = delete; // tables() points into it
    ImageLight& operator=(const ImageLight&) = delete;

    // E(n) / pi per channel: the Lambertian radiance of a white surface with normal n (unit).
    Vec3 diffuse(Vec3 n) const;
    // The prefiltered radiance along the direction r (any length) for a perceptual roughness.
    Vec3 specular(Vec3 r, float roughness) const;
    // The split sum's scale and bias for N.V and roughness (both clamped into [0, 1]).
    void brdfScaleBias(float nDotV, float roughness, float& a, float& b) const;

    static constexpr int kLevels = 6; // roughness 0, 0.2, ..., 1
    // Each level: kSide x kSide texels of the octahedral square (u, v) in [-1, 1]^2, the pole +Y
    // at its centre, u along X, v along Z, the lower hemisphere folded onto the corners; stored
    // with a one-texel border holding the texels across each fold (u > 1 continues at (2 - u, -v)),
    // so a bilinear footprint never leaves the grid.
    static constexpr int kSide = 64;
    static constexpr int kStride = kSide + 2;
    static constexpr int kLevelTexels = kStride * kStride;
    static constexpr int kLut = BrdfAlbedoTable::kSize; // the split sum's table (brdfAlbedoTable)

    // What the per-pixel lookups read (IblTerms.inl).
    struct Tables {
        float sh[9][3];             // E / pi per coefficient and channel
        const float* radiance[3];   // per channel: kLevels levels of kLevelTexels, row-major
        const float* lutA;          // brdfAlbedoTable's a and b
        const float* lutB;
    };
    const Tables& tables() const { return tables_; }

    // The direction of the octahedral square's point (u, v), folded into [-1, 1]^2 first if it
    // lies at most one texel outside (unit length).
    static Vec3 octahedralDirection(double u, double v);

private:
    std::array<std::vector<float>, 3> radiance_; // per channel, kLevels x kLevelTexels
    Tables tables_{};
};

// The operations IblTerms.inl needs beyond Brdf.hpp's, for float (the kernels have their own):
// absOf = |a|, wholeOf = a truncated to a whole number (a in [0, 2^24)), gatherOf = the table's
// entry at a whole-number index.
inline float absOf(float a) { return std::fabs(a); }
inline float wholeOf(float a) { return float(int(a)); }
inline float gatherOf(const float* table, float index) { return table[int(index)]; }

// The lookups for float. In a namespace of their own: their Tables argument would otherwise let
// argument-dependent lookup find them beside each ISA's copy.
namespace ibl {
#include "Raster/Shade/IblTerms.inl"
} // namespace ibl

} // namespace sr
