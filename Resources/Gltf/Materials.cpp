// gltfimport materials: metallic-roughness as the renderer's Material, samplers as wrap modes and filters, KHR_texture_transform.
#include <algorithm>
#include <cmath>
#include <array>
#include <cstdint>
#include <optional>

#include "Resources/Gltf/Import.hpp"
#include "Resources/MaterialFactors.hpp"

namespace sr::gltfimport {

namespace {

// A non-negative finite number at `key` of an extension object, else `fallback`.
double extensionNumber(const gltf::Json& ext, const char* key, double fallback) {
    if (!ext.is_object()) return fallback;
    const auto v = ext.find(key);
    return v != ext.end() && v->is_number() && std::isfinite(v->get<double>()) && v->get<double>() >= 0.0 ? v->get<double>() : fallback;
}

// A texture reference's KHR_texture_transform values (a value missing or not a number: its default).
TextureTransform transformOf(const gltf::Json& v) {
    TextureTransform t;
    const auto number = [&](const gltf::Json& x, double fallback) {
        return x.is_number() && std::isfinite(x.get<double>()) ? x.get<double>() : fallback;
    };
    const auto pair = [&](const char* key) { return v.contains(key) && v[key].is_array() && v[key].size() == 2; };
    for (std::size_t k = 0; k < 2; ++k) {
        if (pair("offset")) t.offset[k] = number(v["offset"][k], 0.0);
        if (pair("scale")) t.scale[k] = number(v["scale"][k], 1.0);
    }
    if (v.contains("rotation")) t.rotation = number(v["rotation"], 0.0);
    return t;
}

// A matrix on glTF's uvs restated on stored uvs (u, 1 - v): with s = u and t = 1 - v,
// s' = m00 s - m01 t + (m01 + m02), t' = -m10 s + m11 t + (1 - m11 - m12).
void restate(const double (&m)[2][3], float out[2][3]) {
    out[0][0] = float(m[0][0]);
    out[0][1] = float(-m[0][1]);
    out[0][2] = float(m[0][1] + m[0][2]);
    out[1][0] = float(-m[1][0]);
    out[1][1] = float(m[1][1]);
    out[1][2] = float(1.0 - m[1][1] - m[1][2]);
}

} // namespace

const gltf::TextureInfo& textureInfoOf(const gltf::Material& gm, MapSlot slot) {
    static const gltf::TextureInfo none;
    switch (slot) {
    case MapSlot::MetallicRoughness: return gm.pbrMetallicRoughness.metallicRoughnessTexture;
    case MapSlot::Emissive: return gm.emissiveTexture;
    case MapSlot::Normal: return gm.normalTexture;
    case MapSlot::Specular: return gm.specularTexture;
    case MapSlot::SpecularColour: return gm.specularColorTexture;
    case MapSlot::Glossiness: return gm.glossinessTexture;
    case MapSlot::Clearcoat: return gm.clearcoatTexture;
    case MapSlot::ClearcoatRoughness: return gm.clearcoatRoughnessTexture;
    case MapSlot::ClearcoatNormal: return gm.clearcoatNormalTexture;
    case MapSlot::SheenColour: return gm.sheenColorTexture;
    case MapSlot::SheenRoughness: return gm.sheenRoughnessTexture;
    case MapSlot::Occlusion: return gm.occlusionTexture;
    case MapSlot::Count: break;
    }
    return none;
}

MaterialFactors factorsOf(const gltf::Material& gm) {
    const auto& pbr = gm.pbrMetallicRoughness;
    MaterialFactors f;
    for (std::size_t c = 0; c < 4 && c < pbr.baseColorFactor.size(); ++c) f.baseColor[c] = pbr.baseColorFactor[c];
    f.metallic = pbr.metallicFactor;
    f.roughness = pbr.roughnessFactor;
    for (std::size_t c = 0; c < 3 && c < gm.emissiveFactor.size(); ++c) f.emissive[c] = gm.emissiveFactor[c];
    if (const auto ext = gm.extensions.find("KHR_materials_emissive_strength"); ext != gm.extensions.end()) {
        const auto v = ext->find("emissiveStrength");
        if (v != ext->end() && v->is_number()) f.emissiveStrength = v->get<double>();
    }
    f.normalScale = gm.normalTexture.scale;
    f.occlusionStrength = gm.occlusionTexture.strength;
    f.alphaMode = gm.alphaMode == "BLEND" ? MaterialFactors::Alpha::Blend
                  : gm.alphaMode == "MASK" ? MaterialFactors::Alpha::Mask
                                           : MaterialFactors::Alpha::Opaque;
    f.alphaCutoff = gm.alphaCutoff;
    f.unlit = gm.extensions.contains("KHR_materials_unlit");
    const auto iorExt = gm.extensions.find("KHR_materials_ior"), specExt = gm.extensions.find("KHR_materials_specular");
    f.hasIor = iorExt != gm.extensions.end();
    f.hasSpecular = specExt != gm.extensions.end();
    if (f.hasIor) f.ior = extensionNumber(*iorExt, "ior", 1.5);
    if (f.hasSpecular) {
        f.specularFactor = extensionNumber(*specExt, "specularFactor", 1.0);
        if (specExt->is_object() && specExt->contains("specularColorFactor")) {
            const gltf::Json& t = (*specExt)["specularColorFactor"];
            for (std::size_t c = 0; c < 3; ++c)
                if (t.is_array() && t.size() == 3 && t[c].is_number()) f.specularColor[c] = t[c].get<double>();
        }
    }
    const auto& sg = gm.specularGlossiness;
    f.specularGlossiness = sg.present;
    f.glossMap = sg.present && gm.glossinessTexture.index >= 0;
    f.glossiness = sg.glossinessFactor;
    for (std::size_t c = 0; c < 3; ++c) f.sgSpecular[c] = c < sg.specularFactor.size() ? sg.specularFactor[c] : 1.0;
    for (std::size_t k = 0; k < f.transforms.size(); ++k) {
        const gltf::TextureInfo& info = k == 0 ? pbr.baseColorTexture : textureInfoOf(gm, kAllMapSlots[k - 1]);
        if (const auto ext = info.extensions.find("KHR_texture_transform"); ext != info.extensions.end() && ext->is_object())
            f.transforms[k] = transformOf(*ext);
    }
    if (const auto ext = gm.extensions.find("KHR_materials_clearcoat"); ext != gm.extensions.end()) {
        f.hasClearcoat = true;
        f.clearcoat = extensionNumber(*ext, "clearcoatFactor", 0.0);
        f.clearcoatRoughness = extensionNumber(*ext, "clearcoatRoughnessFactor", 0.0);
        f.clearcoatNormalScale = gm.clearcoatNormalTexture.scale;
    }
    if (const auto ext = gm.extensions.find("KHR_materials_sheen"); ext != gm.extensions.end()) {
        f.hasSheen = true;
        f.sheenRoughness = extensionNumber(*ext, "sheenRoughnessFactor", 0.0);
        if (ext->is_object() && ext->contains("sheenColorFactor")) {
            const gltf::Json& t = (*ext)["sheenColorFactor"];
            for (std::size_t c = 0; c < 3; ++c)
                if (t.is_array() && t.size() == 3 && t[c].is_number()) f.sheenColor[c] = t[c].get<double>();
        }
    }
    return f;
}

Material materialFrom(const gltf::Material& gm) {
    Material m;
    m.name = gm.name;
    m.fromFile = true;
    m.doubleSided = gm.doubleSided;
    applyFactors(factorsOf(gm), m);
    return m;
}

} // namespace sr::gltfimport

