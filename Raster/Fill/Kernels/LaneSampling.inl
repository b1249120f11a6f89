// Texture sampling lane by lane: wrapping, nearest, bilinear, trilinear, level of detail
// (the fast paths of Raster/Texture/TextureSampling.cpp, with the same operations).
// Part of the span kernels: included by Kernels.inl inside its ISA namespace (see there).

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
template <WrapMode kU, WrapMode kV>
SR_SIMD_INLINE RawRgb bilinearRaw(const Texture::LevelView& l, I fixedU, I fixedV) {
    I x0, x1, wxTaps, y0, y1, wy;
    linearAxis<kU>(fixedU, l.width, l.maskX, x0, x1, wxTaps);
    linearAxis<kV>(fixedV, l.height, l.maskY, y0, y1, wy);
    I x, wx;
    adjacentPair<kU>(x0, x1, wxTaps, x, wx);
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
template <WrapMode kU, WrapMode kV>
SR_SIMD_INLINE Rgb bilinearDecoded(const Texture::LevelView& l, I fixedU, I fixedV) {
    I x0, x1, wx, y0, y1, wy;
    linearAxis<kU>(fixedU, l.width, l.maskX, x0, x1, wx);
    linearAxis<kV>(fixedV, l.height, l.maskY, y0, y1, wy);
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

// The lanes' uv derivatives under exact perspective (uvDerivatives, TextureLod.hpp: the quotient
// rule in float, the same operations).
struct UvLanes {
    F dudx, dvdx, dudy, dvdy;
};
template <class Prog>
SR_SIMD_INLINE UvLanes uvDerivativeLanes(const Prog& p, F u, F v, F invW) {
    const TriangleSetup& t = *p.setup;
    constexpr int kU = kPlaneVarying0, kVp = kPlaneVarying0 + 1;
    const F dqdx = fset(float(t.ddx[kPlaneInvW])), dqdy = fset(float(t.ddy[kPlaneInvW]));
    const F w = fset(1.0f) / invW;
    return {(fset(float(t.ddx[kU])) - u * dqdx) * w, (fset(float(t.ddx[kVp])) - v * dqdx) * w,
            (fset(float(t.ddy[kU])) - u * dqdy) * w, (fset(float(t.ddy[kVp])) - v * dqdy) * w};
}

// The squared footprints along screen x and y in texels (TextureLod.cpp's squaredFootprints).
SR_SIMD_INLINE void squaredFootprintLanes(const Texture& texture, const UvLanes& d, F& rx, F& ry) {
    const F tw = fset(float(texture.width())), th = fset(float(texture.height()));
    const F ax = d.dudx * tw, bx = d.dvdx * th, ay = d.dudy * tw, by = d.dvdy * th;
    rx = ax * ax + bx * bx;
    ry = ay * ay + by * by;
}

// The lanes' mip level under exact perspective, as programs::sampleKd computes it per fragment:
// uvDerivatives at each lane, then mipLevel (TextureLod.cpp) lane by lane.
template <class Prog>
SR_SIMD_INLINE F mipLevels(const Prog& p, const Texture& texture, F u, F v, F invW) {
    F rx, ry;
    squaredFootprintLanes(texture, uvDerivativeLanes(p, u, v, invW), rx, ry);
    const M ok = (rx >= fzero()) & (ry >= fzero()); // not NaN
    const F rho2 = fmin(fmax(fmax(rx, ry), fset(kMinRho2)), fset(kMaxRho2));
    return select(ok, fset(0.5f) * log2Lanes(rho2), fzero());
}

// GL_LINEAR_MIPMAP_LINEAR (TextureSampling::trilinear) for lanes on the vector path: both levels
// fetched here, blended in 8-bit fixed point with the same integer arithmetic (the sum is below
// 2^32: raw < 255 * 65536, times 256). The lanes of a group usually share their level; a group
// that straddles a level boundary runs once per distinct level.
template <WrapMode kU, WrapMode kV>
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
    const I zu = texelFixed<kU>(u, texture.width()), zv = texelFixed<kV>(v, texture.height());
    const int halving = texture.halvingLevels();
    auto coordinates = [&](const Texture::LevelView& l, int k, I& x, I& y) SR_SIMD_LAMBDA {
        if (k < halving) {
            x = l.width == 1 ? iset(0) : levelX(zu, k);
            y = l.height == 1 ? iset(0) : levelX(zv, k);
        } else {
            x = linearX<kU>(u, l.width);
            y = linearX<kV>(v, l.height);
        }
    };
    I r = iset(0), g = iset(0), b = iset(0);
    for (int k = lo; k <= hi; ++k) {
        const M mine = level == iset(k);
        if (bits(mine) == 0) continue;
        const Texture::LevelView here = texture.levelView(k);
        I fixedU, fixedV;
        coordinates(here, k, fixedU, fixedV);
        const RawRgb c0 = bilinearRaw<kU, kV>(here, fixedU, fixedV);
        I r0 = c0.r, g0 = c0.g, b0 = c0.b;
        // The next level only where a lane blends it in (wl > 0): magnified lanes (lod <= 0) and
        // whole-number lods read one level, exactly what the blend with wl = 0 returns.
        if (k < last && bits(mine & (wl > iset(0))) != 0) {
            const Texture::LevelView next = texture.levelView(k + 1);
            I nextU, nextV;
            coordinates(next, k + 1, nextU, nextV);
            const RawRgb c1 = bilinearRaw<kU, kV>(next, nextU, nextV);
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
template <WrapMode kU, WrapMode kV>
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
    const I zu = texelFixed<kU>(u, texture.width()), zv = texelFixed<kV>(v, texture.height());
    const int halving = texture.halvingLevels();
    auto coordinates = [&](const Texture::LevelView& l, int k, I& x, I& y) SR_SIMD_LAMBDA {
        if (k < halving) {
            x = l.width == 1 ? iset(0) : levelX(zu, k);
            y = l.height == 1 ? iset(0) : levelX(zv, k);
        } else {
            x = linearX<kU>(u, l.width);
            y = linearX<kV>(v, l.height);
        }
    };
    Rgb out{fzero(), fzero(), fzero()};
    for (int k = lo; k <= hi; ++k) {
        const M mine = level == iset(k);
        if (bits(mine) == 0) continue;
        const Texture::LevelView here = texture.decodedLevelView(k);
        I fixedU, fixedV;
        coordinates(here, k, fixedU, fixedV);
        Rgb c = bilinearDecoded<kU, kV>(here, fixedU, fixedV);
        const M blend = mine & (wl > iset(0));
        if (k < last && bits(blend) != 0) {
            const Texture::LevelView next = texture.decodedLevelView(k + 1);
            I nextU, nextV;
            coordinates(next, k + 1, nextU, nextV);
            const Rgb c1 = bilinearDecoded<kU, kV>(next, nextU, nextV);
            c = {select(blend, c.r + (c1.r - c.r) * w, c.r), select(blend, c.g + (c1.g - c.g) * w, c.g),
                 select(blend, c.b + (c1.b - c.b) * w, c.b)};
        }
        out = {select(mine, c.r, out.r), select(mine, c.g, out.g), select(mine, c.b, out.b)};
    }
    return out;
}

// The lanes off the vector path (NaN / Inf / huge uv) of a sample, redone by the scalar sampler:
// rare, so out of line (one copy per filter and wrap).
template <TextureFilter kFilter, WrapMode kU, WrapMode kV>
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
        const Color c = linear ? texture.sampleSrgb({us[i], vs[i]}, lods[i], kFilter, WrapModes{kU, kV}) : texture.sample({us[i], vs[i]}, lods[i], kFilter, WrapModes{kU, kV});
        r[i] = c.r;
        g[i] = c.g;
        b[i] = c.b;
    }
    kd = {fload(r), fload(g), fload(b)};
}

// The colour of the lanes from `texture` with the filter and wrap at level of detail `lod`
// (trilinear only); `linear`: texels decoded from sRGB (Texture::sampleSrgb).
template <TextureFilter kFilter, WrapMode kU, WrapMode kV>
SR_SIMD_INLINE Rgb sampleLanes(const Texture& texture, bool linear, F u, F v, F lod) {
    const M good = onVectorPath(u) & onVectorPath(v);
    const F uSafe = select(good, u, fzero()), vSafe = select(good, v, fzero());
    Rgb kd;
    if constexpr (kFilter == TextureFilter::Nearest) {
        const Texture::LevelView l = linear ? texture.decodedLevelView(0) : texture.levelView(0);
        const I x = nearestAxis<kU>(uSafe, l.width, l.maskX);
        const I y = nearestAxis<kV>(vSafe, l.height, l.maskY);
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
            kd = bilinearDecoded<kU, kV>(dl, linearX<kU>(uSafe, l.width), linearX<kV>(vSafe, l.height));
        } else {
            const RawRgb raw = bilinearRaw<kU, kV>(l, linearX<kU>(uSafe, l.width), linearX<kV>(vSafe, l.height));
            const F scale = fset(255.0f * 65536.0f); // then raw / (255 * 65536)
            kd = {toFloat(raw.r) / scale, toFloat(raw.g) / scale, toFloat(raw.b) / scale};
        }
    } else {
        kd = linear ? trilinearDecodedLanes<kU, kV>(texture, uSafe, vSafe, lod) : trilinearLanes<kU, kV>(texture, uSafe, vSafe, lod);
    }
    if (SR_UNLIKELY(bits(good) != bits(mAll()))) redoOffPathLanes<kFilter, kU, kV>(texture, linear, u, v, lod, good, kd);
    return kd;
}

