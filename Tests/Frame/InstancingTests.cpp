// A mesh stored once and drawn at several places (Placement): the same frame as its copies written
// out in world space, in every shading model, with shadows, transparency and several threads;
// picking sees the places; each place costs one vertex stage, not a stored copy.
#include "TestFramework.hpp"

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "Math/Transform.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "RenderTestUtil.hpp"
#include "Raster/Geometry/Placement.hpp"
#include "Resources/Primitives.hpp"

using namespace sr;
using sr::test::differingPixels;

namespace {

constexpr int kW = 160, kH = 120;

// A floor in world space and a torus stored once, its faces listed twice (as they are, then
// reversed for the mirroring place), drawn at four places: turned, scaled unevenly, mirrored, and
// turned again behind a half-transparent surface. Textured, with tangents and a normal map for
// the pbr draws.
Scene placedScene(bool pbr) {
    Scene s;
    s.meshes.push_back(makeGroundPlane(6.0f, 6.0f, 4, 2.0f));
    Mesh torus = makeTorus(0.8f, 0.3f, 24, 12);
    torus.tangents.clear();
    for (std::size_t i = 0; i < torus.vertexCount(); ++i) {
        const Vec3 n = torus.normals[i];
        const Vec3 t = normalize(cross(Vec3{0.3f, 1.0f, 0.2f}, n));
        torus.tangents.emplace_back(t.x, t.y, t.z, i % 2 ? -1.0f : 1.0f);
    }
    const auto faces = std::uint32_t(torus.indices.size());
    for (std::uint32_t k = 0; k < faces; k += 3)
        torus.indices.insert(torus.indices.end(), {torus.indices[k], torus.indices[k + 2], torus.indices[k + 1]});
    s.meshes.push_back(torus);
    const Image checker = makeCheckerImage(32, 4, Color{0.9f, 0.8f, 0.2f, 1.0f}, Color{0.2f, 0.3f, 0.8f, 1.0f});
    const Image bricks = makeBrickImage(32);
    s.textures.push_back(Texture::fromRgba8(checker.width, checker.height, checker.rgba.data()));
    s.textures.push_back(Texture::fromRgba8(bricks.width, bricks.height, bricks.rgba.data()));

    SceneDraw floor;
    floor.mesh = 0;
    floor.indexCount = std::uint32_t(s.meshes[0].indices.size());
    floor.kd = {0.7f, 0.7f, 0.7f, 1.0f};
    s.draws.push_back(floor);
    const Mat4 places[4] = {translate({-2.0f, 1.0f, 0.0f}) * rotate(0.7f, {0.0f, 1.0f, 0.0f}),
                            translate({2.0f, 1.2f, 0.5f}) * scale({1.5f, 0.5f, 1.0f}) * rotate(1.2f, {1.0f, 0.0f, 0.0f}),
                            translate({0.0f, 1.0f, -2.0f}) * scale({-1.0f, 1.0f, 1.0f}) * rotate(0.4f, {0.0f, 0.0f, 1.0f}),
                            translate({0.5f, 0.6f, 2.0f}) * rotate(-0.5f, {0.0f, 1.0f, 0.0f})};
    for (int k = 0; k < 4; ++k) {
        SceneDraw d;
        d.mesh = 1;
        d.placement = Placement::of(places[k]);
        d.firstIndex = d.placement->mirrors() ? faces : 0;
        d.indexCount = faces;
        d.texture = 0;
        d.kd = {0.5f, 0.6f, 0.9f, 1.0f};
        d.alpha = k == 3 ? 0.5f : 1.0f;
        if (pbr) {
            PbrFactors f;
            f.metallic = 0.3f;
            f.roughness = 0.45f;
            d.pbr = f;
            d.maps[MapSlot::Normal] = 1;
        }
        s.draws.push_back(d);
    }
    s.boundsMin = {-6.0f, 0.0f, -6.0f};
    s.boundsMax = {6.0f, 2.0f, 6.0f};
    return s;
}

// The same draws with every placed mesh written out: a world-space copy per draw, its vertices
// moved by the draw's Placement (what the vertex stage does), no placement left.
Scene writtenOut(const Scene& in) {
    Scene out = in;
    for (SceneDraw& d : out.draws) {
        if (!d.placement) continue;
        Mesh copy = in.meshes[std::size_t(d.mesh)];
        for (Vec3& p : copy.positions) p = d.placement->position(p);
        for (Vec3& n : copy.normals) n = d.placement->normal(n);
        for (Vec4& t : copy.tangents) t = d.placement->tangent(t);
        out.meshes.push_back(std::move(copy));
        d.mesh = int(out.meshes.size()) - 1;
        d.placement.reset();
    }
    return out;
}

FrameView sceneView() {
    app::CameraSetup c;
    c.eye = {0.5f, 5.0f, 7.0f};
    c.target = {0.0f, 0.8f, 0.0f};
    c.up = {0, 1, 0};
    c.fovDegrees = 60.0;
    c.nearZ = 0.3;
    c.farZ = 40.0;
    const Vec3 toLight = normalize(Vec3{0.4f, 1.0f, 0.3f});
    FrameView v = app::makeFrameView(c, kW, kH, toLight, {});
    v.lighting.lights = {Light::directional(toLight), Light::point({1.0f, 3.0f, 1.0f}, {1.0f, 0.9f, 0.8f, 1.0f})};
    v.lighting.ambient = 0.1f;
    return v;
}

} // namespace

