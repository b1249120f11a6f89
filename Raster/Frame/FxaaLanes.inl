// FXAA's vector kernels, written once over the vector types of one ISA (see Fxaa.hpp for the
// rule and Fxaa.cpp's filterPixel for the scalar reference: every operation below is its, in
// the same order, lane by lane, so the images are bit-identical). Included by FxaaSse2.cpp,
// FxaaAvx2.cpp and FxaaAvx512.cpp inside their namespace and target region.

namespace fxaa_detail {

SR_SIMD_INLINE F lumaLanes(I p) {
    const F r = toFloat(shiftRightLogical<16>(p) & iset(0xFF));
    const F g = toFloat(shiftRightLogical<8>(p) & iset(0xFF));
    const F b = toFloat(p & iset(0xFF));
    return (r * fset(kFxaaLumaR) + g * fset(kFxaaLumaG)) + b * fset(kFxaaLumaB);
}

SR_SIMD_INLINE F gatherLuma(const float* luma, I index) {
    return asFloat(gather(reinterpret_cast<const std::uint32_t*>(luma), index));
}

SR_SIMD_INLINE M notMask(M m) { return andNot(mAll(), m); }
SR_SIMD_INLINE M differ(M a, M b) { return andNot(a, b) | andNot(b, a); }

// The pixels of a row found on an edge, waiting to be filtered kLanes at a time: x and the 3x3
// lumas around it (left-packed, entries [0, count); room for two groups, as a whole vector is
// stored at count < kLanes).
enum Around { kNW, kN, kNE, kW, kM, kE, kSW, kS, kSE, kAround };
struct EdgeQueue {
    int count = 0;
    alignas(64) std::int32_t x[2 * kLanes];
    alignas(64) float l[kAround][2 * kLanes];
};

// The edge test of one group (pixels x0 .. x0 + kLanes - 1 of row y, `valid` those inside it);
// the pixels on an edge are queued.
SR_SIMD_INLINE void queueEdges(const FxaaScratch& s, int x0, int y, M valid, EdgeQueue& q) {
    const int stride = s.lumaStride();
    const float* lc = s.luma.data() + std::size_t(y + 1) * std::size_t(stride) + std::size_t(x0 + 1);
    const F m = fload(lc), n = fload(lc - stride), so = fload(lc + stride), w = fload(lc - 1), e = fload(lc + 1);
    const F maxL = fmax(fmax(fmax(n, w), fmax(e, so)), m);
    const F minL = fmin(fmin(fmin(n, w), fmin(e, so)), m);
    const M edge = valid & (maxL - minL >= fmax(fset(kFxaaEdgeThresholdMin), maxL * fset(kFxaaEdgeThreshold)));
    if (bits(edge) == 0) return;
    const int at = q.count;
    compressStore(q.x + at, iset(x0) + iiota(), edge);
    compressStore(q.l[kM] + at, m, edge);
    compressStore(q.l[kN] + at, n, edge);
    compressStore(q.l[kS] + at, so, edge);
    compressStore(q.l[kW] + at, w, edge);
    compressStore(q.l[kE] + at, e, edge);
    compressStore(q.l[kNW] + at, fload(lc - stride - 1), edge);
    compressStore(q.l[kNE] + at, fload(lc - stride + 1), edge);
    compressStore(q.l[kSW] + at, fload(lc + stride - 1), edge);
    compressStore(q.l[kSE] + at, fload(lc + stride + 1), edge);
    q.count += laneCount(edge);
}

// The filter at the first kLanes queued pixels of row y (`work`: those queued); their colours.
SR_SIMD_INLINE I filterLanes(const FxaaScratch& s, const Pixel* colours, const EdgeQueue& q, int y, M work) {
    const int stride = s.lumaStride();
    const I x = iload(q.x);
    const F m = fload(q.l[kM]), n = fload(q.l[kN]), so = fload(q.l[kS]), w = fload(q.l[kW]), e = fload(q.l[kE]);
    const F maxL = fmax(fmax(fmax(n, w), fmax(e, so)), m);
    const F minL = fmin(fmin(fmin(n, w), fmin(e, so)), m);
    const F range = maxL - minL;

    const F two = fset(2.0f), halfF = fset(0.5f), zero = fzero();
    const F nw = fload(q.l[kNW]), ne = fload(q.l[kNE]), sw = fload(q.l[kSW]), se = fload(q.l[kSE]);
    const F ns = n + so, we = w + e;
    const F nese = ne + se, nwne = nw + ne, nwsw = nw + sw, swse = sw + se;
    const F horz4 = fabs(ns - m * two) * two + fabs(nese - e * two);
    const F vert4 = fabs(we - m * two) * two + fabs(nwne - n * two);
    const F edgeHorz = fabs(nwsw - w * two) + horz4;
    const F edgeVert = fabs(swse - so * two) + vert4;
    const M horz = edgeHorz >= edgeVert;

    const F a = select(horz, n, w), b = select(horz, so, e);
    const F gradA = fabs(a - m), gradB = fabs(b - m);
    const M pairA = gradA >= gradB;
    const F gradient = fmax(gradA, gradB);
    const I side = select(pairA, iset(-1), iset(1));
    const F half = (select(pairA, a, b) + m) * halfF;
    const F scaled = gradient * fset(0.25f);
    const M mBelow = (m - half) < zero;

    const I yv = iset(y);
    const I along = select(horz, x, yv);
    const I last = select(horz, iset(s.width - 1), iset(s.height - 1));
    const I iStride = iset(stride);
    const I rowBase = iset((y + 1) * stride + 1); // + c: luma (c, y)
    const I columnBase = x + iset(1);               // + (c + 1) * stride: luma (x, c)
    const I across = select(horz, select(pairA, iset(-stride), iset(stride)), side);
    auto tap = [&](I p) SR_SIMD_LAMBDA {
        const I c = imin(imax(p, iset(0)), last);
        const I first = select(work, select(horz, rowBase + c, mulLow(c + iset(1), iStride) + columnBase), iset(0));
        const I second = select(work, first + across, iset(0));
        return (gatherLuma(s.luma.data(), first) + gatherLuma(s.luma.data(), second)) * halfF;
    };
    const F scaledAbs = scaled;
    I posN = along - iset(kFxaaSteps[0]), posP = along + iset(kFxaaSteps[0]);
    F endN = tap(posN) - half, endP = tap(posP) - half;
    const M idle = notMask(work);
    M doneN = (fabs(endN) >= scaledAbs) | idle, doneP = (fabs(endP) >= scaledAbs) | idle;
    for (int k = 1; k < kFxaaSearchSteps; ++k) {
        posN = select(doneN, posN, posN - iset(kFxaaSteps[k]));
        posP = select(doneP, posP, posP + iset(kFxaaSteps[k]));
        if (bits(doneN & doneP) == bits(mAll()) || k == kFxaaSearchSteps - 1) break;
        if (bits(doneN) != bits(mAll())) {
            endN = select(doneN, endN, tap(posN) - half);
            doneN = doneN | (fabs(endN) >= scaledAbs);
        }
        if (bits(doneP) != bits(mAll())) {
            endP = select(doneP, endP, tap(posP) - half);
            doneP = doneP | (fabs(endP) >= scaledAbs);
        }
    }
    const I dstN = along - posN, dstP = posP - along;
    const M goodN = differ(endN < zero, mBelow), goodP = differ(endP < zero, mBelow);
    const M nearerN = dstN < dstP;
    const I dst = select(nearerN, dstN, dstP);
    const M good = (nearerN & goodN) | andNot(goodP, nearerN);
    const F edgeOffset = select(good, halfF - toFloat(dst) / toFloat(dstN + dstP), zero);

    const F subA = (ns + we) * two + (nwsw + nese);
    const F subC = fmin(fabs(subA * fset(1.0f / 12.0f) - m) / range, fset(1.0f));
    const F subF = (fset(3.0f) - subC * two) * (subC * subC);
    const F subH = (subF * subF) * fset(kFxaaSubpix);
    const F offset = fmax(edgeOffset, subH);

    const I xa = select(horz, x, imin(imax(x + side, iset(0)), iset(s.width - 1)));
    const I ya = select(horz, imin(imax(yv + side, iset(0)), iset(s.height - 1)), yv);
    const I original = gather(colours, select(work, iset(y * s.width) + x, iset(0)));
    const I c1 = gather(colours, select(work, mulLow(ya, iset(s.width)) + xa, iset(0)));
    auto mix = [&](I v0i, I v1i) SR_SIMD_LAMBDA {
        const F v0 = toFloat(v0i & iset(0xFF)), v1 = toFloat(v1i & iset(0xFF));
        return truncToInt(v0 + (v1 - v0) * offset + halfF);
    };
    const I r = mix(shiftRightLogical<16>(original), shiftRightLogical<16>(c1));
    const I g = mix(shiftRightLogical<8>(original), shiftRightLogical<8>(c1));
    const I bl = mix(original, c1);
    const I filtered = (iset(int(0xFF000000u)) | shiftLeft<16>(r)) | (shiftLeft<8>(g) | bl);
    return filtered;
}

} // namespace fxaa_detail