// sampleAnisotropic (TextureLod.cpp) lane by lane: anisoFootprint's taps and level with the same
// operations, then the trilinear taps of every lane at once, as many rounds as the most any lane
// takes (a lane past its own count keeps its sum), the sums divided by the counts. Lanes whose
// centre or any tap is off the vector path are redone by the scalar function.
template <WrapMode kU, WrapMode kV>
SR_SIMD_NOINLINE Rgb anisotropicLanes(const Texture& texture, bool linear, F u, F v, const UvLanes& d, int maxAniso) {
    F rx, ry;
    squaredFootprintLanes(texture, d, rx, ry);
    const M ok = (rx >= fzero()) & (ry >= fzero());
    const M xMajor = rx >= ry;
    const F pMax2 = select(xMajor, rx, ry), pMin2 = select(xMajor, ry, rx);
    const F ratio2 = pMax2 / pMin2;
    I taps = iset(1);
    for (int k = 1; k < std::min(maxAniso, kMaxAnisotropy); ++k) taps = taps + select(fset(float(k * k)) < ratio2, iset(1), iset(0));
    taps = select(ok, taps, iset(1));
    const F n = toFloat(taps);
    const F rho2 = fmin(fmax(pMax2 / (n * n), fset(kMinRho2)), fset(kMaxRho2));
    const F lod = select(ok, fset(0.5f) * log2Lanes(rho2), fzero());
    const F du = select(xMajor, d.dudx, d.dudy), dv = select(xMajor, d.dvdx, d.dvdy);
    const M multi = taps > iset(1);
    M good = onVectorPath(u) & onVectorPath(v);
    Rgb sum{fzero(), fzero(), fzero()};
    for (int i = 0, most = reduceMax(taps); i < most; ++i) {
        const M active = iset(i) < taps;
        const F t = (fset(float(i)) + fset(0.5f)) / n - fset(0.5f);
        const F ui = select(multi, u + du * t, u), vi = select(multi, v + dv * t, v);
        const M onPath = onVectorPath(ui) & onVectorPath(vi);
        good = good & (onPath | andNot(mAll(), active));
        const F uSafe = select(onPath, ui, fzero()), vSafe = select(onPath, vi, fzero());
        const Rgb c = linear ? trilinearDecodedLanes<kU, kV>(texture, uSafe, vSafe, lod) : trilinearLanes<kU, kV>(texture, uSafe, vSafe, lod);
        sum = {select(active, sum.r + c.r, sum.r), select(active, sum.g + c.g, sum.g), select(active, sum.b + c.b, sum.b)};
    }
    Rgb kd{select(multi, sum.r / n, sum.r), select(multi, sum.g / n, sum.g), select(multi, sum.b / n, sum.b)};
    if (SR_UNLIKELY(bits(good) != bits(mAll()))) {
        alignas(64) float us[kLanes], vs[kLanes], g[4][kLanes], r[3][kLanes];
        fstore(us, u);
        fstore(vs, v);
        fstore(g[0], d.dudx);
        fstore(g[1], d.dvdx);
        fstore(g[2], d.dudy);
        fstore(g[3], d.dvdy);
        fstore(r[0], kd.r);
        fstore(r[1], kd.g);
        fstore(r[2], kd.b);
        for (int i = 0, m = bits(good); i < kLanes; ++i) {
            if (m & (1 << i)) continue;
            const Color c = sampleAnisotropic(texture, {us[i], vs[i]}, UvDerivatives{g[0][i], g[1][i], g[2][i], g[3][i]}, maxAniso,
                                              WrapModes{kU, kV}, linear);
            r[0][i] = c.r;
            r[1][i] = c.g;
            r[2][i] = c.b;
        }
        kd = {fload(r[0]), fload(r[1]), fload(r[2])};
    }
    return kd;
}

