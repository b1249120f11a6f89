// The pbr mesh program: glTF metallic-roughness per pixel, with its maps (the scalar reference).
#pragma once

#include <cmath>
#include <cstddef>

#include "Raster/Shade/Brdf.hpp"
#include "Raster/Shade/Ibl.hpp"
#include "Raster/Shade/MeshPrograms.hpp"
#include "Raster/Shade/Shadow.hpp"

namespace sr::programs {

// Perturbs the unit normal n by a tangent-space normal-map texel (glTF "normalTexture"): the
// texel's RGB in [0, 1] is the vector 2 c - 1, its x and y scaled by `scale`, expressed in the
// frame T, B = w (n x T), n with T made orthogonal to n (Gram-Schmidt). A degenerate frame (no
// tangent, T parallel to n) or a texel that gives no direction leaves n as it is; the result is
// unit and finite whenever n is.
inline Vec3 perturbNormal(Vec3 n, Vec4 tangent, Color texel, float scale) {
    const Vec3 t0{tangent.x, tangent.y, tangent.z};
    const Vec3 tOrtho = t0 - n * dot(n, t0);
    const float tl = length(tOrtho);
    if (!(tl > 1e-12f) || !std::isfinite(tl)) return n;
    const Vec3 t = tOrtho / tl;
    const Vec3 b = cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
    const float x = (texel.r * 2.0f - 1.0f) * scale, y = (texel.g * 2.0f - 1.0f) * scale, z = texel.b * 2.0f - 1.0f;
    const Vec3 m = t * x + b * y + n * z;
    const float ml = length(m);
    if (!(ml > 1e-12f) || !std::isfinite(ml)) return n;
    return m / ml;
}

// The light a sky sends toward v from a surface (N, V unit): Lambert's c_diff x E(n) / pi plus
// the split sum's prefiltered radiance along R = 2 (N.V) N - V times F0 a + b (Ibl.hpp,
// iblRadiance: the kernels evaluate the same source).
inline Vec3 imageLight(const ImageLight& light, const PbrSurface& s, Vec3 n, Vec3 v) {
    const float base[3] = {s.baseColor.x, s.baseColor.y, s.baseColor.z};
    const float f0[3] = {s.dielectricF0.x, s.dielectricF0.y, s.dielectricF0.z};
    float out[3];
    ibl::iblRadiance(light.tables(), base, f0, s.specularWeight, s.metallic, s.roughness, n.x, n.y, n.z, v.x, v.y, v.z, out);
    return {out[0], out[1], out[2]};
}

// The parts of the pbr model beyond appendix B's that a glTF material has (PbrLobe bits).
inline unsigned pbrLobesOf(const SurfaceMaterial& m) {
    const bool specular = hasDielectricSpecular(*m.pbr) || m.maps.has(MapSlot::Specular) || m.maps.has(MapSlot::SpecularColour);
    const Vec3 sheen = m.pbr->sheenColor;
    return (specular ? kLobeDielectricSpecular : 0u) | (m.pbr->clearcoat > 0.0f ? kLobeClearcoat : 0u) |
           (m.pbr->specularGlossiness ? kLobeSpecularGlossiness : 0u) |
           (sheen.x > 0.0f || sheen.y > 0.0f || sheen.z > 0.0f ? kLobeSheen : 0u);
}

// The light a sky sends toward v from a clear coat with unit normal nc (IblTerms.inl's iblCoat).
inline Vec3 coatImageLight(const ImageLight& light, float coatRoughness, Vec3 nc, Vec3 v) {
    float out[3];
    ibl::iblCoat(light.tables(), coatRoughness, nc.x, nc.y, nc.z, v.x, v.y, v.z, out);
    return {out[0], out[1], out[2]};
}

// Phong's interpolation (world position and normal, perspective-correct), lit per pixel by the
// glTF BRDF (pbrRadiance, compensated for multiple scattering: brdfMultiScatter) plus the
// emissive term. With kMaps: the uv in varyings 0-1 and the material's maps sampled at it (each
// with its own level of detail); with kTangents also the tangent (xyzw) for the normal map; with
// kColours the vertex colour's RGB (glTF COLOR_0), a factor of the base colour after the
// texture's (factor x texture x colour, in that order). Colour maps (base colour, emissive) are
// decoded from sRGB in linear mode; the others are data and read as stored. Double-sided
// surfaces seen from behind are lit on their back (the normal flipped toward the viewer, as the
// specification asks); single-sided ones never show their back (culled).
// A material with a clear coat (KHR_materials_clearcoat, clearcoat > 0) layers it over all of
// that as BrdfTerms.inl's coatWeight says: its lobe on the interpolated normal, or on its own
// normal map (kTangents; the base's normal map does not bend it), in direct and sky light.
// With kAddressed (a material with a MapAddressing) each map reads its own uv set, transform and
// sampler: the raw sets TEXCOORD_0 and _1 (Mesh::uvSets) in varyings 0-3, sampleAddressedAt.
// The span kernels (Raster/Fill/Kernels/Kernels*Pbr.cpp, Kernels*PbrColours.cpp) cover the six
// variants without kAddressed; the addressed ones are filled by this program alone.
template <bool kMaps, bool kTangents = false, bool kColours = false, bool kAddressed = false>
struct PbrProgram {
    static_assert(kMaps || !kTangents, "a normal map needs uvs");
    static_assert(kMaps || !kAddressed, "addressed maps need uvs");
    static constexpr ShadingMode kMode = ShadingMode::Pbr;
    static constexpr bool kIsTextured = kMaps;
    static constexpr bool kNormalMap = kTangents;
    static constexpr bool kVertexColours = kColours;
    static constexpr bool kAddressedMaps = kAddressed;
    static constexpr int kP = kMaps ? (kAddressed ? 4 : 2) : 0; // position kP..kP+2, normal kP+3..kP+5
    static constexpr int kT = kP + 6;        // tangent kT..kT+3 (kTangents)
    static constexpr int kC = kT + (kTangents ? 4 : 0); // vertex colour kC..kC+2 (kColours)
    static constexpr int kVaryings = kC + (kColours ? 3 : 0);
    const DrawContext* d;
    const TriangleSetup* setup = nullptr;
    // The material's parts beyond appendix B's (PbrLobe bits): KHR_materials_ior / _specular values
    // (the kernels' BRDF reads them only then), a clear coat (its maps are read only then).
    unsigned lobes;
    explicit PbrProgram(const DrawContext* dc) : d(dc), lobes(pbrLobesOf(*dc->material)) {}
    bool has(PbrLobe lobe) const { return (lobes & lobe) != 0; }

