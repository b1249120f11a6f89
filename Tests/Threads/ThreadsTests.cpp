// Multi-threaded rendering: images, depth and counters bit-identical to one thread, for many scenes and settings.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <numeric>
#include <random>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Frame/MeshRenderer.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "Raster/Frame/Scene.hpp"
#include "Raster/Frame/ThreadPool.hpp"
#include "Raster/Pipeline.hpp"

using namespace sr;

namespace {

struct Frame {
    FrameBuffer fb;
    RenderStats stats;
};

bool sameStats(const RenderStats& a, const RenderStats& b) {
    return a.trianglesIn == b.trianglesIn && a.trivialRejected == b.trivialRejected && a.clipped == b.clipped &&
           a.culled == b.culled && a.rasterized == b.rasterized && a.nonFinite == b.nonFinite &&
           a.fragmentsShaded == b.fragmentsShaded;
}

// Byte comparison of colour and depth (depth compared as bits: -0 vs +0 or NaN patterns count).
std::size_t differingPixels(const FrameBuffer& a, const FrameBuffer& b) {
    std::size_t n = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const float da = a.depth(x, y), db = b.depth(x, y);
            n += a.pixel(x, y) != b.pixel(x, y) || std::memcmp(&da, &db, sizeof da) != 0;
        }
    return n;
}

// binMin: RenderContext::binningMinTriangles (0: every draw on several lanes binned); weights:
// the lanes' bands fixed to these weights (LaneBalance::fix) instead of adapting;
// sharedSetupBands: RenderContext's.
Frame renderDefault(const app::SceneOptions& options, int threads, const RenderSettings& settings,
                    std::size_t binMin = kBinningMinTriangles, const std::vector<int>& weights = {},
                    int sharedSetupBands = kSharedSetupBands) {
    static auto scene = app::loadScene(app::SceneOptions{});
    REQUIRE(scene.ok());
    const FrameView view =
        app::makeFrameView(app::resolveCamera(options, scene.value()), options.width, options.height, options.light,
                            scene.value().lights);
    Frame f{FrameBuffer(options.width, options.height), {}};
    RenderContext ctx(f.fb);
    ctx.setThreads(threads);
    ctx.binningMinTriangles = binMin;
    ctx.sharedSetupBands = sharedSetupBands;
    if (!weights.empty()) ctx.laneBalance.fix(weights.data(), threads);
    REQUIRE(ctx.threads() == std::max(threads, 1));
    app::renderFrame(ctx, scene.value(), view, settings);
    app::renderFrame(ctx, scene.value(), view, settings); // a second frame reuses every buffer
    f.stats = ctx.stats;
    return f;
}

// One varying: the triangle's id, turned into a colour (ties between ids show in the image).
struct TieProgram {
    static constexpr int kVaryings = 1;
    const std::vector<Vec4>* positions;
    void vertex(std::size_t i, ClipVertex& out) const {
        out.position = (*positions)[i];
        out.varyings[0] = float(i / 3);
    }
    void triangle(std::size_t, const TriangleSetup&) {}
    Pixel fragment(const Fragment<1>& f) const {
        const std::uint32_t id = std::uint32_t(f.varyings[0] + 0.5f);
        return packBgra(std::uint8_t(id * 37), std::uint8_t(id * 91), std::uint8_t(id * 13));
    }
};

// How a draw on several lanes walks its triangles: Plain (unbinned: every lane walks every
// triangle, setting up those its bands meet), Binned (the default sharing: clipped pieces and
// triangles meeting 3 bands or more set up once), Shared (binned, every triangle set up once).
enum class Walk { Plain, Binned, Shared };
constexpr std::size_t kNeverBinned = std::numeric_limits<std::size_t>::max(); // binningMinTriangles
void setWalk(RenderContext& ctx, Walk walk) {
    ctx.binningMinTriangles = walk == Walk::Plain ? kNeverBinned : 0;
    if (walk == Walk::Shared) ctx.sharedSetupBands = 1;
}

// A frame on `threads` lanes walking `walk` into `out`, cleared to `clear`, multisampled when
// samples > 1 (then resolved into `out`, in linear light when `linear`); draws(ctx) draws it.
template <class Draws>
RenderStats frameOfDraws(FrameBuffer& out, int samples, int threads, Walk walk, Pixel clear, bool linear, Draws&& draws) {
    RenderContext ctx(out);
    ctx.setThreads(threads);
    setWalk(ctx, walk);
    if (samples > 1) {
        REQUIRE(ctx.msaa.resize(out.width(), out.height(), samples));
        ctx.multisampling = true;
    }
    ctx.clearTarget(clear, FrameBuffer::kFarDepth);
    draws(ctx);
    if (samples > 1) {
        resolveMsaaRows(ctx.msaa, out, 0, out.height(), linear);
        ctx.multisampling = false;
    }
    return ctx.stats;
}

// One TieProgram draw of `indices` over `positions` with depth mode `depth`, as frameOfDraws.
RenderStats tieFrame(const std::vector<Vec4>& positions, const std::vector<std::uint32_t>& indices, int samples,
                     DepthMode depth, int threads, Walk walk, FrameBuffer& out) {
    return frameOfDraws(out, samples, threads, walk, packBgra(0, 0, 0), false, [&](RenderContext& ctx) {
        DrawState state;
        state.depth = depth;
        TieProgram program{&positions};
        drawProgram<1>(ctx, state, positions.size(), indices.data(), indices.size(), program);
    });
}

// render(threads, walk, out) on 2, 3 and 8 lanes, every walk, gives one thread's `reference` and
// counters `one` (colour, depth bits; set up once: a setup per rasterised triangle).
template <class Render>
void expectOneThreadsFrame(const FrameBuffer& reference, const RenderStats& one, Render&& render) {
    for (int threads : {2, 3, 8})
        for (Walk walk : {Walk::Plain, Walk::Binned, Walk::Shared}) {
            INFO(threads << " threads, walk " << int(walk));
            FrameBuffer fb(reference.width(), reference.height());
            const RenderStats many = render(threads, walk, fb);
            CHECK(differingPixels(reference, fb) == 0);
            CHECK(sameStats(one, many));
            if (walk == Walk::Shared) CHECK(many.setupsBuilt == one.rasterized);
        }
}

