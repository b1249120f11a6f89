// FXAA's scalar reference and its dispatch to the vector kernels (see Fxaa.hpp for the rule).
#include "Raster/Frame/Fxaa.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "Raster/Fill/Kernels/KernelConfig.hpp"

namespace sr {

void FxaaScratch::resize(int w, int h, int bands) {
    width = w;
    height = h;
    luma.resize(std::size_t(w + 2) * std::size_t(h + 2) + kSlack);
    if (writes.size() < std::size_t(bands)) writes.resize(std::size_t(bands));
}

namespace {

float lumaOf(Pixel p) {
    return (float(pixelR(p)) * kFxaaLumaR + float(pixelG(p)) * kFxaaLumaG) + float(pixelB(p)) * kFxaaLumaB;
}

void prepareRowsScalar(const FrameBuffer& image, FxaaScratch& s, int y0, int y1) {
    const int w = s.width, stride = s.lumaStride();
    for (int y = y0; y < y1; ++y) {
        const Pixel* row = image.colorRow(y);
        float* l = s.luma.data() + std::size_t(y + 1) * std::size_t(stride);
        for (int x = 0; x < w; ++x) l[x + 1] = lumaOf(row[x]);
        l[0] = l[1];
        l[w + 1] = l[w];
    }
}

// The border rows, copies of the first and last image rows (their border columns included).
void prepareBorderRows(FxaaScratch& s, int y0, int y1) {
    const std::size_t stride = std::size_t(s.lumaStride());
    float* l = s.luma.data();
    if (y0 == 0) std::memcpy(l, l + stride, stride * sizeof(float));
    if (y1 == s.height) std::memcpy(l + std::size_t(s.height + 1) * stride, l + std::size_t(s.height) * stride, stride * sizeof(float));
}

// One pixel of the filter; false where it is not on an edge (the pixel stays). The vector kernels
// (FxaaLanes.inl) repeat every operation, in this order.
bool filterPixel(const FxaaScratch& s, const FrameBuffer& image, int x, int y, Pixel& out) {
    auto L = [&](int px, int py) { return s.lumaAt(px, py); };
    const float m = L(x, y), n = L(x, y - 1), so = L(x, y + 1), w = L(x - 1, y), e = L(x + 1, y);
    const float maxL = std::max(std::max(std::max(n, w), std::max(e, so)), m);
    const float minL = std::min(std::min(std::min(n, w), std::min(e, so)), m);
    const float range = maxL - minL;
    if (!(range >= std::max(kFxaaEdgeThresholdMin, maxL * kFxaaEdgeThreshold))) return false;

    const float nw = L(x - 1, y - 1), ne = L(x + 1, y - 1), sw = L(x - 1, y + 1), se = L(x + 1, y + 1);
    const float ns = n + so, we = w + e;
    const float nese = ne + se, nwne = nw + ne, nwsw = nw + sw, swse = sw + se;
    const float horz4 = std::fabs(ns - m * 2.0f) * 2.0f + std::fabs(nese - e * 2.0f);
    const float vert4 = std::fabs(we - m * 2.0f) * 2.0f + std::fabs(nwne - n * 2.0f);
    const float edgeHorz = std::fabs(nwsw - w * 2.0f) + horz4;
    const float edgeVert = std::fabs(swse - so * 2.0f) + vert4;
    const bool horz = edgeHorz >= edgeVert; // the edge runs along x: search along the row

    // The two neighbours across the edge, and the steeper one.
    const float a = horz ? n : w, b = horz ? so : e;
    const float gradA = std::fabs(a - m), gradB = std::fabs(b - m);
    const bool pairA = gradA >= gradB;
    const float gradient = std::max(gradA, gradB);
    const int side = pairA ? -1 : 1;
    const float half = ((pairA ? a : b) + m) * 0.5f;
    const float scaled = gradient * 0.25f;
    const bool mBelow = m - half < 0.0f;

    // The search along the edge, between this row (column) and the one across.
    const int along = horz ? x : y, last = horz ? s.width - 1 : s.height - 1;
    auto tap = [&](int p) {
        const int c = std::clamp(p, 0, last);
        return horz ? (L(c, y) + L(c, y + side)) * 0.5f : (L(x, c) + L(x + side, c)) * 0.5f;
    };
    int posN = along - kFxaaSteps[0], posP = along + kFxaaSteps[0];
    float endN = tap(posN) - half, endP = tap(posP) - half;
    bool doneN = std::fabs(endN) >= scaled, doneP = std::fabs(endP) >= scaled;
    for (int k = 1; k < kFxaaSearchSteps; ++k) {
        if (!doneN) posN -= kFxaaSteps[k];
        if (!doneP) posP += kFxaaSteps[k];
        if ((doneN && doneP) || k == kFxaaSearchSteps - 1) break; // the last step moves, reads nothing
        if (!doneN) {
            endN = tap(posN) - half;
            doneN = std::fabs(endN) >= scaled;
        }
        if (!doneP) {
            endP = tap(posP) - half;
            doneP = std::fabs(endP) >= scaled;
        }
    }
    const int dstN = along - posN, dstP = posP - along;
    const bool goodN = (endN < 0.0f) != mBelow, goodP = (endP < 0.0f) != mBelow;
    const bool nearerN = dstN < dstP;
    const int dst = nearerN ? dstN : dstP;
    const bool good = nearerN ? goodN : goodP;
    const float edgeOffset = good ? 0.5f - float(dst) / float(dstN + dstP) : 0.0f;

    const float subA = (ns + we) * 2.0f + (nwsw + nese);
    const float subC = std::min(std::fabs(subA * (1.0f / 12.0f) - m) / range, 1.0f);
    const float subF = (3.0f - subC * 2.0f) * (subC * subC);
    const float subH = (subF * subF) * kFxaaSubpix;
    const float offset = std::max(edgeOffset, subH);

    const Pixel c0 = image.pixel(x, y);
    const int xa = horz ? x : std::clamp(x + side, 0, s.width - 1);
    const int ya = horz ? std::clamp(y + side, 0, s.height - 1) : y;
    const Pixel c1 = image.pixel(xa, ya);
    auto mix = [&](int shift) {
        const float v0 = float((c0 >> shift) & 0xFFu), v1 = float((c1 >> shift) & 0xFFu);
        return Pixel(int(v0 + (v1 - v0) * offset + 0.5f)) << shift;
    };
    out = 0xFF000000u | mix(16) | mix(8) | mix(0);
    return true;
}

void filterRowsScalar(const FxaaScratch& s, const FrameBuffer& image, int y0, int y1, std::vector<FxaaWrite>& writes) {
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < s.width; ++x) {
            Pixel p;
            if (filterPixel(s, image, x, y, p)) writes.push_back({std::uint32_t(y) * std::uint32_t(s.width) + std::uint32_t(x), p});
        }
}

} // namespace

