// RenderContext: the explicit render state (target, per-draw scratch memory, statistics).
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Frame/Fxaa.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "Raster/Frame/ThreadPool.hpp"
#include "Raster/Geometry/Clipper.hpp"
#include "Raster/Geometry/Vertex.hpp"
#include "Raster/Setup/LaneBalance.hpp"
#include "Raster/Setup/TriangleSetup.hpp" // SnappedVertex

namespace sr {

struct SceneShadows;
namespace detail {
struct LaneState; // Raster/Fill/RasterizeTriangle.hpp
}

// Counters of one or more draws (reset by the owner, e.g. once per frame).
struct RenderStats {
    std::uint64_t trianglesIn = 0;      // triangles submitted
    std::uint64_t trivialRejected = 0;  // outside one clip plane (or non-finite): never set up
    std::uint64_t clipped = 0;          // went through the clipper
    std::uint64_t culled = 0;           // back/front-face culled or zero-area on the snapped grid
    std::uint64_t rasterized = 0;       // triangle setups handed to the fill
    // Triangle records built by setup, over every lane: `rasterized` on one lane; with several,
    // a triangle whose rows meet the bands of k lanes is set up by each of them (k times).
    std::uint64_t setupsBuilt = 0;
    std::uint64_t nonFinite = 0;        // dropped for a NaN/Inf position (part of trivialRejected)
    std::uint64_t fragmentsShaded = 0;  // pixels that passed the depth test and were shaded
    std::uint64_t verticesTransformed = 0; // vertex-stage runs (not counting reused vertices)
    std::uint64_t trianglesSorted = 0;     // transparent triangles sorted back to front (renderScene)
    // Milliseconds in the SSAA / MSAA resolve (MSAA's pass also clears the samples for the next
    // frame): one clock reading around each frame's resolve, none inside the fill.
    double resolveMs = 0.0;

    RenderStats& operator+=(const RenderStats& o) {
        trianglesIn += o.trianglesIn;
        trivialRejected += o.trivialRejected;
        clipped += o.clipped;
        culled += o.culled;
        rasterized += o.rasterized;
        setupsBuilt += o.setupsBuilt;
        nonFinite += o.nonFinite;
        fragmentsShaded += o.fragmentsShaded;
        verticesTransformed += o.verticesTransformed;
        trianglesSorted += o.trianglesSorted;
        resolveMs += o.resolveMs;
        return *this;
    }
};

// Most render threads a context runs (lanes of its pool).
inline constexpr int kMaxRenderThreads = 64;
static_assert(kMaxRenderThreads <= kMaxBalancedLanes, "LaneBalance holds every lane");
// Draws of at least this many triangles are binned when drawn on several lanes (see `bins`); a
// smaller one's lanes walk it whole, one fork-join instead of two. Binning every draw, not only
// those of 4,096 triangles or more, took 2 threads 0.82x [0.72, 0.97] as long on the spider close-up
// (its draws have 76-952 triangles), 0.90x [0.65, 1.05] on the built-in scene (9 interleaved rounds).
inline constexpr std::size_t kBinningMinTriangles = 64;
// A binned triangle whose rows meet this many bands or more is set up once for all of them
// (RenderContext::sharedSetups). With 2 (every triangle crossing a band edge) the bunny on 2 threads
// took 1.09x as long at 1920x1080, 1.07x at 800x600 (cull cw): a record written by one core and read
// by the other costs more than setting up a small triangle again.
inline constexpr int kSharedSetupBands = 3;

// One entry of a bin (RenderContext::bins): a triangle or shared record (detail::kBinShared,
// kBinOwner) and, for a triangle, its three vertex indices. A band's walk so reads its bins in
// order and not the index buffer at its triangles' scattered places, whose misses stalled it
// (2 threads: the bunny at 1920x1080 in 0.95-0.99x the time, MSAA 4 0.96x; the spider unchanged).
struct BinEntry {
    std::uint32_t entry = 0;
    std::uint32_t corners[3] = {};
};

// Passed explicitly to every draw (no global state). Owns scratch buffers whose capacity is
// kept from draw to draw, so a steady frame loop allocates nothing but the small records of the
// draws whose fill waits (deferral).
class RenderContext {
public:
    explicit RenderContext(FrameBuffer& target) : target_(&target) {}

    FrameBuffer& target() { return *target_; }
    void setTarget(FrameBuffer& target) { target_ = &target; }

    RenderStats stats;