// Uneven band weights (each list sums to BandPattern::kBandsPerLane per lane).
const std::vector<int> kSkewedWeights[] = {{15, 1}, {1, 15}, {11, 5}, {1, 1, 22}, {10, 4, 10}, {2, 9, 9, 9, 11}};

} // namespace

TEST_CASE("band patterns: equal weights interleave, uneven ones keep their counts and spread out", "[threads]") {
    for (int lanes : {1, 2, 3, 5, 64}) {
        const std::vector<int> equal(std::size_t(lanes), BandPattern::kBandsPerLane);
        const BandPattern p = spreadBands(equal.data(), lanes);
        REQUIRE(p.period == BandPattern::kBandsPerLane * lanes);
        // Every band a target can have (the 64-lane period is longer than that).
        for (int b = 0; b < BandPattern::kMaxBands; ++b) CHECK(p.ownerOfBand(b) == b % lanes);
    }
    for (const std::vector<int>& weights : kSkewedWeights) {
        const int lanes = int(weights.size());
        const BandPattern p = spreadBands(weights.data(), lanes);
        INFO(lanes << " lanes, lane 0 weight " << weights[0]);
        std::vector<int> count(std::size_t(lanes), 0);
        for (int i = 0; i < p.period; ++i) {
            const int l = p.owners[std::size_t(i)];
            REQUIRE(l < lanes);
            ++count[std::size_t(l)];
            // Spread: after every slot each lane holds its share of the slots so far within one
            // band (a pattern that gave lane 0 its 11 bands first would be 3.4 bands off).
            for (int k = 0; k < lanes; ++k)
                CHECK(std::fabs(count[std::size_t(k)] - double(weights[std::size_t(k)]) * (i + 1) / p.period) < 1.0);
        }
        for (int l = 0; l < lanes; ++l) CHECK(count[std::size_t(l)] == weights[std::size_t(l)]);
        for (int b = 0; b < BandPattern::kMaxBands; ++b) CHECK(p.ownerOfBand(b) == p.owners[std::size_t(b % p.period)]);
    }
}

TEST_CASE("weightedPart: the lanes' parts of the vertices and triangles follow their weights", "[threads]") {
    // Exhaustive over these counts and weights: the parts follow each other in lane order, cover
    // [0, count) once, and each is its weight's share of the count, to within one item.
    const std::vector<std::vector<int>> weightSets = {{8, 8},     {3, 13},     {13, 3},
                                                      {1, 15},    {5, 5, 14},  {1, 1, 1, 1, 1, 1, 1, 57}};
    for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(1000), std::size_t(34835),
                              std::size_t(69666)}) {
        for (const std::vector<int>& weights : weightSets) {
            const int lanes = int(weights.size());
            int total = 0;
            for (int w : weights) total += w;
            std::size_t next = 0;
            for (int l = 0; l < lanes; ++l) {
                CAPTURE(count, lanes, l);
                const ItemRange part = weightedPart(count, l, lanes, weights.data());
                REQUIRE(part.begin == next);
                REQUIRE(part.end >= part.begin);
                const double share = double(count) * weights[std::size_t(l)] / total;
                REQUIRE(std::fabs(double(part.end - part.begin) - share) <= 1.0);
                next = part.end;
                const ItemRange equal = weightedPart(count, l, lanes, nullptr);
                REQUIRE(equal.begin == count * std::size_t(l) / std::size_t(lanes));
                REQUIRE(equal.end == count * std::size_t(l + 1) / std::size_t(lanes));
            }
            REQUIRE(next == count);
        }
    }
}

TEST_CASE("lane balance: the weights follow the lanes' speed and stay put when fixed", "[threads]") {
    // Lane l takes cost[l] seconds per band of each period: busy time = weight * cost. The
    // weights that equalise the busy times of 1 : 2 are 2/3 and 1/3 of 16 bands, 10.7 : 5.3.
    auto settle = [](LaneBalance& balance, const std::vector<double>& cost, int draws) {
        for (int d = 0; d < draws; ++d) {
            std::vector<double> busy(cost.size());
            for (std::size_t l = 0; l < cost.size(); ++l) busy[l] = balance.weight(int(l)) * cost[l];
            balance.record(busy.data());
        }
    };
    LaneBalance balance;
    balance.reset(2);
    CHECK(balance.weight(0) == 8);
    CHECK(balance.weight(1) == 8);
    settle(balance, {1e-4, 2e-4}, 200);
    CHECK(balance.weight(0) == 11);
    CHECK(balance.weight(1) == 5);
    // The other way round, and three lanes with the middle one three times slower.
    settle(balance, {3e-4, 1e-4}, 200);
    CHECK(balance.weight(0) == 4);
    CHECK(balance.weight(1) == 12);
    balance.reset(3);
    settle(balance, {1e-4, 3e-4, 1e-4}, 200);
    CHECK(balance.weight(0) == 10);
    CHECK(balance.weight(1) == 4);
    CHECK(balance.weight(2) == 10);
    // Equal speeds keep equal weights (the hysteresis holds them against small noise too).
    balance.reset(2);
    settle(balance, {1e-4, 1.03e-4}, 200);
    CHECK(balance.weight(0) == 8);
    // A lane that did nothing counts as fast, not infinitely so: every lane keeps a band.
    settle(balance, {1e-4, 0.0}, 200);
    CHECK(balance.weight(0) >= 1);
    CHECK(balance.weight(0) + balance.weight(1) == 16);
    // Fixed weights do not move.
    const int fixedWeights[] = {3, 13};
    balance.fix(fixedWeights, 2);
    settle(balance, {1e-4, 5e-4}, 200);
    CHECK(balance.weight(0) == 3);
    CHECK(balance.pattern().owners[0] == 1);
}

