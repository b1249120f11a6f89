// The glTF BRDF's terms over a generic real type: included by Brdf.hpp (float) and Kernels.inl (each ISA's lanes).
//
// Included INSIDE a namespace (sr, or sr::kernels_<isa> within that ISA's target region), with
// no include guard: each includer gets its own copy, compiled for its own instruction set. The
// operations maxOf, minOf, sqrtOf, selectOf and splatAs come from Brdf.hpp (float) or the ISA's
// Simd*.hpp (its lane vector F), found by argument-dependent lookup.

// f(l, v) N.L of appendix B ("Specular BRDF", "Complete model"; its combined implementation),
// per channel, from the dot products of the unit vectors N, L, V and H = normalize(L + V):
//   alpha  = roughness^2, roughness clamped to [kMinRoughness, 1], metallic to [0, 1]
//   D      = alpha^2 / (pi ((N.H)^2 (alpha^2 - 1) + 1)^2)                  (GGX / Trowbridge-Reitz)
//   V      = 0.5 / (N.L sqrt((N.V)^2 (1 - alpha^2) + alpha^2) + N.V sqrt((N.L)^2 (1 - alpha^2) + alpha^2))
//                                                                          (Smith, height-correlated)
//   F      = F0 + (1 - F0) (1 - V.H)^5, F0 = mix(F0_d, baseColor, metallic) (Schlick)
//   f N.L  = ((1 - W F) c_diff / pi + W F D V (1 + F0 k)) N.L, c_diff = baseColor (1 - metallic)
// F0_d is the dielectric's reflectance (0.04, or KHR_materials_ior / _specular's, per channel)
// and W = mix(w, 1, metallic) the specular weight w of KHR_materials_specular on the dielectric
// (scaling its F0 and F90 alike; 1 without the extension, when the terms are appendix B's exactly).
// kSpecular false: F0_d = 0.04 and W = 1 taken as given (dielectricF0 and specularWeight unread),
// the same bits with fewer operations, for the kernels' draws without either extension.
// k = 1 / E_ss - 1 is the multiple-scattering compensation (brdfMultiScatter, IblTerms.inl; per
// pixel, as it depends on N.V and roughness only); k = 0 is appendix B's single scattering exactly.
// V is the specification's G / (4 N.L N.V). D's denominator is written |N x H|^2 + (N.H)^2 alpha^2
// (equal for unit N and H): in float, alpha^2 - 1 keeps only a few bits of a small alpha^2, which
// near the peak is all that is left (0.7% off at roughness 0.05); sin2NH = |N x H|^2 keeps them.
// N.V is clamped to 1e-4 (a viewer at grazing, or just behind an interpolated normal, still sees
// the lit surface), V.H and N.H to 0; where N.L <= 0 the result is 0 (no light on the side the
// surface does not face). A NaN roughness or metallic reads as the end of its range it fails.
// The material inputs as the BRDF reads them: roughness clamped to [kMinRoughness, 1], metallic
// to [0, 1], a NaN read as the end of the range it fails (the lower one). Shared with the image
// light (PbrProgram.hpp's imageLight).
template <class R>
inline R brdfRoughness(R roughness) {
    const R minRoughness = splatAs(roughness, kMinRoughness);
    return selectOf(roughness >= minRoughness, minOf(roughness, splatAs(roughness, 1.0f)), minRoughness);
}
template <class R>
inline R brdfMetallic(R metallic) {
    const R zero = splatAs(metallic, 0.0f);
    return selectOf(metallic > zero, minOf(metallic, splatAs(metallic, 1.0f)), zero);
}

// D V, the microfacet lobe without its Fresnel term (appendix B's specular_brdf over F), from
// N.L, N.V (clamped above 0), N.H (clamped to 0), |N x H|^2 and alpha^2, as brdfCosineTerms has
// them (its source: the base's lobe and the clear coat's are the same operations).
template <class R>
inline R ggxLobe(R nDotL, R nDotV, R nDotH, R sin2NH, R a2) {
    const R zero = splatAs(nDotL, 0.0f), one = splatAs(nDotL, 1.0f);
    const R pi = splatAs(nDotL, kPiF);
    const R d = sin2NH + nDotH * nDotH * a2;
    const R distribution = selectOf(d > zero, a2 / (pi * d * d), zero);
    const R gv = nDotL * sqrtOf(nDotV * nDotV * (one - a2) + a2);
    const R gl = nDotV * sqrtOf(nDotL * nDotL * (one - a2) + a2);
    const R sum = gv + gl;
    const R visibility = selectOf(sum > zero, splatAs(nDotL, 0.5f) / sum, zero);
    return distribution * visibility;
}

