// Tests of scene setup: splitting a loaded model into per-range meshes (contents, work bounded by the range), and the model's cameras (--camera, the demo's V key).
#include "TestFramework.hpp"

#include "Platform/App/DemoController.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "Resources/GltfTestUtil.hpp"
#include "Resources/ObjTestUtil.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace sr;
using namespace sr::app;

namespace {

// A strip of `quads` unit quads along x (2 triangles each, 2 * (quads + 1) vertices), with
// normals and uvs that identify the vertex: normal.x = uv.x = its index.
Mesh strip(int quads) {
    Mesh m;
    for (int i = 0; i <= quads; ++i)
        for (int y = 0; y < 2; ++y) {
            const auto v = float(m.positions.size());
            m.positions.emplace_back(float(i), float(y), 0.0f);
            m.normals.emplace_back(v, 0.0f, 1.0f);
            m.uvs.emplace_back(v, 0.5f);
        }
    for (std::uint32_t i = 0; i < std::uint32_t(quads); ++i) {
        const std::uint32_t a = 2 * i, b = a + 2, c = a + 3, d = a + 1;
        for (std::uint32_t k : {a, b, c, a, c, d}) m.indices.push_back(k);
    }
    return m;
}

} // namespace

TEST_CASE("appendRange keeps the range's vertices in order of first use; clearRange resets the remap",
          "[platform][scene]") {
    const Mesh src = strip(3);
    std::vector<std::uint32_t> remap(src.vertexCount(), kNoVertex);
    // The second quad: source vertices 2, 4, 5, 2, 5, 3.
    Mesh part;
    appendRange(part, src, 6, 6, remap);
    clearRange(src, 6, 6, remap);
    REQUIRE(part.vertexCount() == 4);
    REQUIRE(part.hasNormals());
    REQUIRE(part.hasUvs());
    CHECK(part.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
    const float expected[] = {2, 4, 5, 3};
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(part.positions[i].x == src.positions[std::size_t(expected[i])].x);
        CHECK(part.positions[i].y == src.positions[std::size_t(expected[i])].y);
        CHECK(part.normals[i].x == expected[i]);
        CHECK(part.uvs[i].x == expected[i]);
    }
    for (std::uint32_t r : remap) CHECK(r == kNoVertex);
}

// The work of a range is bounded by its size, not the model's: appendRange and clearRange touch
// only the remap entries of the range's own vertices. Every other entry holds a marker that a reset of
// the whole array per range (a quadratic split: R ranges x V vertices) would overwrite.
TEST_CASE("appendRange and clearRange read and write only the remap entries of the range's vertices",
          "[platform][scene]") {
    const int quads = 500;
    const Mesh src = strip(quads);
    constexpr std::uint32_t kMarker = 0xC0FFEEu;
    std::vector<std::uint32_t> remap(src.vertexCount(), kMarker);
    std::size_t vertices = 0;
    for (int q = 0; q < quads; ++q) {
        // This quad's four vertices are clear on entry; every other entry keeps the marker.
        const std::uint32_t first = 2 * std::uint32_t(q);
        for (std::uint32_t v = first; v < first + 4; ++v) remap[v] = kNoVertex;
        Mesh part;
        appendRange(part, src, std::uint32_t(q) * 6, 6, remap);
        clearRange(src, std::uint32_t(q) * 6, 6, remap);
        REQUIRE(part.triangleCount() == 2);
        vertices += part.vertexCount();
        std::size_t markers = 0, clear = 0;
        for (std::uint32_t r : remap) {
            markers += r == kMarker;
            clear += r == kNoVertex;
        }
        REQUIRE(clear == 4);
        REQUIRE(markers == remap.size() - 4);
        for (std::uint32_t v = first; v < first + 4; ++v) remap[v] = kMarker;
    }
    CHECK(vertices == 4 * std::size_t(quads));
}

