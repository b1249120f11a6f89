// sr_raster_bench: single-threaded fill-rate micro-benchmark of triangle setup + scanline fill.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

#include "Raster/Fill/ScanlineFill.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Setup/TriangleSetup.hpp"

using namespace sr;

namespace {

constexpr int kWidth = 1024, kHeight = 1024;
constexpr int kWarmup = 3, kRuns = 21;

struct Tri {
    ScreenVertex v[3];
};

// N random triangles of about `area` pixels each (equilateral up to a random rotation and a 2:1
// random stretch), inside the framebuffer, with depth rising in draw order so every covered
// pixel passes the GREATER test (the full test + write + shade path is measured).
// The 4-varying mode also measures the per-pixel 1/w divide and 4 multiplies.
std::vector<Tri> makeTriangles(double area, int count, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double side = std::sqrt(4.0 * area / std::sqrt(3.0));
    std::vector<Tri> tris(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        const double angle = u(rng) * 6.283185307179586, stretch = 0.7 + 0.7 * u(rng);
        const double margin = side * 1.5 + 2.0;
        const double cx = margin + u(rng) * (kWidth - 2 * margin), cy = margin + u(rng) * (kHeight - 2 * margin);
        for (int k = 0; k < 3; ++k) {
            const double a = angle + k * 2.0943951023931953;
            ScreenVertex& v = tris[std::size_t(i)].v[k];
            v.x = float(cx + side * 0.57735 * std::cos(a) * stretch);
            v.y = float(cy + side * 0.57735 * std::sin(a) / stretch);
            v.invW = float(0.2 + u(rng));
            for (int j = 0; j < 4; ++j) v.varyings[std::size_t(j)] = float(u(rng));
        }
    }
    // Draw in 64x64-pixel tile order, as a mesh's neighbouring triangles would arrive: the
    // benchmark measures the rasterizer, not DRAM latency of random framebuffer accesses. Then
    // depth rises in draw order.
    auto tile = [](const Tri& t) { return int(t.v[0].y) / 64 * 1024 + int(t.v[0].x) / 64; };
    std::stable_sort(tris.begin(), tris.end(), [&](const Tri& a, const Tri& b) { return tile(a) < tile(b); });
    for (int i = 0; i < count; ++i)
        for (ScreenVertex& v : tris[std::size_t(i)].v) v.z = float(i + 1) / float(count + 1);
    return tris;
}

// Sets up and fills every triangle once; returns the number of pixels shaded.
template <int kVaryings>
long long drawAll(const std::vector<Tri>& tris, FrameBuffer& fb) {
    long long shaded = 0;
    for (const Tri& t : tris) {
        const auto s = setupTriangle(t.v[0], t.v[1], t.v[2], kVaryings);
        if (!s) continue;
        if constexpr (kVaryings == 0) {
            fillTriangle<DepthMode::TestWrite, 0>(*s, fb, [&](const Fragment<0>&) {
                ++shaded;
                return packBgra(200, 120, 40);
            });
        } else {
            fillTriangle<DepthMode::TestWrite, kVaryings>(*s, fb, [&](const Fragment<kVaryings>& f) {
                ++shaded;
                const float r = f.varyings[0] + f.varyings[3], g = f.varyings[1], b = f.varyings[2];
                return packBgra(std::uint8_t(std::clamp(r, 0.0f, 1.0f) * 255.0f),
                                std::uint8_t(std::clamp(g, 0.0f, 1.0f) * 255.0f),
                                std::uint8_t(std::clamp(b, 0.0f, 1.0f) * 255.0f));
            });
        }
    }
    return shaded;
}

template <int kVaryings>
void bench(const char* mode, double area, int count, std::mt19937& rng) {
    const std::vector<Tri> tris = makeTriangles(area, count, rng);
    FrameBuffer fb(kWidth, kHeight);
    std::vector<double> times;
    long long pixels = 0;
    for (int run = 0; run < kWarmup + kRuns; ++run) {
        fb.clear(0); // not timed
        const auto t0 = std::chrono::steady_clock::now();
        pixels = drawAll<kVaryings>(tris, fb);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (run >= kWarmup) times.push_back(s);
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    std::printf("%8.0f  %-22s %8d %10lld %9.3f %10.3f %9.1f\n", area, mode, count, pixels,
                median * 1e3, count / median * 1e-6, pixels / median * 1e-6);
}

} // namespace

int main() {
    std::mt19937 rng(42);
    std::printf("sr_raster_bench: triangle setup + scanline fill, %dx%d framebuffer, depth test GREATER + write\n",
                kWidth, kHeight);
    std::printf("threads used: 1 (hardware threads: %u); median of %d runs after %d warm-up runs\n\n",
                std::thread::hardware_concurrency(), kRuns, kWarmup);
    std::printf("%8s  %-22s %8s %10s %9s %10s %9s\n", "area px", "mode", "tris", "pixels", "ms", "Mtris/s", "Mpix/s");
    const struct {
        double area;
        int count;
    } sizes[] = {{4, 200000}, {100, 20000}, {10000, 400}};
    for (const auto& s : sizes) {
        bench<0>("flat + depth", s.area, s.count, rng);
        bench<4>("4 persp varyings + depth", s.area, s.count, rng);
    }
    return 0;
}