    void vertex(std::size_t i, ClipVertex& out) const {
        const Vec3 p = worldPosition(*d, i), n = worldNormal(*d, i);
        transformVertex<kMaps>(*d, i, p, out);
        if constexpr (kAddressed) {
            for (int set = 0; set < 2; ++set) {
                out.varyings[2 * set] = d->mesh.uvSets[set][i].x;
                out.varyings[2 * set + 1] = d->mesh.uvSets[set][i].y;
            }
        }
        const float values[6] = {p.x, p.y, p.z, n.x, n.y, n.z};
        for (int k = 0; k < 6; ++k) out.varyings[kP + k] = values[k];
        if constexpr (kTangents) {
            const Vec4 t = worldTangent(*d, i);
            out.varyings[kT] = t.x;
            out.varyings[kT + 1] = t.y;
            out.varyings[kT + 2] = t.z;
            out.varyings[kT + 3] = t.w;
        }
        if constexpr (kColours) {
            const Color c = d->mesh.colours[i];
            out.varyings[kC] = c.r;
            out.varyings[kC + 1] = c.g;
            out.varyings[kC + 2] = c.b;
        }
    }
    void triangle(std::size_t, const TriangleSetup& s) { setup = &s; }

    // One map at this fragment (its own level of detail; its own address with kAddressed);
    // colour maps decoded in linear light. The base colour texture: sampleBase.
    template <int kV>
    Color sampleMap(MapSlot slot, const Texture& map, bool colour, const Fragment<kV>& f) const {
        if constexpr (kAddressed) return sampleAddressedAt(*d, setup, f, map, colour && d->linear, (*d->material->addressing)[slot]);
        else return sampleTextureAt(*d, setup, f, map, colour && d->linear);
    }
    template <int kV>
    Color sampleBase(const Texture& map, bool colour, const Fragment<kV>& f) const {
        if constexpr (kAddressed) return sampleAddressedAt(*d, setup, f, map, colour && d->linear, d->material->addressing->base);
        else return sampleTextureAt(*d, setup, f, map, colour && d->linear);
    }