namespace sr {

void TextureTransform::matrix(double m[2][3]) const {
    const double c = std::cos(rotation), s = std::sin(rotation);
    m[0][0] = c * scale[0];
    m[0][1] = s * scale[1];
    m[0][2] = offset[0];
    m[1][0] = -s * scale[0];
    m[1][1] = c * scale[1];
    m[1][2] = offset[1];
}

void TextureTransform::storedMatrix(float out[2][3]) const {
    double m[2][3];
    matrix(m);
    gltfimport::restate(m, out);
}

// The metallic-roughness to Blinn-Phong mapping of GltfLoader.hpp.
void applyFactors(const MaterialFactors& in, Material& m) {
    const auto number = [](double v, double fallback) { return std::isfinite(v) && v >= 0.0 ? v : fallback; };
    double metal = std::clamp(in.metallic, 0.0, 1.0), rough = std::clamp(in.roughness, 0.0, 1.0);
    double base[3];
    for (std::size_t c = 0; c < 3; ++c) base[c] = std::clamp(in.baseColor[c], 0.0, 1.0);
    // The dielectric's F0 and specular weight: KHR_materials_ior (ior >= 1, or 0: F0 = 1) and
    // KHR_materials_specular (specularFactor in [0, 1], specularColorFactor >= 0); without them
    // 0.04 and 1 exactly.
    double f0[3] = {0.04, 0.04, 0.04}, f0Unclamped[3] = {0.04, 0.04, 0.04}, weight = 1.0;
    if (in.hasIor || in.hasSpecular) {
        double ior = in.hasIor ? number(in.ior, 1.5) : 1.5;
        if (ior > 0.0 && ior < 1.0) ior = 1.5; // outside the extension's range: its default
        const double r = (ior - 1.0) / (ior + 1.0);
        for (std::size_t c = 0; c < 3; ++c) {
            const double tint = in.hasSpecular && std::isfinite(in.specularColor[c]) ? std::max(in.specularColor[c], 0.0) : 1.0;
            f0[c] = std::min(r * r * tint, 1.0);
            f0Unclamped[c] = r * r * tint;
        }
        if (in.hasSpecular) weight = std::min(number(in.specularFactor, 1.0), 1.0);
    }
    // KHR_materials_pbrSpecularGlossiness (its appendix): a dielectric with F0 = specular (RGB),
    // roughness 1 - glossiness and c_diff = diffuse x (1 - max(F0)). The diffuse is the base
    // colour here (Document.cpp); without a specularGlossinessTexture the factor 1 - max(F0) is
    // folded into it, with one the program applies it per pixel (kLobeSpecularGlossiness).
    const bool glossMap = in.specularGlossiness && in.glossMap;
    double glossiness = 1.0, diffuseScale = 1.0;
    if (in.specularGlossiness) {
        glossiness = std::isfinite(in.glossiness) ? std::clamp(in.glossiness, 0.0, 1.0) : 1.0;
        metal = 0.0;
        rough = 1.0 - glossiness;
        double largest = 0.0;
        for (std::size_t c = 0; c < 3; ++c) {
            const double v = std::isfinite(in.sgSpecular[c]) ? in.sgSpecular[c] : 1.0;
            f0[c] = f0Unclamped[c] = std::clamp(v, 0.0, 1.0);
            largest = std::max(largest, f0[c]);
        }
        weight = 1.0;
        diffuseScale = 1.0 - largest;
        if (!glossMap)
            for (double& b : base) b *= diffuseScale;
    }
    const double kdScale = (1 - metal) * (glossMap ? diffuseScale : 1.0);
    m.kd = Color{float(base[0] * kdScale), float(base[1] * kdScale), float(base[2] * kdScale), 1.0f};
    m.ks = Color{float(f0[0] * weight * (1 - metal) + base[0] * metal), float(f0[1] * weight * (1 - metal) + base[1] * metal),
                 float(f0[2] * weight * (1 - metal) + base[2] * metal), 1.0f};
    const double alpha = rough * rough;
    const double n = alpha > 0.0 ? 2.0 / (alpha * alpha) - 2.0 : 1024.0;
    m.shininess = float(std::clamp(std::round(n), 1.0, 1024.0));
    PbrFactors f;
    f.baseColor = Color{float(base[0]), float(base[1]), float(base[2]), 1.0f};
    f.metallic = float(metal);
    f.roughness = float(rough);
    f.dielectricF0 = Vec3{float(f0[0]), float(f0[1]), float(f0[2])};
    f.specularColorF0 = Vec3{float(f0Unclamped[0]), float(f0Unclamped[1]), float(f0Unclamped[2])};
    f.specularWeight = float(weight);
    f.specularGlossiness = glossMap;
    f.glossiness = float(glossiness);
    double emissive[3];
    for (std::size_t c = 0; c < 3; ++c) emissive[c] = std::clamp(in.emissive[c], 0.0, 1.0);
    const double strength = std::max(in.emissiveStrength, 0.0);
    f.emissive = Vec3{float(emissive[0] * strength), float(emissive[1] * strength), float(emissive[2] * strength)};
    f.normalScale = std::isfinite(in.normalScale) ? float(in.normalScale) : 1.0f;
    f.occlusionStrength = float(std::clamp(in.occlusionStrength, 0.0, 1.0));
    f.unlit = in.unlit;
    // KHR_materials_clearcoat: the layer's weight and roughness in [0, 1], its normal map's scale.
    if (in.hasClearcoat) {
        f.clearcoat = float(std::min(number(in.clearcoat, 0.0), 1.0));
        f.clearcoatRoughness = float(std::min(number(in.clearcoatRoughness, 0.0), 1.0));
        f.clearcoatNormalScale = std::isfinite(in.clearcoatNormalScale) ? float(in.clearcoatNormalScale) : 1.0f;
    }
    // KHR_materials_sheen: its colour and roughness in [0, 1] (NaN 0).
    if (in.hasSheen) {
        const auto unit = [&](double v) { return float(std::min(number(v, 0.0), 1.0)); };
        f.sheenColor = Vec3{unit(in.sheenColor[0]), unit(in.sheenColor[1]), unit(in.sheenColor[2])};
        f.sheenRoughness = unit(in.sheenRoughness);
    }
    // Alpha modes. With the factor's alpha alone (untextured, or a texture without alpha): BLEND
    // blends with it, MASK keeps the surface when it reaches alphaCutoff and drops it otherwise,
    // OPAQUE ignores it. With a base colour texture, texelAlpha holds the per-fragment rule (the
    // factor times the texel's alpha), used when the texture has alpha.
    const double a = std::clamp(in.baseColor[3], 0.0, 1.0);
    m.alpha = 1.0f;
    m.texelAlpha = TexelAlpha{};
    if (in.alphaMode == MaterialFactors::Alpha::Blend) {
        m.alpha = float(a);
        m.texelAlpha = {AlphaMode::Blend, float(a), 0.5f};
    } else if (in.alphaMode == MaterialFactors::Alpha::Mask) {
        m.alpha = a >= in.alphaCutoff ? 1.0f : 0.0f;
        m.texelAlpha = {AlphaMode::Mask, float(a), float(in.alphaCutoff)};
    }
    f.baseColor.a = float(a);
    m.pbr = f;
}

} // namespace sr