TEST_CASE("thread pool runs every lane once per job and can be reused", "[threads]") {
    for (int lanes : {1, 2, 3, 8}) {
        ThreadPool pool(lanes);
        REQUIRE(pool.lanes() == lanes);
        std::vector<int> hits(std::size_t(lanes), 0);
        for (int round = 0; round < 50; ++round) {
            auto job = [&](int lane) { ++hits[std::size_t(lane)]; };
            pool.run(job);
        }
        for (int h : hits) CHECK(h == 50);
    }
    // The hardware threads this process may use: at least one, at most the machine's.
    const int usable = ThreadPool::usableHardwareThreads();
    CHECK(usable >= 1);
    if (std::thread::hardware_concurrency() > 0) CHECK(usable <= int(std::thread::hardware_concurrency()));
    // The threads worth starting: at least 1, at most the usable hardware threads (0: unknown).
    CHECK(ThreadPool::threadsWorthStarting(8, 2) == 2);
    CHECK(ThreadPool::threadsWorthStarting(2, 8) == 2);
    CHECK(ThreadPool::threadsWorthStarting(0, 4) == 1);
    CHECK(ThreadPool::threadsWorthStarting(-3, 4) == 1);
    CHECK(ThreadPool::threadsWorthStarting(3, 0) == 3);
    CHECK(ThreadPool::threadsWorthStarting(5, 1) == 1);
    // More lanes than hardware threads: no polling, and still every lane once per job.
    for (int hardware : {0, 1, 2, 4, 8}) {
        CAPTURE(hardware);
        ThreadPool pool(4, hardware);
        CHECK(pool.polls() == (hardware == 0 || hardware >= 4));
        std::vector<int> hits(4, 0);
        for (int round = 0; round < 50; ++round) {
            auto job = [&](int lane) { ++hits[std::size_t(lane)]; };
            pool.run(job);
        }
        for (int h : hits) CHECK(h == 50);
    }
}

TEST_CASE("default scene: N threads give the single-threaded image, depth and counters", "[threads]") {
    struct Case {
        int width, height;
        ShadingMode shading;
        CullMode cull;
        PerspectiveMode persp;
        TextureFilter filter;
    };
    const Case cases[] = {
        {160, 120, ShadingMode::Phong, CullMode::None, PerspectiveMode::Exact, TextureFilter::Bilinear},
        {160, 120, ShadingMode::Gouraud, CullMode::CW, PerspectiveMode::Affine, TextureFilter::Trilinear},
        {160, 120, ShadingMode::Flat, CullMode::CCW, PerspectiveMode::Affine, TextureFilter::Nearest},
        {160, 120, ShadingMode::Unlit, CullMode::None, PerspectiveMode::Affine, TextureFilter::Bilinear},
        {333, 77, ShadingMode::Phong, CullMode::CW, PerspectiveMode::Exact, TextureFilter::Bilinear},
        {17, 301, ShadingMode::Phong, CullMode::None, PerspectiveMode::Exact, TextureFilter::Trilinear},
        {1, 1, ShadingMode::Phong, CullMode::None, PerspectiveMode::Exact, TextureFilter::Bilinear},
        {5, 3, ShadingMode::Gouraud, CullMode::None, PerspectiveMode::Exact, TextureFilter::Bilinear},
    };
    for (const Case& c : cases) {
        app::SceneOptions options;
        options.width = c.width;
        options.height = c.height;
        options.shading = c.shading;
        options.cull = c.cull;
        options.perspective = c.persp;
        options.filter = c.filter;
        const RenderSettings settings = app::makeRenderSettings(options);
        const Frame one = renderDefault(options, 1, settings);
        CHECK(one.stats.setupsBuilt == one.stats.rasterized); // one lane sets each triangle up once
        for (int threads : {2, 3, 4, 7}) {
            INFO(c.width << "x" << c.height << " " << shadingModeName(c.shading) << " cull " << cullModeName(c.cull)
                          << " " << perspectiveModeName(c.persp) << " " << filterName(c.filter) << ", " << threads
                          << " threads");
            const Frame many = renderDefault(options, threads, settings);
            CHECK(differingPixels(one.fb, many.fb) == 0);
            CHECK(sameStats(one.stats, many.stats));
            // Several lanes set a triangle up once per lane whose bands it meets: at least once,
            // at most once per lane.
            CHECK(many.stats.setupsBuilt >= many.stats.rasterized);
            CHECK(many.stats.setupsBuilt <= std::uint64_t(threads) * many.stats.rasterized);
            if (c.height >= 2 * detail::LaneBands::kBandRows && c.width > 100)
                CHECK(many.stats.setupsBuilt > many.stats.rasterized); // triangles crossing bands
            // Every draw binned (by default the built-in scene's smallest are not).
            const Frame binned = renderDefault(options, threads, settings, 0);
            CHECK(differingPixels(one.fb, binned.fb) == 0);
            CHECK(sameStats(one.stats, binned.stats));
            // Binned, every triangle set up once (RenderContext::sharedSetupBands 1).
            const Frame shared = renderDefault(options, threads, settings, 0, {}, 1);
            CHECK(differingPixels(one.fb, shared.fb) == 0);
            CHECK(sameStats(one.stats, shared.stats));
            CHECK(shared.stats.setupsBuilt == shared.stats.rasterized);
        }
        // Bands weighted unevenly (LaneBalance), plain and binned: a lane with one band in 16,
        // a lane with most of them, a lane whose only band may lie below a small target.
        for (const std::vector<int>& weights : kSkewedWeights) {
            const int threads = int(weights.size());
            INFO(c.width << "x" << c.height << " " << shadingModeName(c.shading) << ", weights " << weights[0] << "/"
                          << weights[1] << " over " << threads << " threads");
            for (std::size_t binMin : {kNeverBinned, std::size_t(0)}) {
                const Frame skewed = renderDefault(options, threads, settings, binMin, weights);
                CHECK(differingPixels(one.fb, skewed.fb) == 0);
                CHECK(sameStats(one.stats, skewed.stats));
            }
        }
    }
}

