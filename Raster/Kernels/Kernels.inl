// The span kernels, written once over the vector types of one ISA (SimdSse2/Avx2/Avx512.hpp).
//
// Included by KernelsSse2.inl, KernelsAvx2.inl and KernelsAvx512.inl INSIDE their namespace
// (sr::kernels_<isa>) and target region, after `using namespace sr::simd_<isa>;`, so every
// function here exists once per ISA, compiled for it, and no symbol is shared between ISAs.
// Each of those is in turn included by one small .cpp per shading model
// (Kernels<Isa><Model>.cpp), which names the programs to instantiate (SR_KERNEL_PROGRAM): the
// kernels of one ISA compile as four translation units, in parallel and in a quarter of the
// memory (the single AVX-512 file took 826 s and 5.3 GB under ASan + UBSan at -O2).
// The scalar twins are ScanlineFill.hpp's fillTriangle and the programs of MeshPrograms.hpp:
// every operation below is theirs, in the same order, lane by lane (IEEE, no FMA), so the
// pixels, depths and counters are bit-identical (Tests/Threads/KernelIdentityTests.cpp proves it for every key).

using sr::programs::DrawContext;

// Set bits of a lane mask (no POPCNT at the x86-64 baseline): a nibble table.
SR_SIMD_INLINE int popcount(int b) {
    int n = 0;
    for (; b != 0; b >>= 4) n += int((0x4332322132212110ull >> (4 * (b & 0xF))) & 0xFu);
    return n;
}

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

// --- Shadow maps (Shadow.cpp's receiver test, lane by lane) ----------------------------------
// ShadowMap::visibility for points p (unit normals n, unit directions l to the light): the same
// operations in the same order, the k x k PCF taps gathered from the map's depth (a tap off the
// map counts as lit, as there). Any lane may be evaluated: a point off the map, behind the
// light or non-finite is lit (1), as in the scalar code.
SR_SIMD_INLINE F mapVisibility(const ShadowMap& map, const ShadowSettings& s, const V3& p, const V3& n, const V3& l) {
    const float* e = map.viewProj.m;
    // Mat4 * Vec4(p, 1): ((m0 x + m4 y) + m8 z) + m12 w, with m12 w = m12 exactly.
    const F cx = ((fset(e[0]) * p.x + fset(e[4]) * p.y) + fset(e[8]) * p.z) + fset(e[12]);
    const F cy = ((fset(e[1]) * p.x + fset(e[5]) * p.y) + fset(e[9]) * p.z) + fset(e[13]);
    const int size = map.target.width();
    const F fsize = fset(float(size)), one = fset(1.0f), half = fset(0.5f);
    F u, v;
    M inside;
    if (e[3] == 0.0f && e[7] == 0.0f && e[11] == 0.0f && e[15] == 1.0f) {
        // An orthographic map: w is exactly 1 for a finite p, and c / 1 is c. (A non-finite
        // component of p makes cx or cy non-finite, 0 x inf included: off the map and lit, as
        // the scalar code's NaN w.)
        u = ((cx + one) * half) * fsize;
        v = ((one - cy) * half) * fsize;
        inside = mAll();
    } else {
        const F cw = ((fset(e[3]) * p.x + fset(e[7]) * p.y) + fset(e[11]) * p.z) + fset(e[15]);
        u = ((cx / cw + one) * half) * fsize;
        v = ((one - cy / cw) * half) * fsize;
        inside = cw > fzero();
    }
    inside = inside & (u >= fzero()) & (v >= fzero()) & (u < fsize) & (v < fsize);
    if (bits(inside) == 0) return one;
    const F d = dot3({p.x - fset(map.origin.x), p.y - fset(map.origin.y), p.z - fset(map.origin.z)},
                     {fset(map.axis.x), fset(map.axis.y), fset(map.axis.z)});
    // std::clamp, then std::max(x, 0) = maxps(0, x) and std::min(x, k) = minps(k, x).
    const F cosT = clampLanes(fabs(dot3(n, l)), fset(1e-4f), one);
    const F tanT = fmin(fset(kMaxBiasTangent), fsqrt(fmax(fzero(), one - cosT * cosT)) / cosT);
    const F texel = map.perspective ? fset(map.texelWorld) * d : fset(map.texelWorld);
    const F at = d - texel * (fset(s.constantBias) + fset(s.slopeBias) * tanT);
    F receiver; // ShadowMap::depthAt(at)
    if (!map.perspective) {
        receiver = (fset(map.farZ) - at) / fset(map.farZ - map.nearZ);
    } else {
        const float a = map.nearZ / (map.farZ - map.nearZ), b = map.farZ * map.nearZ / (map.farZ - map.nearZ);
        receiver = select(at > fzero(), fset(b) / at - fset(a), fset(std::numeric_limits<float>::max()));
    }
    const int k = std::max(s.pcf, 1) / 2;
    const I tx = truncToInt(select(inside, u, fzero())), ty = truncToInt(select(inside, v, fzero()));
    // ShadowMap::texelIndex with shifts: 32 x 32 tiles, a row of tiles after another.
    static_assert(kShadowTile == 32, "the shifts below are for 32 x 32 tiles");
    const I isize = iset(size), below = iset(-1), low5 = iset(31), tileRow = iset(size / kShadowTile * kShadowTile * kShadowTile);
    const auto* depth = reinterpret_cast<const std::uint32_t*>(map.target.depthData());
    I lit = iset(0);
    for (int dy = -k; dy <= k; ++dy) {
        const I y = ty + iset(dy);
        const M rowIn = (y > below) & (y < isize);
        const I yIn = select(rowIn, y, iset(0));
        const I row = mulLow(shiftRightArith<5>(yIn), tileRow) + shiftLeft<5>(yIn & low5);
        for (int dx = -k; dx <= k; ++dx) {
            const I x = tx + iset(dx);
            const M in = rowIn & (x > below) & (x < isize);
            const I xIn = select(in, x, iset(0));
            const F stored = asFloat(gather(depth, row + shiftLeft<10>(shiftRightArith<5>(xIn)) + (xIn & low5)));
            // Off the map: lit; on it: lit unless behind the nearest caster (reversed-Z).
            lit = lit + select(andNot(mAll(), in) | (receiver >= stored), iset(1), iset(0));
        }
    }
    const F seen = toFloat(lit) / fset(float((2 * k + 1) * (2 * k + 1)));
    return select(inside, seen, one);
}

// SceneShadows::visibility: each lane's cascade (the first whose splitFar is not below the
// point's view depth, else the last), evaluated for the cascades some lane of `lanes` uses.
SR_SIMD_INLINE F shadowVisibility(const SceneShadows& sh, std::size_t light, const V3& p, const V3& n, const V3& l, M lanes) {
    if (light >= sh.mapCount.size() || sh.mapCount[light] == 0) return fset(1.0f);
    const std::size_t first = std::size_t(sh.firstMap[light]), count = std::size_t(sh.mapCount[light]);
    if (count == 1) return mapVisibility(sh.maps[first], sh.settings, p, n, l);
    const F depth = dot3({p.x - fset(sh.eye.x), p.y - fset(sh.eye.y), p.z - fset(sh.eye.z)},
                         {fset(sh.forward.x), fset(sh.forward.y), fset(sh.forward.z)});
    F seen = fset(1.0f);
    M beyond = mAll(); // lanes past every earlier cascade
    for (std::size_t j = 0; j < count; ++j) {
        const ShadowMap& map = sh.maps[first + j];
        const M past = depth > fset(map.splitFar);
        const M here = j + 1 < count ? andNot(beyond, past) : beyond;
        if (bits(here & lanes) != 0) seen = select(here, mapVisibility(map, sh.settings, p, n, l), seen);
        beyond = beyond & past;
        if (bits(beyond & lanes) == 0) break;
    }
    return seen;
}