    // Post-transform vertex cache of the current draw: clip-space vertex, and the screen-space
    // vertex where the clip-space one is finite with w > 0 (usable[i] != 0).
    std::vector<ClipVertex> clipVertices;
    std::vector<ScreenVertex> screenVertices;
    std::vector<std::uint8_t> usable;
    std::vector<unsigned> clipCodes; // Clipper::vertexCode of each vertex
    // snapVertex of each usable screen vertex, read by binTriangles only: made by the vertex
    // stage of a draw on several lanes that bins or whose vertices may be reused
    // (VertexCacheKey::snapped).
    std::vector<SnappedVertex> snappedVertices;

    // What the cache above holds, so that the next draw of the same vertices with the same vertex
    // program reuses it instead of transforming them again: one vertex stage per mesh, shared by
    // its draws (a mesh with many materials costs one transform, not one per material). Reuse is
    // only allowed inside a VertexReuseScope (renderScene: the meshes and the view are constant
    // there); every draw outside one runs its vertex stage and leaves `source` null.
    struct VertexCacheKey {
        const void* source = nullptr;  // the vertex data (a Mesh); null: nothing reusable
        const void* program = nullptr; // identifies the vertex program's type (its output layout)
        std::uint64_t variant = 0;     // the per-draw constants its vertex() reads (vertexVariantOf)
        std::size_t count = 0;
        int width = 0, height = 0;     // the viewport the screen vertices were made for
        bool clipFar = false;
        bool snapped = false;          // snappedVertices filled too
        bool operator==(const VertexCacheKey& o) const {
            return source == o.source && program == o.program && variant == o.variant && count == o.count &&
                   width == o.width && height == o.height && clipFar == o.clipFar && snapped == o.snapped;
        }
    };
    VertexCacheKey vertexCache;
    bool vertexReuse = false; // set by VertexReuseScope only

    // renderScene's transparent pass (Scene.cpp): each transparent triangle's draw, first index
    // and view depth, and the indices of the run being drawn. Kept between frames: a scene with
    // transparent draws sorts them every frame without allocating.
    struct TransparentTriangle {
        float w;                    // clip-space w of the centroid: the view depth
        std::uint32_t draw, first;  // the SceneDraw, and the triangle's first index in its mesh
    };
    std::vector<TransparentTriangle> transparentOrder;
    std::vector<std::uint32_t> transparentIndices;

    // The primitive stage's bins (drawLanes with several lanes): bins[c * bandCount + b] lists, in
    // submission order, the triangles of chunk c whose rows meet band b (32 rows: kBandRows;
    // detail::binTriangles). Kept between draws and frames: no allocation once they have grown. A
    // draw of fewer than binningMinTriangles triangles is not binned (every lane walks all of
    // them: one fork-join less); tests set it to bin every draw, or none.
    std::vector<std::vector<BinEntry>> bins;
    std::size_t binningMinTriangles = kBinningMinTriangles;
    // A binned draw's triangles set up once, by the lane that bins them, for the bands that fill
    // them: every piece of a clipped triangle, and a triangle whose rows meet at least
    // sharedSetupBands bands (one that meets fewer is set up for each: reading a record another
    // core wrote costs more than setting up a small triangle again). Tests lower it to 1.
    // sharedSetups[c] holds chunk c's, referred to by index from the bins (the records past the
    // draw's last are left from earlier draws). Kept between draws and frames, as the bins are.
    struct SharedSetup {
        TriangleSetup setup;
        std::size_t triangle = 0; // its index in the draw
    };
    std::vector<std::vector<SharedSetup>> sharedSetups;
    int sharedSetupBands = kSharedSetupBands;
    // A binned draw's bands in the order the lanes take them, and their sort keys
    // (detail::bandsByWork). Kept between draws, as the bins are.
    std::vector<int> bandOrder;
    std::vector<std::uint64_t> bandKeys;