TEST_CASE("random triangle soup with exact depth ties: submission order survives the bands", "[threads]") {
    // Coplanar overlapping triangles of different colours tie exactly in depth; the strict depth
    // test keeps the first one drawn, so any reordering across threads would change the image.
    // Some triangles straddle the near plane (clipped) or the screen edges, some are degenerate.
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> xy(-1.6f, 1.6f), z(0.05f, 1.3f);
    const int kTriangles = 3000;
    std::vector<Vec4> positions;
    std::vector<std::uint32_t> indices;
    for (int t = 0; t < kTriangles; ++t) {
        const float depth = (t % 7 == 0) ? 0.5f : z(rng); // every 7th shares one plane
        for (int k = 0; k < 3; ++k) {
            const float w = 1.0f;
            positions.push_back({xy(rng) * w, xy(rng) * w, depth * w, w});
            indices.push_back(std::uint32_t(positions.size() - 1));
        }
        if (t % 13 == 0) positions.back() = positions[positions.size() - 2];                 // degenerate
        if (t % 11 == 5 && t % 7 != 0) positions[positions.size() - 3].z = 1.25f; // in front of the near plane
    }
    // The partial pipelines too (the bench's stage times): their counters must match as well.
    for (CullMode cull : {CullMode::None, CullMode::CW}) {
        for (auto [depth, stop] : {std::pair{DepthMode::TestWrite, PipelineStop::Fill}, std::pair{DepthMode::Off, PipelineStop::Fill},
                                   std::pair{DepthMode::TestWrite, PipelineStop::Setup},
                                   std::pair{DepthMode::TestWrite, PipelineStop::Geometry}}) {
            DrawState state;
            state.cull = cull;
            state.depth = depth;
            state.stopAfter = stop;
            FrameBuffer reference(203, 157);
            RenderContext ref(reference);
            reference.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
            TieProgram program{&positions};
            drawProgram<1>(ref, state, positions.size(), indices.data(), indices.size(), program);
            REQUIRE(ref.stats.clipped > 100);
            if (stop >= PipelineStop::Setup) REQUIRE(ref.stats.rasterized > 1000);
            auto draw = [&](int threads, Walk walk, const int* weights) {
                FrameBuffer fb(203, 157);
                RenderContext ctx(fb);
                ctx.setThreads(threads);
                setWalk(ctx, walk);
                if (weights) ctx.laneBalance.fix(weights, threads);
                ctx.clearTarget(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
                TieProgram copy{&positions};
                drawProgram<1>(ctx, state, positions.size(), indices.data(), indices.size(), copy);
                CHECK(differingPixels(reference, fb) == 0);
                CHECK(sameStats(ref.stats, ctx.stats));
                return ctx.stats.setupsBuilt;
            };
            const std::uint64_t once = stop >= PipelineStop::Setup ? ref.stats.rasterized : 0u;
            for (int threads : {2, 3, 5}) {
                INFO("cull " << cullModeName(cull) << ", depth mode " << int(depth) << ", stop " << int(stop) << ", "
                             << threads << " threads");
                const std::uint64_t plain = draw(threads, Walk::Plain, nullptr);
                const std::uint64_t binned = draw(threads, Walk::Binned, nullptr);
                CHECK(draw(threads, Walk::Shared, nullptr) == once);
                if (stop >= PipelineStop::Setup) {
                    CHECK(plain > once); // triangles set up by each lane whose bands they meet
                    CHECK(binned >= once);
                    CHECK(binned < plain); // clipped ones set up once, large ones on 3 lanes or more too
                }
            }
            for (const std::vector<int>& weights : kSkewedWeights) {
                const int threads = int(weights.size());
                INFO("cull " << cullModeName(cull) << ", depth mode " << int(depth) << ", stop " << int(stop) << ", "
                             << threads << " threads, weights " << weights[0] << "/" << weights[1]);
                draw(threads, Walk::Plain, weights.data());
                draw(threads, Walk::Binned, weights.data());
                CHECK(draw(threads, Walk::Shared, weights.data()) == once);
            }
        }
    }
}

TEST_CASE("multisampled soup: 2, 3 and 8 threads, plain, binned and set up once, give one thread's samples",
          "[threads][msaa]") {
    // 1,500 triangles of random sizes (a tenth crossing the near plane, some degenerate, every
    // 7th in one depth plane: exact ties, so any reordering within a band shows), drawn into 2, 4
    // and 8 samples with the depth written, only tested, and off; compared resolved (colour and
    // depth bits) and by counters. Sampled with a fixed seed.
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> centre(-1.3f, 1.3f), size(0.0f, 1.0f), z(0.05f, 0.95f);
    std::vector<Vec4> positions;
    std::vector<std::uint32_t> indices;
    for (int t = 0; t < 1500; ++t) {
        const float cx = centre(rng), cy = centre(rng), r = size(rng) * size(rng) * size(rng) * 2.0f;
        const float depth = t % 7 == 0 ? 0.5f : z(rng);
        for (int k = 0; k < 3; ++k) {
            positions.push_back({cx + r * (2 * size(rng) - 1), cy + r * (2 * size(rng) - 1), depth, 1.0f});
            indices.push_back(std::uint32_t(positions.size() - 1));
        }
        if (t % 10 == 3) positions[positions.size() - 2].z = 1.4f; // in front of the near plane
        if (t % 13 == 0) positions.back() = positions[positions.size() - 2];
    }
    constexpr int kWidth = 131, kHeight = 203;
    for (int samples : {2, 4, 8})
        for (DepthMode depth : {DepthMode::TestWrite, DepthMode::Test, DepthMode::Off}) {
            INFO(samples << " samples, depth mode " << int(depth));
            auto render = [&](int threads, Walk walk, FrameBuffer& out) {
                return tieFrame(positions, indices, samples, depth, threads, walk, out);
            };
            FrameBuffer reference(kWidth, kHeight);
            const RenderStats one = render(1, Walk::Plain, reference);
            REQUIRE(one.clipped > 100);
            REQUIRE(one.rasterized > 1000);
            expectOneThreadsFrame(reference, one, render);
        }
}

TEST_CASE("tiny triangles on band edges, triangles larger than the frame and past the guard band: one thread's image",
          "[threads][clip]") {
    // Sub-pixel and few-pixel triangles centred on the rows where one 32-row band ends and the
    // next begins (LaneBands::kBandRows), triangles whose vertices lie beyond the frame on every
    // side (accepted: each meets every band), and triangles with a vertex far past the guard band
    // (clipped against it, their pieces set up once at binning), in random depths with every 5th
    // in one plane (exact ties keep the first drawn). One sample and 4, depth written and off;
    // compared with one thread by colour, depth bits and counters. Sampled with a fixed seed.
    constexpr int kWidth = 160, kHeight = 150;
    static_assert(kHeight > 4 * detail::LaneBands::kBandRows, "five bands");
    std::mt19937 rng(777);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), z(0.05f, 0.95f);
    auto ndcX = [](float px) { return px / kWidth * 2.0f - 1.0f; };
    auto ndcY = [](float py) { return 1.0f - py / kHeight * 2.0f; };
    std::vector<Vec4> positions;
    std::vector<std::uint32_t> indices;
    int tiny = 0, huge = 0, beyond = 0;
    for (int t = 0; t < 900; ++t) {
        const float depth = t % 5 == 0 ? 0.5f : z(rng);
        Vec4 v[3];
        if (t % 3 != 2) { // tiny, on a band edge
            const float cx = unit(rng) * kWidth;
            const float cy = float(detail::LaneBands::kBandRows * (1 + int(unit(rng) * 4.0f))) + (unit(rng) - 0.5f) * 2.0f;
            const float r = t % 2 == 0 ? 0.4f : 3.0f;
            for (Vec4& p : v) p = {ndcX(cx + r * (2 * unit(rng) - 1)), ndcY(cy + r * (2 * unit(rng) - 1)), depth, 1.0f};
            ++tiny;
        } else if (t % 9 == 2) { // larger than the frame: every vertex outside it, inside the guard band
            for (Vec4& p : v) p = {(unit(rng) < 0.5f ? -1 : 1) * (1.5f + 3 * unit(rng)), 6 * unit(rng) - 3, depth, 1.0f};
            ++huge;
        } else { // one vertex far past the guard band (tens of millions of pixels away)
            for (Vec4& p : v) p = {2 * unit(rng) - 1, 2 * unit(rng) - 1, depth, 1.0f};
            v[t % 3] = {(unit(rng) < 0.5f ? -1 : 1) * 4e5f, 8e5f * unit(rng) - 4e5f, depth, 1.0f};
            ++beyond;
        }
        for (const Vec4& p : v) {
            positions.push_back(p);
            indices.push_back(std::uint32_t(positions.size() - 1));
        }
    }
    REQUIRE((tiny > 500 && huge > 20 && beyond > 150));
    for (int samples : {1, 4})
        for (DepthMode depth : {DepthMode::TestWrite, DepthMode::Off}) {
            INFO(samples << " samples, depth mode " << int(depth));
            auto render = [&](int threads, Walk walk, FrameBuffer& out) {
                return tieFrame(positions, indices, samples, depth, threads, walk, out);
            };
            FrameBuffer reference(kWidth, kHeight);
            const RenderStats one = render(1, Walk::Plain, reference);
            REQUIRE(one.clipped >= std::uint64_t(beyond)); // every one past the guard band is clipped
            REQUIRE(one.rasterized > 400);
            expectOneThreadsFrame(reference, one, render);
        }
}