TEST_CASE("a mesh drawn at its places equals its copies written out in world space, pixel for pixel",
          "[render][instancing]") {
    const FrameView view = sceneView();
    for (const ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong, ShadingMode::Pbr})
        for (const bool shadows : {false, true})
            for (const int threads : {1, 2}) {
                if (shadows && mode != ShadingMode::Phong && mode != ShadingMode::Pbr) continue;
                INFO(shadingModeName(mode) << (shadows ? ", shadows" : "") << ", " << threads << " thread(s)");
                const Scene placed = placedScene(mode == ShadingMode::Pbr);
                const Scene copies = writtenOut(placed);
                RenderSettings settings;
                settings.shading = mode;
                settings.shadows.on = shadows;
                settings.shadows.size = 512;
                if (mode == ShadingMode::Pbr) settings.colour = ColorMode::Linear;
                FrameBuffer a(kW, kH), b(kW, kH), none(kW, kH);
                RenderContext ca(a), cb(b), cn(none);
                for (RenderContext* c : {&ca, &cb, &cn}) c->setThreads(threads);
                renderSceneFrame(ca, placed, view, settings);
                renderSceneFrame(cb, copies, view, settings);
                CHECK(differingPixels(a, b) == 0);
                CHECK(ca.stats.fragmentsShaded == cb.stats.fragmentsShaded);
                CHECK(ca.stats.trianglesSorted == cb.stats.trianglesSorted);
                CHECK(ca.stats.trianglesSorted > 0); // the half-transparent place was sorted
                // The places are really drawn where they are: without them the frame differs
                // over 1500 pixels and more (the floor alone).
                Scene floorOnly = placed;
                floorOnly.draws.resize(1);
                renderSceneFrame(cn, floorOnly, view, settings);
                CHECK(differingPixels(a, none) > 1500);
                // One vertex stage per place, none shared between places: the floor once and the
                // stored torus once for each of its four places (the transparent one drawn in the
                // sorted pass).
                if (threads == 1 && !shadows) {
                    const std::uint64_t torus = placed.meshes[1].vertexCount(), floor = placed.meshes[0].vertexCount();
                    CHECK(ca.stats.verticesTransformed == floor + 4 * torus);
                }
            }
}

