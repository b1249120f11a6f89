// MTL materials end to end: an OBJ's Kd, Ks and Ns through loadScene and
// renderSceneFrame, against colours worked out by hand, under --materials mtl and fixed.
#include "TestFramework.hpp"

#include <optional>
#include <string>
#include <vector>

#include "Math/Transform.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "Resources/Image.hpp"
#include "Resources/ObjTestUtil.hpp" // Tests/Resources: the OBJ tests' temporary files

using namespace sr;
using namespace sr::objtest;

namespace {

// Five unit quads facing +Z, centred at x = 0, 2, 4, 6, 8 (y = 0, z = 0), one per case:
//   A  Kd (0.2, 0.4, 0.6), Ks (0.25, 0, 0.1), Ns 8        untextured, coloured specular
//   B  Kd (0.2, 0.4, 0.6), Ks (1, 1, 1),      Ns 0        untextured, no specular term (Ns 0)
//   C  Kd (0.5, 1, 0.25) x the texel (200, 91, 41), Ks 0  textured, tinted
//   D  Kd (0, 0, 0) with a map_Kd, Ks 0                  textured, "the texture alone"
//   E  no material                                        untextured, the fixed values (--kd)
std::string writeMaterialScene() {
    const std::string dir = freshDir("materials");
    Image texel;
    texel.width = texel.height = 1;
    texel.rgba = {200, 91, 41, 255};
    REQUIRE(writeImage(dir + "/t.png", texel).ok());
    writeText(dir, "m.mtl",
              "newmtl A\nKd 0.2 0.4 0.6\nKs 0.25 0 0.1\nNs 8\n"
              "newmtl B\nKd 0.2 0.4 0.6\nKs 1 1 1\nNs 0\n"
              "newmtl C\nKd 0.5 1 0.25\nKs 0 0 0\nmap_Kd t.png\n"
              "newmtl D\nKd 0 0 0\nmap_Kd t.png\n");
    std::string obj = "mtllib m.mtl\nvt 0.5 0.5\nvn 0 0 1\n";
    const char* materials[] = {"A", "B", "C", "D", nullptr};
    for (int q = 0; q < 5; ++q) {
        const float x = 2.0f * float(q);
        for (const auto& [dx, dy] : {std::pair{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.5f, 0.5f}, {-0.5f, 0.5f}})
            obj += "v " + std::to_string(x + dx) + " " + std::to_string(dy) + " 0\n";
        const int b = 4 * q;
        if (materials[q]) obj += std::string("usemtl ") + materials[q] + "\n";
        else obj += "usemtl (none)\n"; // an unknown name: no material
        obj += "f " + std::to_string(b + 1) + "/1/1 " + std::to_string(b + 2) + "/1/1 " + std::to_string(b + 3) + "/1/1\n";
        obj += "f " + std::to_string(b + 1) + "/1/1 " + std::to_string(b + 3) + "/1/1 " + std::to_string(b + 4) + "/1/1\n";
    }
    return writeText(dir, "m.obj", obj);
}

// The centre pixel of a 33 x 33 image looking straight down -Z at quad q from 100 units, the
// light along +Z: at that pixel N = L = V (to well under 1e-6), so N.L = N.H = 1, diffuse
// 1.1, and any Ns gives a specular sum of 1: colour = 1.1 kd + ks.
Pixel centrePixel(const app::LoadedScene& scene, app::SceneOptions options, int q) {
    options.width = options.height = 33;
    options.eye = Vec3{2.0f * float(q), 0.0f, 100.0f};
    options.target = Vec3{2.0f * float(q), 0.0f, 0.0f};
    options.fovDegrees = 2.0; // the quad covers the middle ~9 x 9 pixels
    options.nearZ = 50.0;
    options.farZ = 200.0;
    options.light = Vec3{0.0f, 0.0f, 1.0f};
    const FrameView view =
        app::makeFrameView(app::resolveCamera(options, scene), options.width, options.height, options.light, scene.lights);
    FrameBuffer fb(options.width, options.height);
    RenderContext ctx(fb);
    app::renderFrame(ctx, scene, view, app::makeRenderSettings(options));
    return fb.pixel(16, 16);
}

struct Expected {
    int r, g, b;
};

void checkCases(app::SceneOptions options, const Expected (&expected)[5]) {
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    REQUIRE(scene.value().scene.draws.size() == 5); // one per material, plus the faces without one
    for (int q = 0; q < 5; ++q) {
        INFO("quad " << "ABCDE"[q] << ", " << shadingModeName(options.shading) << ", materials "
                     << app::materialRuleName(options.materials) << ", isa " << isaName(options.isa));
        const Pixel p = centrePixel(scene.value(), options, q);
        CHECK(int(pixelR(p)) == expected[q].r);
        CHECK(int(pixelG(p)) == expected[q].g);
        CHECK(int(pixelB(p)) == expected[q].b);
    }
}

} // namespace