// sampleLanes out of line, one copy per filter and wrap (a call per group of lanes): what every
// kernel would otherwise copy for each map, wrap and colour mode. Only the Blinn-Phong programs'
// nearest and bilinear on display values are inlined (sampleMap): the cheapest filters, where a
// call (every vector register is the caller's to save across it) costs most in proportion.
template <TextureFilter kFilter, WrapMode kU, WrapMode kV>
SR_SIMD_NOINLINE Rgb sampleLanesOutOfLine(const Texture& texture, bool linear, F u, F v, F lod) {
    return sampleLanes<kFilter, kU, kV>(texture, linear, u, v, lod);
}

// Wrap modes apart on u and v (a glTF sampler's wrapS and wrapT, RenderSettings::wrapV): rare,
// so out of line and compiled once per ISA, in the kernel unit that defines
// SR_KERNEL_SAMPLERS_APART (every other unit calls it): sampleLanes and anisotropicLanes for
// the pair `wrap` (w.u != w.v).
Rgb sampleLanesApart(const Texture& texture, bool linear, F u, F v, F lod, TextureFilter filter, WrapModes wrap);
Rgb anisotropicLanesApart(const Texture& texture, bool linear, F u, F v, const UvLanes& d, int maxAniso, WrapModes wrap);
#ifdef SR_KERNEL_SAMPLERS_APART
// fn(kU, kV) for each pair of different modes.
template <class Fn>
Rgb withWrapsApart(WrapModes w, const Fn& fn) {
    using Repeat = std::integral_constant<WrapMode, WrapMode::Repeat>;
    using Clamp = std::integral_constant<WrapMode, WrapMode::Clamp>;
    using Mirror = std::integral_constant<WrapMode, WrapMode::Mirror>;
    switch (w.u) {
    case WrapMode::Repeat: return w.v == WrapMode::Clamp ? fn(Repeat{}, Clamp{}) : fn(Repeat{}, Mirror{});
    case WrapMode::Clamp: return w.v == WrapMode::Repeat ? fn(Clamp{}, Repeat{}) : fn(Clamp{}, Mirror{});
    case WrapMode::Mirror: break;
    }
    return w.v == WrapMode::Repeat ? fn(Mirror{}, Repeat{}) : fn(Mirror{}, Clamp{});
}
Rgb sampleLanesApart(const Texture& texture, bool linear, F u, F v, F lod, TextureFilter filter, WrapModes wrap) {
    return withWrapsApart(wrap, [&](auto wu, auto wv) {
        constexpr WrapMode kU = decltype(wu)::value, kV = decltype(wv)::value;
        switch (filter) {
        case TextureFilter::Nearest: return sampleLanes<TextureFilter::Nearest, kU, kV>(texture, linear, u, v, lod);
        case TextureFilter::Bilinear: return sampleLanes<TextureFilter::Bilinear, kU, kV>(texture, linear, u, v, lod);
        case TextureFilter::Trilinear: break;
        }
        return sampleLanes<TextureFilter::Trilinear, kU, kV>(texture, linear, u, v, lod);
    });
}
Rgb anisotropicLanesApart(const Texture& texture, bool linear, F u, F v, const UvLanes& d, int maxAniso, WrapModes wrap) {
    return withWrapsApart(wrap, [&](auto wu, auto wv) {
        return anisotropicLanes<decltype(wu)::value, decltype(wv)::value>(texture, linear, u, v, d, maxAniso);
    });
}
#endif

