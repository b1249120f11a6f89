// The image light's per-pixel lookups over a generic real type: included by Ibl.hpp (float) and LanePbr.inl (each ISA's lanes).
//
// Included INSIDE a namespace (sr, or sr::kernels_<isa> within that ISA's target region), with
// no include guard, as BrdfTerms.inl (which must come first: brdfRoughness, brdfMetallic). The
// operations absOf, wholeOf and gatherOf come from Ibl.hpp (float) or LanePbr.inl (lanes), the
// others from Brdf.hpp or the ISA's Simd*.hpp. Every index is computed in float from whole
// numbers below 2^24 (exact), and every coordinate is clamped into the grid first, NaN included,
// so a lane of garbage still reads inside the tables.

// x clamped into [lo, hi]; NaN gives lo.
template <class R>
inline R iblClamp(R x, float lo, float hi) {
    const R l = splatAs(x, lo);
    return selectOf(x > l, minOf(x, splatAs(x, hi)), l);
}

// The grid position (fx, fy) of the direction (x, y, z) on the octahedral levels (Ibl.hpp):
// (u, v) = (x, z) / (|x| + |y| + |z|), folded for y < 0 to ((1 - |v|) sign u, (1 - |u|) sign v),
// then u = -1 at texel column 1's left edge, +1 at column kSide's right edge; texel centres at
// whole numbers, so fx in [0.5, kSide + 0.5].
template <class R>
inline void iblGridPosition(R x, R y, R z, R& fx, R& fy) {
    const R zero = splatAs(x, 0.0f), one = splatAs(x, 1.0f), minusOne = splatAs(x, -1.0f);
    const R s = (absOf(x) + absOf(y)) + absOf(z);
    const R px = x / s, pz = z / s;
    const R ax = absOf(px), az = absOf(pz);
    const auto lower = y < zero;
    const R u = selectOf(lower, (one - az) * selectOf(px < zero, minusOne, one), px);
    const R v = selectOf(lower, (one - ax) * selectOf(pz < zero, minusOne, one), pz);
    const R half = splatAs(x, 0.5f * float(ImageLight::kSide)), centre = splatAs(x, 0.5f);
    fx = iblClamp((u + one) * half + centre, 0.5f, float(ImageLight::kSide) + 0.5f);
    fy = iblClamp((v + one) * half + centre, 0.5f, float(ImageLight::kSide) + 0.5f);
}

// The bilinear radiance at grid position (fx, fy) of the level starting at texel `first`.
template <class R>
inline void iblGridSample(const ImageLight::Tables& t, R first, R fx, R fy, R out[3]) {
    const R one = splatAs(fx, 1.0f), stride = splatAs(fx, float(ImageLight::kStride));
    const R x0 = wholeOf(fx), y0 = wholeOf(fy);
    const R wx = fx - x0, wy = fy - y0;
    const R i00 = first + y0 * stride + x0;
    const R i10 = i00 + one, i01 = i00 + stride, i11 = i01 + one;
    for (int c = 0; c < 3; ++c) {
        const float* p = t.radiance[c];
        const R top = gatherOf(p, i00) * (one - wx) + gatherOf(p, i10) * wx;
        const R bottom = gatherOf(p, i01) * (one - wx) + gatherOf(p, i11) * wx;
        out[c] = top * (one - wy) + bottom * wy;
    }
}

// ImageLight::specular: the two levels around roughness (clamped into [0, 1], NaN 0), blended.
template <class R>
inline void iblSpecular(const ImageLight::Tables& t, R rx, R ry, R rz, R roughness, R out[3]) {
    const R one = splatAs(rx, 1.0f);
    const R level = iblClamp(roughness, 0.0f, 1.0f) * splatAs(rx, float(ImageLight::kLevels - 1));
    const R lo = minOf(wholeOf(level), splatAs(rx, float(ImageLight::kLevels - 2)));
    const R w = level - lo;
    R fx, fy;
    iblGridPosition(rx, ry, rz, fx, fy);
    const R texels = splatAs(rx, float(ImageLight::kLevelTexels));
    R a[3], b[3];
    iblGridSample(t, lo * texels, fx, fy, a);
    iblGridSample(t, (lo + one) * texels, fx, fy, b);
    for (int c = 0; c < 3; ++c) out[c] = a[c] * (one - w) + b[c] * w;
}

// ImageLight::diffuse: E(n) / pi from the nine coefficients, each channel at least 0 (NaN 0).
template <class R>
inline void iblDiffuse(const ImageLight::Tables& t, R x, R y, R z, R out[3]) {
    const R zero = splatAs(x, 0.0f);
    const R basis[9] = {splatAs(x, 0.282095f),
                        splatAs(x, 0.488603f) * y,
                        splatAs(x, 0.488603f) * z,
                        splatAs(x, 0.488603f) * x,
                        splatAs(x, 1.092548f) * x * y,
                        splatAs(x, 1.092548f) * y * z,
                        splatAs(x, 0.315392f) * (splatAs(x, 3.0f) * z * z - splatAs(x, 1.0f)),
                        splatAs(x, 1.092548f) * x * z,
                        splatAs(x, 0.546274f) * (x * x - y * y)};
    for (int c = 0; c < 3; ++c) {
        R e = splatAs(x, t.sh[0][c]) * basis[0];
        for (int k = 1; k < 9; ++k) e = e + splatAs(x, t.sh[k][c]) * basis[k];
        out[c] = selectOf(e > zero, e, zero);
    }
}

