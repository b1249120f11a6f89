// A material's texture maps beside its base colour texture: one slot per map, each named once.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

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
    Occlusion,          // red, on the sky's light only
    Count
};
inline constexpr std::size_t kMapSlots = std::size_t(MapSlot::Count);

// Each slot's name in messages ("its clearcoat roughness texture reads ...").
inline constexpr const char* kMapSlotNames[kMapSlots] = {"metallic-roughness",  "emissive",         "normal",    "specular",
                                                         "specular colour",     "glossiness",       "clearcoat", "clearcoat roughness",
                                                         "clearcoat normal",    "occlusion"};

// Whether the slot reads its image's alpha: the scene holds a copy with the alpha in RGB (the
// samplers filter colour), made once per image (SceneSetup).
constexpr bool readsAlpha(MapSlot s) { return s == MapSlot::Specular || s == MapSlot::Glossiness; }

// Whether the slot belongs to KHR_materials_clearcoat (read only where the material has a coat).
constexpr bool isClearcoatSlot(MapSlot s) {
    return s == MapSlot::Clearcoat || s == MapSlot::ClearcoatRoughness || s == MapSlot::ClearcoatNormal;
}

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
    MapSlot::Glossiness,        MapSlot::Clearcoat, MapSlot::ClearcoatRoughness, MapSlot::ClearcoatNormal, MapSlot::Occlusion};

} // namespace sr