template <class R, bool kSpecular = true>
inline void brdfCosineTerms(R nDotL, R nDotVRaw, R nDotHRaw, R sin2NH, R vDotHRaw, R roughnessIn, R metallicIn,
                            const R base[3], const R dielectricF0[3], R specularWeight, R multiScatter, R out[3]) {
    const R zero = splatAs(nDotL, 0.0f), one = splatAs(nDotL, 1.0f);
    const R nDotV = maxOf(nDotVRaw, splatAs(nDotL, 1e-4f));
    const R nDotH = maxOf(nDotHRaw, zero), vDotH = maxOf(vDotHRaw, zero);
    const R roughness = brdfRoughness(roughnessIn);
    const R metallic = brdfMetallic(metallicIn);
    const R alpha = roughness * roughness;
    const R a2 = alpha * alpha;
    // Schlick's weight (1 - V.H)^5, 1 - V.H clamped to [0, 1] (std::clamp's order of tests).
    const R m0 = one - vDotH;
    const R m = selectOf(m0 < zero, zero, selectOf(one < m0, one, m0));
    const R m2 = m * m;
    const R fw = m2 * m2 * m;
    const R pi = splatAs(nDotL, kPiF);
    const R specular = ggxLobe(nDotL, nDotV, nDotH, sin2NH, a2);
    const R weight = kSpecular ? specularWeight + (one - specularWeight) * metallic : one;
    const auto lit = nDotL > zero;
    for (int c = 0; c < 3; ++c) {
        const R fd = kSpecular ? dielectricF0[c] : splatAs(nDotL, 0.04f);
        const R f0 = fd + (base[c] - fd) * metallic;
        R f = f0 + (one - f0) * fw;
        if constexpr (kSpecular) f = f * weight;
        const R diffuse = (one - f) * (base[c] * (one - metallic)) / pi;
        out[c] = selectOf(lit, (diffuse + f * specular * (one + f0 * multiScatter)) * nDotL, zero);
    }
}

// KHR_materials_clearcoat, layered as the glTF specification's fresnel_coat does it:
//   coated = mix(base, clearcoat_brdf, clearcoat Fc),  Fc = 0.04 + 0.96 (1 - |Nc.V|)^5
// (the coat's ior 1.5, Schlick's weight at the coat normal Nc's N.V: one value per pixel), with
// clearcoat_brdf = D V, appendix B's specular_brdf at the coat's roughness on Nc (no Fresnel
// inside: fresnel_coat holds it). The base (its lights, its sky light and its emission) is
// scaled by 1 - clearcoat Fc, the coat's lobe by clearcoat Fc.
// coatWeight: clearcoat Fc, clearcoat clamped to [0, 1] (NaN 0), |Nc.V| to [0, 1].
template <class R>
inline R coatWeight(R clearcoat, R nDotVc) {
    const R zero = splatAs(clearcoat, 0.0f), one = splatAs(clearcoat, 1.0f);
    const R weight = selectOf(clearcoat > zero, minOf(clearcoat, one), zero);
    const R c = maxOf(nDotVc, zero - nDotVc);
    const R m0 = one - c;
    const R m = selectOf(m0 < zero, zero, selectOf(one < m0, one, m0));
    const R m2 = m * m;
    const R fresnel = splatAs(clearcoat, 0.04f) + splatAs(clearcoat, 0.96f) * (m2 * m2 * m);
    return weight * fresnel;
}

// The coat's lobe times its N.L for one light: D V N.L on the coat normal (ggxLobe; N.V clamped
// to 1e-4, N.H to 0, the roughness by brdfRoughness), 0 where N.L <= 0.
template <class R>
inline R coatCosineTerm(R nDotL, R nDotVRaw, R nDotHRaw, R sin2NH, R roughnessIn) {
    const R zero = splatAs(nDotL, 0.0f);
    const R nDotV = maxOf(nDotVRaw, splatAs(nDotL, 1e-4f));
    const R nDotH = maxOf(nDotHRaw, zero);
    const R roughness = brdfRoughness(roughnessIn);
    const R alpha = roughness * roughness;
    const R lobe = ggxLobe(nDotL, nDotV, nDotH, sin2NH, alpha * alpha);
    return selectOf(nDotL > zero, lobe * nDotL, zero);
}