TEST_CASE("--camera N views through the model's camera N; flags override it; V cycles the cameras in the demo",
          "[platform][cameras]") {
    using gltftest::Asset;
    const std::string dir = objtest::freshDir("scene-cameras");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
    a.nodes = "[{\"mesh\":0,\"children\":[1,2]},{\"translation\":[0,0,4],\"camera\":0},"
              "{\"translation\":[5,0,0],\"rotation\":[0,0.7071067811865476,0,0.7071067811865476],\"camera\":0}]";
    a.extra = ",\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.25,\"zfar\":40}}]";
    SceneOptions options;
    options.obj = objtest::writeText(dir, "two.gltf", a.embedded());
    options.camera = 1;
    auto scene = loadScene(options);
    REQUIRE(scene.ok());
    REQUIRE(scene.value().cameras.size() == 2);
    CameraSetup c = resolveCamera(options, scene.value());
    CHECK(c.eye.x == 5.0f);
    CHECK(c.target.x == Approx(4.0f).margin(1e-6)); // looking down -x
    CHECK(c.fovDegrees == Approx(0.8 * 180.0 / 3.14159265358979).epsilon(1e-12));
    CHECK(c.nearZ == 0.25);
    CHECK(c.farZ == 40.0);
    // Explicit flags win over the camera's values, one by one.
    options.fovDegrees = 30.0;
    options.explicitFov = true;
    options.farZ = 7.0;
    c = resolveCamera(options, scene.value());
    CHECK(c.fovDegrees == 30.0);
    CHECK(c.farZ == 7.0);
    CHECK(c.eye.x == 5.0f);
    // A camera the file does not have is an error naming the file and the count.
    options.camera = 2;
    auto missing = loadScene(options);
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().find("two.gltf") != std::string::npos);
    CHECK(missing.error().find("2 camera(s)") != std::string::npos);
    // The command-line flag.
    std::vector<std::string> args{"--camera", "3"};
    std::size_t i = 0;
    SceneOptions parsed;
    std::string error;
    CHECK(parseSceneFlag(args, i, parsed, error) == FlagResult::Consumed);
    CHECK(parsed.camera == 3);
    args = {"--camera=-1"};
    i = 0;
    CHECK(parseSceneFlag(args, i, parsed, error) == FlagResult::Error);

    // The demo: V goes start -> camera 0 -> camera 1 -> start; each view is the camera exactly.
    options = SceneOptions{};
    options.obj = objtest::writeText(dir, "two.gltf", a.embedded());
    auto loaded = loadScene(options);
    REQUIRE(loaded.ok());
    const CameraSetup start = resolveCamera(options, loaded.value());
    DemoController demo(start, makeRenderSettings(options), options.light);
    const auto same = [](const CameraSetup& x, const CameraSetup& y) {
        return x.eye.x == y.eye.x && x.eye.y == y.eye.y && x.eye.z == y.eye.z && x.target.x == y.target.x &&
               x.target.z == y.target.z && x.fovDegrees == y.fovDegrees && x.nearZ == y.nearZ && x.farZ == y.farZ;
    };
    demo.keyDown(Key::V);
    CHECK(same(demo.cameraSetup(), start)); // no cameras given to the controller yet: nothing changes
    demo.keyUp(Key::V);
    demo.setCameras(loaded.value().cameras);
    for (int expected : {0, 1, -1, 0}) {
        INFO("expected camera " << expected);
        demo.keyDown(Key::V);
        demo.keyUp(Key::V);
        CHECK(demo.cameraIndex() == expected);
        CHECK(same(demo.cameraSetup(), expected < 0 ? start : loaded.value().cameras[std::size_t(expected)]));
        CHECK((demo.modeSummary().find("camera " + std::to_string(expected)) != std::string::npos) == (expected >= 0));
    }
    // R returns to the selected camera after flying away.
    demo.keyDown(Key::W);
    demo.update(0.05);
    demo.keyUp(Key::W);
    CHECK_FALSE(same(demo.cameraSetup(), loaded.value().cameras[0]));
    demo.keyDown(Key::R);
    CHECK(same(demo.cameraSetup(), loaded.value().cameras[0]));
}

TEST_CASE("a file's lights replace --light's one (with a warning if --light was given); the built-in scene has two",
          "[platform][lights]") {
    using gltftest::Asset;
    const std::string dir = objtest::freshDir("scene-lights");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
    a.nodes = "[{\"mesh\":0,\"children\":[1]},{\"translation\":[0,3,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}]";
    a.extra = ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"color\":[1,0,0],\"intensity\":5}]}}";
    SceneOptions options;
    options.obj = objtest::writeText(dir, "lit.gltf", a.embedded());
    auto scene = loadScene(options);
    REQUIRE(scene.ok());
    REQUIRE(scene.value().lights.size() == 1);
    CHECK(scene.value().warnings.empty());
    const FrameView view = makeFrameView(resolveCamera(options, scene.value()), 64, 48, options.light, scene.value().lights);
    REQUIRE(view.lighting.lights.size() == 1);
    CHECK(view.lighting.lights[0].type == LightType::Point);
    CHECK(view.lighting.lights[0].colour.r == 5.0f);
    CHECK_FALSE(view.lighting.whiteDirectional());
    // --light given: still the file's lights, and a warning naming the file.
    options.light = {0, 0, 1};
    options.explicitLight = true;
    auto warned = loadScene(options);
    REQUIRE(warned.ok());
    REQUIRE(warned.value().warnings.size() == 1);
    CHECK(warned.value().warnings[0].find("lit.gltf: --light is ignored") != std::string::npos);
    // A file without lights: --light's one white directional light.
    options.obj.clear();
    SceneOptions plain;
    const FrameView noLights = makeFrameView(resolveCamera(plain, scene.value()), 64, 48, {0, 0, 2}, {});
    REQUIRE(noLights.lighting.lights.size() == 1);
    CHECK(noLights.lighting.lights[0].toLight == Vec3(0, 0, 1));
    CHECK(noLights.lighting.whiteDirectional());
    // The built-in scene: --light's key light first, then its warm fill light.
    auto builtIn = loadScene(options);
    REQUIRE(builtIn.ok());
    REQUIRE(builtIn.value().lights.size() == 2);
    CHECK(builtIn.value().lights[0].toLight == Vec3(0, 0, 1));
    CHECK(builtIn.value().lights[1].type == LightType::Point);
    CHECK(builtIn.value().warnings.empty());
}

