// MaterialFactors: a glTF material's numbers as the file gives them (what KHR_animation_pointer may animate), and the Material they make.
#pragma once

#include <array>

#include "Raster/Shade/MaterialMaps.hpp" // kMapSlots

namespace sr {

struct Material; // Resources/Model.hpp

// KHR_texture_transform of one texture reference: offset, rotation (radians) and scale.
struct TextureTransform {
    std::array<double, 2> offset{0, 0};
    double rotation = 0.0;
    std::array<double, 2> scale{1, 1};
    // uv' = m (u, v, 1) in glTF's uv space (v down the image): translation x rotation x scale,
    // the extension's order, with its rotation matrix [[c, s], [-s, c]].
    void matrix(double m[2][3]) const;
    // The same map restated on stored uvs (u, 1 - v) (MapAddress::m).
    void storedMatrix(float m[2][3]) const;
};

// The numbers of a glTF material (its core factors and those of the extensions SoftRaster
// reads), unclamped, as written in the file or as an animation sets them. applyFactors turns
// them into the Material the renderer reads, under the loader's rules (GltfLoader.hpp): the
// clamps to each property's range, F0 from ior and specular, the Blinn-Phong mapping.
struct MaterialFactors {
    std::array<double, 4> baseColor{1, 1, 1, 1};
    double metallic = 1.0, roughness = 1.0;
    std::array<double, 3> emissive{0, 0, 0};
    double emissiveStrength = 1.0; // KHR_materials_emissive_strength
    double normalScale = 1.0, occlusionStrength = 1.0;
    enum class Alpha { Opaque, Mask, Blend } alphaMode = Alpha::Opaque;
    double alphaCutoff = 0.5;
    bool unlit = false; // KHR_materials_unlit
    // KHR_materials_ior and KHR_materials_specular, where the material has them.
    bool hasIor = false, hasSpecular = false;
    double ior = 1.5, specularFactor = 1.0;
    std::array<double, 3> specularColor{1, 1, 1};
    // KHR_materials_pbrSpecularGlossiness (`glossMap`: with a specularGlossinessTexture).
    bool specularGlossiness = false, glossMap = false;
    std::array<double, 3> sgSpecular{1, 1, 1};
    double glossiness = 1.0;
    // KHR_materials_clearcoat, where the material has it.
    bool hasClearcoat = false;
    double clearcoat = 0.0, clearcoatRoughness = 0.0, clearcoatNormalScale = 1.0;
    // KHR_materials_sheen, where the material has it (colour linear).
    bool hasSheen = false;
    std::array<double, 3> sheenColor{0, 0, 0};
    double sheenRoughness = 0.0;
    // Each texture reference's KHR_texture_transform: the base colour texture's, then each
    // MapSlot's (identity where there is none).
    std::array<TextureTransform, 1 + kMapSlots> transforms;
};

// Sets m's colours (kd, ks, shininess), opacity (alpha, texelAlpha) and pbr input from f; every
// other field of m (name, maps, sampler, sidedness) is left as it is.
void applyFactors(const MaterialFactors& f, Material& m);

} // namespace sr