    // Binned draws whose fill waits for the end of a pass (DeferredFillScope: renderScene's opaque
    // draws). Each is binned when it is drawn; at the end (detail::fillDeferredDraws) the lanes take whole
    // bands and fill each band with every waiting draw in submission order, so a pass has one
    // fork-join for its fill instead of one per draw, a band's rows stay in one core's cache for all
    // its draws, and the lanes wait for each other once. Same image and counters as drawing each at
    // once (a band's pixels see the draws in the same order). Anything the waiting draws read must
    // live until then: the bins and shared setups move into the draw's record, the screen vertices
    // it reads are kept (heldVertices) instead of being written over by a later vertex stage, and
    // what a program points to is kept by its caller (keep(): drawMesh's settings and material).
    struct DeferredDraw {
        virtual ~DeferredDraw() = default;
        // Fills band `band` of this draw on a lane (its counters and scratch: `laneState`), and
        // writes what the program's kernel queued there.
        virtual void fillBand(RenderContext& ctx, int band, detail::LaneState& laneState) = 0;
        std::vector<std::vector<BinEntry>> bins;         // as `bins`, chunks x bands
        std::vector<std::vector<SharedSetup>> sharedSetups; // as `sharedSetups`
        const ScreenVertex* vertices = nullptr;          // the screen vertices its bins index
        int chunks = 0;
    };
    // Something a waiting draw's program points to, kept until the DeferredFillScope ends (keep()).
    struct Kept {
        virtual ~Kept() = default;
    };
    struct Deferral {
        bool active = false;         // inside a DeferredFillScope on several lanes
        std::vector<std::unique_ptr<DeferredDraw>> draws; // waiting, in submission order
        std::vector<std::unique_ptr<Kept>> kept;
        // screenVertices' buffers that waiting draws read; `holdsCurrent`: one reads screenVertices.
        std::vector<std::vector<ScreenVertex>> heldVertices;
        bool holdsCurrent = false;
        // Storage of earlier frames' waiting draws, reused (no allocation once it has grown).
        std::vector<std::vector<std::vector<BinEntry>>> spareBins;
        std::vector<std::vector<std::vector<SharedSetup>>> spareSetups;
        std::vector<std::vector<ScreenVertex>> spareVertices;
        void (*fill)(RenderContext&) = nullptr; // fills and releases the waiting draws (detail::fillDeferredDraws)
        // The last of `spares` (moved out), or an empty one.
        template <class T>
        static T takeSpare(std::vector<T>& spares) {
            if (spares.empty()) return T{};
            T spare = std::move(spares.back());
            spares.pop_back();
            return spare;
        }
    };
    Deferral deferral;
    // Keeps `object` (what a program of a draw that may wait points to) until the DeferredFillScope
    // ends, and returns it.
    template <class T>
    T& keep(std::unique_ptr<T> object) {
        T& kept = *object;
        deferral.kept.push_back(std::move(object));
        return kept;
    }
    // Fills the waiting draws, if any (the end of a DeferredFillScope; drawLanes before a draw
    // that does not wait).
    void fillDeferred() {
        if (!deferral.draws.empty()) deferral.fill(*this);
    }
    // Before a vertex stage writes screenVertices: a buffer a waiting draw reads is set aside
    // (moving a vector keeps its elements where they are) and a spare one takes its place.
    void releaseHeldVertices() {
        if (!deferral.holdsCurrent) return;
        deferral.heldVertices.push_back(std::move(screenVertices));
        screenVertices = Deferral::takeSpare(deferral.spareVertices);
        deferral.holdsCurrent = false;
    }

    // Which lane fills which band of rows in a split draw, weighted by the lanes' measured speed
    // (reset to equal weights by setThreads; tests fix it). The image and the counters do not
    // depend on it.
    LaneBalance laneBalance;

    // Render threads (1..kMaxRenderThreads; 0 or less means 1). More than one starts a
    // persistent pool that drawProgram() splits its work over; the image is the same.
    void setThreads(int threads) {
        threads = std::clamp(threads, 1, kMaxRenderThreads);
        if (threads == this->threads()) return;
        laneBalance.reset(threads);
        pool_.reset();
        if (threads > 1) pool_ = std::make_unique<ThreadPool>(threads);
    }
    int threads() const { return pool_ ? pool_->lanes() : 1; }
    ThreadPool* pool() { return pool_.get(); }

    // Clears the target's colour and depth, split by rows over the render threads. While
    // multisampling, the samples instead (the target's rows are then only the shading scratch
    // and the resolve's output) as a fast clear (MsaaBuffer::clearRowsLazily), and nothing when
    // they are known to be clear already (a resolve that cleared them: MsaaBuffer::isCleared).
    void clearTarget(Pixel colour, float depth) {
        FrameBuffer& fb = *target_;
        MsaaBuffer* msaaTarget = multisampleTarget();
        if (msaaTarget && msaaTarget->isCleared(colour, depth)) return;
        const int lanes = threads(), height = fb.height(), width = fb.width();
        auto job = [&](int lane) {
            const int y0 = height * lane / lanes, y1 = height * (lane + 1) / lanes;
            if (y0 >= y1) return;
            if (msaaTarget) {
                msaaTarget->clearRowsLazily(y0, y1, colour, depth);
                return;
            }
            fillWords(fb.colorRow(y0), std::size_t(y1 - y0) * std::size_t(width), colour);
            fillWords(fb.depthRow(y0), std::size_t(y1 - y0) * std::size_t(width), depth);
        };
        if (pool_) pool_->run(job);
        else job(0);
        if (msaaTarget) msaaTarget->markCleared(colour, depth);
    }

