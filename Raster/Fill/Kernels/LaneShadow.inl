// The shadow-map receiver test lane by lane (Raster/Shade/Shadow.cpp's, with the same operations).
// Part of the span kernels: included by Kernels.inl inside its ISA namespace (see there).

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