namespace sr::gltfimport {

// A glTF sampler as SoftRaster's wrap modes and filter. Wrap, along u (wrapS) and v (wrapT):
// REPEAT (the default), CLAMP_TO_EDGE, MIRRORED_REPEAT. Filter, from minFilter: NEAREST ->
// nearest, LINEAR -> bilinear, any *_MIPMAP_* -> trilinear; without a minFilter, a NEAREST
// magFilter -> nearest, else unset (the settings').
SamplerModes samplerModes(const gltf::Sampler& s) {
    SamplerModes out;
    const auto wrapOf = [&](int gl, const char* axis) -> WrapMode {
        switch (gl) {
        case 10497: return WrapMode::Repeat;
        case 33071: return WrapMode::Clamp;
        case 33648: return WrapMode::Mirror;
        default: out.problem = std::string(axis) + " " + std::to_string(gl) + " is not a glTF wrap mode"; return WrapMode::Repeat;
        }
    };
    out.wrap.u = wrapOf(s.wrapS, "wrapS");
    out.wrap.v = wrapOf(s.wrapT, "wrapT");
    switch (s.minFilter) {
    case -1: break;
    case 9728: out.filter = TextureFilter::Nearest; break;
    case 9729: out.filter = TextureFilter::Bilinear; break;
    case 9984: case 9985: case 9986: case 9987: out.filter = TextureFilter::Trilinear; break;
    default: out.problem = "minFilter " + std::to_string(s.minFilter) + " is not a glTF filter"; break;
    }
    if (s.magFilter != -1 && s.magFilter != 9728 && s.magFilter != 9729)
        out.problem = "magFilter " + std::to_string(s.magFilter) + " is not a glTF filter";
    if (s.minFilter == -1 && s.magFilter == 9728) out.filter = TextureFilter::Nearest;
    return out;
}

bool UvTransform::operator==(const UvTransform& o) const {
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 3; ++c)
            if (m[r][c] != o.m[r][c]) return false;
    return true;
}