TEST_CASE("a glTF scene's --quality presets are its own model's: pbr in linear light, MSAA 4 for balanced; explicit flags win",
          "[platform][quality][pbr]") {
    auto resolve = [](std::vector<std::string> args, bool physical) {
        SceneOptions o;
        std::string error;
        for (std::size_t i = 0; i < args.size(); ++i) REQUIRE(parseSceneFlag(args, i, o, error) == FlagResult::Consumed);
        LoadedScene s;
        s.physical = physical;
        s.builtIn = !physical;
        REQUIRE_FALSE(applySceneDefaults(o, s).has_value());
        return o;
    };
    const SceneOptions fast = resolve({"--quality", "fast"}, true);
    CHECK(fast.antiAliasing.ssaaSamples() == 1);
    CHECK(fast.antiAliasing.msaaSamples() == 1);
    CHECK(fast.filter == TextureFilter::Bilinear);
    CHECK(fast.shading == ShadingMode::Pbr);
    CHECK(fast.colour == ColorMode::Linear);
    const SceneOptions balanced = resolve({"--quality", "balanced"}, true);
    CHECK(balanced.antiAliasing.ssaaSamples() == 1);
    CHECK(balanced.antiAliasing.msaaSamples() == 4);
    CHECK(balanced.filter == TextureFilter::Trilinear);
    CHECK(balanced.shading == ShadingMode::Pbr);
    const SceneOptions accurate = resolve({"--quality", "accurate"}, true);
    CHECK(accurate.antiAliasing.ssaaSamples() == 16);
    CHECK(accurate.antiAliasing.msaaSamples() == 1);
    CHECK(accurate.shading == ShadingMode::Pbr);
    // Explicit flags win, before or after the preset.
    const SceneOptions mixed = resolve({"--shading", "gouraud", "--quality", "balanced", "--ssaa", "4"}, true);
    CHECK(mixed.shading == ShadingMode::Gouraud);
    CHECK(mixed.antiAliasing.ssaaSamples() == 4);
    CHECK(mixed.antiAliasing.msaaSamples() == 1);
    CHECK(mixed.filter == TextureFilter::Trilinear);
    // The built-in scene (and OBJ) keep the display-model presets.
    const SceneOptions plainFast = resolve({"--quality", "fast"}, false);
    CHECK(plainFast.shading == ShadingMode::Gouraud);
    const SceneOptions plainBalanced = resolve({"--quality", "balanced"}, false);
    CHECK(plainBalanced.antiAliasing.ssaaSamples() == 4);
    CHECK(plainBalanced.antiAliasing.msaaSamples() == 1);
    CHECK(plainBalanced.shading == ShadingMode::Phong);
}

#ifndef _WIN32 // Debian's assimp-testmodels: natively
TEST_CASE("an animated scene's picking, shadows and sorting read the posed meshes", "[platform][animation]") {
    SceneOptions o;
    o.obj = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
    auto loaded = loadScene(o);
    REQUIRE(loaded.ok());
    LoadedScene s = std::move(loaded).value();
    REQUIRE(s.animation);
    // The strip stands from y = 0 to 2 at rest; at 1.25 s its joint at y = 1 has turned 90
    // degrees about Z, so its upper half lies toward -x: a ray at (-0.75, 1.5) meets it only then.
    const Vec3 origin{-0.75f, 1.5f, 5.0f}, dir{0.0f, 0.0f, -1.0f};
    CHECK(pickDraw(s.scene, origin, dir) == -1);
    poseScene(s, 1.25, -1);
    CHECK(pickDraw(s.scene, origin, dir) == 0);
    // And back: the clip's first key is the rest pose; clip 0 alone gives the same as all.
    poseScene(s, 0.0, -1);
    CHECK(pickDraw(s.scene, origin, dir) == -1);
    poseScene(s, 1.25, 0);
    CHECK(pickDraw(s.scene, origin, dir) == 0);
    // A scene without animation keeps nothing for it, and posing it changes nothing.
    SceneOptions still;
    auto plain = loadScene(still);
    REQUIRE(plain.ok());
    CHECK_FALSE(plain.value().animation);
    CHECK(plain.value().meshOrigins.empty());
    CHECK(plain.value().posedModel.positions.empty());
}

