// The bench soak mode: a seeded camera flight through the scene (random and adversarial poses), NaN-depth counts and RSS readings.
#include "Platform/Headless/Flight.hpp"

#include <cmath>
#include <fstream>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "Platform/App/AutoQuality.hpp"
#include "Platform/Headless/Json.hpp"
#include "Platform/Headless/Timing.hpp"

namespace sr::headless {

MemoryUsage currentMemoryUsage() {
    MemoryUsage m;
#if defined(__linux__)
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        long long kb = 0;
        if (std::sscanf(line.c_str(), "VmRSS: %lld kB", &kb) == 1) m.rssKb = kb;
        if (std::sscanf(line.c_str(), "VmHWM: %lld kB", &kb) == 1) m.peakKb = kb;
        if (std::sscanf(line.c_str(), "RssAnon: %lld kB", &kb) == 1) m.anonKb = kb;
    }
#endif
    return m;
}

namespace {

// Pose kinds, in the order of the JSON "poses" object.
enum PoseKind { Orbit, AtVertex, InTrianglePlane, InsideBounds, StraightUpDown, Extreme, kPoseKinds };
const char* const kPoseNames[kPoseKinds] = {"orbit", "at_vertex", "in_triangle_plane", "inside_bounds",
                                            "straight_up_down", "extreme"};

// Portable random numbers: mt19937's sequence is fixed by the standard; the distributions are
// not, so the conversions are our own.
struct Random {
    std::mt19937 engine;
    explicit Random(std::uint32_t seed) : engine(seed) {}
    double unit() { return double(engine() >> 8) * (1.0 / 16777216.0); } // [0, 1)
    double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
    std::size_t below(std::size_t n) { return n ? std::size_t(engine()) % n : 0; }
    Vec3 direction() { // uniform on the sphere (Archimedes' z + angle)
        const double z = range(-1.0, 1.0), a = range(0.0, 6.283185307179586), s = std::sqrt(1.0 - z * z);
        return Vec3(float(s * std::cos(a)), float(s * std::sin(a)), float(z));
    }
};

Vec3 add(Vec3 a, Vec3 b) { return Vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
Vec3 sub(Vec3 a, Vec3 b) { return Vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
Vec3 mul(Vec3 a, double s) { return Vec3(float(a.x * s), float(a.y * s), float(a.z * s)); }

struct Pose {
    app::CameraSetup camera;
    PoseKind kind = Orbit;
};

Pose nextPose(Random& rnd, const app::LoadedScene& scene) {
    const Vec3 c = scene.centre;
    const double r = scene.radius > 0 && std::isfinite(scene.radius) ? scene.radius : 1.0;
    const auto around = [&](double lo, double hi) { return add(c, mul(rnd.direction(), r * rnd.range(lo, hi))); };
    // A random triangle of a random draw (or none), where the draw puts it.
    const auto triangle = [&](Vec3 out[3]) {
        const auto& draws = scene.scene.draws;
        if (draws.empty()) return false;
        const SceneDraw& d = draws[rnd.below(draws.size())];
        const Mesh& m = scene.scene.meshes[std::size_t(d.mesh)];
        if (d.indexCount < 3 || m.positions.empty()) return false;
        const std::size_t t = d.firstIndex + rnd.below(d.indexCount / 3) * 3;
        for (int k = 0; k < 3; ++k) out[k] = drawnPosition(d, m.positions[m.indices[t + std::size_t(k)] % m.positions.size()]);
        return true;
    };

    Pose p;
    app::CameraSetup& cam = p.camera;
    cam.up = Vec3(0, 1, 0);
    cam.fovDegrees = rnd.range(30.0, 90.0);
    cam.nearZ = 0.01 * r;
    cam.farZ = rnd.unit() < 0.25 ? INFINITY : 100.0 * r;
    cam.eye = around(0.3, 4.0);
    cam.target = around(0.0, 1.0);
    p.kind = rnd.below(8) < 3 ? Orbit : PoseKind(rnd.below(kPoseKinds - 1) + 1);
    Vec3 tri[3];
    switch (p.kind) {
    case AtVertex: // the eye exactly on a vertex: w = 0 at that vertex for every triangle sharing it
        if (triangle(tri)) cam.eye = tri[rnd.below(3)];
        cam.nearZ = rnd.unit() < 0.5 ? 1e-6 * r : 0.01 * r;
        break;
    case InTrianglePlane: // eye and target in one triangle's plane: it projects to a line
        if (triangle(tri)) {
            const Vec3 e1 = sub(tri[1], tri[0]), e2 = sub(tri[2], tri[0]);
            cam.eye = add(tri[0], add(mul(e1, rnd.range(-2.0, 3.0)), mul(e2, rnd.range(-2.0, 3.0))));
            cam.target = add(tri[0], add(mul(e1, rnd.range(-1.0, 2.0)), mul(e2, rnd.range(-1.0, 2.0))));
        }
        break;
    case InsideBounds: { // inside the model's box (inside closed objects, for most models)
        const Vec3 lo = scene.scene.boundsMin, hi = scene.scene.boundsMax;
        cam.eye = Vec3(float(rnd.range(lo.x, hi.x)), float(rnd.range(lo.y, hi.y)), float(rnd.range(lo.z, hi.z)));
        if (!(hi.x > lo.x)) cam.eye = around(0.0, 0.9);
        break;
    }
    case StraightUpDown: // view direction parallel to up: lookAt's degenerate basis
        cam.target = add(cam.eye, Vec3(0, rnd.unit() < 0.5 ? 1.0f : -1.0f, 0));
        if (rnd.unit() < 0.5) cam.target = add(cam.eye, Vec3(0, float(rnd.unit() < 0.5 ? 1e-30 : -1e-30), 0));
        break;
    case Extreme: // ratios far beyond what the depth buffer resolves, fov at its ends
        switch (rnd.below(4)) {
        case 0: cam.nearZ = 1e-9 * r; cam.farZ = 1e9 * r; break;
        case 1: cam.fovDegrees = rnd.unit() < 0.5 ? 0.01 : 179.9; break;
        case 2: cam.eye = add(c, mul(rnd.direction(), r * 1e7)); cam.target = c; cam.farZ = INFINITY; break;
        default: cam.target = cam.eye; break; // zero-length view direction
        }
        break;
    case Orbit:
    case kPoseKinds: break;
    }
    return p;
}

} // namespace

int runFlight(const CommandArgs& a, PreparedScene& p, std::uint32_t seed, Streams io) {
    Random rnd(seed);
    const int w = p.framebuffer.width(), h = p.framebuffer.height();
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    long long nanPixels = 0, nanFrames = 0, poses[kPoseKinds] = {};
    MemoryUsage atFrame100, atEnd;
    // Written (not just reserved) up front: pages first touched during the flight would count as growth.
    std::vector<double> ms(std::size_t(a.frames), 0.0);
    using Clock = std::chrono::steady_clock;
    (void)currentMemoryUsage(); // the first reading pages in its own code: keep that out of the numbers
    // --quality auto with a budget: the setting follows it frame by frame, as in the demo.
    const bool following = p.autoQuality && !p.options.maxError && !p.autoProbe.points.empty();
    app::AutoQualitySelector selector;
    if (following) selector = app::AutoQualitySelector(p.autoProbe.points, p.options.budgetMs.value_or(1000.0 / 60.0));
    std::vector<int> chosen;
    for (int frame = 1; frame <= a.frames; ++frame) {
        const RenderSettings& settings = following ? p.autoProbe.settings[std::size_t(selector.current())] : p.settings;
        if (following) chosen.push_back(selector.current());
        const Pose pose = nextPose(rnd, p.scene);
        ++poses[pose.kind];
        const auto t0 = Clock::now();
        FrameView view = app::makeFrameView(pose.camera, w, h, a.scene.light, p.scene.lights, p.scene.physical);
        view.ibl = p.scene.ibl.get();
        app::renderFrame(p.context, p.scene, view, settings);
        ms[std::size_t(frame - 1)] = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        if (following) selector.update(ms[std::size_t(frame - 1)]);
        long long bad = 0;
        const float* depth = p.framebuffer.depthData();
        for (std::size_t i = 0; i < pixels; ++i) bad += !std::isfinite(depth[i]);
        nanPixels += bad;
        nanFrames += bad > 0;
        if (bad > 0 && nanFrames <= 5 && !a.quiet)
            io.err << "softraster: frame " << frame << ": " << bad << " non-finite depth values; camera: "
                   << app::cameraFlags(pose.camera) << "\n";
        if (frame == std::min(100, a.frames)) atFrame100 = currentMemoryUsage();
    }
    atEnd = currentMemoryUsage();
    const TimingSummary t = summarise(ms);

    std::string j = "{\"renderer\":\"softraster\",\"mode\":\"flight\",\"flight_seed\":" + std::to_string(seed);
    j += ",\"width\":" + std::to_string(w) + ",\"height\":" + std::to_string(h);
    j += ",\"triangles\":" + std::to_string(p.scene.scene.triangleCount());
    j += ",\"frames\":" + std::to_string(a.frames);
    j += ",\"ms_per_frame_median\":" + jsonNumber(t.median) + ",\"ms_per_frame_max\":" + jsonNumber(ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end()));
    j += ",\"nan_pixels\":" + std::to_string(nanPixels) + ",\"nan_frames\":" + std::to_string(nanFrames);
    j += ",\"rss_kb_frame_100\":" + std::to_string(atFrame100.rssKb) + ",\"rss_kb_end\":" + std::to_string(atEnd.rssKb);
    j += ",\"peak_kb_frame_100\":" + std::to_string(atFrame100.peakKb) + ",\"peak_kb_end\":" + std::to_string(atEnd.peakKb);
    j += ",\"anon_kb_frame_100\":" + std::to_string(atFrame100.anonKb) + ",\"anon_kb_end\":" + std::to_string(atEnd.anonKb);
    if (following) { // the probe's settings, and the one each frame was drawn with
        j += ",\"quality_auto\":{\"budget_ms\":" + jsonNumber(p.options.budgetMs.value_or(1000.0 / 60.0)) + ",\"settings\":[";
        for (std::size_t k = 0; k < p.autoProbe.settings.size(); ++k)
            j += std::string(k ? "," : "") + "\"" + app::settingLabel(p.autoProbe.settings[k], p.textured) + "\"";
        j += "],\"per_frame\":[";
        for (std::size_t k = 0; k < chosen.size(); ++k) j += std::string(k ? "," : "") + std::to_string(chosen[k]);
        j += "]}";
    }
    j += ",\"poses\":{";
    for (int k = 0; k < kPoseKinds; ++k)
        j += std::string(k ? "," : "") + "\"" + kPoseNames[k] + "\":" + std::to_string(poses[k]);
    j += "}}";
    io.out << j << "\n";
    return kExitOk;
}

} // namespace sr::headless