// lightTerms (Shading.hpp) for any lights at world points p (px, py, pz) with unit normals n (nx,
// ny, nz) and unit view vectors v (vx, vy, vz), lane by lane: lightAt's direction and factor,
// then the one-sided terms scaled by colour * a, the same operations in the same order. Lanes whose light vector or half vector is off normalize's fast path lose
// `ok` (a point light exactly at the surface point, non-finite positions). Out of line (its cost
// is per light; every kernel of the ISA shares one copy), with its vectors passed by value so
// that the callers' white-light path keeps them in registers.
SR_SIMD_NOINLINE TermsRgb lightsRgb(const Lighting& lighting, const Specular& material, const SceneShadows* shadows, F nx,
                                    F ny, F nz, F px, F py, F pz, F vx, F vy, F vz, M ok) {
    const V3 n{nx, ny, nz}, p{px, py, pz}, v{vx, vy, vz};
    const F ambient = fset(lighting.ambient);
    TermsRgb t{{ambient, ambient, ambient}, {fzero(), fzero(), fzero()}, ok};
    const bool specularOn = material.on();
    const unsigned exponent = unsigned(material.shininess);
    for (std::size_t i = 0; i < lighting.lights.size(); ++i) {
        const Light& light = lighting.lights[i];
        V3 l;
        F a = fset(1.0f);
        if (light.type == LightType::Directional) {
            l = {fset(light.toLight.x), fset(light.toLight.y), fset(light.toLight.z)};
        } else {
            const V3 d{fset(light.position.x) - p.x, fset(light.position.y) - p.y, fset(light.position.z) - p.z};
            const F d2 = dot3(d, d);
            l = normalizeFast(d, t.ok);
            // std::max(d2, k) is (d2 < k) ? k : d2, i.e. maxps(k, d2) (NaN lanes have failed `ok`).
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
        const M lit = (a > fzero()) & (ndl > fzero());
        if (bits(lit) == 0) continue;
        if (shadows) { // shadowedTerms: a scaled by the lit fraction where it is below 1
            const F seen = shadowVisibility(*shadows, i, p, n, l, lit & t.ok);
            a = select(seen < fset(1.0f), a * seen, a);
        }
        const F diffuse = ndl * a;
        t.diffuse.r = select(lit, t.diffuse.r + fset(light.colour.r) * diffuse, t.diffuse.r);
        t.diffuse.g = select(lit, t.diffuse.g + fset(light.colour.g) * diffuse, t.diffuse.g);
        t.diffuse.b = select(lit, t.diffuse.b + fset(light.colour.b) * diffuse, t.diffuse.b);
        if (!specularOn) continue;
        M hOk = t.ok;
        const V3 h = normalizeFast({l.x + v.x, l.y + v.y, l.z + v.z}, hOk);
        t.ok = (lit & hOk) | andNot(t.ok, lit); // a bad half vector matters only where it is used
        const F base0 = fmax(dot3(n, h), fzero());
        unsigned e = exponent;
        F result = fset(1.0f), base = base0;
        while (e) {
            if (e & 1u) result = result * base;
            base = base * base;
            e >>= 1u;
        }
        const F s = result * a;
        t.specular.r = select(lit, t.specular.r + fset(light.colour.r) * s, t.specular.r);
        t.specular.g = select(lit, t.specular.g + fset(light.colour.g) * s, t.specular.g);
        t.specular.b = select(lit, t.specular.b + fset(light.colour.b) * s, t.specular.b);
    }
    return t;
}

// --- Texture sampling (TextureSampling.cpp's fast paths, lane by lane) -----------------------
// Lanes whose coordinate is NaN, infinite or |u| >= 2^31 are "off" the vector path: they are
// computed with a harmless stand-in (u = 0) and redone by Texture::sample* afterwards.
SR_SIMD_INLINE M onVectorPath(F u) { return fabs(u) < fset(2147483648.0f); }

// reduceCoordinate (TextureSampling.cpp), for finite |u| < 2^31, without branches:
//  Repeat: |d| >= 1 -> d - floor(d); Mirror: |d| >= 2 -> d - 2 floor(d / 2); Clamp: clamp(d, -1, 2).
// The selection multiplies by min(floor(|d|), 1), which is 0 or 1 exactly.
template <WrapMode kWrap>
SR_SIMD_INLINE D reduceCoordinate(D d) {
    if constexpr (kWrap == WrapMode::Repeat) return d - dfloor(d) * dmin(dfloor(dabs(d)), dset(1.0));
    else if constexpr (kWrap == WrapMode::Mirror)
        return d - (dset(2.0) * dfloor(d * dset(0.5))) * dmin(dfloor(dabs(d) * dset(0.5)), dset(1.0));
    else return dmin(dmax(d, dset(-1.0)), dset(2.0));
}

// Wrap<kWrap>::one (TextureSampling.cpp) for an unwrapped texel index i: Repeat i in [-size, size - 1]
// (nearest) or [-size - 1, size] (linear, after the first fix-up below), Mirror and Clamp any
// index the reduced coordinates produce.
template <WrapMode kWrap>
SR_SIMD_INLINE I wrapIndex(I i, int size, std::uint32_t mask) {
    const I n = iset(size), zero = iset(0);
    if constexpr (kWrap == WrapMode::Repeat) {
        if (mask != 0) return i & iset(int(mask)); // power of two: two's complement & is the positive modulo
        return i + select(i < zero, n, zero);
    } else if constexpr (kWrap == WrapMode::Clamp) {
        return imin(imax(i, zero), n - iset(1));
    } else {
        // Mirrored repeat is symmetric about -1/2 (j and -1 - j select the same texel), period 2 size.
        const I twice = iset(2 * size);
        I m = select(i < zero, iset(-1) - i, i);
        m = select(m < twice, m, m - twice);
        return select(m < n, m, (twice - iset(1)) - m);
    }
}

// The texel coordinate of u on an axis of `size` texels with 9 fraction bits, Z = floor(d size 512)
// for the reduced coordinate d (exact in double: d has at most 24 significant bits, size at most
// 15 bits). From it levelX takes linearTaps' 8-bit X = floor((d size - 0.5) 256 + 0.5) of this size
// and of every size / 2^k.
template <WrapMode kWrap>
SR_SIMD_INLINE I texelFixed(F u, int size) {
    const D scale = dset(double(size) * 512.0);
    auto fixedX = [&](D d) SR_SIMD_LAMBDA { return dfloor(reduceCoordinate<kWrap>(d) * scale); };
    return toInt(fixedX(lowHalf(u)), fixedX(highHalf(u)));
}

// linearTaps' 8-bit X on an axis of size / 2^k from texelFixed's Z on the axis of `size`: with
// Y = d size 256, X_k = floor(Y / 2^k - 127.5) = floor((2 Y - 255 2^k) / 2^(k + 1)) =
// floor((Z - 255 2^k) / 2^(k + 1)), since floor(y / n) == floor(floor(y) / n) for integer n and
// 255 2^k is an integer. k = 0 is the axis's own X.
SR_SIMD_INLINE I levelX(I z, int k) { return shiftRightArith(z - iset(255 << k), k + 1); }

// linearTaps' 8-bit X of u on an axis of `size` texels, from u itself.
template <WrapMode kWrap>
SR_SIMD_INLINE I linearX(F u, int size) { return levelX(texelFixed<kWrap>(u, size), 0); }

// GL_LINEAR taps along one axis (linearTaps + Wrap<kWrap>::pair) from the 8-bit X of
// levelX: wrapped texel indices a (i0) and b (i0 + 1), and the 8-bit weight w of b.
template <WrapMode kWrap>
SR_SIMD_INLINE void linearAxis(I x, int size, std::uint32_t mask, I& a, I& b, I& w) {
    const I i0 = shiftRightArith<8>(x);
    w = x & iset(255);
    const I one = iset(1);
    if (kWrap == WrapMode::Repeat && mask == 0) {
        // Wrap<Repeat>::pair without a mask: i0 >= -size - 1, so size is added up to twice; b is
        // a + 1 wrapped past the end.
        const I n = iset(size), zero = iset(0);
        a = wrapIndex<kWrap>(wrapIndex<kWrap>(i0, size, mask), size, mask);
        const I next = a + one;
        b = select(next == n, zero, next);
        return;
    }
    a = wrapIndex<kWrap>(i0, size, mask);
    b = wrapIndex<kWrap>(i0 + one, size, mask);
}

// GL_NEAREST along one axis (nearestTap + Wrap<kWrap>::one).
template <WrapMode kWrap>
SR_SIMD_INLINE I nearestAxis(F u, int size, std::uint32_t mask) {
    const D sizeD = dset(double(size));
    auto tap = [&](D d) SR_SIMD_LAMBDA { return dfloor(reduceCoordinate<kWrap>(d) * sizeD); };
    return wrapIndex<kWrap>(toInt(tap(lowHalf(u)), tap(highHalf(u))), size, mask);
}

// Byte k of each texel as a float.
template <int kShift>
SR_SIMD_INLINE F channel(I texel) { return toFloat(shiftRightLogical<kShift>(texel) & iset(0xFF)); }

// The horizontal taps a (weight 256 - w) and b (weight w) of linearAxis as one pair of texels
// next to each other in memory, x and x + 1 (Texture::LevelView: each row ends with a copy of its
// texel 0), and the weight w' of x + 1, such that t[a] (256 - w) + t[b] w == t[x] (256 - w') +
// t[x + 1] w' exactly:
//  Repeat: b is a + 1, or 0 after the last texel, which the row's copy stands for: x = a, w' = w;
//  Clamp: b is a + 1, or a at an edge: x = a, w' = w or 0 (t[a] 256 either way);
//  Mirror: b is a + 1, a - 1 (a mirrored period) or a: x = min(a, b), w' = w, 256 - w or 0.
template <WrapMode kWrap>
SR_SIMD_INLINE void adjacentPair(I a, I b, I w, I& x, I& wPair) {
    if constexpr (kWrap == WrapMode::Repeat) {
        x = a;
        wPair = w;
    } else if constexpr (kWrap == WrapMode::Clamp) {
        x = a;
        wPair = select(b == a, iset(0), w);
    } else {
        x = imin(a, b);
        wPair = select(b == a, iset(0), select(b < a, iset(256) - w, w));
    }
}

// A level's GL_LINEAR result per channel before the final division (TextureSampling's Raw):
// integers below 255 * 65536.
struct RawRgb {
    I r, g, b;
};

// GL_LINEAR in one level (TextureSampling::bilinear + blend2x2), before the final division:
// per channel the integer blend ((t00 (256 - wx) + t10 wx) (256 - wy) + (t01 (256 - wx) + t11 wx) wy),
// exactly. The horizontal blend takes two channels at once: red and blue (bytes 0 and 2) sit in
// the two 16-bit halves of one word, as do green and alpha, and each half's t (256 - wx) + t' wx
// is at most 255 * 256 < 2^16, so one 32-bit multiply-add blends both without a carry between
// them; the vertical blend is per channel in 32 bits. fixedU, fixedV: the 8-bit X of u and v on
// this level (levelX), of uv on the vector path. Each row's two texels come from one 64-bit
// load per lane (adjacentPair).
template <WrapMode kWrap>
SR_SIMD_INLINE RawRgb bilinearRaw(const Texture::LevelView& l, I fixedU, I fixedV) {
    I x0, x1, wxTaps, y0, y1, wy;
    linearAxis<kWrap>(fixedU, l.width, l.maskX, x0, x1, wxTaps);
    linearAxis<kWrap>(fixedV, l.height, l.maskY, y0, y1, wy);
    I x, wx;
    adjacentPair<kWrap>(x0, x1, wxTaps, x, wx);
    const I stride = iset(l.stride);
    I t00, t10, t01, t11;
    gatherPair(l.texels, mulLow(y0, stride) + x, t00, t10);
    gatherPair(l.texels, mulLow(y1, stride) + x, t01, t11);
    const I w256 = iset(256), evenBytes = iset(0x00FF00FF), low16 = iset(0xFFFF);
    const I ax = w256 - wx, ay = w256 - wy;
    auto row = [&](I t0, I t1, I& rb, I& ga) SR_SIMD_LAMBDA {
        rb = mulLow(t0 & evenBytes, ax) + mulLow(t1 & evenBytes, wx);
        ga = mulLow(shiftRightLogical<8>(t0) & evenBytes, ax) + mulLow(shiftRightLogical<8>(t1) & evenBytes, wx);
    };
    I rb0, ga0, rb1, ga1;
    row(t00, t10, rb0, ga0);
    row(t01, t11, rb1, ga1);
    return {mulLow(rb0 & low16, ay) + mulLow(rb1 & low16, wy), mulLow(ga0 & low16, ay) + mulLow(ga1 & low16, wy),
            mulLow(shiftRightLogical<16>(rb0), ay) + mulLow(shiftRightLogical<16>(rb1), wy)};
}

// GL_LINEAR in one level on decoded texels (Texture::sampleSrgb's bilinear): the taps and 8-bit
// weights of bilinearRaw on the level's decoded storage (l.decoded: two words per texel,
// r | g << 16 and b | a << 16, one 64-bit load per tap and lane); per channel the rows
// t0 (256 - wx) + t1 wx in integers, then (row0 (256 - wy) + row1 wy) / (65535 * 65536) in float.
template <WrapMode kWrap>
SR_SIMD_INLINE Rgb bilinearDecoded(const Texture::LevelView& l, I fixedU, I fixedV) {
    I x0, x1, wx, y0, y1, wy;
    linearAxis<kWrap>(fixedU, l.width, l.maskX, x0, x1, wx);
    linearAxis<kWrap>(fixedV, l.height, l.maskY, y0, y1, wy);
    const I stride = iset(l.stride);
    const I row0 = mulLow(y0, stride), row1 = mulLow(y1, stride);
    I rg00, ba00, rg10, ba10, rg01, ba01, rg11, ba11;
    gatherPair(l.decoded, shiftLeft<1>(row0 + x0), rg00, ba00);
    gatherPair(l.decoded, shiftLeft<1>(row0 + x1), rg10, ba10);
    gatherPair(l.decoded, shiftLeft<1>(row1 + x0), rg01, ba01);
    gatherPair(l.decoded, shiftLeft<1>(row1 + x1), rg11, ba11);
    const I low16 = iset(0xFFFF), ax = iset(256) - wx;
    const F ay = toFloat(iset(256) - wy), by = toFloat(wy), scale = fset(65535.0f * 65536.0f);
    auto blend = [&](I t00, I t10, I t01, I t11) SR_SIMD_LAMBDA {
        const I r0 = mulLow(t00, ax) + mulLow(t10, wx), r1 = mulLow(t01, ax) + mulLow(t11, wx);
        return (toFloat(r0) * ay + toFloat(r1) * by) / scale;
    };
    return {blend(rg00 & low16, rg10 & low16, rg01 & low16, rg11 & low16),
            blend(shiftRightLogical<16>(rg00), shiftRightLogical<16>(rg10), shiftRightLogical<16>(rg01), shiftRightLogical<16>(rg11)),
            blend(ba00 & low16, ba10 & low16, ba01 & low16, ba11 & low16)};
}

// log2Positive (TextureLod.hpp) per lane, for normal positive finite x: the same operations.
SR_SIMD_INLINE F log2Lanes(F x) {
    const I xBits = asInt(x);
    F e = toFloat(shiftRightLogical<23>(xBits) - iset(127));
    F m = asFloat((xBits & iset(0x007FFFFF)) | iset(0x3F800000));
    const M big = m > fset(kSqrt2f);
    m = select(big, m * fset(0.5f), m);
    e = select(big, e + fset(1.0f), e);
    const F one = fset(1.0f);
    const F s = (m - one) / (m + one);
    const F s2 = s * s;
    const float* c = kLog2Series;
    return e + s * (fset(c[0]) + s2 * (fset(c[1]) + s2 * (fset(c[2]) + s2 * (fset(c[3]) + s2 * fset(c[4])))));
}

// The mip level of an affine triangle, as programs::sampleKd computes it per fragment from the
// triangle's constant plane gradients: one value per triangle (fillSpans computes it once).
template <class Prog>
float affineMipLevel(const Prog& p, const Texture& texture) {
    const TriangleSetup& t = *p.setup;
    constexpr int kU = kPlaneVarying0, kVp = kPlaneVarying0 + 1;
    return mipLevel(float(t.ddx[kU]), float(t.ddx[kVp]), float(t.ddy[kU]), float(t.ddy[kVp]), texture.width(), texture.height());
}
template <class Prog>
float affineMipLevel(const Prog& p) {
    return affineMipLevel(p, *p.d->texture);
}

// The lanes' mip level under exact perspective, as programs::sampleKd computes it per fragment:
// uvDerivatives (the quotient rule in float) at each lane, then mipLevel (TextureLod.cpp) lane by
// lane.
template <class Prog>
SR_SIMD_INLINE F mipLevels(const Prog& p, const Texture& texture, F u, F v, F invW) {
    const TriangleSetup& t = *p.setup;
    constexpr int kU = kPlaneVarying0, kVp = kPlaneVarying0 + 1;
    const F dqdx = fset(float(t.ddx[kPlaneInvW])), dqdy = fset(float(t.ddy[kPlaneInvW]));
    const F w = fset(1.0f) / invW;
    const F dudx = (fset(float(t.ddx[kU])) - u * dqdx) * w;
    const F dvdx = (fset(float(t.ddx[kVp])) - v * dqdx) * w;
    const F dudy = (fset(float(t.ddy[kU])) - u * dqdy) * w;
    const F dvdy = (fset(float(t.ddy[kVp])) - v * dqdy) * w;
    const F tw = fset(float(texture.width())), th = fset(float(texture.height()));
    const F ax = dudx * tw, bx = dvdx * th, ay = dudy * tw, by = dvdy * th;
    const F rx = ax * ax + bx * bx, ry = ay * ay + by * by;
    const M ok = (rx >= fzero()) & (ry >= fzero()); // not NaN
    const F rho2 = fmin(fmax(fmax(rx, ry), fset(kMinRho2)), fset(kMaxRho2));
    return select(ok, fset(0.5f) * log2Lanes(rho2), fzero());
}

// GL_LINEAR_MIPMAP_LINEAR (TextureSampling::trilinear) for lanes on the vector path: both levels
// fetched here, blended in 8-bit fixed point with the same integer arithmetic (the sum is below
// 2^32: raw < 255 * 65536, times 256). The lanes of a group usually share their level; a group
// that straddles a level boundary runs once per distinct level.
template <WrapMode kWrap>
SR_SIMD_INLINE Rgb trilinearLanes(const Texture& texture, F u, F v, F lod) {
    const int last = texture.levelCount() - 1;
    lod = select(lod > fzero(), lod, fzero()); // magnification (and NaN) -> the base level
    const M top = lod >= fset(float(last));
    const I level = select(top, iset(last), truncToInt(select(top, fzero(), lod)));
    const I wl = select(top, iset(0), truncToInt((lod - toFloat(level)) * fset(256.0f)));
    const I keep = iset(256) - wl;
    // The levels the lanes read: usually one (no reduction across the lanes then).
    const int first = firstLane(level);
    const bool oneLevel = bits(level == iset(first)) == bits(mAll());
    const int lo = oneLevel ? first : reduceMin(level), hi = oneLevel ? first : reduceMax(level);
    // The base level's fixed-point coordinates, from which the levels that halve it take theirs
    // (levelX; an axis of size 1 reads its one texel whatever the coordinate: 0); other levels
    // convert u and v at their own size.
    const I zu = texelFixed<kWrap>(u, texture.width()), zv = texelFixed<kWrap>(v, texture.height());
    const int halving = texture.halvingLevels();
    auto coordinates = [&](const Texture::LevelView& l, int k, I& x, I& y) SR_SIMD_LAMBDA {
        if (k < halving) {
            x = l.width == 1 ? iset(0) : levelX(zu, k);
            y = l.height == 1 ? iset(0) : levelX(zv, k);
        } else {
            x = linearX<kWrap>(u, l.width);
            y = linearX<kWrap>(v, l.height);
        }
    };
    I r = iset(0), g = iset(0), b = iset(0);
    for (int k = lo; k <= hi; ++k) {
        const M mine = level == iset(k);
        if (bits(mine) == 0) continue;
        const Texture::LevelView here = texture.levelView(k);
        I fixedU, fixedV;
        coordinates(here, k, fixedU, fixedV);
        const RawRgb c0 = bilinearRaw<kWrap>(here, fixedU, fixedV);
        I r0 = c0.r, g0 = c0.g, b0 = c0.b;
        // The next level only where a lane blends it in (wl > 0): magnified lanes (lod <= 0) and
        // whole-number lods read one level, exactly what the blend with wl = 0 returns.
        if (k < last && bits(mine & (wl > iset(0))) != 0) {
            const Texture::LevelView next = texture.levelView(k + 1);
            I nextU, nextV;
            coordinates(next, k + 1, nextU, nextV);
            const RawRgb c1 = bilinearRaw<kWrap>(next, nextU, nextV);
            const I half = iset(128);
            r0 = shiftRightLogical<8>(mulLow(r0, keep) + mulLow(c1.r, wl) + half);
            g0 = shiftRightLogical<8>(mulLow(g0, keep) + mulLow(c1.g, wl) + half);
            b0 = shiftRightLogical<8>(mulLow(b0, keep) + mulLow(c1.b, wl) + half);
        }
        r = select(mine, r0, r);
        g = select(mine, g0, g);
        b = select(mine, b0, b);
    }
    const F scale = fset(255.0f * 65536.0f); // toColor: raw / kRawScale
    return {toFloat(r) / scale, toFloat(g) / scale, toFloat(b) / scale};
}

// trilinearLanes on decoded texels (Texture::sampleSrgb's trilinear): each level's
// bilinearDecoded, the levels mixed in float by wl / 256 where wl > 0.
template <WrapMode kWrap>
SR_SIMD_INLINE Rgb trilinearDecodedLanes(const Texture& texture, F u, F v, F lod) {
    const int last = texture.levelCount() - 1;
    lod = select(lod > fzero(), lod, fzero());
    const M top = lod >= fset(float(last));
    const I level = select(top, iset(last), truncToInt(select(top, fzero(), lod)));
    const I wl = select(top, iset(0), truncToInt((lod - toFloat(level)) * fset(256.0f)));
    const F w = toFloat(wl) / fset(256.0f);
    const int first = firstLane(level);
    const bool oneLevel = bits(level == iset(first)) == bits(mAll());
    const int lo = oneLevel ? first : reduceMin(level), hi = oneLevel ? first : reduceMax(level);
    const I zu = texelFixed<kWrap>(u, texture.width()), zv = texelFixed<kWrap>(v, texture.height());
    const int halving = texture.halvingLevels();
    auto coordinates = [&](const Texture::LevelView& l, int k, I& x, I& y) SR_SIMD_LAMBDA {
        if (k < halving) {
            x = l.width == 1 ? iset(0) : levelX(zu, k);
            y = l.height == 1 ? iset(0) : levelX(zv, k);
        } else {
            x = linearX<kWrap>(u, l.width);
            y = linearX<kWrap>(v, l.height);
        }
    };
    Rgb out{fzero(), fzero(), fzero()};
    for (int k = lo; k <= hi; ++k) {
        const M mine = level == iset(k);
        if (bits(mine) == 0) continue;
        const Texture::LevelView here = texture.decodedLevelView(k);
        I fixedU, fixedV;
        coordinates(here, k, fixedU, fixedV);
        Rgb c = bilinearDecoded<kWrap>(here, fixedU, fixedV);
        const M blend = mine & (wl > iset(0));
        if (k < last && bits(blend) != 0) {
            const Texture::LevelView next = texture.decodedLevelView(k + 1);
            I nextU, nextV;
            coordinates(next, k + 1, nextU, nextV);
            const Rgb c1 = bilinearDecoded<kWrap>(next, nextU, nextV);
            c = {select(blend, c.r + (c1.r - c.r) * w, c.r), select(blend, c.g + (c1.g - c.g) * w, c.g),
                 select(blend, c.b + (c1.b - c.b) * w, c.b)};
        }
        out = {select(mine, c.r, out.r), select(mine, c.g, out.g), select(mine, c.b, out.b)};
    }
    return out;
}

// The lanes off the vector path (NaN / Inf / huge uv) of a sample, redone by the scalar sampler:
// rare, so out of line (one copy per filter and wrap).
template <TextureFilter kFilter, WrapMode kWrap>
SR_SIMD_NOINLINE void redoOffPathLanes(const Texture& texture, bool linear, F u, F v, F lod, M good, Rgb& kd) {
    alignas(64) float us[kLanes], vs[kLanes], lods[kLanes], r[kLanes], g[kLanes], b[kLanes];
    fstore(us, u);
    fstore(vs, v);
    fstore(lods, lod);
    fstore(r, kd.r);
    fstore(g, kd.g);
    fstore(b, kd.b);
    for (int i = 0, m = bits(good); i < kLanes; ++i) {
        if (m & (1 << i)) continue;
        const Color c = linear ? texture.sampleSrgb({us[i], vs[i]}, lods[i], kFilter, kWrap) : texture.sample({us[i], vs[i]}, lods[i], kFilter, kWrap);
        r[i] = c.r;
        g[i] = c.g;
        b[i] = c.b;
    }
    kd = {fload(r), fload(g), fload(b)};
}

// The colour of the lanes from `texture` with the filter and wrap at level of detail `lod`
// (trilinear only); `linear`: texels decoded from sRGB (Texture::sampleSrgb).
template <TextureFilter kFilter, WrapMode kWrap>
SR_SIMD_INLINE Rgb sampleLanes(const Texture& texture, bool linear, F u, F v, F lod) {
    const M good = onVectorPath(u) & onVectorPath(v);
    const F uSafe = select(good, u, fzero()), vSafe = select(good, v, fzero());
    Rgb kd;
    if constexpr (kFilter == TextureFilter::Nearest) {
        const Texture::LevelView l = linear ? texture.decodedLevelView(0) : texture.levelView(0);
        const I x = nearestAxis<kWrap>(uSafe, l.width, l.maskX);
        const I y = nearestAxis<kWrap>(vSafe, l.height, l.maskY);
        const I i = mulLow(y, iset(l.stride)) + x;
        if (linear) {
            I rg, ba;
            gatherPair(l.decoded, shiftLeft<1>(i), rg, ba);
            const I low16 = iset(0xFFFF);
            const F scale = fset(65535.0f); // the decoded value d / 65535, correctly rounded
            kd = {toFloat(rg & low16) / scale, toFloat(shiftRightLogical<16>(rg)) / scale, toFloat(ba & low16) / scale};
        } else {
            const I t = gather(l.texels, i);
            const F scale = fset(255.0f); // kUnorm8: byte / 255.0f, correctly rounded
            kd = {channel<0>(t) / scale, channel<8>(t) / scale, channel<16>(t) / scale};
        }
    } else if constexpr (kFilter == TextureFilter::Bilinear) {
        const Texture::LevelView l = texture.levelView(0);
        if (linear) {
            const Texture::LevelView dl = texture.decodedLevelView(0);
            kd = bilinearDecoded<kWrap>(dl, linearX<kWrap>(uSafe, l.width), linearX<kWrap>(vSafe, l.height));
        } else {
            const RawRgb raw = bilinearRaw<kWrap>(l, linearX<kWrap>(uSafe, l.width), linearX<kWrap>(vSafe, l.height));
            const F scale = fset(255.0f * 65536.0f); // then raw / (255 * 65536)
            kd = {toFloat(raw.r) / scale, toFloat(raw.g) / scale, toFloat(raw.b) / scale};
        }
    } else {
        kd = linear ? trilinearDecodedLanes<kWrap>(texture, uSafe, vSafe, lod) : trilinearLanes<kWrap>(texture, uSafe, vSafe, lod);
    }
    if (SR_UNLIKELY(bits(good) != bits(mAll()))) redoOffPathLanes<kFilter, kWrap>(texture, linear, u, v, lod, good, kd);
    return kd;
}

// sampleLanes out of line, one copy per filter and wrap (a call per group of lanes): what every
// kernel would otherwise copy for each map, wrap and colour mode. Only the Blinn-Phong programs'
// nearest and bilinear on display values are inlined (sampleMap): the cheapest filters, where a
// call (every vector register is the caller's to save across it) costs most in proportion.
template <TextureFilter kFilter, WrapMode kWrap>
SR_SIMD_NOINLINE Rgb sampleLanesOutOfLine(const Texture& texture, bool linear, F u, F v, F lod) {
    return sampleLanes<kFilter, kWrap>(texture, linear, u, v, lod);
}

// sampleLanes for the draw: the lanes' level of detail (trilinear: the affine triangle's
// `triangleLod`, or per lane under exact perspective), then the draw's wrap mode, read here per
// group of lanes rather than made a template parameter of the kernels (one predictable branch
// per group).
template <PerspectiveMode kPersp, TextureFilter kFilter, class Prog>
SR_SIMD_INLINE Rgb sampleMap(const Prog& p, const Texture& texture, bool linear, F u, F v, F invW, F triangleLod) {
    F lod = fzero();
    if constexpr (kFilter == TextureFilter::Trilinear) {
        if constexpr (kPersp == PerspectiveMode::Affine) lod = triangleLod;
        else lod = mipLevels(p, texture, u, v, invW);
    } else {
        (void)invW;
        (void)triangleLod;
    }
    auto sample = [&](auto wrap) SR_SIMD_LAMBDA {
        constexpr WrapMode kWrap = decltype(wrap)::value;
        if constexpr (kFilter != TextureFilter::Trilinear && Prog::kMode != ShadingMode::Pbr) {
            if (!linear) return sampleLanes<kFilter, kWrap>(texture, false, u, v, lod);
        }
        return sampleLanesOutOfLine<kFilter, kWrap>(texture, linear, u, v, lod);
    };
    switch (p.d->settings.wrap) {
    case WrapMode::Clamp: return sample(std::integral_constant<WrapMode, WrapMode::Clamp>{});
    case WrapMode::Mirror: return sample(std::integral_constant<WrapMode, WrapMode::Mirror>{});
    case WrapMode::Repeat: break;
    }
    return sample(std::integral_constant<WrapMode, WrapMode::Repeat>{});
}
// The draw's texture (programs::sampleTexel).
template <PerspectiveMode kPersp, TextureFilter kFilter, class Prog>
SR_SIMD_INLINE Rgb sampleTexture(const Prog& p, F u, F v, F invW, F triangleLod) {
    return sampleMap<kPersp, kFilter>(p, *p.d->texture, p.d->linear, u, v, invW, triangleLod);
}

// --- The pbr program (PbrProgram::fragment, Brdf.hpp), lane by lane -------------------------
// brdfCosineTerms compiled for this ISA (the scalar reference's source, Brdf.hpp).
#include "Raster/BrdfTerms.inl"

// The radiance at the lanes' points (px, py, pz) with unit normals n and view vectors v:
// pbrRadiance's loop over the lights (lightAt's direction and factor as lightsRgb computes
// them, the shadow maps' lit fraction, brdfCosineTerms), the same operations in the same
// order. Lanes whose light or half vector is off normalize's fast path lose `ok`.
SR_SIMD_NOINLINE Rgb pbrLights(const Lighting& lighting, const SceneShadows* shadows, F baseR, F baseG, F baseB, F metallic,
                               F roughness, F nx, F ny, F nz, F px, F py, F pz, F vx, F vy, F vz, M& ok) {
    const V3 n{nx, ny, nz}, p{px, py, pz}, v{vx, vy, vz};
    const F base[3] = {baseR, baseG, baseB};
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
        const M lit = (a > fzero()) & (ndl > fzero());
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
        brdfCosineTerms(ndl, dot3(n, v), dot3(n, h), dot3(nxh, nxh), dot3(v, h), roughness, metallic, base, f);
        sum.r = select(lit, sum.r + f[0] * fset(light.colour.r) * a, sum.r);
        sum.g = select(lit, sum.g + f[1] * fset(light.colour.g) * a, sum.g);
        sum.b = select(lit, sum.b + f[2] * fset(light.colour.b) * a, sum.b);
    }
    return sum;
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
// the emission, encoded.
template <class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
SR_SIMD_INLINE Rgb shadePbr(const Prog& p, const F* v, F invW, M& ok) {
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
    F baseR = fset(k.baseColor.r), baseG = fset(k.baseColor.g), baseB = fset(k.baseColor.b);
    F metallic = fset(k.metallic), roughness = fset(k.roughness);
    F eR = fset(k.emissive.x), eG = fset(k.emissive.y), eB = fset(k.emissive.z);
    if constexpr (Prog::kIsTextured) {
        // Each map at its own level of detail (PbrProgram::sampleMap).
        auto mapLanes = [&](const Texture& map, bool colour) SR_SIMD_LAMBDA {
            F lod = fzero();
            if constexpr (kPersp == PerspectiveMode::Affine && kFilter == TextureFilter::Trilinear) lod = fset(affineMipLevel(p, map));
            return sampleMap<kPersp, kFilter>(p, map, colour && d.linear, v[0], v[1], invW, lod);
        };
        if (m.texture) {
            const Rgb c = mapLanes(*m.texture, true);
            baseR = baseR * c.r;
            baseG = baseG * c.g;
            baseB = baseB * c.b;
        }
        if (m.metallicRoughness) {
            const Rgb c = mapLanes(*m.metallicRoughness, false);
            roughness = roughness * c.g;
            metallic = metallic * c.b;
        }
        if (m.emissive && (k.emissive.x > 0.0f || k.emissive.y > 0.0f || k.emissive.z > 0.0f)) {
            const Rgb c = mapLanes(*m.emissive, true);
            eR = eR * c.r;
            eG = eG * c.g;
            eB = eB * c.b;
        }
        if constexpr (Prog::kNormalMap) {
            constexpr int kT = Prog::kT;
            n = perturbNormalLanes(n, {v[kT], v[kT + 1], v[kT + 2]}, v[kT + 3], mapLanes(*m.normalMap, false), k.normalScale);
        }
    }
    const Rgb r = pbrLights(d.view.lighting, d.view.shadows, baseR, baseG, baseB, metallic, roughness, n.x, n.y, n.z, v[kP],
                            v[kP + 1], v[kP + 2], toEye.x, toEye.y, toEye.z, ok);
    return {r.r + eR, r.g + eG, r.b + eB};
}

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
        const V3 n = normalizeFast({v[kT + 3], v[kT + 4], v[kT + 5]}, ok);
        const Vec3 eye = d.view.eye;
        const V3 toEye = normalizeFast({fset(eye.x) - v[kT], fset(eye.y) - v[kT + 1], fset(eye.z) - v[kT + 2]}, ok);
        // Coloured, point or spot lights: the out-of-line RGB path, kept off the white-light path's registers.
        if (SR_UNLIKELY(!d.whiteLights || d.view.shadows)) {
            const TermsRgb t = lightsRgb(d.view.lighting, d.specular, d.view.shadows, n.x, n.y, n.z, v[kT], v[kT + 1], v[kT + 2], toEye.x,
                                         toEye.y, toEye.z, ok);
            ok = t.ok;
            out = encodeLanes(p, applyTerms(kd, d.specular.ks, t));
        } else {
            out = encodeLanes(p, applyTerms(kd, d.specular.ks, blinnPhong(d.view.lighting, d.specular, n, toEye, ok)));
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

// --- The span loop ---------------------------------------------------------------------------
// The fragments of one triangle that passed the depth test in partial groups, waiting to be
// shaded kLanes at a time (left-packed: entries [0, count) are used). Room for two groups: a
// whole vector is stored at `count` < kLanes.
template <int kV>
struct FragmentQueue {
    int count = 0;
    alignas(64) std::int32_t x[2 * kLanes];
    alignas(64) std::int32_t y[2 * kLanes];
    alignas(64) float invW[2 * kLanes];
    alignas(64) float v[kV > 0 ? kV : 1][2 * kLanes];
};

// fillTriangle (ScanlineFill.hpp) kLanes pixels per step. Per span: the plane values at the
// first pixel in double (fillTriangle's very expression), then pixel k of the span gets depth
// and 1/w as start + k * ddx in double (rounded once) and the varyings as start + k * gradient
// in float, as one lane. Groups whose lanes all pass the depth test are
// shaded at once and stored with one vector store; the passing lanes of the other groups go to
// the queue (so the shading runs on few wasted lanes for small triangles). A draw whose
// colour is constant per triangle (no varyings) stores it without shading anything.
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
struct SpanKernel {
    static constexpr int kV = Prog::kVaryings;
    static constexpr int kPlanes = kV > 0 ? kPlaneVarying0 + kV : 1;
    const Prog& p;
    const TriangleSetup& t;
    FrameBuffer& fb;
    std::uint64_t& shaded;
    FragmentQueue<kV>& queue;
    F gradient[kPlanes]; // per plane: its step one pixel right
    F triangleLod = fzero(); // affine trilinear: the triangle's mip level (else unused)
    float alpha = 1.0f; // below 1: a transparent draw, every colour blended over the target (blendOver)
    // On (fillSpans, kDeferrable programs): the queue outlives the triangle, so that a draw of
    // small triangles shades full groups of lanes; see fillSpans.
    bool deferred = false;

    // Transparent draws are drawn with DepthMode::Test (drawStateFor): only those kernels carry
    // the blending code, so the opaque ones have none of it.
    static constexpr bool kMayBlend = kDepth == DepthMode::Test;
    bool blending() const { return kMayBlend && alpha < 1.0f; }
    // Programs whose shading of a fragment reads nothing of its triangle (only the draw's
    // constants and the fragment's own varyings): their queued fragments may wait for the next
    // triangle's. Not flat (lit per triangle) nor trilinear (the triangle's uv gradients).
    static constexpr bool kDeferrable =
        kV > 0 && Prog::kMode != ShadingMode::Flat && !(Prog::kIsTextured && kFilter == TextureFilter::Trilinear);

    // A constructor, not an aggregate: aggregate initialisation would zero the whole kernel (its
    // plane steps are 8 vectors for Phong) before filling it, every triangle.
    SpanKernel(const Prog& program, const TriangleSetup& setup, FrameBuffer& target, std::uint64_t& shadedCount,
               FragmentQueue<kV>& fragments, float opacity = 1.0f, bool deferQueue = false)
        : p(program), t(setup), fb(target), shaded(shadedCount), queue(fragments), alpha(opacity),
          deferred(deferQueue) {
        for (int k = 0; k < kPlanes; ++k) gradient[k] = fset(setup.ddxStep[k]);
    }

    // Writes the shaded colour of pixel `dst` (opaque: the colour itself; transparent: blendOver,
    // the scalar pipeline's very function, lane by lane).
    void put(Pixel& dst, Pixel colour) const { dst = blending() ? blendOver(colour, dst, alpha, p.d->linear) : colour; }

    // fillTriangle's depth and 1/w: start + step * ddx in double, rounded once.
    F planeInDouble(D startValue, int plane, F step) const {
        const D g = dset(t.ddx[plane]);
        return toFloat(startValue + g * lowHalf(step), startValue + g * highHalf(step));
    }

    // Shades the queue's first kLanes fragments and stores the first `used` colours.
    void shadeQueued(int used) const {
        F values[kV > 0 ? kV : 1];
        for (int k = 0; k < kV; ++k) values[k] = fload(queue.v[k]);
        alignas(64) std::uint32_t out[kLanes];
        istore(out, shadeGroup<Prog, kPersp, kFilter>(p, values, fload(queue.invW), iload(queue.x), iload(queue.y), triangleLod));
        for (int i = 0; i < used; ++i) put(fb.colorRow(queue.y[i])[queue.x[i]], out[i]);
    }

    // Shades and writes the queued fragments (fewer than kLanes) and empties the queue.
    void flush() const {
        const int used = queue.count;
        if (used == 0) return;
        // Lanes [used, kLanes) repeat the last fragment (their results are dropped): a vector
        // blend per array, not a scalar store per lane and array.
        const M keep = firstN(used);
        istore(queue.x, select(keep, iload(queue.x), iset(queue.x[used - 1])));
        istore(queue.y, select(keep, iload(queue.y), iset(queue.y[used - 1])));
        fstore(queue.invW, select(keep, fload(queue.invW), fset(queue.invW[used - 1])));
        for (int k = 0; k < kV; ++k) fstore(queue.v[k], select(keep, fload(queue.v[k]), fset(queue.v[k][used - 1])));
        shadeQueued(used);
        queue.count = 0;
    }

    // True when a queued fragment lies in row y, columns [x, x + kLanes): a group about to be
    // written there directly must not be overwritten by an older fragment written later.
    bool queuedIn(int y, int x) const {
        const M used = firstN(queue.count);
        const I qx = iload(queue.x), qy = iload(queue.y);
        const M hit = used & (qy == iset(y)) & (qx > iset(x - 1)) & (qx < iset(x + kLanes));
        return bits(hit) != 0;
    }

    // A one-pixel span [x, x + 1) of row y on the setup with its plane origin at `origin`
    // (movedOrigin: a pixel shaded at its centroid), without a depth test: lane 0 of operator()'s
    // one group, computed alone (the same double plane values, the same float operations with
    // step 0) and queued, instead of a whole group of lanes for one.
    void queueOne(int y, int x, PlaneOrigin origin) const {
        static_assert(kDepth == DepthMode::Off && kV > 0, "the multisampled fill's centroid pixels");
        const double dx = (x + 0.5) - origin.x, dy = (y + 0.5) - origin.y;
        const int at = queue.count;
        const double invWValue = t.value[kPlaneInvW] + t.ddx[kPlaneInvW] * dx + t.ddy[kPlaneInvW] * dy;
        const float invW = float(invWValue + t.ddx[kPlaneInvW] * 0.0);
        const float w = 1.0f / invW;
        for (int k = 0; k < kV; ++k) {
            const int plane = kPlaneVarying0 + k;
            const float start = float(t.value[plane] + t.ddx[plane] * dx + t.ddy[plane] * dy);
            const float value = start + t.ddxStep[plane] * 0.0f;
            queue.v[k][at] = kPersp == PerspectiveMode::Exact ? value * w : value;
        }
        queue.x[at] = x;
        queue.y[at] = y;
        queue.invW[at] = invW;
        ++shaded;
        queue.count = at + 1;
        if (queue.count == kLanes) {
            shadeQueued(kLanes);
            queue.count = 0;
        }
    }

    void operator()(int y, int x0, int x1) const {
        // Plane values at the centre of the span's first pixel (double, rounded once), as fillTriangle.
        const double dx = (x0 + 0.5) - t.originX, dy = (y + 0.5) - t.originY;
        F start[kPlanes];
        D startD[kPlaneVarying0]; // depth and 1/w, unrounded: evaluated per lane in double
        for (int k = 0; k < kPlanes; ++k) {
            const double value = t.value[k] + t.ddx[k] * dx + t.ddy[k] * dy;
            start[k] = fset(float(value));
            if (k < kPlaneVarying0) startD[k] = dset(value);
        }
        Pixel* colour = fb.colorRow(y);
        float* depth = fb.depthRow(y);
        const int rowWidth = fb.width();
        // Pixel index along the span (whole numbers, exact in float), clamped to the last pixel so
        // that lanes past the end never see values extrapolated off the triangle.
        const F lastStep = fset(float(x1 - 1 - x0));
        const I row = iset(y);
        Pixel constant = 0; // kV == 0: the triangle's one colour, read at its first passing group
        for (int x = x0; x < x1; x += kLanes) {
            const int n = std::min(kLanes, x1 - x);
            const M inside = firstN(n);
            // Whole vectors load and store whenever the group lies in the row: lanes past the
            // span are read and written back unchanged (they belong to this row, i.e. this band).
            const bool inRow = x + kLanes <= rowWidth;
            const F step = fmin(fset(float(x - x0)) + fiota(), lastStep);
            const F z = planeInDouble(startD[kPlaneZ], kPlaneZ, step);
            M pass = inside;
            F stored = fzero();
            if constexpr (kDepth != DepthMode::Off) {
                if (inRow) {
                    stored = fload(depth + x);
                } else {
                    alignas(64) float part[kLanes] = {};
                    for (int i = 0; i < n; ++i) part[i] = depth[x + i];
                    stored = fload(part);
                }
                pass = pass & (z > stored);
            }
            const int passBits = bits(pass);
            if (passBits == 0) continue;
            if constexpr (kDepth == DepthMode::TestWrite) {
                if (inRow) {
                    fstore(depth + x, select(pass, z, stored));
                } else {
                    alignas(64) float zs[kLanes];
                    fstore(zs, z);
                    for (int i = 0; i < n; ++i)
                        if (passBits & (1 << i)) depth[x + i] = zs[i];
                }
            }
            const int passed = popcount(passBits);
            shaded += std::uint64_t(passed);
            if constexpr (kV == 0) {
                if constexpr (Prog::kMode == ShadingMode::Flat) p.ensureLit(); // lazy flat lighting
                constant = p.flat;
                if (inRow && !blending()) {
                    istore(colour + x, select(pass, iset(int(constant)), iload(colour + x)));
                } else {
                    for (int i = 0; i < n; ++i)
                        if (passBits & (1 << i)) put(colour[x + i], constant);
                }
                continue;
            } else {
                const F invW = planeInDouble(startD[kPlaneInvW], kPlaneInvW, step);
                F values[kV];
                if constexpr (kPersp == PerspectiveMode::Exact) {
                    const F w = fset(1.0f) / invW;
                    for (int k = 0; k < kV; ++k) values[k] = (start[kPlaneVarying0 + k] + gradient[kPlaneVarying0 + k] * step) * w;
                } else {
                    for (int k = 0; k < kV; ++k) values[k] = start[kPlaneVarying0 + k] + gradient[kPlaneVarying0 + k] * step;
                }
                const I columns = iset(x) + iiota();
                if (passBits == bits(mAll())) {
                    // (A deferred queue may hold older fragments of these pixels: written first.)
                    if (deferred && queue.count > 0 && queuedIn(y, x)) flush();
                    const I shaded = shadeGroup<Prog, kPersp, kFilter>(p, values, invW, columns, row, triangleLod);
                    if (!blending()) {
                        istore(colour + x, shaded);
                    } else {
                        alignas(64) std::uint32_t out[kLanes];
                        istore(out, shaded);
                        for (int i = 0; i < kLanes; ++i) put(colour[x + i], out[i]);
                    }
                    continue;
                }
                const int at = queue.count;
                compressStore(queue.x + at, columns, pass);
                compressStore(queue.y + at, row, pass);
                compressStore(queue.invW + at, invW, pass);
                for (int k = 0; k < kV; ++k) compressStore(queue.v[k] + at, values[k], pass);
                queue.count = at + passed;
                if (queue.count >= kLanes) {
                    shadeQueued(kLanes);
                    queue.count -= kLanes; // move the rest (fewer than kLanes) to the front
                    istore(queue.x, iload(queue.x + kLanes));
                    istore(queue.y, iload(queue.y + kLanes));
                    fstore(queue.invW, fload(queue.invW + kLanes));
                    for (int k = 0; k < kV; ++k) fstore(queue.v[k], fload(queue.v[k] + kLanes));
                }
            }
        }
    }
};

// The fill kernels' fragment queue: one per thread and kernel, reused by every triangle (only
// `count` carries over; the rest is written before it is read).
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
FragmentQueue<Prog::kVaryings>& fillQueue() {
    static thread_local FragmentQueue<Prog::kVaryings> queue;
    return queue;
}

// A kDeferrable program's queue is not flushed at the end of the triangle: the fragments of a
// draw's small triangles (the bunny's average 4 pixels at 800x600) fill whole groups of lanes
// together instead of a group each. The colours then reach the target later, in the same order
// (the queue is written first in order; a whole group written directly first flushes the older
// fragments of its pixels, queuedIn), and the depth test stays immediate: the image is the
// same. The pipeline calls flushSpans at the end of each lane's walk of a draw and before
// anything else writes colour (a wireframe edge).
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
void fillSpans(const Prog& p, const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, std::uint64_t& shaded) {
    using Span = SpanKernel<Prog, kDepth, kPersp, kFilter>;
    assert(Prog::kVaryings <= t.varyingCount);
    assert(s.x0 >= 0 && s.y0 >= 0 && s.x1 <= fb.width() && s.y1 <= fb.height());
    FragmentQueue<Prog::kVaryings>& queue = fillQueue<Prog, kDepth, kPersp, kFilter>();
    if constexpr (!Span::kDeferrable) queue.count = 0;
    assert(kDepth == DepthMode::Test || p.d->alpha >= 1.0f); // blending kernels: DepthMode::Test only
    Span span(p, t, fb, shaded, queue, p.d->alpha, Span::kDeferrable);
    if constexpr (Prog::kIsTextured && kFilter == TextureFilter::Trilinear && kPersp == PerspectiveMode::Affine)
        span.triangleLod = fset(affineMipLevel(p));
    forEachSpan(t, s, span);
    if constexpr (Prog::kVaryings > 0 && !Span::kDeferrable) span.flush();
}

// Shades and writes what fillSpans left queued on this thread (nothing for a program that is not
// kDeferrable); `p` is any program of the draw (the queued fragments read only its constants).
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
void flushSpans(const Prog& p, FrameBuffer& fb) {
    using Span = SpanKernel<Prog, kDepth, kPersp, kFilter>;
    if constexpr (Span::kDeferrable) {
        FragmentQueue<Prog::kVaryings>& queue = fillQueue<Prog, kDepth, kPersp, kFilter>();
        if (queue.count == 0) return;
        const TriangleSetup none{}; // (the shading of a deferrable program reads no triangle)
        std::uint64_t shaded = 0;   // (counted when queued)
        const Span span(p, none, fb, shaded, queue, p.d->alpha, true);
        span.flush();
    } else {
        (void)p;
        (void)fb;
    }
}

// The multisampled fill's shading (MsaaFill.hpp): the pixels of the given runs, shaded into fb's
// rows without a depth test, as fillSpan<DepthMode::Off> with fragment() does (SpanKernel's very
// loop, one span per run; the queue is flushed before returning).
template <class Prog, PerspectiveMode kPersp, TextureFilter kFilter>
void shadeRunSpans(const Prog& p, const TriangleSetup& t, FrameBuffer& fb, const SpanRun* runs, int count) {
    assert(Prog::kVaryings <= t.varyingCount);
    static thread_local FragmentQueue<Prog::kVaryings> queue;
    queue.count = 0;
    std::uint64_t shaded = 0; // the multisampled fill counts its pixels itself
    using Span = SpanKernel<Prog, DepthMode::Off, kPersp, kFilter>;
    // Runs at the centre go through the span loop; a pixel shaded off its centre (at its
    // centroid) is queued on its own with the plane origin moved (queueOne, movedOrigin).
    Span span(p, t, fb, shaded, queue);
    if constexpr (Prog::kIsTextured && kFilter == TextureFilter::Trilinear && kPersp == PerspectiveMode::Affine)
        span.triangleLod = fset(affineMipLevel(p));
    for (int r = 0; r < count; ++r) {
        const SpanRun& run = runs[r];
        if constexpr (Prog::kVaryings > 0) {
            if (run.dx != 0.0 || run.dy != 0.0) { // at the centroid: one lane each
                const PlaneOrigin origin = movedOrigin(t, run);
                for (int x = run.x0; x < run.x1; ++x) span.queueOne(run.y, x, origin);
                continue;
            }
        }
        span(run.y, run.x0, run.x1); // (without varyings the colour is the triangle's wherever it is shaded)
    }
    if constexpr (Prog::kVaryings > 0) span.flush();
}

// --- The table ---------------------------------------------------------------------------------
// Both entries of a key: the fill (per depth mode) and the multisampled run shader (the same
// for every depth mode: one instantiation).
template <class Prog>
struct KernelPair {
    FillKernel<Prog> fill = nullptr;
    ShadeRunsKernel<Prog> runs = nullptr;
    FlushKernel<Prog> flush = nullptr; // the fill's deferred queue
};

template <class Prog, DepthMode kDepth, PerspectiveMode kPersp, TextureFilter kFilter>
KernelPair<Prog> entries() {
    return {&fillSpans<Prog, kDepth, kPersp, kFilter>, &shadeRunSpans<Prog, kPersp, kFilter>,
            &flushSpans<Prog, kDepth, kPersp, kFilter>};
}

// Resolves the key's run-time values into template arguments, one level at a time; a program
// that does not read a setting gets the one instantiation that ignores it. (The wrap mode is
// read per group by sampleTexture: the key's wrap selects nothing here.)
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp>
KernelPair<Prog> pickFilter(const KernelKey& key) {
    if constexpr (!Prog::kIsTextured) {
        (void)key;
        return entries<Prog, kDepth, kPersp, TextureFilter::Bilinear>();
    } else {
        switch (key.filter) {
        case TextureFilter::Nearest: return entries<Prog, kDepth, kPersp, TextureFilter::Nearest>();
        case TextureFilter::Bilinear: return entries<Prog, kDepth, kPersp, TextureFilter::Bilinear>();
        case TextureFilter::Trilinear: return entries<Prog, kDepth, kPersp, TextureFilter::Trilinear>();
        }
        return {};
    }
}

template <class Prog, DepthMode kDepth>
KernelPair<Prog> pickPerspective(const KernelKey& key) {
    if constexpr (Prog::kVaryings == 0) {
        return pickFilter<Prog, kDepth, PerspectiveMode::Exact>(key); // nothing to interpolate
    } else {
        switch (key.perspective) {
        case PerspectiveMode::Exact: return pickFilter<Prog, kDepth, PerspectiveMode::Exact>(key);
        case PerspectiveMode::Affine: return pickFilter<Prog, kDepth, PerspectiveMode::Affine>(key);
        }
        return {};
    }
}

template <class Prog>
KernelPair<Prog> pickDepth(const KernelKey& key) {
    switch (key.depth) {
    case DepthMode::Off: return pickPerspective<Prog, DepthMode::Off>(key);
    case DepthMode::Test: return pickPerspective<Prog, DepthMode::Test>(key);
    case DepthMode::TestWrite: return pickPerspective<Prog, DepthMode::TestWrite>(key);
    }
    return {};
}

template <class Prog>
FillKernel<Prog> fillKernel(const KernelKey& key) {
    return pickDepth<Prog>(key).fill;
}

template <class Prog>
ShadeRunsKernel<Prog> shadeRunsKernel(const KernelKey& key) {
    return pickPerspective<Prog, DepthMode::Off>(key).runs; // no depth test: the fill did it per sample
}

template <class Prog>
FlushKernel<Prog> flushKernel(const KernelKey& key) {
    return pickDepth<Prog>(key).flush;
}

// The one shading model this translation unit instantiates, untextured and textured:
// SR_KERNEL_PROGRAM, defined by the file that includes Kernels<Isa>.inl (one file per ISA and
// shading model, so that no single file compiles all 2 x 4 programs' kernels).
template FillKernel<programs::SR_KERNEL_PROGRAM<false>> fillKernel(const KernelKey&);
template FillKernel<programs::SR_KERNEL_PROGRAM<true>> fillKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<false>> shadeRunsKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true>> shadeRunsKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<false>> flushKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true>> flushKernel(const KernelKey&);
#ifdef SR_KERNEL_NORMAL_MAP_VARIANT // the textured program's normal-mapped variant too (pbr)
template FillKernel<programs::SR_KERNEL_PROGRAM<true, true>> fillKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true, true>> shadeRunsKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true, true>> flushKernel(const KernelKey&);
#endif
#ifdef SR_KERNEL_RGB_VARIANTS // the program's RGB-terms variant too (Gouraud under coloured lights)
template FillKernel<programs::SR_KERNEL_PROGRAM<false, true>> fillKernel(const KernelKey&);
template FillKernel<programs::SR_KERNEL_PROGRAM<true, true>> fillKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<false, true>> shadeRunsKernel(const KernelKey&);
template ShadeRunsKernel<programs::SR_KERNEL_PROGRAM<true, true>> shadeRunsKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<false, true>> flushKernel(const KernelKey&);
template FlushKernel<programs::SR_KERNEL_PROGRAM<true, true>> flushKernel(const KernelKey&);
#endif
