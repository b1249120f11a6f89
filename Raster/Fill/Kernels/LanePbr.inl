// The metallic-roughness program lane by lane (PbrProgram::fragment, Brdf.hpp): lights, normal maps.
// Part of the span kernels: included by Kernels.inl inside its ISA namespace (see there).

// --- The pbr program (PbrProgram::fragment, Brdf.hpp), lane by lane -------------------------
// brdfCosineTerms compiled for this ISA (the scalar reference's source, Brdf.hpp).
#include "Raster/Shade/BrdfTerms.inl"

// The image light's lookups compiled for this ISA (Ibl.hpp's source, IblTerms.inl), with its
// operations on lanes: absOf, wholeOf (truncation: the callers pass values in [0, 2^24)) and
// gatherOf (a float table at whole-number indices).
SR_SIMD_INLINE F absOf(F a) { return fabs(a); }
SR_SIMD_INLINE F wholeOf(F a) { return toFloat(truncToInt(a)); }
SR_SIMD_INLINE F gatherOf(const float* table, F index) {
    return asFloat(gather(reinterpret_cast<const std::uint32_t*>(table), truncToInt(index)));
}
#include "Raster/Shade/IblTerms.inl"

// programs::imageLight per lane (iblRadiance), out of line: about forty gathers.
// kSpecular: the material has KHR_materials_ior / _specular values (hasDielectricSpecular).
template <bool kSpecular>
SR_SIMD_NOINLINE Rgb imageLightLanes(const ImageLight::Tables& t, const F f0[3], F weight, F baseR, F baseG, F baseB, F metallic,
                                     F roughness, const V3& n, const V3& v) {
    const F base[3] = {baseR, baseG, baseB};
    F out[3];
    iblRadiance<F, kSpecular>(t, base, f0, weight, metallic, roughness, n.x, n.y, n.z, v.x, v.y, v.z, out);
    return {out[0], out[1], out[2]};
}

// programs::coatImageLight per lane (iblCoat), out of line.
SR_SIMD_NOINLINE Rgb coatImageLightLanes(const ImageLight::Tables& t, F roughness, const V3& n, const V3& v) {
    F out[3];
    iblCoat<F>(t, roughness, n.x, n.y, n.z, v.x, v.y, v.z, out);
    return {out[0], out[1], out[2]};
}