UvTransform uvTransformOf(const gltf::Json& extensions) {
    UvTransform t;
    const auto ext = extensions.find("KHR_texture_transform");
    if (ext == extensions.end() || !ext->is_object()) return t;
    t.found = true;
    transformOf(*ext).matrix(t.m);
    return t;
}

namespace {

// A texture reference's uv set (its texCoord, or its KHR_texture_transform's texCoord) and transform.
UvSource sourceOf(const gltf::TextureInfo& info) {
    UvSource out;
    out.transform = uvTransformOf(info.extensions);
    out.texCoord = info.texCoord;
    if (const auto ext = info.extensions.find("KHR_texture_transform"); ext != info.extensions.end() && ext->is_object())
        if (const auto tc = ext->find("texCoord"); tc != ext->end() && tc->is_number_unsigned() && tc->get<std::uint64_t>() < 64)
            out.texCoord = int(tc->get<std::uint64_t>());
    return out;
}

// One texture reference of a material: its uv set, transform and sampler (a sampler that does
// not exist or says nothing valid reads as the default: addTextures refuses the file for it).
struct Reference {
    const char* name = nullptr;
    UvSource source;
    SamplerModes sampler;
};
Reference referenceOf(const gltf::Document& g, const gltf::TextureInfo& info, const char* name) {
    Reference r;
    r.name = name;
    r.source = sourceOf(info);
    if (info.index >= 0 && std::size_t(info.index) < g.textures.size()) {
        const int sampler = g.textures[std::size_t(info.index)].sampler;
        if (sampler >= 0 && std::size_t(sampler) < g.samplers.size()) {
            r.sampler = samplerModes(g.samplers[std::size_t(sampler)]);
            if (!r.sampler.problem.empty()) r.sampler = {};
        }
    }
    return r;
}

// The base colour texture's reference, then each slot's (MapSlot's order); null info: none.
std::array<std::pair<const gltf::TextureInfo*, const char*>, 1 + kMapSlots> referencesOf(const gltf::Material& gm) {
    std::array<std::pair<const gltf::TextureInfo*, const char*>, 1 + kMapSlots> maps;
    maps[0] = {&gm.pbrMetallicRoughness.baseColorTexture, "base colour"};
    for (const MapSlot s : kAllMapSlots) maps[1 + std::size_t(s)] = {&textureInfoOf(gm, s), kMapSlotNames[std::size_t(s)]};
    return maps;
}

// KHR_texture_transform's matrix (on glTF's uvs) restated on stored uvs (u, 1 - v).
void storedTransform(const UvTransform& t, float out[2][3]) { restate(t.m, out); }

} // namespace