void fxaaPrepareRows(const FrameBuffer& image, FxaaScratch& scratch, int y0, int y1, Isa isa) {
#if SR_KERNELS_X86
    switch (isa) {
    case Isa::Sse2: kernels_sse2::fxaaPrepareRows(image, scratch, y0, y1); break;
    case Isa::Avx2: kernels_avx2::fxaaPrepareRows(image, scratch, y0, y1); break;
    case Isa::Avx512: kernels_avx512::fxaaPrepareRows(image, scratch, y0, y1); break;
    case Isa::Scalar: prepareRowsScalar(image, scratch, y0, y1); break;
    }
#else
    (void)isa;
    prepareRowsScalar(image, scratch, y0, y1);
#endif
    prepareBorderRows(scratch, y0, y1);
}

void fxaaFilterRows(FxaaScratch& scratch, const FrameBuffer& image, int band, int y0, int y1, Isa isa) {
    std::vector<FxaaWrite>& writes = scratch.writes[std::size_t(band)];
    writes.clear();
#if SR_KERNELS_X86
    switch (isa) {
    case Isa::Sse2: kernels_sse2::fxaaFilterRows(scratch, image, y0, y1, writes); return;
    case Isa::Avx2: kernels_avx2::fxaaFilterRows(scratch, image, y0, y1, writes); return;
    case Isa::Avx512: kernels_avx512::fxaaFilterRows(scratch, image, y0, y1, writes); return;
    case Isa::Scalar: break;
    }
#else
    (void)isa;
#endif
    filterRowsScalar(scratch, image, y0, y1, writes);
}

void fxaaWriteBand(const FxaaScratch& scratch, FrameBuffer& image, int band) {
    Pixel* pixels = image.colorData();
    for (const FxaaWrite& w : scratch.writes[std::size_t(band)]) pixels[w.index] = w.colour;
}

void applyFxaa(FrameBuffer& image, FxaaScratch& scratch, Isa isa) {
    if (image.empty()) return;
    scratch.resize(image.width(), image.height(), 1);
    fxaaPrepareRows(image, scratch, 0, image.height(), isa);
    fxaaFilterRows(scratch, image, 0, 0, image.height(), isa);
    fxaaWriteBand(scratch, image, 0);
}

} // namespace sr