// The radiance at the lanes' points (px, py, pz) with unit normals n and view vectors v:
// pbrRadiance's loop over the lights (lightAt's direction and factor as lightsRgb computes
// them, the shadow maps' lit fraction, brdfCosineTerms with brdfMultiScatter's k), the same
// operations in the same order. Lanes whose light or half vector is off normalize's fast path lose `ok`.
// kLobes (PbrLobe bits): with kLobeDielectricSpecular brdfCosineTerms reads the dielectric's F0
// and weight; with kLobeClearcoat the loop also adds coatRadiance's sum on the coat normal nc at
// coatRoughness to `coat` (the light's direction, factor and lit fraction computed once for both).
template <unsigned kLobes>
SR_SIMD_NOINLINE Rgb pbrLights(const Lighting& lighting, const SceneShadows* shadows, const F f0[3], F weight, F baseR, F baseG,
                               F baseB, F metallic, F roughness, F nx, F ny, F nz, F px, F py, F pz, F vx, F vy, F vz, M& ok,
                               const V3& nc, F coatRoughness, Rgb& coat) {
    constexpr bool kSpecular = (kLobes & kLobeDielectricSpecular) != 0, kCoat = (kLobes & kLobeClearcoat) != 0;
    if (lighting.lights.empty()) return {fzero(), fzero(), fzero()};
    const V3 n{nx, ny, nz}, p{px, py, pz}, v{vx, vy, vz};
    const F base[3] = {baseR, baseG, baseB};
    const F multiScatter = brdfMultiScatter(brdfAlbedoTable().ess.data(), dot3(n, v), roughness);
    Rgb sum{fzero(), fzero(), fzero()};
    for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
        const Light& light = lighting.lights[i];
        V3 l;
        F a = fset(1.0f);
        if (light.type == LightType::Directional) {
            l = {fset(light.toLight.x), fset(light.toLight.y), fset(light.toLight.z)};
        } else {
            const V3 d{fset(light.position.x) - p.x, fset(light.position.y) - p.y, fset(light.position.z) - p.z};
            const F d2 = dot3(d, d);
            l = normalizeFast(d, ok);
            a = fset(1.0f) / fmax(fset(kMinLightDistance2), d2);
            if (light.range > 0.0f) {
                const F q = d2 / fset(light.range * light.range);
                a = a * clampLanes(fset(1.0f) - q * q, fzero(), fset(1.0f));
            }
            if (light.type == LightType::Spot) {
                const V3 s{fset(light.spotDirection.x), fset(light.spotDirection.y), fset(light.spotDirection.z)};
                const F c = clampLanes((fzero() - dot3(s, l)) * fset(light.coneScale) + fset(light.coneOffset), fzero(),
                                       fset(1.0f));
                a = a * (c * c);
            }
        }
        const F ndl = dot3(n, l);
        const M baseLit = (a > fzero()) & (ndl > fzero());
        F ndlc = fzero();
        M coatLit = baseLit;
        if constexpr (kCoat) {
            ndlc = dot3(nc, l);
            coatLit = (a > fzero()) & (ndlc > fzero());
        }
        const M lit = kCoat ? (baseLit | coatLit) : baseLit;
        if (bits(lit) == 0) continue;
        if (shadows) {
            const F seen = shadowVisibility(*shadows, i, p, n, l, lit & ok);
            a = select(seen < fset(1.0f), a * seen, a);
        }
        M hOk = ok;
        const V3 h = normalizeFast({l.x + v.x, l.y + v.y, l.z + v.z}, hOk);
        ok = (lit & hOk) | andNot(ok, lit);
        const V3 nxh{n.y * h.z - n.z * h.y, n.z * h.x - n.x * h.z, n.x * h.y - n.y * h.x}; // cross(n, h)
        F f[3];
        brdfCosineTerms<F, kSpecular>(ndl, dot3(n, v), dot3(n, h), dot3(nxh, nxh), dot3(v, h), roughness, metallic, base, f0, weight, multiScatter, f);
        sum.r = select(baseLit, sum.r + f[0] * fset(light.colour.r) * a, sum.r);
        sum.g = select(baseLit, sum.g + f[1] * fset(light.colour.g) * a, sum.g);
        sum.b = select(baseLit, sum.b + f[2] * fset(light.colour.b) * a, sum.b);
        if constexpr (kCoat) {
            const V3 ncxh{nc.y * h.z - nc.z * h.y, nc.z * h.x - nc.x * h.z, nc.x * h.y - nc.y * h.x}; // cross(nc, h)
            const F fc = coatCosineTerm<F>(ndlc, dot3(nc, v), dot3(nc, h), dot3(ncxh, ncxh), coatRoughness);
            coat.r = select(coatLit, coat.r + fc * fset(light.colour.r) * a, coat.r);
            coat.g = select(coatLit, coat.g + fc * fset(light.colour.g) * a, coat.g);
            coat.b = select(coatLit, coat.b + fc * fset(light.colour.b) * a, coat.b);
        }
    }
    return sum;
}

// fn(std::integral_constant<unsigned, kSet>) for the set kSet == lobes among kSets: the
// instantiation for a draw's PbrLobe bits.
template <class Fn, unsigned... kSets>
SR_SIMD_INLINE Rgb withLobeSet(unsigned lobes, const Fn& fn, std::integer_sequence<unsigned, kSets...>) {
    Rgb r{fzero(), fzero(), fzero()};
    (void)((lobes == kSets && (r = fn(std::integral_constant<unsigned, kSets>{}), true)) || ...);
    return r;
}

