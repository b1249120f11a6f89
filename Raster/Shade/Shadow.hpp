// Shadow maps: their settings, their storage, and the receiver test with percentage-closer filtering
// and slope-scaled bias (the pass that draws them: Raster/Frame/ShadowPass.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "Math/Mat4.hpp"
#include "Math/Vec.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Shade/Shading.hpp"

namespace sr {

// --shadows, --shadow-size, --shadow-pcf. Off: no shadow pass, no memory, the lighting as before.
struct ShadowSettings {
    bool on = false;
    int size = 2048; // texels per side of each light's map, kMinShadowSize..kMaxShadowSize (shadowMapSide)
    // PCF kernel side k (1, 3 or 5): the receiver test compares k x k texels, the one under the
    // point and its neighbours at whole-texel offsets, each lit or not, and takes the mean.
    int pcf = 3;
    // Slope-scaled bias, in texels of the map at the receiver (its world size there):
    // bias = texel x (constantBias + slopeBias x tan(angle between normal and light)), the tangent
    // capped at kMaxBiasTangent. Documented with pictures in docs/SHADOWS.md.
    float constantBias = 1.0f;
    float slopeBias = 1.0f;
    // A directional light's maps: the camera's depth range (out to the farthest point of the
    // scene's bounds) cut into this many slices, each with its own map fitted to it (cascades;
    // split at the mean of the logarithmic and the uniform split). 1..kMaxCascades.
    int cascades = 3;
};
inline constexpr int kMaxCascades = 4;
inline constexpr int kMinShadowSize = 16, kMaxShadowSize = 8192;
// A map's depth is stored in tiles of kShadowTile x kShadowTile texels (4 KiB: one page), so
// the PCF taps of a point and the texels of neighbouring screen pixels lie on a few pages and
// cache lines rather than on as many rows 8 KiB apart; a map's side is --shadow-size rounded up
// to a whole number of tiles.
inline constexpr int kShadowTile = 32;
constexpr int shadowMapSide(int size) {
    const int s = size < kMinShadowSize ? kMinShadowSize : size > kMaxShadowSize ? kMaxShadowSize : size;
    return (s + kShadowTile - 1) / kShadowTile * kShadowTile;
}
inline constexpr float kMaxBiasTangent = 10.0f;
constexpr bool validShadowPcf(int k) { return k == 1 || k == 3 || k == 5; }

// One light's map: the depth (reversed-Z, FrameBuffer::kFarDepth where nothing is) of what is
// nearest to the light, seen through `viewProj`.
struct ShadowMap {
    int light = -1;           // index into Lighting::lights
    Mat4 viewProj;            // world -> the light's clip space
    Vec3 origin, axis;        // distance from the light's near side: dot(p - origin, axis)
    bool perspective = false; // spot: perspective(fov, 1, nearZ, farZ); directional: orthographic
    float nearZ = 0.0f, farZ = 1.0f;
    float texelWorld = 0.0f;  // directional: a texel's world size; spot: per unit of distance
    float splitFar = 0.0f;    // directional: the cascade serves view depths up to this
    FrameBuffer target;       // the depth, in tiles (texelIndex; its colour is never written or read)

    // Where texel (x, y), 0 <= x, y < side, is in target's depth array: tile by tile, a row of
    // tiles after another, each tile row-major.
    std::size_t texelIndex(int x, int y) const {
        const std::size_t tilesX = std::size_t(target.width() / kShadowTile);
        const std::size_t tile = std::size_t(y / kShadowTile) * tilesX + std::size_t(x / kShadowTile);
        return tile * std::size_t(kShadowTile * kShadowTile) + std::size_t(y % kShadowTile * kShadowTile + x % kShadowTile);
    }
    float texel(int x, int y) const { return target.depthData()[texelIndex(x, y)]; }

    // z_ndc the projection gives a point at distance d (reversed-Z: nearer is larger).
    float depthAt(float d) const;
    // The fraction of the k x k PCF taps that see point p (unit normal n, unit direction l to
    // the light) lit: 1 outside the map.
    float visibility(Vec3 p, Vec3 n, Vec3 l, const ShadowSettings& s) const;
};

// Every shadow-casting light's map for one frame (RenderContext::shadows; FrameView::shadows).
struct SceneShadows {
    ShadowSettings settings;
    std::vector<ShadowMap> maps;
    // Per light: its maps are maps[firstMap .. firstMap + mapCount) (0 maps: no shadow, e.g. a
    // point light), a directional light's ordered by splitFar.
    std::vector<int> firstMap, mapCount;
    Vec3 eye, forward; // the camera: view depth = dot(p - eye, forward), forward unit

    float visibility(std::size_t light, Vec3 p, Vec3 n, Vec3 l) const {
        if (light >= mapCount.size() || mapCount[light] == 0) return 1.0f;
        const std::size_t first = std::size_t(firstMap[light]);
        std::size_t k = 0;
        if (mapCount[light] > 1) { // the cascade that covers p's view depth (the last beyond)
            const float depth = dot(p - eye, forward);
            while (k + 1 < std::size_t(mapCount[light]) && depth > maps[first + k].splitFar) ++k;
        }
        return maps[first + k].visibility(p, n, l, settings);
    }
};

// Blinn-Phong for any lights (lightTerms, Shading.hpp) with each light's contribution scaled by
// the shadow maps' visibility: where every visibility is 1 the same floats as lightTerms (and
// hence, for white directional lights, as blinnPhong).
RgbTerms shadowedTerms(const Lighting& lighting, const Specular& specular, Vec3 n, Vec3 p, Vec3 v,
                       const SceneShadows& shadows);

} // namespace sr