TEST_CASE("transparent soup: blended in submission order within each band, for any thread count and walk",
          "[threads][transparency]") {
    // 200 opaque triangles (depth written), then 600 transparent ones over them (alpha 0.4,
    // depth tested, not written): a pixel's colour depends on the order its transparent
    // triangles are blended in, so any reordering within a band shows. Some triangles cross the
    // near plane, some are degenerate; one sample and 4, display and linear blending; compared
    // with one thread by colour, depth bits and counters. Sampled with a fixed seed.
    std::mt19937 rng(5150);
    std::uniform_real_distribution<float> centre(-1.2f, 1.2f), unit(0.0f, 1.0f), z(0.05f, 0.95f);
    std::vector<Vec4> positions;
    std::vector<std::uint32_t> opaque, glass;
    for (int t = 0; t < 800; ++t) {
        const float cx = centre(rng), cy = centre(rng), r = 0.05f + 0.6f * unit(rng) * unit(rng);
        const float depth = z(rng);
        for (int k = 0; k < 3; ++k) {
            positions.push_back({cx + r * (2 * unit(rng) - 1), cy + r * (2 * unit(rng) - 1), depth, 1.0f});
            (t < 200 ? opaque : glass).push_back(std::uint32_t(positions.size() - 1));
        }
        if (t % 10 == 3) positions[positions.size() - 2].z = 1.4f; // in front of the near plane
        if (t % 17 == 0) positions.back() = positions[positions.size() - 2];
    }
    constexpr int kWidth = 157, kHeight = 141;
    auto render = [&](int samples, bool linear, int threads, Walk walk, const std::vector<std::uint32_t>& transparent,
                      FrameBuffer& out) {
        return frameOfDraws(out, samples, threads, walk, packBgra(30, 60, 90), linear, [&](RenderContext& ctx) {
            DrawState solid;
            solid.depth = DepthMode::TestWrite;
            TieProgram first{&positions};
            drawProgram<1>(ctx, solid, positions.size(), opaque.data(), opaque.size(), first);
            DrawState blended;
            blended.depth = DepthMode::Test;
            blended.blendAlpha = 0.4f;
            blended.linearBlend = linear;
            TieProgram second{&positions};
            drawProgram<1>(ctx, blended, positions.size(), transparent.data(), transparent.size(), second);
        });
    };
    // The transparent triangles in the opposite order (each keeps its vertices' winding).
    std::vector<std::uint32_t> reversed;
    for (std::size_t t = glass.size() / 3; t-- > 0;) reversed.insert(reversed.end(), glass.begin() + 3 * t, glass.begin() + 3 * t + 3);
    for (int samples : {1, 4})
        for (bool linear : {false, true}) {
            INFO(samples << " samples, " << (linear ? "linear" : "display") << " blending");
            FrameBuffer reference(kWidth, kHeight), backwards(kWidth, kHeight);
            const RenderStats one = render(samples, linear, 1, Walk::Plain, glass, reference);
            REQUIRE(one.clipped > 50);
            REQUIRE(one.rasterized > 600);
            // The scene tells the orders apart: drawn back to front, hundreds of pixels change.
            render(samples, linear, 1, Walk::Plain, reversed, backwards);
            REQUIRE(differingPixels(reference, backwards) > 500);
            expectOneThreadsFrame(reference, one, [&](int threads, Walk walk, FrameBuffer& out) {
                return render(samples, linear, threads, walk, glass, out);
            });
        }
}