TEST_CASE("a glTF material whose only map is occlusion keeps its uvs and its map", "[platform][gltf]") {
    gltftest::Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    a.nodes = R"([{"mesh":0}])";
    a.meshes = R"([{"primitives":[{"attributes":{"POSITION":)" + std::to_string(pos) + R"(,"TEXCOORD_0":)" + std::to_string(uv) +
               R"(},"material":0}]}])";
    a.materials = R"([{"occlusionTexture":{"index":0}}])";
    const std::string ppm = "P6\n1 1\n255\n\x40\x40\x40";
    a.extra = R"(,"textures":[{"source":0}],"images":[{"uri":"data:image/x-portable-pixmap;base64,)" +
              gltftest::base64(std::vector<unsigned char>(ppm.begin(), ppm.end())) + R"("}])";
    SceneOptions o;
    o.obj = objtest::writeText(objtest::freshDir("occlusion-only"), "occlusion.gltf", a.embedded());
    auto loaded = loadScene(o);
    REQUIRE(loaded.ok());
    const Scene& scene = loaded.value().scene;
    REQUIRE(scene.draws.size() == 1);
    const SceneDraw& d = scene.draws[0];
    REQUIRE(d.maps[MapSlot::Occlusion] >= 0);
    CHECK(scene.textures[std::size_t(d.maps[MapSlot::Occlusion])].width() == 1);
    CHECK(scene.meshes[std::size_t(d.mesh)].hasUvs());
}

TEST_CASE("a scene mesh keeps the file's vertex colours (COLOR_0), and drops them where all are white", "[platform][gltf]") {
    // Two meshes: the textured primitive's and the untextured one's (sceneFromModel). Coloured
    // in the untextured one only: the textured mesh's colours (all the white given to vertices
    // without COLOR_0) are dropped, so its draw interpolates none.
    gltftest::Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    const int colour = a.floats({1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3");
    const int white = a.floats({1, 1, 1, 1, 1, 1, 1, 1, 1}, "VEC3");
    a.nodes = R"([{"mesh":0}])";
    a.meshes = R"([{"primitives":[{"attributes":{"POSITION":)" + std::to_string(pos) + R"(,"TEXCOORD_0":)" + std::to_string(uv) +
               R"(,"COLOR_0":)" + std::to_string(white) + R"(},"material":0},{"attributes":{"POSITION":)" + std::to_string(pos) +
               R"(,"COLOR_0":)" + std::to_string(colour) + R"(},"material":1}]}])";
    a.materials = R"([{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}},{}])";
    const std::string ppm = "P6\n1 1\n255\n\x40\x40\x40";
    a.extra = R"(,"textures":[{"source":0}],"images":[{"uri":"data:image/x-portable-pixmap;base64,)" +
              gltftest::base64(std::vector<unsigned char>(ppm.begin(), ppm.end())) + R"("}])";
    SceneOptions o;
    o.obj = objtest::writeText(objtest::freshDir("colour0"), "colour0.gltf", a.embedded());
    auto loaded = loadScene(o);
    REQUIRE(loaded.ok());
    const Scene& scene = loaded.value().scene;
    REQUIRE(scene.draws.size() == 2);
    REQUIRE(scene.meshes.size() == 2);
    const Mesh& textured = scene.meshes[std::size_t(scene.draws[0].mesh)];
    const Mesh& coloured = scene.meshes[std::size_t(scene.draws[1].mesh)];
    CHECK(textured.hasUvs());
    CHECK(textured.colours.empty());
    REQUIRE(coloured.hasColours());
    CHECK(coloured.colours[0].r == 1.0f);
    CHECK(coloured.colours[0].g == 0.0f);
    CHECK(coloured.colours[2].b == 1.0f);
    CHECK(coloured.colours[2].r == 0.0f);
}