// robustLength (Vec.cpp) for the lanes whose vector is finite and non-zero: the largest
// |component| m, then m sqrt(sum (c / m)^2). Lanes with a zero, infinite or NaN component come
// out NaN, 0 or infinite, which the callers reject as robustLength's 0 / NaN / Inf would be.
SR_SIMD_INLINE F lengthLanes(const V3& a) {
    const F m = fmax(fmax(fabs(a.x), fabs(a.y)), fabs(a.z));
    const F x = a.x / m, y = a.y / m, z = a.z / m;
    F sum = x * x;
    sum = sum + y * y;
    sum = sum + z * z;
    return m * fsqrt(sum);
}

// programs::perturbNormal per lane: the tangent made orthogonal to n, the bitangent w (n x T), the
// map's vector (2 c - 1, x and y scaled) in that frame, normalised; lanes whose frame or vector
// is degenerate (a length not above 1e-12, or not finite) keep n.
SR_SIMD_NOINLINE V3 perturbNormalLanes(const V3& n, const V3& t0, F w, const Rgb& texel, float scale) {
    const F nt = dot3(n, t0);
    const V3 tOrtho{t0.x - n.x * nt, t0.y - n.y * nt, t0.z - n.z * nt};
    const F tl = lengthLanes(tOrtho);
    const F tiny = fset(1e-12f), huge = fset(3.40282347e38f);
    const M frameOk = (tl > tiny) & (tl <= huge);
    const V3 t{tOrtho.x / tl, tOrtho.y / tl, tOrtho.z / tl};
    const F sign = select(w < fzero(), fset(-1.0f), fset(1.0f));
    const V3 b{(n.y * t.z - n.z * t.y) * sign, (n.z * t.x - n.x * t.z) * sign, (n.x * t.y - n.y * t.x) * sign};
    const F two = fset(2.0f), one = fset(1.0f), s = fset(scale);
    const F x = (texel.r * two - one) * s, y = (texel.g * two - one) * s, z = texel.b * two - one;
    const V3 m{t.x * x + b.x * y + n.x * z, t.y * x + b.y * y + n.y * z, t.z * x + b.z * y + n.z * z};
    const F ml = lengthLanes(m);
    const M ok = frameOk & (ml > tiny) & (ml <= huge);
    return {select(ok, m.x / ml, n.x), select(ok, m.y / ml, n.y), select(ok, m.z / ml, n.z)};
}

