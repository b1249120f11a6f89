// The sky: the cube map's orientation (OpenGL's table 8.19) and seamless
// edges, the gradient, and the pass that draws it only where no geometry was drawn.
#include "TestFramework.hpp"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Fill/Blend.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "Raster/Frame/Sky.hpp"

using namespace sr;

namespace {

// Face f's quadrant q (0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right of the image):
// 24 distinct colours.
std::array<std::uint8_t, 3> quadrantColour(int f, int q) {
    return {std::uint8_t(40 * f + 10), std::uint8_t(60 * q + 20), std::uint8_t(100 + 7 * f + 3 * q)};
}

// Six 8 x 8 faces, each of four 4 x 4 quadrants of one colour.
CubeMap quadrantCube() {
    static std::vector<std::uint8_t> faces[kCubeFaces];
    std::array<const std::uint8_t*, kCubeFaces> ptrs{};
    for (int f = 0; f < kCubeFaces; ++f) {
        faces[f].assign(8 * 8 * 4, 255);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                const auto c = quadrantColour(f, (y >= 4 ? 2 : 0) + (x >= 4 ? 1 : 0));
                for (int k = 0; k < 3; ++k) faces[f][std::size_t((y * 8 + x) * 4 + k)] = c[std::size_t(k)];
            }
        ptrs[std::size_t(f)] = faces[f].data();
    }
    return CubeMap::fromRgba8(8, ptrs);
}

Pixel expected(int f, int q) {
    const auto c = quadrantColour(f, q);
    return packBgra(c[0], c[1], c[2]);
}

constexpr int kSize = 64;

FrameView lookingAlong(Vec3 forward, Vec3 up) {
    app::CameraSetup c;
    c.eye = {0, 0, 0};
    c.target = forward;
    c.up = up;
    c.fovDegrees = 90.0;
    c.nearZ = 0.1;
    c.farZ = 10.0;
    return app::makeFrameView(c, kSize, kSize, {0, 0, 1}, {});
}

// A red square (side 2, unlit colour) facing +z at z = -3, with opacity `alpha`.
Scene redSquare(float alpha) {
    Scene scene;
    Mesh m;
    m.positions = {{-1, -1, -3}, {1, -1, -3}, {1, 1, -3}, {-1, 1, -3}};
    m.normals.assign(4, {0, 0, 1});
    m.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes = {m};
    SceneDraw d;
    d.indexCount = 6;
    d.kd = {1, 0, 0, 1};
    d.alpha = alpha;
    scene.draws = {d};
    return scene;
}

// Every colour channel of a and b within one unit (the sky pass's float path against the double
// reference, Sky::sample).
bool withinOne(Pixel a, Pixel b) {
    return std::abs(int(pixelR(a)) - int(pixelR(b))) <= 1 && std::abs(int(pixelG(a)) - int(pixelG(b))) <= 1 &&
           std::abs(int(pixelB(a)) - int(pixelB(b))) <= 1;
}

// The reference colour of pixel (x, y) of a kSize x kSize image: the ray of its centre, sampled in
// double.
Pixel referenceSky(const Sky& sky, const FrameView& view, int x, int y, int size = kSize) {
    return packBgra8(sky.sample(view.rays.at(2.0 * (x + 0.5) / size - 1.0, 1.0 - 2.0 * (y + 0.5) / size)));
}

} // namespace

TEST_CASE("cube map: the face and texel OpenGL's table 8.19 gives each direction", "[render][sky]") {
    const CubeMap cube = quadrantCube();
    // Directions at quadrant centres (s, t = 0.25 or 0.75: texel coordinates 1.5 or 5.5, inside
    // a quadrant's 4 x 4 texels, so bilinear returns its colour exactly), by hand from the table:
    //  +X: sc = -rz, tc = -ry: (1, 0.5, 0.5) -> s = 0.25, t = 0.25: top-left.
    CHECK(packBgra8(cube.sample({1, 0.5f, 0.5f})) == expected(0, 0));
    CHECK(packBgra8(cube.sample({1, 0.5f, -0.5f})) == expected(0, 1));  // s = 0.75: top-right
    CHECK(packBgra8(cube.sample({1, -0.5f, 0.5f})) == expected(0, 2));  // t = 0.75: bottom-left
    //  -X: sc = +rz, tc = -ry.
    CHECK(packBgra8(cube.sample({-1, 0.5f, -0.5f})) == expected(1, 0));
    CHECK(packBgra8(cube.sample({-1, -0.5f, 0.5f})) == expected(1, 3));
    //  +Y: sc = +rx, tc = +rz.
    CHECK(packBgra8(cube.sample({-0.5f, 1, -0.5f})) == expected(2, 0));
    CHECK(packBgra8(cube.sample({0.5f, 1, 0.5f})) == expected(2, 3));
    //  -Y: sc = +rx, tc = -rz.
    CHECK(packBgra8(cube.sample({-0.5f, -1, 0.5f})) == expected(3, 0));
    CHECK(packBgra8(cube.sample({0.5f, -1, -0.5f})) == expected(3, 3));
    //  +Z: sc = +rx, tc = -ry.
    CHECK(packBgra8(cube.sample({-0.5f, 0.5f, 1})) == expected(4, 0));
    CHECK(packBgra8(cube.sample({0.5f, -0.5f, 1})) == expected(4, 3));
    //  -Z: sc = -rx, tc = -ry.
    CHECK(packBgra8(cube.sample({0.5f, 0.5f, -1})) == expected(5, 0));
    CHECK(packBgra8(cube.sample({-0.5f, -0.5f, -1})) == expected(5, 3));
    // Length does not matter; NaN and zero read +X's centre (a mean of its four quadrants).
    CHECK(packBgra8(cube.sample({10, 5, 5})) == expected(0, 0));
    CHECK(cube.sample({0, 0, 0}).r == cube.sample({1, 0, 0}).r);
    CHECK(cube.sample({std::nanf(""), 1, 0}).g == cube.sample({1, 0, 0}).g);
}