TEST_CASE("a glTF specularTexture is drawn from a copy holding its alpha in RGB; its specularColorTexture as it is",
          "[platform][gltf][specular]") {
    const std::string dir = objtest::freshDir("specular-maps");
    // A 2 x 1 TGA with alpha (32 bits, top row first): (10, 20, 30, 64) and (200, 100, 50, 255), as BGRA.
    const unsigned char tga[] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 1, 0, 32, 0x28, 30, 20, 10, 64, 50, 100, 200, 255};
    objtest::writeText(dir, "s.tga", std::string(reinterpret_cast<const char*>(tga), sizeof tga));
    gltftest::Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    a.nodes = R"([{"mesh":0}])";
    a.meshes = R"([{"primitives":[{"attributes":{"POSITION":)" + std::to_string(pos) + R"(,"TEXCOORD_0":)" + std::to_string(uv) +
               R"(},"material":0}]}])";
    a.materials = R"([{"extensions":{"KHR_materials_specular":{"specularTexture":{"index":0},"specularColorTexture":{"index":0}}}}])";
    a.extra = R"(,"textures":[{"source":0}],"images":[{"uri":"s.tga"}])";
    SceneOptions o;
    o.obj = objtest::writeText(dir, "specular.gltf", a.embedded());
    auto loaded = loadScene(o);
    REQUIRE(loaded.ok());
    const Scene& scene = loaded.value().scene;
    REQUIRE(scene.draws.size() == 1);
    const SceneDraw& d = scene.draws[0];
    REQUIRE(d.maps[MapSlot::Specular] >= 0);
    REQUIRE(d.maps[MapSlot::SpecularColour] >= 0);
    CHECK(d.maps[MapSlot::Specular] != d.maps[MapSlot::SpecularColour]);
    const Texture& alpha = scene.textures[std::size_t(d.maps[MapSlot::Specular])];
    const Texture& colour = scene.textures[std::size_t(d.maps[MapSlot::SpecularColour])];
    // Nearest texel of each column (u 0.25 and 0.75).
    const Color a0 = alpha.sample({0.25f, 0.5f}, 0.0f, TextureFilter::Nearest, WrapMode::Clamp);
    const Color a1 = alpha.sample({0.75f, 0.5f}, 0.0f, TextureFilter::Nearest, WrapMode::Clamp);
    CHECK(a0.r == 64.0f / 255.0f);
    CHECK(a0.g == 64.0f / 255.0f);
    CHECK(a0.b == 64.0f / 255.0f);
    CHECK(a1.r == 1.0f);
    const Color c0 = colour.sample({0.25f, 0.5f}, 0.0f, TextureFilter::Nearest, WrapMode::Clamp);
    CHECK(c0.r == 10.0f / 255.0f);
    CHECK(c0.g == 20.0f / 255.0f);
}

TEST_CASE("a glTF scene drawn pbr in front of a sky is lit by it unless --no-ibl; other scenes only with --ibl", "[platform][ibl]") {
    // The flags.
    std::vector<std::string> args{"--no-ibl", "--ibl"};
    std::size_t i = 0;
    SceneOptions parsed;
    std::string error;
    CHECK_FALSE(parsed.ibl.has_value());
    CHECK(parseSceneFlag(args, i, parsed, error) == FlagResult::Consumed);
    CHECK(parsed.ibl == false);
    ++i;
    CHECK(parseSceneFlag(args, i, parsed, error) == FlagResult::Consumed);
    CHECK(parsed.ibl == true);
    parsed.sky = Sky::Kind::None;
    CHECK(validateSceneOptions(parsed).has_value()); // --ibl needs a sky
    parsed.ibl = false;
    CHECK_FALSE(validateSceneOptions(parsed).has_value()); // --no-ibl does not

    const auto iblOf = [](SceneOptions o) {
        auto loaded = loadScene(o);
        REQUIRE(loaded.ok());
        return loaded.value().ibl != nullptr;
    };
    SceneOptions gltf;
    gltf.obj = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    CHECK_FALSE(iblOf(gltf)); // no sky
    gltf.sky = Sky::Kind::Gradient;
    CHECK(iblOf(gltf));
    SceneOptions off = gltf;
    off.ibl = false;
    CHECK_FALSE(iblOf(off));
    SceneOptions phong = gltf;
    phong.shading = ShadingMode::Phong;
    phong.explicitShading = true;
    CHECK_FALSE(iblOf(phong)); // nothing would read it
    SceneOptions builtIn;
    builtIn.sky = Sky::Kind::Gradient;
    CHECK_FALSE(iblOf(builtIn));
    builtIn.ibl = true;
    CHECK(iblOf(builtIn));
}
#endif