void fxaaPrepareRows(const FrameBuffer& image, FxaaScratch& s, int y0, int y1) {
    const int w = s.width, stride = s.lumaStride();
    for (int y = y0; y < y1; ++y) {
        const Pixel* row = image.colorRow(y);
        float* l = s.luma.data() + std::size_t(y + 1) * std::size_t(stride) + 1;
        int x = 0;
        for (; x + kLanes <= w; x += kLanes) fstore(l + x, fxaa_detail::lumaLanes(iload(row + x)));
        if (x < w) { // the tail through a buffer: a full store would reach into the next row
            alignas(64) std::uint32_t in[kLanes] = {};
            alignas(64) float out[kLanes];
            std::memcpy(in, row + x, std::size_t(w - x) * sizeof(Pixel));
            fstore(out, fxaa_detail::lumaLanes(iload(in)));
            std::memcpy(l + x, out, std::size_t(w - x) * sizeof(float));
        }
        l[-1] = l[0];
        l[w] = l[w - 1];
    }
}

// Per row: the edge test a group at a time, the pixels on an edge queued, and the filter run on
// full vectors of queued pixels (a frame's edges are a small share of its pixels, scattered:
// filtering whole groups would run the search on mostly idle lanes). The filtered pixels go to
// `writes`; the image is only read.
void fxaaFilterRows(const FxaaScratch& s, const FrameBuffer& image, int y0, int y1, std::vector<FxaaWrite>& writes) {
    const int w = s.width;
    const Pixel* colours = image.colorData();
    fxaa_detail::EdgeQueue q;
    alignas(64) std::uint32_t result[kLanes];
    for (int y = y0; y < y1; ++y) {
        q.count = 0;
        auto flush = [&](int count) {
            istore(result, fxaa_detail::filterLanes(s, colours, q, y, firstN(count)));
            const std::uint32_t rowStart = std::uint32_t(y) * std::uint32_t(w);
            for (int k = 0; k < count; ++k) writes.push_back({rowStart + std::uint32_t(q.x[k]), result[k]});
            q.count -= count;
            std::memcpy(q.x, q.x + count, std::size_t(q.count) * sizeof(std::int32_t));
            for (auto& l : q.l) std::memcpy(l, l + count, std::size_t(q.count) * sizeof(float));
        };
        for (int x = 0; x < w; x += kLanes) {
            fxaa_detail::queueEdges(s, x, y, firstN(std::min(kLanes, w - x)), q);
            if (q.count >= kLanes) flush(kLanes);
        }
        if (q.count > 0) flush(q.count);
    }
}
