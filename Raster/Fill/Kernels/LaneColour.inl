// Colour and lighting lane by lane: vectors of lanes, packing, sRGB encoding, Blinn-Phong.
// Part of the span kernels: included by Kernels.inl inside its ISA namespace (see there).

// --- Colour and lighting, lane by lane -------------------------------------------------------
struct V3 {
    F x, y, z;
};
struct Rgb {
    F r, g, b;
};

// dot(a, b) as Vec.hpp evaluates it: (ax bx + ay by) + az bz.
SR_SIMD_INLINE F dot3(const V3& a, const V3& b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }

// normalize(Vec3)'s inline fast path (Vec.hpp): divide by the largest |component|, sum of
// squares, 1 / sqrt, three products. `ok` loses the lanes off that path (zero, non-finite, or
// |x| + |y| + |z| overflowing), which the caller redoes with the scalar code.
SR_SIMD_INLINE V3 normalizeFast(const V3& v, M& ok) {
    const F ax = fabs(v.x), ay = fabs(v.y), az = fabs(v.z);
    // std::max(std::max(ax, ay), az): maxps returns its second operand on ties and NaN; NaN lanes fail `ok`.
    const F m = fmax(fmax(ax, ay), az);
    ok = ok & (m > fzero()) & ((ax + ay) + az <= fset(3.40282347e38f));
    const F x = v.x / m, y = v.y / m, z = v.z / m;
    F sum = x * x;
    sum = sum + y * y;
    sum = sum + z * z;
    const F inv = fset(1.0f) / fsqrt(sum);
    return {x * inv, y * inv, z * inv};
}

// toUnorm8 (Color.hpp): 0 for !(c > 0), 255 for c >= 1, else c * 255 rounded to nearest-even
// with the 2^23 trick.
SR_SIMD_INLINE I toUnorm8(F c) {
    const F x = c * fset(255.0f);
    const F two23 = fset(8388608.0f);
    const F rounded = (x + two23) - two23;
    const F value = select(c >= fset(1.0f), fset(255.0f), select(c > fzero(), rounded, fzero()));
    return truncToInt(value);
}

// packBgra8 (Color.hpp): 0xFF000000 | r << 16 | g << 8 | b.
SR_SIMD_INLINE I packBgra8(const Rgb& c) {
    return (iset(int(0xFF000000u)) | shiftLeft<16>(toUnorm8(c.r))) | (shiftLeft<8>(toUnorm8(c.g)) | toUnorm8(c.b));
}

// encodeSrgb8 (ColorSpace.cpp) per lane, through its table (SrgbTables::encodeBits): the bucket
// of the float's top 16 bits, one step up where its low 16 bits exceed the bucket's midpoint's;
// 0 for !(l > 0), 255 for l >= 1.
SR_SIMD_INLINE I encodeSrgbLanes(F l) {
    const SrgbTables& t = srgbTables();
    const M pos = l > fzero(), one = l >= fset(1.0f);
    const I b = asInt(select(pos, fmin(l, fset(0.99999994f)), fzero()));
    const I e = gather(t.encodeBits, imax(shiftRightLogical<16>(b) - iset(kSrgbEncodeFirst), iset(0)));
    const I low16 = iset(0xFFFF);
    const I stepped = (e & low16) + select((b & low16) > shiftRightLogical<16>(e), iset(1), iset(0));
    return select(one, iset(255), select(pos, stepped, iset(0)));
}

// packLinearBgra8 (ColorSpace.hpp) without tone mapping or exposure: each channel encoded. Out
// of line (one copy per ISA): six gathers, too much code to copy into every kernel.
SR_SIMD_NOINLINE I packLinearBgra8(const Rgb& c) {
    return (iset(int(0xFF000000u)) | shiftLeft<16>(encodeSrgbLanes(c.r))) | (shiftLeft<8>(encodeSrgbLanes(c.g)) | encodeSrgbLanes(c.b));
}