TEST_CASE("KHR_animation_pointer: a posed scene draws its material's animated colour and opacity, its lights and camera at that time",
          "[platform][animation][pointer]") {
    gltftest::Asset a;
    // A quad facing +Z (an unlit MASK material, cutoff 0.5), a point light and a camera.
    const int pos = a.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3");
    const int input = a.floats({0, 1}, "SCALAR");
    const int colours = a.floats({1, 0, 0, 0, 0, 0, 1, 1}, "VEC4"); // red, alpha 0 -> blue, alpha 1
    const int ramp = a.floats({0, 10}, "SCALAR");
    const int fov = a.floats({0.5f, 1.0f}, "SCALAR");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":0}]}]";
    a.materials = R"([{"alphaMode":"MASK","doubleSided":true,"extensions":{"KHR_materials_unlit":{}}}])";
    a.nodes = R"([{"mesh":0},{"translation":[0,0,3],"extensions":{"KHR_lights_punctual":{"light":0}}},{"camera":0,"translation":[0,0,4]}])";
    a.scenes = R"([{"nodes":[0,1,2]}])";
    const auto channel = [](int sampler, const std::string& pointer) {
        return R"({"sampler":)" + std::to_string(sampler) + R"(,"target":{"path":"pointer","extensions":{"KHR_animation_pointer":{"pointer":")" +
               pointer + "\"}}}}";
    };
    a.extra = R"(,"extensionsUsed":["KHR_animation_pointer","KHR_lights_punctual","KHR_materials_unlit"],)"
              R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":1}]}},)"
              R"("cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}}],)"
              R"("animations":[{"samplers":[{"input":)" + std::to_string(input) + R"(,"output":)" + std::to_string(colours) +
              R"(},{"input":)" + std::to_string(input) + R"(,"output":)" + std::to_string(ramp) + R"(},{"input":)" +
              std::to_string(input) + R"(,"output":)" + std::to_string(fov) + R"(}],"channels":[)" +
              channel(0, "/materials/0/pbrMetallicRoughness/baseColorFactor") + "," +
              channel(1, "/extensions/KHR_lights_punctual/lights/0/intensity") + "," + channel(2, "/cameras/0/perspective/yfov") + "]}]";
    SceneOptions o;
    o.obj = objtest::writeText(objtest::freshDir("pointer-scene"), "pointer.gltf", a.embedded());
    o.camera = 0;
    auto loaded = loadScene(o);
    REQUIRE(loaded.ok());
    LoadedScene s = std::move(loaded).value();
    REQUIRE_FALSE(applySceneDefaults(o, s).has_value());
    // Alpha 0 at rest (below the cutoff): the draw is kept, for the animation to show it.
    REQUIRE(s.scene.draws.size() == 1);
    REQUIRE(s.drawMaterials == std::vector<int>{0});
    FrameBuffer fb(32, 32);
    RenderContext ctx(fb);
    const auto centre = [&](double t) {
        poseScene(s, t, -1);
        const FrameView view = makeFrameView(resolveCamera(o, s), 32, 32, o.light, s.lights, s.physical);
        renderFrame(ctx, s, view, makeRenderSettings(o));
        return fb.pixel(16, 16);
    };
    const Pixel hidden = centre(0.0);
    CHECK(s.scene.draws[0].alpha == 0.0f);
    const Pixel late = centre(0.75); // alpha 0.75: drawn; base (0.25, 0, 0.75)
    const Pixel background = fb.pixel(0, 0); // outside the quad at 0.75 s's field of view
    CHECK(hidden == background);              // at 0 s, hidden: the background
    CHECK(s.scene.draws[0].alpha == 1.0f);
    REQUIRE(s.scene.draws[0].pbr);
    CHECK(s.scene.draws[0].pbr->baseColor.b == Approx(0.75));
    CHECK(late != background);
    CHECK(pixelB(late) > pixelR(late));
    CHECK(pixelR(late) > 0);
    const Pixel early = centre(0.5); // alpha 0.5 reaches the cutoff: drawn, red and blue even
    CHECK(pixelB(early) == pixelR(early));
    CHECK(pixelB(early) < pixelB(late));
    // The light's intensity and the camera's field of view at 0.5 s.
    REQUIRE(s.lights.size() == 1);
    CHECK(s.lights[0].colour.r == Approx(5.0));
    CHECK(makeFrameView(resolveCamera(o, s), 32, 32, o.light, s.lights, s.physical).lighting.lights[0].colour.g == Approx(5.0));
    CHECK(resolveCamera(o, s).fovDegrees == Approx(0.75 * 180.0 / 3.14159265358979323846));
}

