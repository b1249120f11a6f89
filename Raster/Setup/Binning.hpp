// Binned draws (several lanes, many triangles): each triangle screened once into the bins of the
// lanes whose bands it meets, then each lane draws its bins in submission order.
#pragma once

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
// setupTriangleCulled would make) and appends each survivor to the bins of the lanes whose bands
// it meets, marked for the lane that counts it; then every lane draws its bins chunk by chunk, so
// still in submission order. Same image, same counters.
inline constexpr std::uint32_t kBinOwner = 1u << 31; // this lane counts the triangle
inline constexpr std::uint32_t kBinClip = 1u << 30;  // crosses a clip plane: clipped by the lane
inline constexpr std::uint32_t kBinIndex = kBinClip - 1u;

inline void binTriangles(RenderContext& ctx, const DrawState& state, const Clipper& clipper, int chunk, int lanes,
                         const BandPattern* pattern, const std::uint32_t* indices, std::size_t triangleBegin,
                         std::size_t triangleEnd, RenderStats& stats) {
    const unsigned* codes = ctx.clipCodes.data();
    const SnappedVertex* snapped = ctx.snappedVertices.data();
    const int height = ctx.target().height();
    const bool multisampled = ctx.multisampleTarget() != nullptr;
    std::vector<std::uint32_t>* bins = ctx.bins.data() + std::size_t(chunk) * std::size_t(lanes);
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
        case ClipClass::Clip:
            for (int l = 0; l < lanes; ++l) bins[l].push_back(std::uint32_t(tri) | kBinClip);
            break;
        case ClipClass::Accept: {
            // Accepted: every vertex inside the clipper's guard band, which lies inside setup's
            // (kClipGuardBand < kGuardBand), so every one was snapped.
            Fixed minY = 0, maxY = 0;
            const SetupOutcome outcome =
                screenSnapped(snapped[i0], snapped[i1], snapped[i2], state.cull, multisampled, minY, maxY);
            if (outcome == SetupOutcome::Culled) ++stats.culled; // isCulled's decision too
            if (outcome != SetupOutcome::Ready || state.stopAfter == PipelineStop::Geometry) break;
            // rasterizeTriangle's decision: the owner of the first row counts it, every other lane
            // whose bands meet its rows fills them.
            int rowBegin = 0, rowEnd = 0;
            rowsOfSnappedExtent(minY, maxY, multisampled, rowBegin, rowEnd);
            const LaneBands bands{0, lanes, height, pattern};
            const int owner = bands.ownerOfRow(rowBegin);
            bins[owner].push_back(std::uint32_t(tri) | kBinOwner);
            std::uint64_t helpers = bands.lanesMeeting(rowBegin, rowEnd) & ~(std::uint64_t(1) << owner);
            for (; helpers != 0; helpers &= helpers - 1) bins[lowestSetBit(helpers)].push_back(std::uint32_t(tri));
            break;
        }
        }
    }
}

// Lane `bands.lane`'s share of a binned draw: its bins of every chunk, in chunk order.
template <int kVaryings, class Program>
void rasterBinned(RenderContext& ctx, const DrawState& state, const Clipper& clipperProto, const LaneBands& bands,
                  LaneState& lane, const std::uint32_t* indices, Program& program) {
    FrameBuffer& fb = ctx.target();
    MsaaBuffer* msaa = ctx.multisampleTarget();
    Clipper clipper = clipperProto;
    RenderStats sink;
    const ScreenVertex* vertices = ctx.screenVertices.data();
    for (int chunk = 0; chunk < bands.lanes; ++chunk) {
        const std::vector<std::uint32_t>& bin = ctx.bins[std::size_t(chunk) * std::size_t(bands.lanes) + std::size_t(bands.lane)];
        const std::size_t count = bin.size();
        for (std::size_t k = 0; k < count; ++k) {
            if (k + kPrefetchTriangles < count) {
                const std::uint32_t* ahead = indices + 3 * std::size_t(bin[k + kPrefetchTriangles] & kBinIndex);
                for (int j = 0; j < 3; ++j) {
                    prefetchForRead(vertices + ahead[j]);
                    prefetchForRead(reinterpret_cast<const char*>(vertices + ahead[j] + 1) - 1);
                }
            }
            const std::uint32_t entry = bin[k];
            const std::size_t t = entry & kBinIndex;
            const std::uint32_t i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
            if (entry & kBinClip) {
                if (bands.lane == 0) ++lane.stats.clipped;
                clipAndRasterize<kVaryings>(ctx, state, clipper, bands, lane, sink, t, i0, i1, i2, program);
                continue;
            }
            // (No wireframe here: a wireframe draw runs on one lane.)
            rasterizeTriangle<kVaryings>(fb, msaa, state, bands, lane, sink, t, vertices[i0], vertices[i1], vertices[i2],
                                         program, (entry & kBinOwner) ? LaneRole::Owner : LaneRole::Helper);
        }
    }
}

} // namespace detail
} // namespace sr
