// Binned draws (several lanes, many triangles): each triangle screened once into the bins of the
// bands of rows it meets, then the lanes take the bands one at a time and draw each band's bins
// in submission order.
#pragma once

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "Raster/Geometry/PrimitiveStage.hpp"

namespace sr {
namespace detail {

// Every lane of the plain walk classifies every triangle, and sets up every one its bands meet,
// the culled ones included; with several lanes that front end is repeated per lane. A binned draw
// screens each triangle once instead: lane c classifies and culls chunk c of the triangles
// (screenSnapped, from the positions the vertex stage snapped once per vertex: the decisions
// setupTriangleCulled would make) and appends each survivor, with its vertex indices (BinEntry), to
// chunk c's bins of the 32-row bands (LaneBands::kBandRows) its rows meet, marked in the band of its
// first row, which counts it. Then each lane takes the bands of its own part of the rows, the
// largest first, then what the other lanes left (bandsByWork, BandQueue), until none is left
// (fillBinnedBand), and draws its bins chunk by chunk, so in submission order: a band is drawn by
// one lane, whole, while its rows are in that lane's cache, and a lane that runs slower (or shares
// its CPU) simply takes fewer.
// Every piece of a triangle that crosses a clip plane (clipped here, once), and a triangle whose
// rows meet RenderContext::sharedSetupBands bands or more, is set up here, once, into the chunk's
// shared records (RenderContext::sharedSetups), which its bands read; any other triangle is set up
// for each band it meets, next to its fill. Same image, same counters (with sharedSetupBands 1:
// setupsBuilt == rasterized).
inline constexpr std::uint32_t kBinOwner = 1u << 31;  // this band counts the triangle
inline constexpr std::uint32_t kBinShared = 1u << 30; // the index is of a shared record, not a triangle
inline constexpr std::uint32_t kBinIndex = kBinShared - 1u;

// The bands of a target `height` rows high.
inline int bandCount(int height) { return (height + LaneBands::kBandRows - 1) / LaneBands::kBandRows; }

template <int kVaryings>
void binTriangles(RenderContext& ctx, const DrawState& state, const Clipper& clipperProto, int chunk,
                  const std::uint32_t* indices, std::size_t triangleBegin, std::size_t triangleEnd, RenderStats& stats) {
    const unsigned* codes = ctx.clipCodes.data();
    const SnappedVertex* snapped = ctx.snappedVertices.data();
    const ScreenVertex* screen = ctx.screenVertices.data();
    const int height = ctx.target().height();
    const bool multisampled = ctx.multisampleTarget() != nullptr;
    const bool setUp = state.stopAfter >= PipelineStop::Setup; // else only the partial pipeline's counters
    const int bandsHigh = bandCount(height);
    Clipper clipper = clipperProto;
    std::vector<BinEntry>* bins = ctx.bins.data() + std::size_t(chunk) * std::size_t(bandsHigh);
    std::vector<RenderContext::SharedSetup>& shared = ctx.sharedSetups[std::size_t(chunk)];
    std::size_t sharedUsed = 0;
    auto nextShared = [&shared, &sharedUsed]() -> RenderContext::SharedSetup& {
        if (sharedUsed == shared.size()) shared.resize(std::max<std::size_t>(64, 2 * shared.size()));
        return shared[sharedUsed];
    };
    // The bands rows [rowBegin, rowEnd) meet on the target: [first, last] (first > last: none).
    auto bandsMet = [height](int rowBegin, int rowEnd, int& first, int& last) {
        rowBegin = std::max(rowBegin, 0);
        rowEnd = std::min(rowEnd, height);
        first = rowBegin / LaneBands::kBandRows;
        last = rowBegin < rowEnd ? (rowEnd - 1) / LaneBands::kBandRows : first - 1;
    };
    // An entry (triangle or shared record) into the bins of the bands rows [rowBegin, rowEnd)
    // meet, marked in the band of the first row (on the target), which counts it.
    auto addToBins = [&](BinEntry entry, int rowBegin, int rowEnd) {
        const int owner = std::clamp(rowBegin, 0, std::max(height - 1, 0)) / LaneBands::kBandRows;
        BinEntry owned = entry;
        owned.entry |= kBinOwner;
        bins[owner].push_back(owned);
        int first = 0, last = 0;
        bandsMet(rowBegin, rowEnd, first, last);
        for (int b = first; b <= last; ++b)
            if (b != owner) bins[b].push_back(entry);
    };
    for (std::size_t tri = triangleBegin; tri < triangleEnd; ++tri) {
        const std::uint32_t i0 = indices[3 * tri], i1 = indices[3 * tri + 1], i2 = indices[3 * tri + 2];
        const unsigned c0 = codes[i0], c1 = codes[i1], c2 = codes[i2];
        ++stats.trianglesIn;
        if (tri + kPrefetchTriangles < triangleEnd) {
            for (std::size_t k = 3 * (tri + kPrefetchTriangles); k < 3 * (tri + kPrefetchTriangles) + 3; ++k) {
                prefetchForRead(snapped + indices[k]);
                prefetchForRead(codes + indices[k]);
            }
        }
        switch (clipper.classifyCodes(c0, c1, c2)) {
        case ClipClass::Reject:
            ++stats.trivialRejected;
            if ((c0 | c1 | c2) & kCodeNonFinite) ++stats.nonFinite;
            break;
        case ClipClass::Clip: {
            ++stats.clipped;
            ClippedPolygon polygon;
            ScreenVertex pieces[kMaxClipVertices];
            clipToScreen<kVaryings>(ctx, state, clipper, i0, i1, i2, polygon, pieces);
            for (int k = 0; k < polygon.triangleCount(); ++k) {
                const ScreenVertex &a = pieces[0], &b = pieces[k + 1], &c = pieces[k + 2];
                if (!setUp) { // stopped after geometry or binning: the cull decision only
                    if (isCulled(state.cull, a, b, c)) ++stats.culled;
                    continue;
                }
                RenderContext::SharedSetup& record = nextShared();
                const SetupOutcome outcome = setupForDraw<kVaryings>(record.setup, state, multisampled, a, b, c);
                if (outcome == SetupOutcome::Culled) ++stats.culled;
                if (outcome != SetupOutcome::Ready) continue;
                ++stats.setupsBuilt;
                record.triangle = tri;
                int rowBegin = 0, rowEnd = 0;
                rowsForBands(a, b, c, multisampled, rowBegin, rowEnd);
                addToBins({std::uint32_t(sharedUsed++) | kBinShared, {}}, rowBegin, rowEnd);
            }
            break;
        }
        case ClipClass::Accept: {
            // Accepted: every vertex inside the clipper's guard band, which lies inside setup's
            // (kClipGuardBand < kGuardBand), so every one was snapped.
            Fixed minY = 0, maxY = 0;
            const SetupOutcome outcome =
                screenSnapped(snapped[i0], snapped[i1], snapped[i2], state.cull, multisampled, minY, maxY);
            if (outcome == SetupOutcome::Culled) ++stats.culled; // isCulled's decision too
            if (outcome != SetupOutcome::Ready || state.stopAfter == PipelineStop::Geometry) break;
            // rasterizeTriangle's decision: the band of the first row counts it, every band its
            // rows meet fills them.
            int rowBegin = 0, rowEnd = 0;
            rowsOfSnappedExtent(minY, maxY, multisampled, rowBegin, rowEnd);
            int first = 0, last = 0;
            bandsMet(rowBegin, rowEnd, first, last);
            if (!setUp || last - first + 1 < ctx.sharedSetupBands) { // each band sets it up
                addToBins({std::uint32_t(tri), {i0, i1, i2}}, rowBegin, rowEnd);
                break;
            }
            RenderContext::SharedSetup& record = nextShared();
            [[maybe_unused]] const SetupOutcome built =
                setupForDraw<kVaryings>(record.setup, state, multisampled, screen[i0], screen[i1], screen[i2]);
            assert(built == SetupOutcome::Ready); // screenSnapped's decision
            ++stats.setupsBuilt;
            record.triangle = tri;
            addToBins({std::uint32_t(sharedUsed++) | kBinShared, {}}, rowBegin, rowEnd);
            break;
        }
        }
    }
}

// The bands' split into `regions` parts of consecutive rows, regionSize(bands, regions) bands
// each (the last may be shorter): part r is first drawn by lane r (BandQueue).
inline int regionSize(int bands, int regions) { return (bands + regions - 1) / regions; }

// The order the lanes take a binned draw's bands in (ctx.bandOrder, from its `chunks` x
// `bandsHigh` bins), within each of `regions` parts (regionSize): the most bin entries first,
// ties the upper band first. Taken in row order, a full band taken last can leave one lane
// drawing while the others wait; taken largest first, the last bands are the smallest and the
// lanes finish close together (2 threads: bunny 1920x1080 0.977x the time; docs/PERFORMANCE.md).
// Which lane draws a band does not change the image. orderBands: that order from each band's bin
// entries in ctx.bandKeys[band] (overwritten); bandsByWork: from the bins in ctx.bins.
inline void orderBands(RenderContext& ctx, int bandsHigh, int regions) {
    // Key: entries << 16 | (65535 - band), sorted descending within each part.
    static_assert(FrameBuffer::kMaxDimension / LaneBands::kBandRows < 65536, "a band number fits 16 bits");
    std::vector<std::uint64_t>& keys = ctx.bandKeys;
    for (int b = 0; b < bandsHigh; ++b) keys[std::size_t(b)] = keys[std::size_t(b)] << 16 | std::uint64_t(65535 - b);
    const int size = regionSize(bandsHigh, std::max(regions, 1));
    for (int begin = 0; begin < bandsHigh; begin += size)
        std::sort(keys.begin() + begin, keys.begin() + std::min(bandsHigh, begin + size),
                  [](std::uint64_t x, std::uint64_t y) { return x > y; });
    ctx.bandOrder.resize(std::size_t(bandsHigh));
    for (int k = 0; k < bandsHigh; ++k) ctx.bandOrder[std::size_t(k)] = 65535 - int(keys[std::size_t(k)] & 0xFFFFu);
}

// Adds each band's entries in `bins` (chunks x bandsHigh, as RenderContext::bins) to keys[band].
inline void countBinEntries(std::vector<std::uint64_t>& keys, const std::vector<std::vector<BinEntry>>& bins,
                            int chunks, int bandsHigh) {
    for (int c = 0; c < chunks; ++c)
        for (int b = 0; b < bandsHigh; ++b)
            keys[std::size_t(b)] += bins[std::size_t(c) * std::size_t(bandsHigh) + std::size_t(b)].size();
}

inline void bandsByWork(RenderContext& ctx, int chunks, int bandsHigh, int regions = 1) {
    ctx.bandKeys.assign(std::size_t(bandsHigh), 0);
    countBinEntries(ctx.bandKeys, ctx.bins, chunks, bandsHigh);
    orderBands(ctx, bandsHigh, regions);
}

// Which entry of ctx.bandOrder each lane draws next. The bands are split into one part of
// consecutive rows per lane (regionSize); a lane takes its own part's bands first, in order, then
// what is left of the other parts. So a band is mostly drawn by the same lane (the same thread
// and core) from draw to draw and frame to frame, and its rows' colour and depth are still in
// that core's cache instead of another's (2 threads, spider close-up: 0.88-0.90x the time of one
// shared counter over all the bands); a lane that runs slower still takes fewer. Every band is
// handed out exactly once, whatever the interleaving of the lanes' calls.
class BandQueue {
public:
    BandQueue(int bands, int lanes)
        : bands_(bands), lanes_(std::clamp(lanes, 1, kMaxRenderThreads)), size_(regionSize(bands, lanes_)) {}
    // The next entry of the order for lane `lane` (its own part's first), or -1: none left (with
    // ownOnly: none left in its own part).
    int next(int lane, bool ownOnly = false) {
        for (int i = 0; i < (ownOnly ? 1 : lanes_); ++i) {
            const int r = (lane + i) % lanes_, begin = r * size_, end = std::min(bands_, begin + size_);
            if (begin >= end) continue;
            // (Past its end a part's count keeps growing by one per lane that asks: harmless.)
            const int k = begin + parts_[r].taken.fetch_add(1, std::memory_order_relaxed);
            if (k < end) return k;
        }
        return -1;
    }

private:
    struct Part { // 64 bytes apart: no two lanes' counters share a cache line (no over-alignment
        std::atomic<int> taken{0}; // asked of the stack, which MinGW does not honour)
        char padding[64 - sizeof(std::atomic<int>)];
    };
    int bands_, lanes_, size_;
    Part parts_[kMaxRenderThreads];
};

// What a binned draw's fill reads: its bins (chunks x bandsHigh, as RenderContext::bins), shared
// setups (one list per chunk) and screen vertices; RenderContext's own for a draw filled at once, a
// waiting draw's record (RenderContext::DeferredDraw) otherwise.
struct BinnedDraw {
    const std::vector<BinEntry>* bins = nullptr;
    const std::vector<RenderContext::SharedSetup>* sharedSetups = nullptr;
    const ScreenVertex* vertices = nullptr;
    int chunks = 0, bandsHigh = 0;
    const std::vector<BinEntry>& bin(int chunk, int band) const {
        return bins[std::size_t(chunk) * std::size_t(bandsHigh) + std::size_t(band)];
    }
};

// Band `band` of a binned draw on a lane (`lane`: its counters and scratch): the band's bins of
// every chunk, in chunk order.
template <int kVaryings, class Program>
void fillBinnedBand(FrameBuffer& fb, MsaaBuffer* msaa, const BinnedDraw& draw, const DrawState& state, int band,
                    LaneState& lane, Program& program) {
    LaneBands bands{0, 1, fb.height()};
    bands.onlyBand = band;
    RenderStats sink;
    const ScreenVertex* vertices = draw.vertices;
    for (int chunk = 0; chunk < draw.chunks; ++chunk) {
        const std::vector<BinEntry>& bin = draw.bin(chunk, band);
        const RenderContext::SharedSetup* shared = draw.sharedSetups[std::size_t(chunk)].data();
        const std::size_t count = bin.size();
        for (std::size_t k = 0; k < count; ++k) {
            if (k + kPrefetchTriangles < count) {
                const BinEntry& aheadEntry = bin[k + kPrefetchTriangles];
                const std::uint32_t ahead = aheadEntry.entry;
                if (ahead & kBinShared) {
                    const TriangleSetup& s = shared[ahead & kBinIndex].setup;
                    prefetchForRead(&s);
                    prefetchForRead(&s.lowerEdge);
                    prefetchForRead(&s.value[0]);
                    prefetchForRead(&s.value[kVaryings + 1]);
                    prefetchForRead(&s.ddx[0]);
                    prefetchForRead(&s.ddx[kVaryings + 1]);
                    prefetchForRead(&s.ddy[0]);
                    prefetchForRead(&s.ddy[kVaryings + 1]);
                    prefetchForRead(&s.ddxStep[0]);
                } else {
                    for (const std::uint32_t corner : aheadEntry.corners) {
                        prefetchForRead(vertices + corner);
                        prefetchForRead(reinterpret_cast<const char*>(vertices + corner + 1) - 1);
                    }
                }
            }
            const BinEntry& binned = bin[k];
            const std::uint32_t entry = binned.entry;
            if (entry & kBinShared) {
                const RenderContext::SharedSetup& record = shared[entry & kBinIndex];
                fillSetUpTriangle<kVaryings>(fb, msaa, state, bands, lane, (entry & kBinOwner) ? lane.stats : sink,
                                             record.triangle, record.setup, program);
                continue;
            }
            const std::size_t t = entry & kBinIndex;
            const std::uint32_t* corners = binned.corners;
            // (No wireframe here: a wireframe draw runs on one lane.)
            rasterizeTriangle<kVaryings>(fb, msaa, state, bands, lane, sink, t, vertices[corners[0]], vertices[corners[1]],
                                         vertices[corners[2]], program,
                                         (entry & kBinOwner) ? LaneRole::Owner : LaneRole::Helper);
        }
    }
}

// A binned draw waiting for its pass's fill (RenderContext::deferral): its state, its program and
// the draw's stages while multisampling.
template <int kVaryings, class Program>
struct DeferredDrawOf final : RenderContext::DeferredDraw {
    DeferredDrawOf(const DrawState& s, const Program& p, const MsaaStages& m) : state(s), program(p), stages(m) {}
    void fillBand(RenderContext& ctx, int band, LaneState& laneState) override {
        const BinnedDraw draw{bins.data(), sharedSetups.data(), vertices, chunks, bandCount(ctx.target().height())};
        bool any = false;
        for (int c = 0; c < chunks && !any; ++c) any = !draw.bin(c, band).empty();
        if (!any) return;
        // The lane's own copy (per-triangle state), on its stack: lanes never write one cache line.
        Program copy = program;
        laneState.msaaStages = stages;
        fillBinnedBand<kVaryings>(ctx.target(), ctx.multisampleTarget(), draw, state, band, laneState, copy);
        // Its queued colours written before the next draw's triangles reach these pixels.
        flushFill(copy, ctx.target());
    }
    DrawState state;
    Program program;
    MsaaStages stages;
};

// A lane fills the waiting draws over this many bands of its own part at a time, draw by draw:
// each draw's texture is read for two bands before the next draw's takes its place in the cache.
// One band at a time, the spider at its own camera (five draws, five textures) took 1.05-1.07x
// the time of filling each draw at once on 2 threads; two: 0.91x; three: no better.
inline constexpr int kDeferredBatch = 2;

// Fills the waiting draws (RenderContext::deferral) on every lane: each lane takes its own part's
// bands first, the most bin entries of all the draws first, then what the others left (orderBands,
// BandQueue), kDeferredBatch of its own at a time, and fills them with every draw in submission
// order. Then their storage goes back to the spares (what their programs point to stays kept
// until the scope's end: the draw that cannot wait, which fills them first, may have its own
// inputs there).
inline void fillDeferredDraws(RenderContext& ctx) {
    RenderContext::Deferral& q = ctx.deferral;
    if (q.draws.empty()) return;
    const int bandsHigh = bandCount(ctx.target().height());
    const int lanes = ctx.threads();
    ctx.bandKeys.assign(std::size_t(bandsHigh), 0);
    for (const auto& d : q.draws) countBinEntries(ctx.bandKeys, d->bins, d->chunks, bandsHigh);
    orderBands(ctx, bandsHigh, lanes);
    BandQueue queue(bandsHigh, lanes);
    LaneState laneStates[kMaxRenderThreads];
    auto job = [&](int l) {
        for (int k = queue.next(l); k >= 0; k = queue.next(l)) {
            int batch[kDeferredBatch];
            int n = 0;
            batch[n++] = ctx.bandOrder[std::size_t(k)];
            for (int more = 0; n < kDeferredBatch && (more = queue.next(l, true)) >= 0;)
                batch[n++] = ctx.bandOrder[std::size_t(more)];
            for (const auto& d : q.draws)
                for (int i = 0; i < n; ++i) d->fillBand(ctx, batch[i], laneStates[l]);
        }
    };
    if (ThreadPool* pool = ctx.pool()) pool->run(job);
    else job(0);
    for (int l = 0; l < lanes; ++l) ctx.stats += laneStates[l].stats;
    for (auto& d : q.draws) {
        q.spareBins.push_back(std::move(d->bins));
        q.spareSetups.push_back(std::move(d->sharedSetups));
    }
    q.draws.clear();
    for (auto& v : q.heldVertices) q.spareVertices.push_back(std::move(v));
    q.heldVertices.clear();
    q.holdsCurrent = false;
}

} // namespace detail
} // namespace sr