// PbrProgram::fragment for the lanes: the interpolated normal and view vector (the normal
// flipped toward the viewer on a double-sided surface), the factors times the maps, the lights,
// the emission, encoded. kLobes false: the material has none of the PbrLobe parts (the code for
// them is not compiled in); true: each is tested (p.has) and run where the material has it.
template <bool kLobes, class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
SR_SIMD_INLINE Rgb shadePbrBody(const Prog& p, const F* v, F invW, M& ok) {
    const DrawContext& d = *p.d;
    const SurfaceMaterial& m = *d.material;
    const PbrFactors& k = *m.pbr;
    constexpr int kP = Prog::kP;
    V3 n = normalizeFast({v[kP + 3], v[kP + 4], v[kP + 5]}, ok);
    const Vec3 eye = d.view.eye;
    const V3 toEye = normalizeFast({fset(eye.x) - v[kP], fset(eye.y) - v[kP + 1], fset(eye.z) - v[kP + 2]}, ok);
    if (d.doubleSided) {
        const M back = dot3(n, toEye) < fzero();
        const F minus = fset(-1.0f);
        n = {select(back, minus * n.x, n.x), select(back, minus * n.y, n.y), select(back, minus * n.z, n.z)};
    }
    const V3 geometric = n; // the clear coat's normal without a map of its own
    F baseR = fset(k.baseColor.r), baseG = fset(k.baseColor.g), baseB = fset(k.baseColor.b);
    F metallic = fset(k.metallic), roughness = fset(k.roughness);
    F eR = fset(k.emissive.x), eG = fset(k.emissive.y), eB = fset(k.emissive.z);
    F occlusion = fset(1.0f); // the occlusion map's factor on the light from the sky
    F f0[3] = {fset(k.dielectricF0.x), fset(k.dielectricF0.y), fset(k.dielectricF0.z)}; // the dielectric's F0 and weight
    F weight = fset(k.specularWeight);
    // Each map at its own level of detail (PbrProgram::sampleMap); generic, so that it is
    // instantiated only where a textured program calls it.
    auto mapLanes = [&](const auto& map, bool colour) SR_SIMD_LAMBDA {
        F lod = fzero();
        if constexpr (kPersp == PerspectiveMode::Affine && kFilter == TextureFilter::Trilinear) lod = fset(affineMipLevel(p, map));
        return sampleMap<kPersp, kFilter>(p, map, colour && d.linear, v[0], v[1], invW, lod);
    };
    if constexpr (Prog::kIsTextured) {
        if (m.texture) {
            const Rgb c = mapLanes(*m.texture, true);
            baseR = baseR * c.r;
            baseG = baseG * c.g;
            baseB = baseB * c.b;
        }
    }
    if constexpr (Prog::kVertexColours) { // after the texture, as PbrProgram::fragment
        constexpr int kC = Prog::kC;
        baseR = baseR * v[kC];
        baseG = baseG * v[kC + 1];
        baseB = baseB * v[kC + 2];
    }
    if constexpr (Prog::kIsTextured) {
        if (const Texture* map = m.map(MapSlot::MetallicRoughness)) {
            const Rgb c = mapLanes(*map, false);
            roughness = roughness * c.g;
            metallic = metallic * c.b;
        }
        if (const Texture* map = m.map(MapSlot::Emissive); map && (k.emissive.x > 0.0f || k.emissive.y > 0.0f || k.emissive.z > 0.0f)) {
            const Rgb c = mapLanes(*map, true);
            eR = eR * c.r;
            eG = eG * c.g;
            eB = eB * c.b;
        }
        if (const Texture* map = m.map(MapSlot::Occlusion); d.view.ibl && map) {
            const F one = fset(1.0f);
            occlusion = one + fset(k.occlusionStrength) * (mapLanes(*map, false).r - one);
        }
        // KHR_materials_specular's maps (PbrProgram::fragment; a material with either has kLobeDielectricSpecular).
        if constexpr (kLobes) {
            if (const Texture* map = m.map(MapSlot::SpecularColour)) {
                const Rgb c = mapLanes(*map, true);
                const F one = fset(1.0f);
                f0[0] = minOf(fset(k.specularColorF0.x) * c.r, one);
                f0[1] = minOf(fset(k.specularColorF0.y) * c.g, one);
                f0[2] = minOf(fset(k.specularColorF0.z) * c.b, one);
            }
            if (const Texture* map = m.map(MapSlot::Specular)) // (its alpha, held in red: MapSlot::Specular)
                weight = weight * mapLanes(*map, false).r;
        }
        if constexpr (Prog::kNormalMap) {
            constexpr int kT = Prog::kT;
            if (const Texture* map = m.map(MapSlot::Normal))
                n = perturbNormalLanes(n, {v[kT], v[kT + 1], v[kT + 2]}, v[kT + 3], mapLanes(*map, false), k.normalScale);
        }
    }
    // KHR_materials_pbrSpecularGlossiness's per-pixel inputs (PbrProgram::fragment).
    if (kLobes && p.has(kLobeSpecularGlossiness)) {
        F glossiness = fset(k.glossiness);
        if constexpr (Prog::kIsTextured) {
            if (const Texture* map = m.map(MapSlot::Glossiness)) glossiness = glossiness * mapLanes(*map, false).r; // (its alpha, in red)
        }
        roughness = fset(1.0f) - glossiness;
        const F keep = fset(1.0f) - maxOf(maxOf(f0[0], f0[1]), f0[2]);
        baseR = baseR * keep;
        baseG = baseG * keep;
        baseB = baseB * keep;
    }
    // The clear coat's weight, roughness and normal, each x its map (PbrProgram::fragment).
    F clearcoat = fset(k.clearcoat), coatRoughness = fset(k.clearcoatRoughness);
    V3 nc = geometric;
    if constexpr (Prog::kIsTextured) {
        if (kLobes && p.has(kLobeClearcoat)) {
            if (const Texture* map = m.map(MapSlot::Clearcoat)) clearcoat = clearcoat * mapLanes(*map, false).r;
            if (const Texture* map = m.map(MapSlot::ClearcoatRoughness)) coatRoughness = coatRoughness * mapLanes(*map, false).g;
            if constexpr (Prog::kNormalMap) {
                constexpr int kT = Prog::kT;
                if (const Texture* map = m.map(MapSlot::ClearcoatNormal))
                    nc = perturbNormalLanes(geometric, {v[kT], v[kT + 1], v[kT + 2]}, v[kT + 3], mapLanes(*map, false),
                                            k.clearcoatNormalScale);
            }
        }
    }
    // The lights' loop for the material's lobes and no other (a material without KHR_materials_ior /
    // _specular values takes brdfCosineTerms' shortcut: the same bits).
    const bool specular = kLobes && p.has(kLobeDielectricSpecular);
    Rgb coat{fzero(), fzero(), fzero()};
    const auto lights = [&](auto set) SR_SIMD_LAMBDA {
        return pbrLights<decltype(set)::value>(d.view.lighting, d.view.shadows, f0, weight, baseR, baseG, baseB, metallic, roughness, n.x,
                                               n.y, n.z, v[kP], v[kP + 1], v[kP + 2], toEye.x, toEye.y, toEye.z, ok, nc, coatRoughness, coat);
    };
    Rgb r;
    if constexpr (kLobes) r = withLobeSet(p.lobes & kLightLobes, lights, std::make_integer_sequence<unsigned, kLightLobes + 1>{});
    else r = lights(std::integral_constant<unsigned, 0>{});
    if (d.view.ibl) {
        const Rgb sky = specular ? imageLightLanes<true>(d.view.ibl->tables(), f0, weight, baseR, baseG, baseB, metallic, roughness, n, toEye)
                                 : imageLightLanes<false>(d.view.ibl->tables(), f0, weight, baseR, baseG, baseB, metallic, roughness, n, toEye);
        r = {r.r + sky.r * occlusion, r.g + sky.g * occlusion, r.b + sky.b * occlusion};
    }
    Rgb out{r.r + eR, r.g + eG, r.b + eB};
    if (kLobes && p.has(kLobeClearcoat)) {
        if (d.view.ibl) {
            const Rgb sky = coatImageLightLanes(d.view.ibl->tables(), coatRoughness, nc, toEye);
            coat = {coat.r + sky.r * occlusion, coat.g + sky.g * occlusion, coat.b + sky.b * occlusion};
        }
        const F w = coatWeight<F>(clearcoat, dot3(nc, toEye));
        const F keep = fset(1.0f) - w;
        out = {out.r * keep + coat.r * w, out.g * keep + coat.g * w, out.b * keep + coat.b * w};
    }
    return out;
}

// A material with any PbrLobe part shades out of line (shadePbrBody<true>), so that the span
// loop of one without keeps the base program's code alone.
template <class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
SR_SIMD_NOINLINE Rgb shadePbrLobes(const Prog& p, const F* v, F invW, M& ok) {
    return shadePbrBody<true, Prog, kPersp, kFilter>(p, v, invW, ok);
}
template <class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
SR_SIMD_INLINE Rgb shadePbr(const Prog& p, const F* v, F invW, M& ok) {
    if (p.lobes != 0) return shadePbrLobes<Prog, kPersp, kFilter>(p, v, invW, ok);
    return shadePbrBody<false, Prog, kPersp, kFilter>(p, v, invW, ok);
}