TEST_CASE("cube map: seamless across face edges", "[render][sky]") {
    // Solid faces of very different colours. On the edge between +X and -Z (direction (1, 0, -1),
    // +X by the tie rule) the footprint is half +X, half -Z: their mean; just inside either face
    // it is (nearly) the same mean, not that face's own colour: no seam.
    const std::uint8_t colours[kCubeFaces][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255},
                                                {255, 255, 0, 255}, {0, 255, 255, 255}, {255, 0, 255, 255}};
    std::vector<std::uint8_t> faces[kCubeFaces];
    std::array<const std::uint8_t*, kCubeFaces> ptrs{};
    for (int f = 0; f < kCubeFaces; ++f) {
        for (int i = 0; i < 16 * 16; ++i) faces[f].insert(faces[f].end(), colours[f], colours[f] + 4);
        ptrs[std::size_t(f)] = faces[f].data();
    }
    const CubeMap cube = CubeMap::fromRgba8(16, ptrs);
    const auto near = [](Color a, Color b) {
        return std::abs(a.r - b.r) < 0.02f && std::abs(a.g - b.g) < 0.02f && std::abs(a.b - b.b) < 0.02f;
    };
    const Color mean{0.5f * (1.0f + 1.0f), 0.0f, 0.5f * (0.0f + 1.0f), 1.0f}; // (+X red + -Z magenta) / 2
    CHECK(near(cube.sample({1, 0, -1}), mean));
    CHECK(near(cube.sample({1, 0, -0.999f}), mean));  // on +X, 0.004 texel from its edge
    CHECK(near(cube.sample({0.999f, 0, -1}), mean));  // on -Z
    // Every edge: crossing it changes the colour by at most the footprint's move.
    const Vec3 edges[][2] = {{{1, 0.999f, 0}, {0.999f, 1, 0}},   {{1, -0.999f, 0}, {0.999f, -1, 0}},
                             {{0, 0.999f, 1}, {0, 1, 0.999f}},   {{0, -1, 0.999f}, {0, -0.999f, 1}},
                             {{-1, 0, 0.999f}, {-0.999f, 0, 1}}, {{-1, 0.999f, 0}, {-0.999f, 1, 0}}};
    for (const auto& e : edges) {
        INFO("edge at " << e[0].x << ", " << e[0].y << ", " << e[0].z);
        CHECK(near(cube.sample(e[0]), cube.sample(e[1])));
    }
    // Half a texel inside a face (and farther), the face's own colour.
    CHECK(packBgra8(cube.sample({1, 0, -(1.0f - 2.0f / 16.0f)})) == packBgra(255, 0, 0));
}

TEST_CASE("gradient sky: ground below the horizon, horizon to zenith above", "[render][sky]") {
    SkyGradient g;
    g.zenith = {0.0f, 0.0f, 1.0f, 1.0f};
    g.horizon = {1.0f, 1.0f, 1.0f, 1.0f};
    g.ground = {0.2f, 0.1f, 0.0f, 1.0f};
    CHECK(packBgra8(g.sample({0, 1, 0})) == packBgra(0, 0, 255));
    CHECK(packBgra8(g.sample({0, 5, 0})) == packBgra(0, 0, 255));
    CHECK(packBgra8(g.sample({1, 0, 0})) == packBgra(255, 255, 255));
    CHECK(packBgra8(g.sample({1, -0.01f, 0})) == packBgra8(g.ground));
    // Elevation e = 0.25: a quarter of the way: 0.75 x 255 = 191.25 -> 191.
    CHECK(packBgra8(g.sample({0.9682458f, 0.25f, 0})) == packBgra(191, 191, 255));
}