// The bilinear value of a brdfAlbedoTable table at (N.V, roughness), each clamped into [0, 1]
// (NaN 0).
template <class R>
inline R albedoBilinear(const float* table, R nDotV, R roughness) {
    const R one = splatAs(nDotV, 1.0f), last = splatAs(nDotV, float(ImageLight::kLut - 1));
    const R secondLast = splatAs(nDotV, float(ImageLight::kLut - 2)), row = splatAs(nDotV, float(ImageLight::kLut));
    const R fx = iblClamp(nDotV, 0.0f, 1.0f) * last, fy = iblClamp(roughness, 0.0f, 1.0f) * last;
    const R x0 = minOf(wholeOf(fx), secondLast), y0 = minOf(wholeOf(fy), secondLast);
    const R wx = fx - x0, wy = fy - y0;
    const R i00 = y0 * row + x0;
    const R i10 = i00 + one, i01 = i00 + row, i11 = i01 + one;
    const R top = gatherOf(table, i00) * (one - wx) + gatherOf(table, i10) * wx;
    const R bottom = gatherOf(table, i01) * (one - wx) + gatherOf(table, i11) * wx;
    return top * (one - wy) + bottom * wy;
}

// ImageLight::brdfScaleBias: the split sum's a and b at (N.V, roughness).
template <class R>
inline void iblScaleBias(const ImageLight::Tables& t, R nDotV, R roughness, R& a, R& b) {
    a = albedoBilinear(t.lutA, nDotV, roughness);
    b = albedoBilinear(t.lutB, nDotV, roughness);
}

// The energy that single scattering loses, as the factor k = 1 / E_ss - 1 on F0 (Turquin,
// "Practical multiple scattering compensation for microfacet models", 2019): the specular lobe
// times 1 + F0 k returns what a white metal receives. E_ss at the BRDF's N.V (clamped to 1e-4)
// and roughness (brdfRoughness) from brdfAlbedoTable's E_ss (`ess`); 0 where E_ss is not above 0.
template <class R>
inline R brdfMultiScatter(const float* ess, R nDotV, R roughnessIn) {
    const R e = albedoBilinear(ess, maxOf(nDotV, splatAs(nDotV, 1e-4f)), brdfRoughness(roughnessIn));
    const R zero = splatAs(nDotV, 0.0f), one = splatAs(nDotV, 1.0f);
    return selectOf(e > zero, one / e - one, zero);
}

// The light a sky sends toward v from a surface with unit normal n (programs::imageLight): the
// prefiltered radiance along R = 2 (N.V) N - V times the lobe's albedo S = (F0 a + b) W (1 + F0 k)
// (the split sum, compensated for multiple scattering as the direct light is: brdfMultiScatter's
// k, with E_ss = a + b here), plus Lambert's c_diff x E(n) / pi times 1 - S, the light the lobe
// did not reflect (per channel; the direct light's (1 - W F) integrated over the sky; F0 and the
// specular weight W as brdfCosineTerms has them), with the
// BRDF's roughness and metallic (brdfRoughness, brdfMetallic). A white metal, and a white
// dielectric, return the uniform sky they sit in.
// kSpecular false: brdfCosineTerms' shortcut (F0_d = 0.04, W = 1 as given), the same bits.
template <class R, bool kSpecular = true>
inline void iblRadiance(const ImageLight::Tables& t, const R base[3], const R dielectricF0[3], R specularWeight, R metallicIn,
                        R roughnessIn, R nx, R ny, R nz, R vx, R vy, R vz, R out[3]) {
    const R one = splatAs(nx, 1.0f);
    const R roughness = brdfRoughness(roughnessIn), metallic = brdfMetallic(metallicIn);
    const R ndv = (nx * vx + ny * vy) + nz * vz;
    const R nDotV = maxOf(ndv, splatAs(nx, 1e-4f));
    const R twice = splatAs(nx, 2.0f) * ndv;
    R a, b, e[3], spec[3];
    iblScaleBias(t, nDotV, roughness, a, b);
    iblDiffuse(t, nx, ny, nz, e);
    iblSpecular(t, nx * twice - vx, ny * twice - vy, nz * twice - vz, roughness, spec);
    const R ess = a + b, zero = splatAs(nx, 0.0f);
    const R k = selectOf(ess > zero, one / ess - one, zero);
    const R weight = kSpecular ? specularWeight + (one - specularWeight) * metallic : one; // brdfCosineTerms' W
    for (int c = 0; c < 3; ++c) {
        const R fd = kSpecular ? dielectricF0[c] : splatAs(nx, 0.04f);
        const R f0 = fd + (base[c] - fd) * metallic;
        R albedo = f0 * a + b;
        if constexpr (kSpecular) albedo = albedo * weight;
        albedo = albedo * (one + f0 * k);
        out[c] = base[c] * (one - metallic) * e[c] * (one - albedo) + spec[c] * albedo;
    }
}

// The clear coat's sky light (BrdfTerms.inl's coatWeight layers it): the prefiltered radiance
// along R = 2 (Nc.V) Nc - V at the coat's roughness times the directional albedo of its lobe D V,
// which has no Fresnel inside: E_ss = a + b at (Nc.V clamped to 1e-4, the roughness by
// brdfRoughness).
template <class R>
inline void iblCoat(const ImageLight::Tables& t, R roughnessIn, R nx, R ny, R nz, R vx, R vy, R vz, R out[3]) {
    const R roughness = brdfRoughness(roughnessIn);
    const R ndv = (nx * vx + ny * vy) + nz * vz;
    const R nDotV = maxOf(ndv, splatAs(nx, 1e-4f));
    const R twice = splatAs(nx, 2.0f) * ndv;
    R a, b, spec[3];
    iblScaleBias(t, nDotV, roughness, a, b);
    iblSpecular(t, nx * twice - vx, ny * twice - vy, nz * twice - vz, roughness, spec);
    const R ess = a + b;
    for (int c = 0; c < 3; ++c) out[c] = spec[c] * ess;
}