TEST_CASE("KHR_animation_pointer: a texture transform's animated offset moves the texture across a posed draw", "[platform][animation][pointer]") {
    gltftest::Asset a;
    // A quad filling the view (uv u from 0 at the left to 1 at the right), an unlit material
    // whose base colour texture is 2 x 1 texels, red | green, nearest and clamped; its offset
    // goes from (0, 0) to (1, 0) over a second (looped: at 1 s it is back at (0, 0)).
    const int pos = a.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3");
    const int uv = a.floats({0, 1, 1, 1, 1, 0, 0, 1, 1, 0, 0, 0}, "VEC2");
    const int input = a.floats({0, 1}, "SCALAR");
    const int offsets = a.floats({0, 0, 1, 0}, "VEC2");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
               "},\"material\":0}]}]";
    a.materials = R"([{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"offset":[0,0]}}}},)"
                  R"("extensions":{"KHR_materials_unlit":{}}}])";
    a.nodes = R"([{"mesh":0}])";
    const std::string ppm = std::string("P6\n2 1\n255\n") + std::string("\xff\x00\x00\x00\xff\x00", 6);
    a.extra = R"(,"textures":[{"source":0,"sampler":0}],"samplers":[{"magFilter":9728,"minFilter":9728,"wrapS":33071,"wrapT":33071}],)"
              R"("images":[{"uri":"data:image/x-portable-pixmap;base64,)" + gltftest::base64(std::vector<unsigned char>(ppm.begin(), ppm.end())) +
              R"("}],"extensionsUsed":["KHR_animation_pointer","KHR_texture_transform","KHR_materials_unlit"],"animations":[{"samplers":[{"input":)" +
              std::to_string(input) + R"(,"output":)" + std::to_string(offsets) +
              R"(}],"channels":[{"sampler":0,"target":{"path":"pointer","extensions":{"KHR_animation_pointer":{"pointer":)"
              R"("/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/offset"}}}}]}])";
    SceneOptions o;
    o.obj = objtest::writeText(objtest::freshDir("pointer-transform"), "scroll.gltf", a.embedded());
    o.eye = Vec3{0, 0, 1};
    o.target = Vec3{0, 0, 0};
    o.fovDegrees = 90.0;
    auto loaded = loadScene(o);
    REQUIRE(loaded.ok());
    LoadedScene s = std::move(loaded).value();
    REQUIRE_FALSE(applySceneDefaults(o, s).has_value());
    FrameBuffer fb(32, 32);
    RenderContext ctx(fb);
    const auto render = [&] {
        renderFrame(ctx, s, makeFrameView(resolveCamera(o, s), 32, 32, o.light, s.lights, s.physical), makeRenderSettings(o));
        return std::vector<Pixel>(fb.colorData(), fb.colorData() + 32 * 32);
    };
    const std::vector<Pixel> still = render();
    // Left quarter: u = 0.25, red; with the offset 0.5 it reads u = 0.75, green.
    CHECK(pixelR(still[16 * 32 + 8]) == 255);
    CHECK(pixelG(still[16 * 32 + 8]) == 0);
    poseScene(s, 0.5, -1);
    const std::vector<Pixel> moved = render();
    CHECK(pixelR(moved[16 * 32 + 8]) == 0);
    CHECK(pixelG(moved[16 * 32 + 8]) == 255);
    CHECK(pixelG(moved[16 * 32 + 24]) == 255); // the right quarter: clamped to the green texel
    // At 0 s the file's own offset: the image the unposed scene drew, pixel for pixel.
    poseScene(s, 0.0, -1);
    CHECK(render() == still);
}

TEST_CASE("--camera N on an animated camera node: the view from where the clip has moved it; its lights too", "[platform][animation]") {
    gltftest::Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int input = a.floats({0, 1}, "SCALAR");
    const int moves = a.floats({0, 0, 5, 0, 4, 5}, "VEC3");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
    a.nodes = R"([{"mesh":0},{"camera":0,"translation":[0,0,5],"children":[2]},)"
              R"({"translation":[1,0,0],"extensions":{"KHR_lights_punctual":{"light":0}}}])";
    a.scenes = R"([{"nodes":[0,1]}])";
    a.extra = R"(,"extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[{"type":"point"}]}},)"
              R"("cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}],"animations":[{"samplers":[{"input":)" +
              std::to_string(input) + R"(,"output":)" + std::to_string(moves) +
              R"(}],"channels":[{"sampler":0,"target":{"node":1,"path":"translation"}}]}])";
    SceneOptions o;
    o.obj = objtest::writeText(objtest::freshDir("moving-camera"), "moving.gltf", a.embedded());
    o.camera = 0;
    auto loaded = loadScene(o);
    REQUIRE(loaded.ok());
    LoadedScene s = std::move(loaded).value();
    CHECK(resolveCamera(o, s).eye.y == 0.0f);
    poseScene(s, 0.5, -1);
    const CameraSetup c = resolveCamera(o, s);
    CHECK(c.eye.y == Approx(2.0));
    CHECK(c.eye.z == Approx(5.0));
    CHECK(c.target.y == Approx(2.0));
    CHECK(c.target.z == Approx(4.0));
    REQUIRE(s.lights.size() == 1);
    CHECK(s.lights[0].position.x == Approx(1.0));
    CHECK(s.lights[0].position.y == Approx(2.0));
}

TEST_CASE("EXT_mesh_gpu_instancing: the instances drawn from one stored mesh look like one node per instance",
          "[platform][gltf][instancing]") {
    // A box (24 vertices, outward normals) at three places under a turned parent node: as
    // instances of one node, and as three child nodes with the same T R S (the extension's
    // meaning). One of them mirrors (scale -1 in x).
    gltftest::Asset a;
    std::vector<float> pos, nrm;
    std::vector<std::uint32_t> idx;
    const float n[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& f : n) {
        const Vec3 a3{f[0], f[1], f[2]};
        const Vec3 u = std::fabs(a3.y) > 0.5f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 v = cross(a3, u);
        const auto base = std::uint32_t(pos.size() / 3);
        for (const Vec3 c : {a3 * 0.5f - u * 0.5f - v * 0.5f, a3 * 0.5f + u * 0.5f - v * 0.5f, a3 * 0.5f + u * 0.5f + v * 0.5f,
                             a3 * 0.5f - u * 0.5f + v * 0.5f}) {
            pos.insert(pos.end(), {c.x, c.y * 0.6f, c.z});
            nrm.insert(nrm.end(), {f[0], f[1], f[2]});
        }
        idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    const int p = a.floats(pos, "VEC3"), nm = a.floats(nrm, "VEC3"), ix = a.indices(idx, 5125);
    const int t = a.floats({-1.5f, 0, 0, 0, 0.3f, 0, 1.5f, 0, -0.5f}, "VEC3");
    const int r = a.floats({0, 0, 0, 1, 0, 0.38268343f, 0, 0.92387953f, 0.25881905f, 0, 0, 0.96592583f}, "VEC4");
    const int s = a.floats({1, 1, 1, -1, 1, 1, 0.7f, 1.4f, 1}, "VEC3");
    a.meshes = R"([{"primitives":[{"attributes":{"POSITION":)" + std::to_string(p) + R"(,"NORMAL":)" + std::to_string(nm) +
               R"(},"indices":)" + std::to_string(ix) + R"(,"material":0}]}])";
    a.materials = R"([{"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.5,0.3,1],"metallicFactor":0.2,"roughnessFactor":0.5}}])";
    const std::string parent = R"({"rotation":[0.0998,0.0998,0,0.99],"translation":[0,0,-0.5])";
    a.nodes = "[" + parent + R"(,"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":)" + std::to_string(t) +
              R"(,"ROTATION":)" + std::to_string(r) + R"(,"SCALE":)" + std::to_string(s) + "}}}}]";
    a.extra = R"(,"extensionsUsed":["EXT_mesh_gpu_instancing"])";
    const std::string dir = objtest::freshDir("instancing-scene");
    SceneOptions o;
    o.obj = objtest::writeText(dir, "instanced.gltf", a.embedded());
    o.width = 160;
    o.height = 120;
    o.cull = CullMode::CW; // back faces culled: a face turned inside out would show
    // The same places as child nodes.
    gltftest::Asset b = a;
    b.nodes = "[" + parent + R"(,"children":[1,2,3]},)"
              R"({"mesh":0,"translation":[-1.5,0,0]},)"
              R"({"mesh":0,"translation":[0,0.3,0],"rotation":[0,0.38268343,0,0.92387953],"scale":[-1,1,1]},)"
              R"({"mesh":0,"translation":[1.5,0,-0.5],"rotation":[0.25881905,0,0,0.96592583],"scale":[0.7,1.4,1]}])";
    b.extra.clear();
    SceneOptions oNodes = o;
    oNodes.obj = objtest::writeText(dir, "nodes.gltf", b.embedded());
    auto instanced = loadScene(o);
    auto nodes = loadScene(oNodes);
    INFO((instanced.ok() ? std::string() : instanced.error()) << (nodes.ok() ? std::string() : nodes.error()));
    REQUIRE(instanced.ok());
    REQUIRE(nodes.ok());
    LoadedScene si = std::move(instanced).value(), sn = std::move(nodes).value();
    // One stored box drawn three times; the node file stores three.
    REQUIRE(si.scene.draws.size() == 3);
    std::size_t storedI = 0, storedN = 0;
    for (const Mesh& m : si.scene.meshes) storedI += m.vertexCount();
    for (const Mesh& m : sn.scene.meshes) storedN += m.vertexCount();
    CHECK(storedI == 24);
    CHECK(storedN == 72);
    for (const SceneDraw& d : si.scene.draws) CHECK(d.placement.has_value());
    CHECK(si.scene.triangleCount() == sn.scene.triangleCount());
    for (int k = 0; k < 3; ++k) {
        CHECK(si.scene.boundsMin[k] == Approx(sn.scene.boundsMin[k]).margin(1e-5));
        CHECK(si.scene.boundsMax[k] == Approx(sn.scene.boundsMax[k]).margin(1e-5));
    }
    CHECK(si.radius == Approx(sn.radius).epsilon(1e-5));
    REQUIRE_FALSE(applySceneDefaults(o, si).has_value());
    REQUIRE_FALSE(applySceneDefaults(oNodes, sn).has_value());
    const auto render = [&](const SceneOptions& opts, LoadedScene& ls) {
        FrameBuffer fb(160, 120);
        RenderContext ctx(fb);
        renderFrame(ctx, ls, makeFrameView(resolveCamera(opts, ls), 160, 120, opts.light, ls.lights, ls.physical), makeRenderSettings(opts));
        return std::vector<Pixel>(fb.colorData(), fb.colorData() + 160 * 120);
    };
    const std::vector<Pixel> pi = render(o, si), pn = render(oNodes, sn);
    // The transforms are rounded apart (single precision at draw time, double at load time): a
    // few edge pixels may differ, by little.
    int differing = 0, drawn = 0;
    for (std::size_t k = 0; k < pi.size(); ++k) {
        const int d = std::max({std::abs(int(pixelR(pi[k])) - int(pixelR(pn[k]))), std::abs(int(pixelG(pi[k])) - int(pixelG(pn[k]))),
                                std::abs(int(pixelB(pi[k])) - int(pixelB(pn[k])))});
        differing += d > 2;
        drawn += pn[k] != pn[0];
    }
    CHECK(drawn > 1500);
    CHECK(differing <= 40);
}