// sampleLanes for the draw: the lanes' level of detail (trilinear: the affine triangle's
// `triangleLod`, or per lane under exact perspective), then the draw's wrap modes, read here per
// group of lanes rather than made a template parameter of the kernels (one predictable branch
// per group; modes apart on the two axes: sampleLanesApart).
template <PerspectiveMode kPersp, TextureFilter kFilter, class Prog>
SR_SIMD_INLINE Rgb sampleMap(const Prog& p, const Texture& texture, bool linear, F u, F v, F invW, F triangleLod) {
    const WrapModes wrap = wrapModesOf(p.d->settings);
    F lod = fzero();
    if constexpr (kFilter == TextureFilter::Trilinear) {
        if constexpr (kPersp == PerspectiveMode::Affine) {
            lod = triangleLod;
        } else {
            if (const int aniso = p.d->settings.aniso; aniso > 1) {
                const UvLanes d = uvDerivativeLanes(p, u, v, invW);
                if (SR_UNLIKELY(wrap.u != wrap.v)) return anisotropicLanesApart(texture, linear, u, v, d, aniso, wrap);
                switch (wrap.u) {
                case WrapMode::Clamp: return anisotropicLanes<WrapMode::Clamp, WrapMode::Clamp>(texture, linear, u, v, d, aniso);
                case WrapMode::Mirror: return anisotropicLanes<WrapMode::Mirror, WrapMode::Mirror>(texture, linear, u, v, d, aniso);
                case WrapMode::Repeat: break;
                }
                return anisotropicLanes<WrapMode::Repeat, WrapMode::Repeat>(texture, linear, u, v, d, aniso);
            }
            lod = mipLevels(p, texture, u, v, invW);
        }
    } else {
        (void)invW;
        (void)triangleLod;
    }
    if (SR_UNLIKELY(wrap.u != wrap.v)) return sampleLanesApart(texture, linear, u, v, lod, kFilter, wrap);
    auto sample = [&](auto mode) SR_SIMD_LAMBDA {
        constexpr WrapMode kWrap = decltype(mode)::value;
        if constexpr (kFilter != TextureFilter::Trilinear && Prog::kMode != ShadingMode::Pbr) {
            if (!linear) return sampleLanes<kFilter, kWrap, kWrap>(texture, false, u, v, lod);
        }
        return sampleLanesOutOfLine<kFilter, kWrap, kWrap>(texture, linear, u, v, lod);
    };
    switch (wrap.u) {
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
