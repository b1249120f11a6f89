// Shadow maps: a box floating over a floor, lit by one directional light. The
// floor's pixels against a ray-cast reference (away from the penumbra), for steep and grazing
// light directions; no acne on the lit floor; PCF softness growing with the kernel; the memory
// only while shadows are on.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Shade/Shadow.hpp"

using namespace sr;

namespace {

constexpr int kW = 160, kH = 120;

// Floor: y = 0, x and z in [-8, 8]. Box: [-1, 1] x [lift, lift + 1] x [-1, 1] (by default floating 1
// above the floor; lift 0: standing on it).
Scene boxOverFloor(float lift = 1.0f) {
    Scene s;
    Mesh floor;
    floor.positions = {{-8, 0, -8}, {-8, 0, 8}, {8, 0, 8}, {8, 0, -8}};
    floor.normals.assign(4, {0, 1, 0});
    floor.indices = {0, 1, 2, 0, 2, 3};
    Mesh box;
    const Vec3 lo{-1, lift, -1}, hi{1, lift + 1, 1};
    const Vec3 n[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) {
        // Four corners of face f, counter-clockwise seen from outside.
        const Vec3 a = n[f];
        const Vec3 u = std::fabs(a.y) > 0.5f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 v = cross(a, u);
        const Vec3 c = (lo + hi) * 0.5f + Vec3{a.x * 1.0f, a.y * 0.5f, a.z * 1.0f};
        const Vec3 hu{u.x * 1.0f, u.y * 0.5f, u.z * 1.0f}, hv{v.x * 1.0f, v.y * 0.5f, v.z * 1.0f};
        const std::uint32_t base = std::uint32_t(box.positions.size());
        box.positions.insert(box.positions.end(), {c - hu - hv, c + hu - hv, c + hu + hv, c - hu + hv});
        box.normals.insert(box.normals.end(), 4, a);
        box.indices.insert(box.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    s.meshes = {floor, box};
    for (int m = 0; m < 2; ++m) {
        SceneDraw d;
        d.mesh = m;
        d.indexCount = 36;
        d.kd = {0.8f, 0.8f, 0.8f, 1};
        d.specular.shininess = 0.0f; // diffuse only
        s.draws.push_back(d);
    }
    s.draws[0].indexCount = 6;
    s.boundsMin = {-8, 0, -8};
    s.boundsMax = {8, lift + 1, 8};
    return s;
}

FrameView viewWith(Vec3 toLight) {
    app::CameraSetup c;
    c.eye = {0, 9, 9};
    c.target = {0, 0, 0};
    c.up = {0, 1, 0};
    c.fovDegrees = 60.0;
    c.nearZ = 0.5;
    c.farZ = 60.0;
    FrameView v = app::makeFrameView(c, kW, kH, normalize(toLight), {});
    v.lighting.lights = {Light::directional(normalize(toLight))};
    v.lighting.ambient = 0.1f;
    return v;
}

// Whether the ray p + t d, t > 0, meets the box [-1, 1] x [lift, lift + 1] x [-1, 1] grown by `grow`.
bool hitsBox(Vec3 p, Vec3 d, float grow, float lift = 1.0f) {
    double t0 = 1e-6, t1 = 1e30;
    const double lo[3] = {-1.0 - grow, lift - grow, -1.0 - grow}, hi[3] = {1.0 + grow, lift + 1.0 + grow, 1.0 + grow};
    const double o[3] = {p.x, p.y, p.z}, dir[3] = {d.x, d.y, d.z};
    for (int k = 0; k < 3; ++k) {
        if (std::fabs(dir[k]) < 1e-12) {
            if (o[k] < lo[k] || o[k] > hi[k]) return false;
            continue;
        }
        double a = (lo[k] - o[k]) / dir[k], b = (hi[k] - o[k]) / dir[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1;
}

// The floor point under pixel (x, y), if the pixel's centre ray meets the floor before anything
// else (the box, grown a little, must not be in the way).
bool floorPoint(const FrameView& v, int x, int y, Vec3& p, float lift = 1.0f) {
    const Vec3 r = v.rays.at(2.0 * (x + 0.5) / kW - 1.0, 1.0 - 2.0 * (y + 0.5) / kH);
    if (!(r.y < 0.0f)) return false;
    const float t = -v.eye.y / r.y;
    p = v.eye + r * t;
    if (std::fabs(p.x) > 7.5f || std::fabs(p.z) > 7.5f) return false;
    return !hitsBox(v.eye, r, 0.05f, lift);
}

struct Frames {
    FrameBuffer shadowed{kW, kH}, lit{kW, kH}, dark{kW, kH};
    std::size_t maps = 0; // shadow maps the shadowed frame made
};

// The scene with shadows (`shadows`, turned on), without, and without the light (ambient only).
Frames render(const Scene& scene, const FrameView& view, ShadowSettings shadows = {}) {
    Frames f;
    RenderSettings s;
    s.shading = ShadingMode::Phong;
    {
        RenderContext ctx(f.lit);
        renderSceneFrame(ctx, scene, view, s);
    }
    {
        FrameView unlit = view;
        unlit.lighting.lights.clear();
        RenderContext ctx(f.dark);
        renderSceneFrame(ctx, scene, unlit, s);
    }
    s.shadows = shadows;
    s.shadows.on = true;
    RenderContext ctx(f.shadowed);
    renderSceneFrame(ctx, scene, view, s);
    REQUIRE(ctx.shadows);
    f.maps = ctx.shadows->maps.size();
    return f;
}

// The floor pixels against the ray-cast reference: the shadow ray from each floor point toward
// the light (`toLight(p)`) through the box shrunk by 0.15 is surely shadowed, and must equal the
// ambient-only frame; missing the box grown by 0.15 (and lit at all) surely lit, and must equal the
// unshadowed frame. Between: the penumbra and the bias's reach, not counted.
struct Tally {
    int shadowed = 0, lit = 0, wrongShadow = 0, wrongLit = 0; // wrongShadow: leak; wrongLit: acne
};
template <class ToLight>
Tally tally(const Frames& f, const FrameView& view, ToLight toLight, float lift = 1.0f) {
    Tally t;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            Vec3 p;
            if (!floorPoint(view, x, y, p, lift)) continue;
            const Vec3 l = toLight(p);
            if (hitsBox(p, l, -0.15f, lift)) {
                ++t.shadowed;
                t.wrongShadow += f.shadowed.pixel(x, y) != f.dark.pixel(x, y);
            } else if (!hitsBox(p, l, 0.15f, lift) && f.lit.pixel(x, y) != f.dark.pixel(x, y)) {
                ++t.lit;
                t.wrongLit += f.shadowed.pixel(x, y) != f.lit.pixel(x, y);
            }
        }
    return t;
}

// The tally's verdict: enough surely shadowed and surely lit floor pixels, and every one of them
// right.
void checkTally(const Tally& t, int minShadowed, int minLit) {
    INFO("shadowed " << t.shadowed << " lit " << t.lit);
    CHECK(t.shadowed > minShadowed);
    CHECK(t.lit > minLit);
    CHECK(t.wrongShadow == 0);
    CHECK(t.wrongLit == 0);
}

ShadowSettings withPcf(int pcf, int size = 2048) {
    ShadowSettings s;
    s.pcf = pcf;
    s.size = size;
    return s;
}

} // namespace

TEST_CASE("shadow maps: the floor in the box's shadow against a ray-cast reference, steep to grazing light", "[render][shadow]") {
    // Per floor pixel, the reference casts the ray from the floor point toward the light: through
    // the box grown by 0.15 (and not through the box shrunk by 0.15) it is surely shadowed, so the
    // pixel must equal the ambient-only image; missing the grown box it is surely lit, and must
    // equal the image without shadows, exactly (no acne, no light leaking); in between lies the
    // penumbra (PCF) and the bias's reach, not checked. Light elevations from 54 down to 10.5 degrees.
    const Scene scene = boxOverFloor();
    const Vec3 lights[] = {{0.7f, 1.0f, 0.2f}, {1.0f, 1.0f, 0.5f}, {-1.0f, 0.5f, 0.3f}, {1.0f, 0.25f, 0.3f},
                           {0.4f, 0.2f, 1.0f}};
    for (const Vec3& toLight : lights) {
        INFO("light " << toLight.x << ", " << toLight.y << ", " << toLight.z);
        const FrameView view = viewWith(toLight);
        const Frames f = render(scene, view, withPcf(3));
        CHECK(f.maps == std::size_t(ShadowSettings{}.cascades));
        const Vec3 l = normalize(toLight);
        checkTally(tally(f, view, [l](Vec3) { return l; }), 40, 2000);
    }
}

TEST_CASE("shadow maps: PCF softness grows with the kernel", "[render][shadow]") {
    // The penumbra: floor pixels neither fully lit nor fully dark. A 1 x 1 kernel has none (each
    // pixel is one comparison); 3 x 3 some; 5 x 5 more. A small map makes the texels, and hence
    // the kernel's reach, large enough to see on a 160 x 120 image.
    const Scene scene = boxOverFloor();
    const FrameView view = viewWith({1.0f, 1.0f, 0.5f});
    int penumbra[3] = {};
    const int kernels[3] = {1, 3, 5};
    for (int k = 0; k < 3; ++k) {
        const Frames f = render(scene, view, withPcf(kernels[k], 256));
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                Vec3 p;
                if (!floorPoint(view, x, y, p)) continue;
                const Pixel s = f.shadowed.pixel(x, y);
                penumbra[k] += s != f.lit.pixel(x, y) && s != f.dark.pixel(x, y);
            }
    }
    CHECK(penumbra[0] == 0);
    CHECK(penumbra[1] > 20);
    CHECK(penumbra[2] > penumbra[1] * 3 / 2);
}

TEST_CASE("shadow maps: memory only while on; a scene without them is drawn as before", "[render][shadow]") {
    const Scene scene = boxOverFloor();
    const FrameView view = viewWith({1.0f, 1.0f, 0.5f});
    FrameBuffer a(kW, kH), b(kW, kH);
    RenderSettings s;
    RenderContext ctx(a);
    renderSceneFrame(ctx, scene, view, s);
    CHECK(!ctx.shadows);
    s.shadows.on = true;
    renderSceneFrame(ctx, scene, view, s);
    CHECK(ctx.shadows);
    s.shadows.on = false;
    RenderContext other(b);
    renderSceneFrame(ctx, scene, view, s);
    renderSceneFrame(other, scene, view, s);
    CHECK(!ctx.shadows);
    int differing = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) differing += a.pixel(x, y) != b.pixel(x, y);
    CHECK(differing == 0);
}

TEST_CASE("shadow maps: the bias against acne and peter-panning at steep and grazing light", "[render][shadow]") {
    // The box standing on the floor (where peter-panning shows: at the contact). Acne: floor
    // pixels the reference says are surely lit but the shadowed image darkens. Leak
    // (peter-panning): pixels the reference says are surely shadowed but the image lights (the
    // shadow pulled away from its caster). Without any bias the lit floor is covered in acne;
    // the default bias (1 texel + 1 texel x tan) has neither; a large bias (40, 40) leaks light
    // at the grazing angle. (Run with -s for the counts: docs/SHADOWS.md.)
    const float lift = 0.0f;
    const Scene scene = boxOverFloor(lift);
    struct Bias {
        float constant, slope;
    };
    const Bias biases[] = {{0, 0}, {1, 0}, {1, 1}, {4, 4}, {40, 40}};
    for (const Vec3 toLight : {Vec3{1.0f, 1.0f, 0.5f}, Vec3{1.0f, 0.25f, 0.3f}}) {
        const FrameView view = viewWith(toLight);
        const Vec3 l = normalize(toLight);
        int acne[5] = {}, leak[5] = {};
        for (int b = 0; b < 5; ++b) {
            ShadowSettings bias;
            bias.constantBias = biases[b].constant;
            bias.slopeBias = biases[b].slope;
            const Frames f = render(scene, view, bias);
            const Tally t = tally(f, view, [l](Vec3) { return l; }, lift);
            acne[b] = t.wrongLit;
            leak[b] = t.wrongShadow;
            INFO("light " << toLight.x << "," << toLight.y << "," << toLight.z << " bias " << biases[b].constant << ","
                          << biases[b].slope << ": acne " << acne[b] << " leak " << leak[b]);
            if (b == 0) {
                CHECK(acne[0] > 1000); // unbiased: acne all over the lit floor
            } else { // more bias: never more acne, never less leak
                CHECK(acne[b] <= acne[b - 1]);
                CHECK(leak[b] >= leak[b - 1]);
            }
        }
        CHECK(acne[2] == 0);
        CHECK(leak[2] == 0);
        if (toLight.y < 0.5f) CHECK(leak[4] > 0); // grazing, a large bias: the shadow detaches
    }
}

TEST_CASE("shadow maps: a spot light's shadow against a ray-cast reference", "[render][shadow]") {
    // A spot light above and beside the floating box, shining down: the ray from each floor pixel
    // to the light's position decides, as for the directional light (surely shadowed: through
    // the box shrunk by 0.15; surely lit: missing it grown by 0.15 and inside the cone, where the
    // spot lights the floor at all).
    const Scene scene = boxOverFloor();
    FrameView view = viewWith({1, 1, 0.5f});
    const Vec3 position{1.5f, 6.0f, 1.0f};
    view.lighting.lights = {Light::spot(position, normalize(Vec3{-0.2f, -1.0f, -0.1f}), {30, 30, 30, 1}, 0.6f, 0.8f)};
    const Frames f = render(scene, view);
    CHECK(f.maps == 1); // one map for a spot light, no cascades
    checkTally(tally(f, view, [position](Vec3 p) { return position - p; }), 100, 1000);
}

TEST_CASE("shadow maps: sides are whole tiles; texelIndex puts every texel at its own place, tile by tile", "[render][shadow]") {
    CHECK(shadowMapSide(1) == 32);
    CHECK(shadowMapSide(kMinShadowSize) == 32);
    CHECK(shadowMapSide(100) == 128);
    CHECK(shadowMapSide(2048) == 2048);
    CHECK(shadowMapSide(2049) == 2080);
    CHECK(shadowMapSide(kMaxShadowSize) == kMaxShadowSize);
    CHECK(shadowMapSide(1 << 20) == kMaxShadowSize);
    ShadowMap map;
    map.target = FrameBuffer(96, 96); // 3 x 3 tiles
    std::vector<int> seen(96 * 96, 0);
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            const std::size_t i = map.texelIndex(x, y);
            REQUIRE(i < seen.size());
            ++seen[i];
            // Tile (x / 32, y / 32) holds 1024 consecutive texels, row-major inside.
            CHECK(i / 1024 == std::size_t(y / 32 * 3 + x / 32));
            CHECK(i % 1024 == std::size_t(y % 32 * 32 + x % 32));
        }
    CHECK(std::count(seen.begin(), seen.end(), 1) == 96 * 96);
}