// The uv set and transform a material's maps are drawn with when they share them: its base
// colour texture's (else that of its first other map, in MapSlot's order), baked into the
// vertices of its primitives (every vertex of a glTF primitive is its own: no other material
// reads it).
UvSource materialUvSource(const gltf::Material& gm) {
    for (const auto& [info, name] : referencesOf(gm))
        if (info->index >= 0) return sourceOf(*info);
    return {};
}

// The sampler of the material's first map (materialUvSource's order): the draw's wrap and filter
// where the maps share one.
SamplerModes materialSampler(const gltf::Document& g, const gltf::Material& gm) {
    for (const auto& [info, name] : referencesOf(gm))
        if (info->index >= 0) return referenceOf(g, *info, name).sampler;
    return {};
}

// Each map's address when the material's maps do not all read one uv set through one transform
// with one sampler: otherwise none (materialUvSource's uvs and the sampler serve them all). Only
// TEXCOORD_0 and _1 are read per map: a map on a later set is named in `problem` and reads
// TEXCOORD_0.
std::optional<MapAddressing> materialAddressing(const gltf::Document& g, const gltf::Material& gm, std::string* problem, bool force) {
    const auto maps = referencesOf(gm);
    std::optional<Reference> first;
    bool shared = true;
    for (const auto& [info, name] : maps) {
        if (info->index < 0) continue;
        const Reference r = referenceOf(g, *info, name);
        if (!first) {
            first = r;
        } else if (r.source.texCoord != first->source.texCoord || !(r.source.transform == first->source.transform) ||
                   r.sampler.wrap != first->sampler.wrap || r.sampler.filter != first->sampler.filter) {
            shared = false;
        }
    }
    if (!first || (shared && !force)) return std::nullopt;
    MapAddressing out;
    for (std::size_t k = 0; k < maps.size(); ++k) {
        const auto& [info, name] = maps[k];
        if (info->index < 0) continue;
        const Reference r = referenceOf(g, *info, name);
        MapAddress& a = k == 0 ? out.base : out.maps[k - 1];
        a.uvSet = r.source.texCoord;
        if (a.uvSet >= MapAddressing::kUvSets) {
            if (problem && problem->empty())
                *problem = std::string("its ") + name + " texture reads TEXCOORD_" + std::to_string(a.uvSet) +
                           ": a material whose maps read different uv sets reads TEXCOORD_0 and _1 only; it reads TEXCOORD_0";
            a.uvSet = 0;
        }
        storedTransform(r.source.transform, a.m);
        a.wrap = r.sampler.wrap;
        a.filter = r.sampler.filter;
    }
    return out;
}

} // namespace sr::gltfimport
