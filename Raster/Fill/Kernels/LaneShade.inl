// The programs' fragment() lane by lane: one group of fragments shaded and packed.
// Part of the span kernels: included by Kernels.inl inside its ISA namespace (see there).

// --- Shading: the programs' fragment(), lane by lane -----------------------------------------
// Shades one group of fragments (pixel columns xs, rows ys, 1/w and the perspective-correct
// varyings) and returns their packed colours. Lanes the vector code does not cover (a normal
// or half vector off normalize's fast path) are redone by the scalar program.
template <class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
SR_SIMD_INLINE I shadeGroup(const Prog& p, const F* v, F invW, I xs, I ys, F triangleLod) {
    constexpr int kV = Prog::kVaryings;
    const DrawContext& d = *p.d;
    M ok = mAll();
    Rgb kd{fset(d.kd.r), fset(d.kd.g), fset(d.kd.b)};
    if constexpr (Prog::kIsTextured && Prog::kMode != ShadingMode::Pbr) {
        const Rgb texel = sampleTexture<kPersp, kFilter>(p, v[0], v[1], invW, triangleLod);
        kd = {kd.r * texel.r, kd.g * texel.g, kd.b * texel.b}; // sampleKd: the draw's kd times the texel
    }
    constexpr int kT = Prog::kIsTextured ? 2 : 0; // the first varying after the uv
    I out;
    if constexpr (Prog::kMode == ShadingMode::Pbr) {
        (void)triangleLod; // each map takes its own (shadePbr)
        out = encodeLanes(p, shadePbr<Prog, kPersp, kFilter>(p, v, invW, ok));
    } else if constexpr (Prog::kMode == ShadingMode::Unlit) {
        if constexpr (Prog::kVertexColours) kd = {kd.r * v[kT], kd.g * v[kT + 1], kd.b * v[kT + 2]}; // UnlitProgram::fragment
        out = encodeLanes(p, kd);
    } else if constexpr (Prog::kMode == ShadingMode::Flat) {
        p.ensureLit(); // FlatProgram lights on its first shaded fragment
        const RgbTerms& ft = p.terms;
        const TermsRgb t{{fset(ft.diffuse.r), fset(ft.diffuse.g), fset(ft.diffuse.b)},
                         {fset(ft.specular.r), fset(ft.specular.g), fset(ft.specular.b)},
                         mAll()};
        out = encodeLanes(p, applyTerms(kd, d.specular.ks, t));
    } else if constexpr (Prog::kMode == ShadingMode::Gouraud) {
        if constexpr (Prog::kRgbTerms)
            out = encodeLanes(p, applyTerms(kd, d.specular.ks, TermsRgb{{v[kT], v[kT + 1], v[kT + 2]}, {v[kT + 3], v[kT + 4], v[kT + 5]}, mAll()}));
        else out = encodeLanes(p, applyTerms(kd, d.specular.ks, Terms{v[kT], v[kT + 1]}));
    } else {
        constexpr int kN = Prog::kN; // the normal's varyings (after the position's, kPositions)
        const V3 n = normalizeFast({v[kN], v[kN + 1], v[kN + 2]}, ok);
        if constexpr (!Prog::kPositions) {
            // White directional lights, no specular term, no shadows (phongReadsPosition).
            out = encodeLanes(p, applyTerms(kd, d.specular.ks, blinnPhong(d.view.lighting, d.specular, n, V3{fzero(), fzero(), fzero()}, ok)));
        } else {
            // The direction to the eye feeds the specular term only: without one (black Ks or Ns 0),
            // no lane forms it (and none fails on it).
            V3 toEye{fzero(), fzero(), fzero()};
            if (d.specular.on()) {
                const Vec3 eye = d.view.eye;
                toEye = normalizeFast({fset(eye.x) - v[kT], fset(eye.y) - v[kT + 1], fset(eye.z) - v[kT + 2]}, ok);
            }
            // Coloured, point or spot lights: the out-of-line RGB path, kept off the white-light path's registers.
            if (SR_UNLIKELY(!d.whiteLights || d.view.shadows)) {
                const TermsRgb t = lightsRgb(d.view.lighting, d.specular, d.view.shadows, n.x, n.y, n.z, v[kT], v[kT + 1], v[kT + 2],
                                             toEye.x, toEye.y, toEye.z, ok);
                ok = t.ok;
                out = encodeLanes(p, applyTerms(kd, d.specular.ks, t));
            } else {
                out = encodeLanes(p, applyTerms(kd, d.specular.ks, blinnPhong(d.view.lighting, d.specular, n, toEye, ok)));
            }
        }
    }
    if (bits(ok) != bits(mAll())) {
        alignas(64) std::int32_t pixels[kLanes], x[kLanes], y[kLanes];
        alignas(64) float w[kLanes], lanes[kV > 0 ? kV : 1][kLanes];
        istore(pixels, out);
        istore(x, xs);
        istore(y, ys);
        fstore(w, invW);
        for (int k = 0; k < kV; ++k) fstore(lanes[k], v[k]);
        for (int i = 0, m = bits(ok); i < kLanes; ++i) {
            if (m & (1 << i)) continue;
            Fragment<kV> f;
            f.x = x[i];
            f.y = y[i];
            f.invW = w[i];
            for (int k = 0; k < kV; ++k) f.varyings[std::size_t(k)] = lanes[k][i];
            pixels[i] = std::int32_t(p.fragment(f));
        }
        out = iload(pixels);
    }
    return out;
}