TEST_CASE("the sky seen along each axis: the face the table gives, oriented as OpenGL samples it", "[render][sky]") {
    Scene scene;
    scene.sky.kind = Sky::Kind::Cube;
    scene.sky.cube = std::make_shared<CubeMap>(quadrantCube());
    // Camera basis: right = forward x up. Upper-left of the image (pixel 16, 16: ndc -0.484,
    // +0.484) looks along forward - 0.48 right + 0.48 up; by hand from the table, for each view
    // that is the face's top-right quadrant, and the lower-right pixel (47, 47) its bottom-left:
    // a cube map seen from inside with a right-handed camera is mirrored, as in OpenGL.
    struct View {
        Vec3 forward, up;
        int face;
    };
    const View views[] = {{{1, 0, 0}, {0, 1, 0}, 0},  {{-1, 0, 0}, {0, 1, 0}, 1}, {{0, 1, 0}, {0, 0, -1}, 2},
                          {{0, -1, 0}, {0, 0, 1}, 3}, {{0, 0, 1}, {0, 1, 0}, 4},  {{0, 0, -1}, {0, 1, 0}, 5}};
    for (const View& v : views) {
        INFO("face " << v.face);
        FrameBuffer fb(kSize, kSize);
        RenderContext ctx(fb);
        renderSceneFrame(ctx, scene, lookingAlong(v.forward, v.up), RenderSettings{});
        CHECK(fb.pixel(16, 16) == expected(v.face, 1));
        CHECK(fb.pixel(47, 47) == expected(v.face, 2));
        CHECK(fb.pixel(47, 16) == expected(v.face, 0));
    }
}

TEST_CASE("the sky is drawn only where no geometry was, per sample before the resolve", "[render][sky]") {
    // A red unlit square in front of the camera (looking down -z) covering the middle.
    const Scene scene = redSquare(1.0f);
    const FrameView view = lookingAlong({0, 0, -1}, {0, 1, 0});
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    FrameBuffer plain(kSize, kSize);
    {
        RenderContext ctx(plain);
        renderSceneFrame(ctx, scene, view, settings);
    }
    Scene withSky = scene;
    withSky.sky.kind = Sky::Kind::Gradient;
    withSky.sky.gradient.horizon = {0.0f, 1.0f, 0.0f, 1.0f}; // green at the horizon, blue above
    withSky.sky.gradient.zenith = {0.0f, 0.0f, 1.0f, 1.0f};
    withSky.sky.gradient.ground = {0.0f, 0.5f, 0.5f, 1.0f}; // no red anywhere in the sky
    FrameBuffer fb(kSize, kSize);
    RenderContext ctx(fb);
    renderSceneFrame(ctx, withSky, view, settings);
    int geometry = 0, sky = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (plain.pixel(x, y) != packBgra(0, 0, 0)) { // the square: untouched by the sky
                CHECK(fb.pixel(x, y) == plain.pixel(x, y));
                ++geometry;
            } else { // background: the sky along that pixel's ray
                CHECK(withinOne(fb.pixel(x, y), referenceSky(withSky.sky, view, x, y)));
                ++sky;
            }
        }
    CHECK(geometry > 200);
    CHECK(sky > 1000);
    // Multisampled (4): away from the square's edges the same pixels; on an edge pixel the
    // uncovered samples hold the sky, so the resolve mixes red with sky (green/blue), not black.
    RenderSettings msaa = settings;
    msaa.antiAliasing = *AntiAliasing::multisample(4);
    FrameBuffer fm(kSize, kSize), fmPlain(kSize, kSize);
    {
        RenderContext c(fm);
        renderSceneFrame(c, withSky, view, msaa);
        RenderContext cp(fmPlain);
        renderSceneFrame(cp, scene, view, msaa);
    }
    CHECK(fm.pixel(2, 2) == fb.pixel(2, 2));
    CHECK(fm.pixel(kSize / 2, kSize / 2) == fb.pixel(kSize / 2, kSize / 2));
    int mixedEdges = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const Pixel p = fmPlain.pixel(x, y);
            if (pixelR(p) > 0 && pixelR(p) < 255) { // an edge pixel of the square
                const Pixel q = fm.pixel(x, y);
                CHECK(int(pixelR(q)) == int(pixelR(p))); // the square's share is the same
                mixedEdges += pixelG(q) + pixelB(q) > 0;
            }
        }
    CHECK(mixedEdges > 20);
    // Supersampled (4): the sky is drawn per sample, so the background is the mean of four rays.
    RenderSettings ssaa = settings;
    ssaa.antiAliasing = *AntiAliasing::supersample(4);
    FrameBuffer fs(kSize, kSize);
    RenderContext cs(fs);
    renderSceneFrame(cs, withSky, view, ssaa);
    CHECK(pixelB(fs.pixel(kSize / 2, 1)) > 0); // above the square: sky, not black
}