// toneMap (ColorSpace.cpp) per lane, then packLinearBgra8: the exposure scale, then ACES or
// Khronos PBR Neutral, the same operations in the same order (std::max / std::min / std::clamp as
// the selects they are).
SR_SIMD_NOINLINE I packToneMapped(const Rgb& linear, ToneMap op, float exposureScale) {
    const F e = fset(exposureScale), zero = fzero(), one = fset(1.0f);
    Rgb c{linear.r * e, linear.g * e, linear.b * e};
    if (op == ToneMap::Aces) {
        auto f = [&](F x) SR_SIMD_LAMBDA {
            x = select(x < zero, zero, x);
            const F v = x * (fset(2.51f) * x + fset(0.03f)) / (x * (fset(2.43f) * x + fset(0.59f)) + fset(0.14f));
            return select(v < zero, zero, select(one < v, one, v));
        };
        c = {f(c.r), f(c.g), f(c.b)};
    } else if (op == ToneMap::Neutral) {
        constexpr float kStart = 0.8f - 0.04f, kDesaturation = 0.15f, d = 1.0f - kStart;
        const F gb = select(c.b < c.g, c.b, c.g);
        const F x = select(gb < c.r, gb, c.r);
        const F offset = select(x < fset(0.08f), x - fset(6.25f) * x * x, fset(0.04f));
        c = {c.r - offset, c.g - offset, c.b - offset};
        const F gbMax = select(c.g < c.b, c.b, c.g);
        const F peak = select(c.r < gbMax, gbMax, c.r);
        const M on = peak >= fset(kStart); // false for NaN: left to the encoder's clamp
        if (bits(on) != 0) {
            const F newPeak = one - fset(d * d) / (peak + fset(d) - fset(kStart));
            const F s = newPeak / peak;
            Rgb m{c.r * s, c.g * s, c.b * s};
            const F g = one - one / (fset(kDesaturation) * (peak - newPeak) + one);
            m = {m.r + (newPeak - m.r) * g, m.g + (newPeak - m.g) * g, m.b + (newPeak - m.b) * g};
            c = {select(on, m.r, c.r), select(on, m.g, c.g), select(on, m.b, c.b)};
        }
    }
    return packLinearBgra8(c);
}

// programs::encode per lane: the draw's colour mode decides (one branch per group).
template <class Prog>
SR_SIMD_INLINE I encodeLanes(const Prog& p, const Rgb& c) {
    const DrawContext& d = *p.d;
    if (!d.linear) return packBgra8(c);
    if (d.settings.toneMap == ToneMap::None && d.exposureScale == 1.0f) return packLinearBgra8(c);
    return packToneMapped(c, d.settings.toneMap, d.exposureScale);
}

struct Terms {
    F diffuse, specular;
};

// blinnPhong (Shading.hpp) for unit n and v, with a whole-number shininess in [0, 1024] (the
// table only offers kernels for such lighting; shininessPow's binary exponentiation, the same
// multiplications in the same order).
SR_SIMD_INLINE Terms blinnPhong(const Lighting& lighting, const Specular& material, const V3& n, const V3& v, M& ok) {
    F diffuse = fset(lighting.ambient);
    F specular = fzero();
    const bool specularOn = material.on();
    const unsigned exponent = unsigned(material.shininess);
    for (const Light& light : lighting.lights) {
        const Vec3 l = light.toLight;
        const V3 lv{fset(l.x), fset(l.y), fset(l.z)};
        const F ndl = dot3(n, lv);
        const M lit = ndl > fzero();
        diffuse = select(lit, diffuse + ndl, diffuse);
        if (!specularOn) continue; // no half vector (the scalar blinnPhong forms none either)
        M hOk = ok;
        const V3 h = normalizeFast({lv.x + v.x, lv.y + v.y, lv.z + v.z}, hOk);
        ok = (lit & hOk) | andNot(ok, lit); // a bad half vector matters only where it is used
        // std::max(dot(n, h), 0.0f): NaN lanes already failed `ok`.
        const F base0 = fmax(dot3(n, h), fzero());
        unsigned e = exponent;
        F result = fset(1.0f), base = base0;
        while (e) {
            if (e & 1u) result = result * base;
            base = base * base;
            e >>= 1u;
        }
        specular = select(lit, specular + result, specular);
    }
    return {diffuse, specular};
}

// applyTerms (Shading.hpp): kd * diffuse + ks * specular per channel.
SR_SIMD_INLINE Rgb applyTerms(const Rgb& kd, Color ks, const Terms& t) {
    return {kd.r * t.diffuse + fset(ks.r) * t.specular, kd.g * t.diffuse + fset(ks.g) * t.specular,
            kd.b * t.diffuse + fset(ks.b) * t.specular};
}

// The RGB terms (RgbTerms) and their applyTerms; `ok` as blinnPhong's (lightsRgb returns it).
struct TermsRgb {
    Rgb diffuse, specular;
    M ok;
};
SR_SIMD_INLINE Rgb applyTerms(const Rgb& kd, Color ks, const TermsRgb& t) {
    return {kd.r * t.diffuse.r + fset(ks.r) * t.specular.r, kd.g * t.diffuse.g + fset(ks.g) * t.specular.g,
            kd.b * t.diffuse.b + fset(ks.b) * t.specular.b};
}

// std::clamp(x, lo, hi) as the scalar code evaluates it: (x < lo) ? lo : (hi < x) ? hi : x.
SR_SIMD_INLINE F clampLanes(F x, F lo, F hi) { return select(x < lo, lo, select(hi < x, hi, x)); }
