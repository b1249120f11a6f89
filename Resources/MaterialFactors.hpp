// MaterialFactors: a glTF material's numbers as the file gives them (what KHR_animation_pointer may animate), and the Material they make.
#pragma once

#include <array>

namespace sr {

struct Material; // Resources/Model.hpp

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
};

// Sets m's colours (kd, ks, shininess), opacity (alpha, texelAlpha) and pbr input from f; every
// other field of m (name, maps, sampler, sidedness) is left as it is.
void applyFactors(const MaterialFactors& f, Material& m);

} // namespace sr