TEST_CASE("transparent surfaces blend over the sky, which is drawn before them", "[render][sky][transparency]") {
    // A half-transparent red square against a gradient sky: its pixels are red over the sky
    // colour along their rays, not the sky alone (a sky drawn after it would cover it: the
    // square writes no depth).
    Scene scene = redSquare(0.5f);
    scene.sky.kind = Sky::Kind::Gradient;
    const FrameView view = lookingAlong({0, 0, -1}, {0, 1, 0});
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    for (const int msaa : {1, 4}) {
        INFO("msaa " << msaa);
        settings.antiAliasing = *AntiAliasing::multisample(msaa);
        FrameBuffer fb(kSize, kSize);
        RenderContext ctx(fb);
        renderSceneFrame(ctx, scene, view, settings);
        const int x = kSize / 2, y = kSize / 2 - 4; // inside the square
        CHECK(withinOne(fb.pixel(x, y), blendOver(packBgra(255, 0, 0), referenceSky(scene.sky, view, x, y), 0.5f)));
        CHECK(fb.pixel(x, y) != referenceSky(scene.sky, view, x, y));
    }
}

TEST_CASE("the sky pass's float path agrees with the double reference within one unit", "[render][sky]") {
    // Random views (fixed seed; every direction, roll, field of view 20-150 degrees) of a random
    // gradient and of a cube map of random texels (so the bilinear weights matter everywhere):
    // every pixel of the pass (one sample and MSAA 4) within one unit per channel of the reference
    // Sky::sample along the same ray, and most of them exact. A wrong face, orientation, texel
    // offset or gradient step would be off by far more on a large share of pixels.
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), colour(0.0f, 1.0f);
    std::vector<std::uint8_t> faces[kCubeFaces];
    std::array<const std::uint8_t*, kCubeFaces> ptrs{};
    for (int f = 0; f < kCubeFaces; ++f) {
        for (int i = 0; i < 16 * 16 * 4; ++i) faces[f].push_back(std::uint8_t(rng() & 0xFFu));
        ptrs[std::size_t(f)] = faces[f].data();
    }
    Sky cube;
    cube.kind = Sky::Kind::Cube;
    cube.cube = std::make_shared<CubeMap>(CubeMap::fromRgba8(16, ptrs));
    constexpr int kViews = 24;
    long pixels = 0, exact = 0;
    for (int v = 0; v < kViews; ++v) {
        Sky gradient;
        gradient.kind = Sky::Kind::Gradient;
        gradient.gradient.zenith = {colour(rng), colour(rng), colour(rng), 1.0f};
        gradient.gradient.horizon = {colour(rng), colour(rng), colour(rng), 1.0f};
        gradient.gradient.ground = {colour(rng), colour(rng), colour(rng), 1.0f};
        app::CameraSetup c;
        c.eye = {0, 0, 0};
        c.target = {unit(rng), unit(rng), unit(rng)};
        c.up = {unit(rng), unit(rng), unit(rng)};
        c.fovDegrees = 20.0 + 130.0 * colour(rng);
        const FrameView view = app::makeFrameView(c, kSize, kSize, {0, 0, 1}, {});
        for (const Sky* sky : {&gradient, &cube}) {
            INFO("view " << v << (sky == &cube ? " cube" : " gradient"));
            FrameBuffer fb(kSize, kSize);
            fb.clear(0u, FrameBuffer::kFarDepth);
            CHECK(drawSkyRows(fb, view.rays, *sky, 0, kSize) == std::uint64_t(kSize) * kSize);
            MsaaBuffer ms;
            REQUIRE(ms.resize(kSize, kSize, 4));
            ms.clearRows(0, kSize, 0u, FrameBuffer::kFarDepth);
            CHECK(drawSkyMsaaRows(ms, view.rays, *sky, 0, kSize) == std::uint64_t(kSize) * kSize);
            int bad = 0;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const Pixel ref = referenceSky(*sky, view, x, y);
                    bad += !withinOne(fb.pixel(x, y), ref);
                    bad += ms.colourRow(y)[std::size_t(x) * 4 + 3] != fb.pixel(x, y); // the same colour
                    exact += fb.pixel(x, y) == ref;
                    ++pixels;
                }
            CHECK(bad == 0);
        }
    }
    CHECK(exact > pixels * 9 / 10);
}
