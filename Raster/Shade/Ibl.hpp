// Image-based light: the sky's diffuse irradiance (spherical harmonics) and split-sum specular, made once.
#pragma once

#include <array>
#include <vector>

#include "Math/Vec.hpp"
#include "Raster/Frame/Sky.hpp"

namespace sr {

// The light a sky sends onto a surface, prepared once when the sky is loaded (Karis, "Real
// Shading in Unreal Engine 4", 2013: the split-sum approximation; Ramamoorthi and Hanrahan,
// "An Efficient Representation for Irradiance Environment Maps", 2001):
//  - the sky in linear light (its texels decoded from sRGB) on a latitude-longitude grid;
//  - the irradiance E(n) = integral of L(l) max(n.l, 0) dl as nine spherical-harmonic
//    coefficients (bands 0-2, convolved with the cosine lobe): a uniform sky of radiance 1 gives
//    E = pi everywhere;
//  - the specular radiance prefiltered by GGX for roughness 0, 0.2, ..., 1 (importance-sampled
//    around R = N = V), each level a grid of its own, blended between levels by roughness;
//  - the BRDF's scale and bias (a, b) by N.V and roughness, with F0 a + b the directional albedo
//    of the GGX lobe with height-correlated Smith visibility and Schlick's F.
// The sky is looked up as Sky::sample does (OpenGL's cube-map faces), so what a mirror reflects
// is the background the frame shows.
class ImageLight {
public:
    explicit ImageLight(const Sky& sky);

    // E(n) / pi per channel: the Lambertian radiance of a white surface with normal n (unit).
    Vec3 diffuse(Vec3 n) const;
    // The prefiltered radiance along the unit direction r for a perceptual roughness.
    Vec3 specular(Vec3 r, float roughness) const;
    // The split sum's scale and bias for N.V and roughness (both clamped into [0, 1]).
    void brdfScaleBias(float nDotV, float roughness, float& a, float& b) const;

    static constexpr int kLevels = 6; // roughness 0, 0.2, ..., 1

private:
    struct Grid {
        int width = 0, height = 0;
        std::vector<Vec3> texels; // row 0 at the zenith (+Y), column 0 at azimuth 0 (+X), eastward to +Z
        Vec3 sample(Vec3 r) const; // bilinear, wrapping in azimuth
    };
    std::array<Vec3, 9> sh_{};              // irradiance / pi, per coefficient
    std::array<Grid, kLevels> levels_;
    static constexpr int kLut = 32;
    std::vector<float> lutA_, lutB_;        // kLut x kLut, row = roughness, column = N.V
};

} // namespace sr
