// The built-in default scene: every feature at a glance, generated in code (no third-party assets).
#pragma once

#include "Math/Vec.hpp"
#include "Raster/Frame/Scene.hpp"
#include "Raster/Shade/Shading.hpp"

namespace sr {

// A checker floor receding to the horizon (perspective correction and filtering visible), brick
// textured cubes, a smooth sphere and a torus with specular highlights, a block of tinted glass
// (transparent: blended after the opaque draws), and a single-sided banner that the default
// camera sees from BEHIND: cull none shows it, cull CW (back faces) hides it, cull CCW hides
// everything else and keeps it.
Scene makeDefaultScene();

// The built-in scene's second light, besides the white directional key light (--light): a
// warm point light low in front of the sphere, so the RGB lighting path is seen.
Light defaultSceneFillLight();

// The default camera of the built-in scene (world space; the floor is infinite-looking, so the
// projection has no far plane).
struct DefaultView {
    Vec3 eye{0.0f, 2.2f, 7.0f};
    Vec3 target{0.0f, 0.8f, 0.0f};
    float fovYDegrees = 60.0f;
    float nearZ = 0.1f;
};

// Where the banner's back face is drawn in the default view (normalised image coordinates of a
// point well inside it, x right, y down), for end-to-end tests that toggle the cull mode.
inline constexpr float kBannerProbeX = 0.80f;
inline constexpr float kBannerProbeY = 0.38f;

} // namespace sr
