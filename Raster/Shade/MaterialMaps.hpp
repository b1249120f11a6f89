// A material's texture maps beside its base colour texture: one slot per map, each named once.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "Math/Vec.hpp"
#include "Raster/Texture/Texture.hpp" // TextureFilter, WrapModes

namespace sr {

// The maps the pbr program samples (the base colour texture, which every shading model reads,
// is the material's `texture`). The order is the one in which a material's first map is taken
// for its uvs' rebase and uv set (MeshRenderer, the glTF loader's materialUvSource).
enum class MapSlot : std::uint8_t {
    MetallicRoughness,  // roughness x green, metallic x blue
    Emissive,           // RGB, sRGB
    Normal,             // tangent-space normal (PbrFactors::normalScale)
    Specular,           // KHR_materials_specular's specularTexture: its alpha, copied into RGB (SceneSetup)
    SpecularColour,     // its specularColorTexture (or KHR_materials_pbrSpecularGlossiness's specular): RGB, sRGB
    Glossiness,         // KHR_materials_pbrSpecularGlossiness's glossiness: its texture's alpha, copied into RGB
    Clearcoat,          // KHR_materials_clearcoat's weight: red
    ClearcoatRoughness, // its roughness: green
    ClearcoatNormal,    // its normal map (PbrFactors::clearcoatNormalScale)
    SheenColour,        // KHR_materials_sheen's sheenColorTexture: RGB, sRGB
    SheenRoughness,     // its sheenRoughnessTexture: its alpha, copied into RGB (SceneSetup)
    Occlusion,          // red, on the sky's light only
    Count
};
inline constexpr std::size_t kMapSlots = std::size_t(MapSlot::Count);

// Each slot's name in messages ("its clearcoat roughness texture reads ...").
inline constexpr const char* kMapSlotNames[kMapSlots] = {"metallic-roughness",  "emissive",         "normal",    "specular",
                                                         "specular colour",     "glossiness",       "clearcoat", "clearcoat roughness",
                                                         "clearcoat normal",    "sheen colour",     "sheen roughness",
                                                         "occlusion"};

// Whether the slot reads its image's alpha: the scene holds a copy with the alpha in RGB (the
// samplers filter colour), made once per image (SceneSetup).
constexpr bool readsAlpha(MapSlot s) { return s == MapSlot::Specular || s == MapSlot::Glossiness || s == MapSlot::SheenRoughness; }

// Whether the slot belongs to KHR_materials_clearcoat (read only where the material has a coat).
constexpr bool isClearcoatSlot(MapSlot s) {
    return s == MapSlot::Clearcoat || s == MapSlot::ClearcoatRoughness || s == MapSlot::ClearcoatNormal;
}

// Whether the slot belongs to KHR_materials_sheen (read only where the material has a sheen).
constexpr bool isSheenSlot(MapSlot s) { return s == MapSlot::SheenColour || s == MapSlot::SheenRoughness; }

// "No map" for a slot's value type: -1 for a texture index, null for a pointer.
template <class T>
inline constexpr T kNoMap = T{};
template <>
inline constexpr int kNoMap<int> = -1;

// One value per slot (a texture index, a texture), every slot "no map" at first.
template <class T>
struct MaterialMaps {
    std::array<T, kMapSlots> at;
    MaterialMaps() { at.fill(kNoMap<T>); }
    T& operator[](MapSlot s) { return at[std::size_t(s)]; }
    const T& operator[](MapSlot s) const { return at[std::size_t(s)]; }
    bool has(MapSlot s) const { return at[std::size_t(s)] != kNoMap<T>; }
    bool any() const {
        for (const T& v : at)
            if (v != kNoMap<T>) return true;
        return false;
    }
};

// Every slot, in order: `for (MapSlot s : kAllMapSlots)`.
inline constexpr std::array<MapSlot, kMapSlots> kAllMapSlots = {
    MapSlot::MetallicRoughness, MapSlot::Emissive,  MapSlot::Normal,             MapSlot::Specular,        MapSlot::SpecularColour,
    MapSlot::Glossiness,        MapSlot::Clearcoat, MapSlot::ClearcoatRoughness, MapSlot::ClearcoatNormal, MapSlot::SheenColour,
    MapSlot::SheenRoughness,    MapSlot::Occlusion};

// Where a material reads one map (a glTF texture reference with its sampler and
// KHR_texture_transform): its uv set (TEXCOORD_<uvSet>, Mesh::uvSets), the affine map m from
// that set's stored uvs (u, 1 - v) to the texture's (the transform, restated on stored uvs), the
// wrap along u and v, and the filter (unset: the draw's).
struct MapAddress {
    int uvSet = 0;
    float m[2][3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    WrapModes wrap;
    std::optional<TextureFilter> filter;
    Vec2 apply(Vec2 uv) const { return {m[0][0] * uv.x + m[0][1] * uv.y + m[0][2], m[1][0] * uv.x + m[1][1] * uv.y + m[1][2]}; }
};

// Every map's address, the base colour texture's included, for a material whose maps do not all
// read one uv set through one transform with one sampler; a material whose maps do has none, and
// its draws read the uvs baked with that transform (Mesh::uvs) under the draw's wrap and filter.
struct MapAddressing {
    static constexpr int kUvSets = 2; // TEXCOORD_0 and TEXCOORD_1
    MapAddress base;                  // the base colour texture's
    std::array<MapAddress, kMapSlots> maps;
    const MapAddress& operator[](MapSlot s) const { return maps[std::size_t(s)]; }
    MapAddress& operator[](MapSlot s) { return maps[std::size_t(s)]; }
};

} // namespace sr