TEST_CASE("picking sees a mesh at its places; a mirrored place keeps its faces outward", "[render][instancing]") {
    const Scene placed = placedScene(false);
    const Scene copies = writtenOut(placed);
    const FrameView view = sceneView();
    int hits = 0;
    for (int y = 4; y < kH; y += 8)
        for (int x = 4; x < kW; x += 8) {
            const Vec3 dir = view.rays.at(2.0 * (x + 0.5) / kW - 1.0, 1.0 - 2.0 * (y + 0.5) / kH);
            const int a = pickDraw(placed, view.eye, dir), b = pickDraw(copies, view.eye, dir);
            CHECK(a == b);
            hits += a >= 1;
        }
    CHECK(hits > 10);
    // The mirrored place drawn from the reversed faces is not inside out: culling its back faces
    // leaves its image as it is (its hidden faces are the culled ones). Drawn from the faces as
    // stored, culling would take its visible faces away.
    const auto drawMirrored = [&](CullMode cull, bool reversed) {
        Scene one = placed;
        one.draws = {placed.draws[3]};
        REQUIRE(one.draws[0].placement->mirrors());
        if (!reversed) one.draws[0].firstIndex = 0;
        RenderSettings settings;
        settings.shading = ShadingMode::Phong;
        settings.cull = cull;
        auto fb = std::make_unique<FrameBuffer>(kW, kH);
        RenderContext ctx(*fb);
        renderSceneFrame(ctx, one, view, settings);
        return fb;
    };
    const auto unculled = drawMirrored(CullMode::None, true);
    FrameBuffer empty(kW, kH);
    RenderContext ce(empty);
    Scene nothing = placed;
    nothing.draws.clear();
    renderSceneFrame(ce, nothing, view, RenderSettings{});
    CHECK(differingPixels(*unculled, empty) > 200); // the torus covers that much
    CHECK(differingPixels(*drawMirrored(CullMode::CW, true), *unculled) <= 8);
    CHECK(differingPixels(*drawMirrored(CullMode::CW, false), *unculled) > 200);
}

TEST_CASE("Placement: positions, normals and tangents against hand values; a mirror flips the handedness",
          "[render][instancing]") {
    // x scaled by 2, then turned 90 degrees about z, then moved by (1, 2, 3).
    const Placement p = Placement::of(translate({1, 2, 3}) * rotate(1.57079633f, {0, 0, 1}) * scale({2, 1, 1}));
    const Vec3 q = p.position({1, 0, 0}); // (2, 0, 0) -> (0, 2, 0) -> (1, 4, 3)
    CHECK(q.x == Approx(1.0f).margin(1e-5f));
    CHECK(q.y == Approx(4.0f).margin(1e-5f));
    CHECK(q.z == Approx(3.0f).margin(1e-5f));
    // The normal of the plane x + y = 0 stretched along x: (1, 1, 0) -> (1/2, 1, 0) by the
    // inverse transpose, turned: (-1, 1/2, 0), renormalised.
    const Vec3 n = p.normal(normalize(Vec3{1, 1, 0}));
    CHECK(n.x == Approx(-2.0f / std::sqrt(5.0f)).margin(1e-5f));
    CHECK(n.y == Approx(1.0f / std::sqrt(5.0f)).margin(1e-5f));
    CHECK(n.z == Approx(0.0f).margin(1e-6f));
    CHECK_FALSE(p.mirrors());
    const Vec4 t = p.tangent({1, 0, 0, -1}); // along x: stretched, turned to +y; w kept
    CHECK(t.y == Approx(1.0f).margin(1e-6f));
    CHECK(t.w == -1.0f);
    const Placement m = Placement::of(scale({1, -3, 1}));
    CHECK(m.mirrors());
    CHECK(m.tangent({1, 0, 0, 1}).w == -1.0f);
    const Vec3 up = m.normal({0, 1, 0}); // the mirrored surface's outward normal points down
    CHECK(up.y == Approx(-1.0f).margin(1e-6f));
}