TEST_CASE("MTL Kd, Ks and Ns shade as the reference renderer's --materials mtl", "[render][materials]") {
    app::SceneOptions options;
    options.obj = writeMaterialScene();
    options.kd = Color{0.2f, 0.32f, 0.12f, 1.0f}; // faces without a material (E)
    // Lit (N.L = N.H = 1): colour = 1.1 kd + ks, x 255, rounded to nearest:
    //  A: r 0.22 + 0.25 = 0.47 -> 119.85 -> 120; g 0.44 -> 112.2 -> 112; b 0.66 + 0.1 = 0.76 -> 193.8 -> 194
    //  B: no specular (Ns 0, although x^0 = 1): 56.1, 112.2, 168.3 -> (56, 112, 168)
    //  C: kd = Kd x texel = (0.5 x 200, 91, 0.25 x 41) / 255 -> x 1.1 x 255 = 110, 100.1, 11.275 -> (110, 100, 11)
    //  D: black Kd with a map = the texel alone: 220, 100.1, 45.1 -> (220, 100, 45)
    //  E: fixed: 1.1 x (0.2, 0.32, 0.12) + 0.5 = 0.72, 0.852, 0.632 -> 183.6, 217.26, 161.16 -> (184, 217, 161)
    const Expected lit[5] = {{120, 112, 194}, {56, 112, 168}, {110, 100, 11}, {220, 100, 45}, {184, 217, 161}};
    // Unlit: kd alone: A, B (51, 102, 153); C (100, 91, 10.25 -> 10); D (200, 91, 41);
    //  E (51, 81.6 -> 82, 30.6 -> 31).
    const Expected unlit[5] = {{51, 102, 153}, {51, 102, 153}, {100, 91, 10}, {200, 91, 41}, {51, 82, 31}};
    for (Isa isa : {Isa::Scalar, bestIsa()}) {
        options.isa = isa;
        for (ShadingMode mode : {ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong}) {
            options.shading = mode;
            checkCases(options, lit);
        }
        options.shading = ShadingMode::Unlit;
        checkCases(options, unlit);
    }
}

TEST_CASE("--materials fixed ignores the MTL values: kd = --kd or the texel, white ks 0.5, shininess 32",
          "[render][materials]") {
    app::SceneOptions options;
    options.obj = writeMaterialScene();
    options.kd = Color{0.2f, 0.32f, 0.12f, 1.0f};
    options.materials = app::MaterialRule::Fixed;
    // Every untextured quad is E's (184, 217, 161); the textured ones are 1.1 x texel + 0.5:
    // 220 + 127.5 -> 255, 100.1 + 127.5 = 227.6 -> 228, 45.1 + 127.5 = 172.6 -> 173.
    const Expected lit[5] = {{184, 217, 161}, {184, 217, 161}, {255, 228, 173}, {255, 228, 173}, {184, 217, 161}};
    const Expected unlit[5] = {{51, 82, 31}, {51, 82, 31}, {200, 91, 41}, {200, 91, 41}, {51, 82, 31}};
    for (Isa isa : {Isa::Scalar, bestIsa()}) {
        options.isa = isa;
        options.shading = ShadingMode::Phong;
        checkCases(options, lit);
        options.shading = ShadingMode::Unlit;
        checkCases(options, unlit);
    }
}

TEST_CASE("--materials parses mtl and fixed; the default is mtl", "[render][materials]") {
    CHECK(app::SceneOptions{}.materials == app::MaterialRule::Mtl);
    CHECK(app::parseMaterialRule("mtl") == app::MaterialRule::Mtl);
    CHECK(app::parseMaterialRule("fixed") == app::MaterialRule::Fixed);
    CHECK_FALSE(app::parseMaterialRule("MTL").has_value());
    CHECK_FALSE(app::parseMaterialRule("").has_value());
    std::vector<std::string> args{"--materials", "fixed"};
    std::size_t i = 0;
    app::SceneOptions o;
    std::string error;
    CHECK(app::parseSceneFlag(args, i, o, error) == app::FlagResult::Consumed);
    CHECK(o.materials == app::MaterialRule::Fixed);
    args = {"--materials=phong"};
    i = 0;
    CHECK(app::parseSceneFlag(args, i, o, error) == app::FlagResult::Error);
    CHECK(error.find("mtl or fixed") != std::string::npos);
}