    Pixel fragment(const Fragment<kVaryings>& f) const {
        const SurfaceMaterial& m = *d->material;
        const PbrFactors& k = *m.pbr;
        const Vec3 p{f.varyings[kP], f.varyings[kP + 1], f.varyings[kP + 2]};
        Vec3 n = normalize(Vec3{f.varyings[kP + 3], f.varyings[kP + 4], f.varyings[kP + 5]});
        const Vec3 v = normalize(d->view.eye - p);
        if (d->doubleSided && dot(n, v) < 0.0f) n = -n;
        const Vec3 geometric = n; // the clear coat's normal without a map of its own
        PbrSurface s;
        s.baseColor = {k.baseColor.r, k.baseColor.g, k.baseColor.b};
        s.metallic = k.metallic;
        s.roughness = k.roughness;
        s.dielectricF0 = k.dielectricF0;
        s.specularWeight = k.specularWeight;
        Vec3 emissive = k.emissive;
        if constexpr (kMaps) {
            if (m.texture) {
                const Color c = sampleBase(*m.texture, true, f);
                s.baseColor = {s.baseColor.x * c.r, s.baseColor.y * c.g, s.baseColor.z * c.b};
            }
        }
        if constexpr (kColours)
            s.baseColor = {s.baseColor.x * f.varyings[kC], s.baseColor.y * f.varyings[kC + 1], s.baseColor.z * f.varyings[kC + 2]};
        if constexpr (kMaps) {
            if (const Texture* map = m.map(MapSlot::MetallicRoughness)) {
                const Color c = sampleMap(MapSlot::MetallicRoughness, *map, false, f);
                s.roughness *= c.g;
                s.metallic *= c.b;
            }
            if (const Texture* map = m.map(MapSlot::Emissive); map && (emissive.x > 0.0f || emissive.y > 0.0f || emissive.z > 0.0f)) {
                const Color c = sampleMap(MapSlot::Emissive, *map, true, f);
                emissive = {emissive.x * c.r, emissive.y * c.g, emissive.z * c.b};
            }
            // KHR_materials_specular's maps: F0 = min(specularColorF0 x texel, 1), the weight x its alpha.
            if (const Texture* map = m.map(MapSlot::SpecularColour)) {
                const Color c = sampleMap(MapSlot::SpecularColour, *map, true, f);
                s.dielectricF0 = {std::min(k.specularColorF0.x * c.r, 1.0f), std::min(k.specularColorF0.y * c.g, 1.0f),
                                  std::min(k.specularColorF0.z * c.b, 1.0f)};
            }
            if (const Texture* map = m.map(MapSlot::Specular)) // (its alpha, in red)
                s.specularWeight = k.specularWeight * sampleMap(MapSlot::Specular, *map, false, f).r;
        }
        if (has(kLobeSpecularGlossiness)) { // roughness 1 - glossiness, c_diff = diffuse x (1 - max(F0))
            float glossiness = k.glossiness;
            if constexpr (kMaps) {
                if (const Texture* map = m.map(MapSlot::Glossiness)) // (its alpha, in red)
                    glossiness *= sampleMap(MapSlot::Glossiness, *map, false, f).r;
            }
            s.roughness = 1.0f - glossiness;
            const float keep = 1.0f - std::max(std::max(s.dielectricF0.x, s.dielectricF0.y), s.dielectricF0.z);
            s.baseColor = {s.baseColor.x * keep, s.baseColor.y * keep, s.baseColor.z * keep};
        }
        if constexpr (kMaps) {
            if constexpr (kTangents) {
                const Vec4 t{f.varyings[kT], f.varyings[kT + 1], f.varyings[kT + 2], f.varyings[kT + 3]};
                if (const Texture* map = m.map(MapSlot::Normal))
                    n = perturbNormal(n, t, sampleMap(MapSlot::Normal, *map, false, f), k.normalScale);
            }
        }
        // The clear coat's weight, roughness and normal, each x its map.
        float clearcoat = k.clearcoat, coatRoughness = k.clearcoatRoughness;
        Vec3 nc = geometric;
        if constexpr (kMaps) {
            if (has(kLobeClearcoat)) {
                if (const Texture* map = m.map(MapSlot::Clearcoat)) clearcoat *= sampleMap(MapSlot::Clearcoat, *map, false, f).r;
                if (const Texture* map = m.map(MapSlot::ClearcoatRoughness))
                    coatRoughness *= sampleMap(MapSlot::ClearcoatRoughness, *map, false, f).g;
                if constexpr (kTangents) {
                    const Vec4 t{f.varyings[kT], f.varyings[kT + 1], f.varyings[kT + 2], f.varyings[kT + 3]};
                    if (const Texture* map = m.map(MapSlot::ClearcoatNormal))
                        nc = perturbNormal(geometric, t, sampleMap(MapSlot::ClearcoatNormal, *map, false, f), k.clearcoatNormalScale);
                }
            }
        }
        const float multiScatter =
            d->view.lighting.lights.empty() ? 0.0f : ibl::brdfMultiScatter(brdfAlbedoTable().ess.data(), dot(n, v), s.roughness);
        Vec3 r = d->view.shadows ? pbrRadiance(d->view.lighting, s, n, p, v, multiScatter,
                                               [sh = d->view.shadows](std::size_t light, Vec3 q, Vec3 normal, Vec3 l) {
                                                   return sh->visibility(light, q, normal, l);
                                               })
                                 : pbrRadiance(d->view.lighting, s, n, p, v, multiScatter);
        float occlusion = 1.0f;
        if (d->view.ibl) {
            if constexpr (kMaps) {
                if (const Texture* map = m.map(MapSlot::Occlusion))
                    occlusion = 1.0f + k.occlusionStrength * (sampleMap(MapSlot::Occlusion, *map, false, f).r - 1.0f);
            }
            const Vec3 sky = imageLight(*d->view.ibl, s, n, v) * occlusion;
            r = r + sky;
        }
        Vec3 out{r.x + emissive.x, r.y + emissive.y, r.z + emissive.z};
        if (has(kLobeSheen)) { // over the base (and its emission, as three.js does), under the coat
            Vec3 sheen = k.sheenColor;
            float sheenRoughness = k.sheenRoughness;
            if constexpr (kMaps) {
                if (const Texture* map = m.map(MapSlot::SheenColour)) {
                    const Color c = sampleMap(MapSlot::SheenColour, *map, true, f);
                    sheen = {sheen.x * c.r, sheen.y * c.g, sheen.z * c.b};
                }
                if (const Texture* map = m.map(MapSlot::SheenRoughness)) // (its alpha, in red)
                    sheenRoughness *= sampleMap(MapSlot::SheenRoughness, *map, false, f).r;
            }
            sheenRoughness = sheenRoughnessClamped(sheenRoughness);
            Vec3 lobe = d->view.shadows ? sheenRadiance(d->view.lighting, sheenRoughness, n, p, v,
                                                        [sh = d->view.shadows](std::size_t light, Vec3 q, Vec3 normal, Vec3 l) {
                                                            return sh->visibility(light, q, normal, l);
                                                        })
                                        : sheenRadiance(d->view.lighting, sheenRoughness, n, p, v);
            if (d->view.ibl) // E(n) = pi x the Lambertian radiance of a white surface
                lobe = lobe + d->view.ibl->diffuse(n) * (3.14159265f * sheenImageBrdf(sheenRoughness, dot(n, v)) * occlusion);
            const float keep = 1.0f - kSheenAlbedo * std::max(std::max(sheen.x, sheen.y), sheen.z);
            out = {out.x * keep + lobe.x * sheen.x, out.y * keep + lobe.y * sheen.y, out.z * keep + lobe.z * sheen.z};
        }
        if (has(kLobeClearcoat)) {
            Vec3 c = d->view.shadows ? coatRadiance(d->view.lighting, nc, coatRoughness, n, p, v,
                                                    [sh = d->view.shadows](std::size_t light, Vec3 q, Vec3 normal, Vec3 l) {
                                                        return sh->visibility(light, q, normal, l);
                                                    })
                                     : coatRadiance(d->view.lighting, nc, coatRoughness, n, p, v);
            if (d->view.ibl) c = c + coatImageLight(*d->view.ibl, coatRoughness, nc, v) * occlusion;
            const float w = coatWeight(clearcoat, dot(nc, v));
            out = {out.x * (1.0f - w) + c.x * w, out.y * (1.0f - w) + c.y * w, out.z * (1.0f - w) + c.z * w};
        }
        return encode(*d, Color{out.x, out.y, out.z, 1.0f});
    }
    template <bool kM = kMaps, std::enable_if_t<kM, int> = 0> // textured programs only (HasFragmentAlpha)
    float fragmentAlpha(const Fragment<kVaryings>& f) const {
        return d->material->texture ? sampleBase(*d->material->texture, false, f).a : 1.0f;
    }
};

} // namespace sr::programs