    // Supersampling's sample target (renderSceneFrame with ssaa > 1): factor x factor times the
    // output's size while a supersampled frame is drawn, released by the next frame without SSAA
    // (memory only while supersampling).
    FrameBuffer supersampleTarget;

    // The shadow maps of the last frame drawn with shadows (renderSceneFrame; Raster/Shade/Shadow.hpp),
    // kept for their memory; reset by a frame without them.
    std::shared_ptr<SceneShadows> shadows;

    // Multisampling's sample target (renderSceneFrame with msaa > 1). While `multisampling` is
    // set and it has the target's size, every draw fills its samples instead of the target (the
    // target's colour rows serve as the per-pixel shading scratch) until the frame resolves it.
    MsaaBuffer msaa;
    bool multisampling = false;
    // FXAA's luma and filtered pixels (renderSceneFrame with AntiAliasing::fxaa()); kept between
    // frames, released when the mode changes.
    FxaaScratch fxaa;
    MsaaBuffer* multisampleTarget() {
        const bool active = multisampling && msaa.width() == target_->width() && msaa.height() == target_->height() &&
                            !msaa.empty();
        return active ? &msaa : nullptr;
    }

    // Runs job(rowBegin, rowEnd) over rows [0, height) split evenly over the render threads.
    template <class Job>
    void forRows(int height, Job&& job) {
        forBands(height, [&](int, int y0, int y1) { job(y0, y1); });
    }
    // The same with the band's number (0 .. threads() - 1, in row order): job(band, y0, y1).
    template <class Job>
    void forBands(int height, Job&& job) {
        const int lanes = threads();
        auto run = [&](int lane) {
            const int y0 = height * lane / lanes, y1 = height * (lane + 1) / lanes;
            if (y0 < y1) job(lane, y0, y1);
        };
        if (pool_) pool_->run(run);
        else run(0);
    }

private:
    FrameBuffer* target_;
    std::unique_ptr<ThreadPool> pool_;
};

// Allows draws to share the post-transform vertex cache while it lives (see
// RenderContext::vertexCache); the caller promises that the vertex data and the view do not
// change meanwhile. The cache is forgotten when the scope opens and closes.
class VertexReuseScope {
public:
    explicit VertexReuseScope(RenderContext& ctx) : ctx_(ctx) {
        ctx_.vertexCache = {};
        ctx_.vertexReuse = true;
    }
    ~VertexReuseScope() {
        ctx_.vertexCache = {};
        ctx_.vertexReuse = false;
    }
    VertexReuseScope(const VertexReuseScope&) = delete;
    VertexReuseScope& operator=(const VertexReuseScope&) = delete;

private:
    RenderContext& ctx_;
};

// Lets the binned draws on several lanes wait (RenderContext::deferral) until finish() or the
// scope's end, which fill them all. The caller promises that nothing else draws into the target
// meanwhile (a draw that cannot wait fills the waiting ones first) and keeps what their programs
// point to alive (or passes it to RenderContext::keep()). Not while multisampling: a band's
// samples are four to eight times its pixels' bytes, and filling the draws band by band took the
// spider close-up 1.03-1.04x the time of filling each at once (MSAA 4, 2 threads).
class DeferredFillScope {
public:
    explicit DeferredFillScope(RenderContext& ctx) : ctx_(ctx) {
        ctx_.deferral.active = ctx_.threads() > 1 && !ctx_.multisampleTarget();
    }
    ~DeferredFillScope() { finish(); }
    bool active() const { return ctx_.deferral.active; }
    void finish() {
        ctx_.fillDeferred();
        ctx_.deferral.kept.clear();
        ctx_.deferral.active = false;
    }
    DeferredFillScope(const DeferredFillScope&) = delete;
    DeferredFillScope& operator=(const DeferredFillScope&) = delete;

private:
    RenderContext& ctx_;
};

} // namespace sr