TEST_CASE("a material's own sampler (glTF) sets its draw's wrap and filter unless the settings chose them",
          "[render][materials][samplers]") {
    // A quad whose uvs run from -1 to 2 over a 2x2 texture: repeat, clamp and mirror give three
    // different images, nearest and bilinear two more. The material's sampler says clamp +
    // nearest; the frame's settings say repeat + bilinear.
    Mesh quad;
    quad.positions = {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}};
    quad.normals.assign(4, {0.0f, 0.0f, 1.0f});
    quad.uvs = {{-1.0f, -1.0f}, {2.0f, -1.0f}, {2.0f, 2.0f}, {-1.0f, 2.0f}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    const std::uint8_t rgba[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    const Texture texture = Texture::fromRgba8(2, 2, rgba);
    FrameView view;
    view.eye = {0.0f, 0.0f, 50.0f};
    view.viewProj = perspectiveInfinite(radians(1.5f), 1.0f, 1.0f) * lookAt(view.eye, {0, 0, 0}, {0, 1, 0});
    view.finiteFar = false;
    auto render = [&](RenderSettings settings, std::optional<WrapModes> wrap, std::optional<TextureFilter> filter) {
        SurfaceMaterial material;
        material.texture = &texture;
        material.wrap = wrap;
        material.filter = filter;
        settings.shading = ShadingMode::Unlit;
        FrameBuffer fb(48, 48);
        fb.clear(0);
        RenderContext ctx(fb);
        drawMesh(ctx, view, settings, quad, material);
        return std::vector<Pixel>(fb.colorRow(0), fb.colorRow(0) + 48 * 48);
    };
    RenderSettings frame; // repeat + bilinear
    RenderSettings clampNearest = frame;
    clampNearest.wrap = WrapMode::Clamp;
    clampNearest.filter = TextureFilter::Nearest;
    REQUIRE(render(frame, std::nullopt, std::nullopt) != render(clampNearest, std::nullopt, std::nullopt));
    // The file's sampler applies by default...
    const WrapModes clamp{WrapMode::Clamp, WrapMode::Clamp};
    CHECK(render(frame, clamp, TextureFilter::Nearest) == render(clampNearest, std::nullopt, std::nullopt));
    // ... each half on its own ...
    RenderSettings clampOnly = frame;
    clampOnly.wrap = WrapMode::Clamp;
    CHECK(render(frame, clamp, std::nullopt) == render(clampOnly, std::nullopt, std::nullopt));
    // ... each axis its own mode (wrapS clamps u, wrapT repeats v): neither mode on both axes ...
    const auto apart = render(frame, WrapModes{WrapMode::Clamp, WrapMode::Repeat}, std::nullopt);
    CHECK(apart != render(frame, clamp, std::nullopt));
    CHECK(apart != render(frame, WrapModes{WrapMode::Repeat, WrapMode::Repeat}, std::nullopt));
    // ... and not where the user chose (--wrap / --filter, the demo's T key, the report).
    RenderSettings chosen = frame;
    chosen.wrapFromFile = false;
    chosen.filterFromFile = false;
    CHECK(render(chosen, clamp, TextureFilter::Nearest) == render(frame, std::nullopt, std::nullopt));
    RenderSettings wrapChosen = frame;
    wrapChosen.wrapFromFile = false;
    RenderSettings nearestOnly = frame;
    nearestOnly.filter = TextureFilter::Nearest;
    CHECK(render(wrapChosen, clamp, TextureFilter::Nearest) == render(nearestOnly, std::nullopt, std::nullopt));
}

TEST_CASE("--wrap and --filter given on the command line win over a file's samplers; --quality's filter does not",
          "[render][materials][samplers]") {
    auto parse = [](std::vector<std::string> args) {
        app::SceneOptions o;
        std::string error;
        for (std::size_t i = 0; i < args.size(); ++i) REQUIRE(app::parseSceneFlag(args, i, o, error) == app::FlagResult::Consumed);
        return app::makeRenderSettings(o);
    };
    const RenderSettings none = parse({});
    CHECK(none.wrapFromFile);
    CHECK(none.filterFromFile);
    const RenderSettings both = parse({"--wrap", "clamp", "--filter", "nearest"});
    CHECK_FALSE(both.wrapFromFile);
    CHECK_FALSE(both.filterFromFile);
    const RenderSettings preset = parse({"--quality", "balanced"});
    CHECK(preset.filterFromFile);
}