TEST_CASE("a draw stopped after binning fills the bins and nothing else; unbinned, it stops as after geometry",
          "[threads]") {
    // The bench's binning stage (PipelineStop::Bin): 600 small on-screen triangles, 2 threads.
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> xy(-0.9f, 0.9f), d(-0.05f, 0.05f);
    std::vector<Vec4> positions;
    std::vector<std::uint32_t> indices;
    for (int t = 0; t < 600; ++t) {
        const float cx = xy(rng), cy = xy(rng);
        for (int k = 0; k < 3; ++k) {
            positions.push_back({cx + d(rng), cy + d(rng), 0.5f, 1.0f});
            indices.push_back(std::uint32_t(positions.size() - 1));
        }
    }
    auto draw = [&](int threads, std::size_t binMin, PipelineStop stop, FrameBuffer& fb) {
        RenderContext ctx(fb);
        ctx.setThreads(threads);
        ctx.binningMinTriangles = binMin;
        ctx.clearTarget(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
        DrawState state;
        state.stopAfter = stop;
        TieProgram program{&positions};
        drawProgram<1>(ctx, state, positions.size(), indices.data(), indices.size(), program);
        std::size_t binned = 0, owned = 0;
        for (const auto& bin : ctx.bins) {
            binned += bin.size();
            for (const BinEntry& e : bin) owned += (e.entry & detail::kBinOwner) != 0;
        }
        return std::tuple{ctx.stats, binned, owned};
    };
    FrameBuffer cleared(96, 80), fb(96, 80);
    cleared.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
    const auto [stats, binned, owned] = draw(2, 0, PipelineStop::Bin, fb);
    CHECK(differingPixels(cleared, fb) == 0);
    CHECK(std::memcmp(cleared.depthData(), fb.depthData(), sizeof(float) * 96 * 80) == 0);
    // Every triangle the full draw rasterises is in its owner's bin, once, and some also in another's.
    FrameBuffer full(96, 80);
    const RenderStats drawn = std::get<0>(draw(2, 0, PipelineStop::Fill, full));
    CHECK(drawn.rasterized > 500);
    CHECK(owned == drawn.rasterized);
    CHECK(binned > owned);
    CHECK(stats.trianglesIn == 600);
    CHECK(stats.setupsBuilt == 0);       // set up by nobody
    CHECK(stats.fragmentsShaded == 0);
    // Not binned (one thread, or below the threshold): the same as stopping after geometry.
    for (auto [threads, binMin] : {std::pair{1, std::size_t(0)}, std::pair{2, kNeverBinned}}) {
        FrameBuffer a(96, 80), b(96, 80);
        const auto bin = draw(threads, binMin, PipelineStop::Bin, a);
        const auto geometry = draw(threads, binMin, PipelineStop::Geometry, b);
        CHECK(sameStats(std::get<0>(bin), std::get<0>(geometry)));
        CHECK(differingPixels(a, cleared) == 0);
    }
}

TEST_CASE("binned draws: each band's bins list the triangles whose rows meet it, in submission order", "[threads]") {
    // 400 triangles of random sizes (some spanning every band) over a 96 x 150 target: five bands
    // of 32 rows, the last one 22 rows high. Sampled with a fixed seed.
    std::mt19937 rng(3803);
    std::uniform_real_distribution<float> centre(-1.0f, 1.0f), size(0.0f, 1.0f);
    std::vector<Vec4> positions;
    std::vector<std::uint32_t> indices;
    constexpr int kWidth = 96, kHeight = 150, kBands = 5;
    // Screen y on a quarter-pixel grid offset by 1/8: never within 1/8 pixel of a pixel centre,
    // so the rows below do not depend on rounding.
    auto onGrid = [](float y) {
        const double screen = std::floor((1.0 - double(y)) * 0.5 * kHeight * 4.0) / 4.0 + 0.125;
        return float(1.0 - 2.0 * screen / kHeight);
    };
    for (int t = 0; t < 400; ++t) {
        const float cx = centre(rng), cy = centre(rng), r = size(rng) * size(rng) * 1.5f;
        for (int k = 0; k < 3; ++k)
            positions.push_back({cx + r * (2 * size(rng) - 1), onGrid(cy + r * (2 * size(rng) - 1)), 0.5f, 1.0f});
        // Corners 3t+1, 3t+2, 3t (the same triangle and winding): no index equals its position
        // in the index buffer, so bin entries that named the wrong vertices would show.
        for (int k = 1; k <= 3; ++k) indices.push_back(std::uint32_t(3 * t + k % 3));
    }
    REQUIRE(detail::bandCount(kHeight) == kBands);
    // The rows whose pixel centres each triangle's y extent [minY, maxY) holds, from its screen
    // positions (y down: (1 - y) / 2 * height), in double.
    // A triangle wholly beyond one side of the view is rejected, one of zero area on the 1/256
    // pixel grid culled ({0, 0}: no row).
    std::vector<std::pair<int, int>> rows;
    for (int t = 0; t < 400; ++t) {
        const Vec4* p = positions.data() + 3 * t;
        auto beyond = [p](auto side) { return side(p[0]) && side(p[1]) && side(p[2]); };
        auto snapped = [](double ndc, int size) { return std::llround((ndc + 1.0) * 0.5 * size * 256.0); };
        const long long x0 = snapped(p[0].x, kWidth), x1 = snapped(p[1].x, kWidth), x2 = snapped(p[2].x, kWidth);
        const long long y0 = snapped(p[0].y, kHeight), y1 = snapped(p[1].y, kHeight), y2 = snapped(p[2].y, kHeight);
        if (beyond([](const Vec4& v) { return v.x < -1.0f; }) || beyond([](const Vec4& v) { return v.x > 1.0f; }) ||
            beyond([](const Vec4& v) { return v.y < -1.0f; }) || beyond([](const Vec4& v) { return v.y > 1.0f; }) ||
            (x1 - x0) * (y2 - y0) == (x2 - x0) * (y1 - y0)) {
            rows.emplace_back(0, 0);
            continue;
        }
        double lo = 1e9, hi = -1e9;
        for (int k = 0; k < 3; ++k) {
            const double y = (1.0 - double(positions[std::size_t(3 * t + k)].y)) * 0.5 * kHeight;
            lo = std::min(lo, y);
            hi = std::max(hi, y);
        }
        rows.emplace_back(int(std::ceil(lo - 0.5)), int(std::ceil(hi - 0.5)));
    }
    for (int threads : {2, 3}) {
        for (int shared : {kSharedSetupBands, 1}) {
            INFO(threads << " threads, set up once from " << shared << " bands");
            FrameBuffer fb(kWidth, kHeight);
            RenderContext ctx(fb);
            ctx.setThreads(threads);
            ctx.binningMinTriangles = 0;
            ctx.sharedSetupBands = shared;
            ctx.clearTarget(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
            DrawState state;
            TieProgram program{&positions};
            drawProgram<1>(ctx, state, positions.size(), indices.data(), indices.size(), program);
            std::size_t sharedEntries = 0, owners = 0, wrongCorners = 0;
            for (int b = 0; b < kBands; ++b) {
                std::vector<std::size_t> listed; // band b's triangles, chunk by chunk
                for (int c = 0; c < threads; ++c)
                    for (const BinEntry& e : ctx.bins[std::size_t(c * kBands + b)]) {
                        const std::uint32_t entry = e.entry;
                        owners += (entry & detail::kBinOwner) != 0;
                        if (entry & detail::kBinShared) {
                            ++sharedEntries;
                            listed.push_back(ctx.sharedSetups[std::size_t(c)][entry & detail::kBinIndex].triangle);
                        } else {
                            const std::size_t t = entry & detail::kBinIndex;
                            listed.push_back(t);
                            // A triangle's entry carries its vertex indices (the walk reads no index buffer).
                            for (int k = 0; k < 3; ++k) wrongCorners += e.corners[k] != indices[3 * t + std::size_t(k)];
                        }
                    }
                CHECK(std::is_sorted(listed.begin(), listed.end())); // submission order
                CHECK(std::adjacent_find(listed.begin(), listed.end()) == listed.end()); // each once
                std::vector<std::size_t> expected;
                for (std::size_t t = 0; t < rows.size(); ++t) {
                    if (rows[t].first >= rows[t].second) continue; // no centre row: not drawn
                    // The band of its first row (on the target) counts it; it is in every band it meets.
                    const int owner = std::clamp(rows[t].first, 0, kHeight - 1) / 32;
                    const int first = std::max(rows[t].first, 0), end = std::min(rows[t].second, kHeight);
                    if (b == owner || (first < end && first < 32 * (b + 1) && end > 32 * b)) expected.push_back(t);
                }
                std::vector<std::size_t> missing, extra;
                std::set_difference(expected.begin(), expected.end(), listed.begin(), listed.end(), std::back_inserter(missing));
                std::set_difference(listed.begin(), listed.end(), expected.begin(), expected.end(), std::back_inserter(extra));
                CAPTURE(b, missing, extra);
                CHECK(listed == expected);
            }
            CHECK(owners == ctx.stats.rasterized);
            CHECK(wrongCorners == 0);
            // Only triangles meeting 3 bands or more share a record (every one with 1); none is clipped.
            CHECK(ctx.stats.clipped == 0);
            if (shared == 1) CHECK(ctx.stats.setupsBuilt == ctx.stats.rasterized);
            else CHECK(ctx.stats.setupsBuilt > ctx.stats.rasterized);
            CHECK(sharedEntries > 0);
        }
    }
}

TEST_CASE("bandsByWork: the lanes take the bands with the most bin entries first, ties upper first", "[threads]") {
    // Entries per band summed over the chunks' bins, the order a permutation of the bands.
    FrameBuffer fb(8, 8);
    RenderContext ctx(fb);
    const int chunks = 2, bandsHigh = 6;
    const std::size_t sizes[2][6] = {{3, 1, 0, 2, 1, 0}, {0, 1, 0, 3, 1, 4}}; // per band: 3 2 0 5 2 4
    ctx.bins.resize(std::size_t(chunks * bandsHigh));
    for (int c = 0; c < chunks; ++c)
        for (int b = 0; b < bandsHigh; ++b)
            ctx.bins[std::size_t(c * bandsHigh + b)].assign(sizes[c][b], BinEntry{std::uint32_t(b), {}});
    detail::bandsByWork(ctx, chunks, bandsHigh);
    CHECK(ctx.bandOrder == std::vector<int>{3, 5, 0, 1, 4, 2});
    // In parts of consecutive bands (one per lane: BandQueue), the same rule within each part.
    detail::bandsByWork(ctx, chunks, bandsHigh, 2); // parts {0, 1, 2} and {3, 4, 5}
    CHECK(ctx.bandOrder == std::vector<int>{0, 1, 2, 3, 5, 4});
    detail::bandsByWork(ctx, chunks, bandsHigh, 4); // parts of 2: {0, 1} {2, 3} {4, 5}
    CHECK(ctx.bandOrder == std::vector<int>{0, 1, 3, 2, 5, 4});
    // Every band empty: row order. Fewer bands than before: the order shrinks with them.
    for (auto& bin : ctx.bins) bin.clear();
    detail::bandsByWork(ctx, chunks, 4);
    CHECK(ctx.bandOrder == std::vector<int>{0, 1, 2, 3});
    // The largest band number a frame can have (kMaxDimension rows) survives the packed key.
    const int most = detail::bandCount(FrameBuffer::kMaxDimension);
    ctx.bins.assign(std::size_t(most), {});
    ctx.bins[std::size_t(most - 1)].assign(7, BinEntry{});
    detail::bandsByWork(ctx, 1, most);
    REQUIRE(ctx.bandOrder.size() == std::size_t(most));
    CHECK(ctx.bandOrder.front() == most - 1);
    CHECK(ctx.bandOrder[1] == 0);
    CHECK(ctx.bandOrder.back() == most - 2);
}

TEST_CASE("BandQueue: a lane takes its own part first, then the others'; every band exactly once", "[threads]") {
    // One lane asking alone: its part in order, then the next parts, then -1.
    {
        detail::BandQueue queue(7, 2); // parts [0, 4) and [4, 7)
        std::vector<int> got;
        for (int k = queue.next(1); k >= 0; k = queue.next(1)) got.push_back(k);
        CHECK(got == std::vector<int>{4, 5, 6, 0, 1, 2, 3});
        CHECK(queue.next(0) == -1);
    }
    {
        detail::BandQueue queue(7, 2);
        CHECK(queue.next(0) == 0);
        CHECK(queue.next(1) == 4);
        CHECK(queue.next(0) == 1);
    }
    // Its own part only (fillDeferredDraws' batches): none left there is -1 while others remain.
    {
        detail::BandQueue queue(7, 2);
        CHECK(queue.next(1, true) == 4);
        CHECK(queue.next(1, true) == 5);
        CHECK(queue.next(1, true) == 6);
        CHECK(queue.next(1, true) == -1);
        CHECK(queue.next(1) == 0);
        CHECK(queue.next(0, true) == 1);
    }
    // Lanes on threads of their own, racing (each asking for its own part's bands in every other
    // call): the bands handed out are 0 .. bands - 1, each once.
    for (int lanes : {1, 2, 3, 8}) {
        for (int bands : {1, 2, 5, 19, 34, 70}) {
            CAPTURE(lanes, bands);
            for (int round = 0; round < 20; ++round) {
                detail::BandQueue queue(bands, lanes);
                std::vector<std::vector<int>> got(static_cast<std::size_t>(lanes));
                std::vector<std::thread> threads;
                for (int l = 0; l < lanes; ++l)
                    threads.emplace_back([&, l] {
                        for (int k = queue.next(l); k >= 0; k = queue.next(l)) {
                            got[std::size_t(l)].push_back(k);
                            if (const int own = queue.next(l, true); own >= 0) got[std::size_t(l)].push_back(own);
                        }
                    });
                for (std::thread& t : threads) t.join();
                std::vector<int> all;
                for (const std::vector<int>& g : got) all.insert(all.end(), g.begin(), g.end());
                std::sort(all.begin(), all.end());
                std::vector<int> expected(static_cast<std::size_t>(bands));
                std::iota(expected.begin(), expected.end(), 0);
                REQUIRE(all == expected);
            }
        }
    }
}

TEST_CASE("a pass's binned draws wait and are filled together, band by band: one thread's image", "[threads]") {
    // The built-in scene's opaque draws through drawMesh inside a DeferredFillScope, as renderScene
    // draws them but in an order where waiting draws' screen vertices would be written over by the
    // next mesh's vertex stage (sphere, ground; sphere, torus, ground), a draw too small to be binned
    // (a cube: 12 triangles) comes between waiting ones, and each material is a copy that is gone
    // before the fill.
    static auto loaded = app::loadScene(app::SceneOptions{});
    REQUIRE(loaded.ok());
    const Scene& scene = loaded.value().scene;
    REQUIRE(scene.draws.size() >= 5); // ground (128 triangles), two cubes, sphere, torus, ...
    app::SceneOptions options;
    options.width = 203;
    options.height = 150; // five bands, the last 22 rows
    const FrameView view = app::makeFrameView(app::resolveCamera(options, loaded.value()), options.width,
                                              options.height, options.light, loaded.value().lights);
    const RenderSettings settings = app::makeRenderSettings(options);
    const int order[] = {3, 0, 1, 3, 4, 0};
    struct Pass {
        FrameBuffer fb{203, 150};
        RenderStats stats;
        std::size_t waitingBeforeCube = 0, touchedBeforeCube = 0, waitingAtEnd = 0;
    };
    const Pixel clear = packBgra(9, 8, 7);
    auto pass = [&](int threads) {
        Pass p;
        RenderContext ctx(p.fb);
        ctx.setThreads(threads);
        ctx.clearTarget(clear, FrameBuffer::kFarDepth);
        const VertexReuseScope reuse(ctx);
        DeferredFillScope deferred(ctx);
        for (std::size_t k = 0; k < std::size(order); ++k) {
            const SceneDraw& d = scene.draws[std::size_t(order[k])];
            const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
            {
                const SurfaceMaterial material = materialOf(scene, d, nullptr);
                drawMesh(ctx, view, settings, mesh, mesh.indices.data() + d.firstIndex, d.indexCount, material);
            }
            // What each draw's program points to lives until the scope ends, also across the fill
            // that a draw which cannot wait runs first (its own inputs are among them).
            CHECK(ctx.deferral.kept.size() == (threads > 1 ? k + 1 : 0));
            if (k == 1) {
                p.waitingBeforeCube = ctx.deferral.draws.size();
                for (int y = 0; y < p.fb.height(); ++y)
                    for (int x = 0; x < p.fb.width(); ++x) p.touchedBeforeCube += p.fb.pixel(x, y) != clear;
            }
        }
        p.waitingAtEnd = ctx.deferral.draws.size();
        deferred.finish();
        CHECK(ctx.deferral.draws.empty());
        CHECK(ctx.deferral.kept.empty());
        p.stats = ctx.stats;
        return p;
    };
    const Pass one = pass(1);
    CHECK(one.waitingBeforeCube == 0); // one lane: nothing is binned, nothing waits
    CHECK(one.touchedBeforeCube > 1000);
    for (int threads : {2, 3, 8}) {
        INFO(threads << " threads");
        const Pass many = pass(threads);
        CHECK(differingPixels(one.fb, many.fb) == 0);
        CHECK(sameStats(one.stats, many.stats));
        // The sphere and the ground waited (the target untouched), the cube filled them first, the
        // three draws after it waited for finish().
        CHECK(many.waitingBeforeCube == 2);
        CHECK(many.touchedBeforeCube == 0);
        CHECK(many.waitingAtEnd == 3);
    }
    // While multisampling the draws fill at once (their bands' samples would not stay in cache).
    FrameBuffer small(64, 64);
    RenderContext ctx(small);
    ctx.setThreads(2);
    REQUIRE(ctx.msaa.resize(64, 64, 4));
    ctx.multisampling = true;
    CHECK_FALSE(DeferredFillScope(ctx).active());
    ctx.multisampling = false;
    CHECK(DeferredFillScope(ctx).active());
}

TEST_CASE("wireframe falls back to one lane and still matches", "[threads]") {
    app::SceneOptions options;
    options.width = 120;
    options.height = 90;
    options.wireframe = true;
    const RenderSettings settings = app::makeRenderSettings(options);
    const Frame one = renderDefault(options, 1, settings);
    const Frame two = renderDefault(options, 2, settings);
    CHECK(differingPixels(one.fb, two.fb) == 0);
    CHECK(sameStats(one.stats, two.stats));
}
