// Transparency: "over" blending with a constant opacity, transparent triangles after the opaque ones, back to front, depth tested but not written; texel alpha (MASK, BLEND).
#include "TestFramework.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include "Platform/App/SceneSetup.hpp"
#include "Raster/Fill/Blend.hpp"
#include "Resources/ObjTestUtil.hpp" // Tests/Resources: the OBJ tests' temporary files

using namespace sr;

namespace {

// A square facing +z at depth z, centred at (cx, 0), side 2.
Mesh square(float cx, float z) {
    Mesh m;
    m.positions = {{cx - 1, -1, z}, {cx + 1, -1, z}, {cx + 1, 1, z}, {cx - 1, 1, z}};
    m.normals.assign(4, {0, 0, 1});
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

SceneDraw drawOf(int mesh, Color kd, float alpha) {
    SceneDraw d;
    d.mesh = mesh;
    d.indexCount = 6;
    d.kd = kd;
    d.alpha = alpha;
    return d;
}

// Listed front to back on purpose: green (alpha 0.4, z = -1, x shifted right), opaque red
// (z = -2), blue (alpha 0.25, z = -1.5), and a yellow one (alpha 0.5) hidden behind red (z = -3).
Scene layered() {
    Scene s;
    s.meshes = {square(0.5f, -1.0f), square(0.0f, -2.0f), square(0.0f, -1.5f), square(0.0f, -3.0f)};
    s.draws = {drawOf(0, {0, 1, 0, 1}, 0.4f), drawOf(1, {1, 0, 0, 1}, 1.0f), drawOf(2, {0, 0, 1, 1}, 0.25f),
               drawOf(3, {1, 1, 0, 1}, 0.5f)};
    return s;
}

constexpr int kSize = 64;

FrameView topView() {
    app::CameraSetup c;
    c.eye = {0, 0, 4};
    c.target = {0, 0, 0};
    c.up = {0, 1, 0};
    c.fovDegrees = 60.0;
    c.nearZ = 0.5;
    c.farZ = 20.0;
    return app::makeFrameView(c, kSize, kSize, {0, 0, 1}, {});
}

// The pixel over world point (x, y) at depth z, as the view projects it.
Pixel pixelAt(const FrameBuffer& fb, const FrameView& v, Vec3 p) {
    const Vec4 c = v.viewProj * Vec4(p, 1.0f);
    const int px = int((c.x / c.w * 0.5f + 0.5f) * float(kSize)), py = int((0.5f - c.y / c.w * 0.5f) * float(kSize));
    return fb.pixel(px, py);
}

// One frame of `scene` on `threads` render threads (its triangles-sorted counter into *sorted
// when given).
FrameBuffer frameOf(const Scene& scene, const FrameView& view, const RenderSettings& settings,
                    std::uint64_t* sorted = nullptr, int threads = 1) {
    FrameBuffer fb(kSize, kSize);
    RenderContext ctx(fb);
    ctx.setThreads(threads);
    renderSceneFrame(ctx, scene, view, settings);
    if (sorted) *sorted = ctx.stats.trianglesSorted;
    return fb;
}

int differingPixels(const FrameBuffer& a, const FrameBuffer& b) {
    int n = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) n += a.pixel(x, y) != b.pixel(x, y);
    return n;
}

} // namespace

TEST_CASE("blendOver: alpha x src + (1 - alpha) x dst per channel, rounded as packBgra8", "[render][transparency]") {
    const Pixel red = packBgra(255, 0, 0), blue = packBgra(0, 0, 255);
    // alpha 0.25: r = 0.25 -> 63.75 -> 64; b = 0.75 -> 191.25 -> 191.
    CHECK(blendOver(red, blue, 0.25f) == packBgra(64, 0, 191));
    CHECK(blendOver(red, blue, 1.0f) == red);
    CHECK(blendOver(red, blue, 0.0f) == blue);
    // 100 over 200 at 0.3: 0.3 x 100 + 0.7 x 200 = 170 (within float rounding of the bytes).
    CHECK(blendOver(packBgra(100, 100, 100), packBgra(200, 200, 200), 0.3f) == packBgra(170, 170, 170));
}

TEST_CASE("transparent draws: after the opaque ones, back to front, over what is behind, depth not written",
          "[render][transparency]") {
    const Scene scene = layered();
    const FrameView view = topView();
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    FrameBuffer fb(kSize, kSize);
    RenderContext ctx(fb);
    renderSceneFrame(ctx, scene, view, settings);
    // Where all overlap (x = 0.25): red, then blue over it at 0.25 (0.75, 0, 0.25 -> 191, 0, 64),
    // then green over that at 0.4: r = 191/255 x 0.6 -> 114.6 -> 115, g = 0.4 -> 102,
    // b = 64/255 x 0.6 -> 38.4 -> 38. (Green first and blue last would give g = 76.5.)
    CHECK(pixelAt(fb, view, {0.25f, 0.0f, -1.0f}) == packBgra(115, 102, 38));
    // Green alone over the black background (x = 1.3: right of the others): (0, 102, 0).
    CHECK(pixelAt(fb, view, {1.3f, 0.0f, -1.0f}) == packBgra(0, 102, 0));
    // The yellow square behind the red one never shows; the transparent squares wrote no depth:
    // the depth there is the red square's, as in a render of the opaque square alone.
    Scene opaqueOnly = scene;
    opaqueOnly.draws = {scene.draws[1]};
    FrameBuffer ref(kSize, kSize);
    RenderContext cref(ref);
    renderSceneFrame(cref, opaqueOnly, view, settings);
    int depthDiffers = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) depthDiffers += fb.depth(x, y) != ref.depth(x, y);
    CHECK(depthDiffers == 0);
    CHECK(ctx.stats.trianglesSorted == 6); // the three transparent squares
    CHECK(cref.stats.trianglesSorted == 0); // nothing transparent: no sort

    // The same image with two threads, the scalar loop, and multisampled where no edge is near.
    for (int variant = 0; variant < 3; ++variant) {
        INFO("variant " << variant);
        RenderSettings s = settings;
        if (variant == 1) s.isa = Isa::Scalar;
        if (variant == 2) s.antiAliasing = *AntiAliasing::multisample(4);
        const FrameBuffer other = frameOf(scene, view, s, nullptr, variant == 0 ? 2 : 1);
        if (variant < 2) {
            CHECK(differingPixels(other, fb) == 0);
        } else {
            CHECK(pixelAt(other, view, {0.25f, 0.0f, -1.0f}) == packBgra(115, 102, 38));
            CHECK(pixelAt(other, view, {1.3f, 0.0f, -1.0f}) == packBgra(0, 102, 0));
        }
    }
}

TEST_CASE("the back-to-front order follows the view, not the file", "[render][transparency]") {
    // Two half-transparent squares; seen from +z the blue one (z = 0) is in front of the green
    // one (z = -1), seen from -z the green one is. Over black at alpha 0.5 each:
    //  back then front: front x 0.5 + back x 0.25 -> the front colour 127.5 -> 128, the back's 63.75 -> 64.
    Scene s;
    s.meshes = {square(0.0f, 0.0f), square(0.0f, -1.0f)};
    s.draws = {drawOf(0, {0, 0, 1, 1}, 0.5f), drawOf(1, {0, 1, 0, 1}, 0.5f)};
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    for (const float side : {1.0f, -1.0f}) {
        INFO("eye on the " << (side > 0 ? "+z" : "-z") << " side");
        app::CameraSetup c;
        c.eye = {0, 0, 4 * side - 0.5f};
        c.target = {0, 0, -0.5f};
        c.up = {0, 1, 0};
        c.nearZ = 0.5;
        c.farZ = 20.0;
        const FrameView view = app::makeFrameView(c, kSize, kSize, {0, 0, 1}, {});
        FrameBuffer fb(kSize, kSize);
        RenderContext ctx(fb);
        renderSceneFrame(ctx, s, view, settings);
        const Pixel p = fb.pixel(kSize / 2, kSize / 2);
        const int front = side > 0 ? int(pixelB(p)) : int(pixelG(p)), back = side > 0 ? int(pixelG(p)) : int(pixelB(p));
        CHECK(front == 128);
        CHECK(back == 64);
    }
}

TEST_CASE("opacity from the files: MTL d and Tr, glTF BLEND and MASK; --materials fixed is opaque",
          "[render][transparency][materials]") {
    using namespace sr::objtest;
    const std::string dir = freshDir("opacity");
    writeText(dir, "m.mtl", "newmtl half\nKd 1 0 0\nd 0.5\nnewmtl tr\nKd 0 1 0\nTr 0.25\nnewmtl solid\nKd 0 0 1\n");
    writeText(dir, "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl half\nf 1 2 3\nusemtl tr\nf 1 3 2\n"
                            "usemtl solid\nf 2 1 3\n");
    app::SceneOptions options;
    options.obj = dir + "/m.obj";
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    REQUIRE(scene.value().scene.draws.size() == 3);
    CHECK(scene.value().scene.draws[0].alpha == 0.5f);
    CHECK(scene.value().scene.draws[1].alpha == 0.75f); // Tr = 1 - d
    CHECK(scene.value().scene.draws[2].alpha == 1.0f);
    options.materials = app::MaterialRule::Fixed;
    auto fixed = app::loadScene(options);
    REQUIRE(fixed.ok());
    for (const SceneDraw& d : fixed.value().scene.draws) CHECK(d.alpha == 1.0f);

    // glTF: BLEND takes the factor's alpha; MASK drops a surface below its cutoff, keeps one at it.
    const std::string json =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0},{\"attributes\":{\"POSITION\":0},"
        "\"material\":1},{\"attributes\":{\"POSITION\":0},\"material\":2}]}],"
        "\"materials\":[{\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.3]}},"
        "{\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5,\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.4]}},"
        "{\"alphaMode\":\"MASK\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.5]}}],"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}]}";
    options.obj = writeText(dir, "alpha.gltf", json);
    options.materials = app::MaterialRule::Mtl;
    auto gltf = app::loadScene(options);
    REQUIRE(gltf.ok());
    REQUIRE(gltf.value().scene.draws.size() == 2); // the MASK material below its cutoff is not drawn
    CHECK(gltf.value().scene.draws[0].alpha == 0.3f);
    CHECK(gltf.value().scene.draws[1].alpha == 1.0f); // MASK at its (default 0.5) cutoff: opaque
}

namespace {

// A 4 x 1 texture: red texels with alphas a[0..3] (columns left to right).
Texture alphaRamp(const std::uint8_t (&a)[4]) {
    const std::uint8_t rgba[16] = {255, 0, 0, a[0], 255, 0, 0, a[1], 255, 0, 0, a[2], 255, 0, 0, a[3]};
    return Texture::fromRgba8(4, 1, rgba);
}

// square(0, z) with uvs: u = (x + 1) / 2, v = (y + 1) / 2, so texel column c of a 4-wide texture
// covers world x in [-1 + c / 2, -0.5 + c / 2).
Mesh texturedSquare(float z) {
    Mesh m = square(0.0f, z);
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    return m;
}

// The textured square (draw 0, listed FIRST) at z = -1 with texel alpha `mode`, and an opaque
// blue square behind it (z = -2). Unlit, nearest: each texel column shows its own colour.
Scene texelAlphaScene(AlphaMode mode, float factor, float cutoff, const std::uint8_t (&a)[4]) {
    Scene s;
    s.meshes = {texturedSquare(-1.0f), square(0.0f, -2.0f)};
    s.textures = {alphaRamp(a)};
    SceneDraw top = drawOf(0, {1, 1, 1, 1}, 1.0f);
    top.texture = 0;
    top.texelAlpha = {mode, factor, cutoff};
    if (mode == AlphaMode::Blend) top.alpha = factor;
    s.draws = {top, drawOf(1, {0, 0, 1, 1}, 1.0f)};
    return s;
}

RenderSettings unlitNearest() {
    RenderSettings settings;
    settings.shading = ShadingMode::Unlit;
    settings.filter = TextureFilter::Nearest;
    return settings;
}

// The pixels over the four texel columns' centres (x = -0.75, -0.25, 0.25, 0.75) at z = -1.
std::vector<Pixel> columns(const FrameBuffer& fb, const FrameView& view) {
    std::vector<Pixel> out;
    for (const float x : {-0.75f, -0.25f, 0.25f, 0.75f}) out.push_back(pixelAt(fb, view, {x, 0.0f, -1.0f}));
    return out;
}

// The same scene with the blue square behind (draw 1) alone.
FrameBuffer behindAlone(const Scene& scene, const FrameView& view, const RenderSettings& settings) {
    Scene alone = scene;
    alone.draws = {scene.draws[1]};
    return frameOf(alone, view, settings);
}

} // namespace

TEST_CASE("texel alpha MASK: a fragment below the cutoff writes neither colour nor depth", "[render][transparency]") {
    const FrameView view = topView();
    const Pixel red = packBgra(255, 0, 0), blue = packBgra(0, 0, 255);
    // Alphas 1, 128/255 = 0.50196, 127/255 = 0.49804, 0 against the cutoff 0.5: kept, kept,
    // discarded, discarded. A discarded fragment wrote no depth: the blue square drawn AFTER it,
    // farther away, shows there.
    const std::uint8_t ramp[4] = {255, 128, 127, 0};
    const Scene scene = texelAlphaScene(AlphaMode::Mask, 1.0f, 0.5f, ramp);
    std::uint64_t sorted = 1;
    const FrameBuffer fb = frameOf(scene, view, unlitNearest(), &sorted);
    CHECK(columns(fb, view) == std::vector<Pixel>{red, red, blue, blue});
    CHECK(sorted == 0); // masked, not blended: drawn with the opaque draws
    // Where the red square was kept, its depth is the one stored (the blue square lost there).
    const FrameBuffer blueOnly = behindAlone(scene, view, unlitNearest());
    int keptDepth = 0, discardedDepth = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (fb.pixel(x, y) == red) keptDepth += fb.depth(x, y) > blueOnly.depth(x, y);
            if (fb.pixel(x, y) == blue) discardedDepth += fb.depth(x, y) != blueOnly.depth(x, y);
        }
    CHECK(keptDepth > 100);
    CHECK(discardedDepth == 0);

    // The factor multiplies the texel: 0.99 x 0.50196 = 0.4969 < 0.5 drops the second column too;
    // a cutoff of 0 keeps even alpha 0.
    CHECK(columns(frameOf(texelAlphaScene(AlphaMode::Mask, 0.99f, 0.5f, ramp), view, unlitNearest()), view) ==
          std::vector<Pixel>{red, blue, blue, blue});
    CHECK(columns(frameOf(texelAlphaScene(AlphaMode::Mask, 1.0f, 0.0f, ramp), view, unlitNearest()), view) ==
          std::vector<Pixel>{red, red, red, red});

    // The same image from the scalar loop, on two threads, lit (Phong: the lighting plays no
    // part in the test), and multisampled (4 samples: the columns' interiors are unchanged).
    for (int variant = 0; variant < 4; ++variant) {
        INFO("variant " << variant);
        RenderSettings s = unlitNearest();
        if (variant == 0) s.isa = Isa::Scalar;
        if (variant == 2) s.shading = ShadingMode::Phong;
        if (variant == 3) s.antiAliasing = *AntiAliasing::multisample(4);
        const FrameBuffer other = frameOf(scene, view, s, nullptr, variant == 1 ? 2 : 1);
        if (variant < 2) {
            CHECK(differingPixels(other, fb) == 0);
        } else {
            // Discarded: what the blue square alone shows there, under the same settings.
            const std::vector<Pixel> got = columns(other, view), behind = columns(behindAlone(scene, view, s), view);
            CHECK(got[2] == behind[2]);
            CHECK(got[3] == behind[3]);
            CHECK(pixelB(behind[2]) > pixelR(behind[2]));
            for (int c = 0; c < 2; ++c) { // kept: the red texel (lit: shaded, mostly red)
                CHECK(got[std::size_t(c)] != blue);
                CHECK(pixelR(got[std::size_t(c)]) > pixelB(got[std::size_t(c)]));
            }
        }
    }
}

TEST_CASE("texel alpha BLEND: factor x texel alpha over what is behind, sorted with the transparent draws",
          "[render][transparency]") {
    const FrameView view = topView();
    const Pixel red = packBgra(255, 0, 0), blue = packBgra(0, 0, 255);
    // Alpha 64/255 = 0.25098 over blue: r = 0.25098 -> 64, b = 0.74902 -> 191. Alpha 0: blue.
    // The blended square is listed first, yet drawn after the opaque blue one.
    const std::uint8_t ramp[4] = {255, 128, 64, 0};
    const Scene scene = texelAlphaScene(AlphaMode::Blend, 1.0f, 0.5f, ramp);
    std::uint64_t sorted = 0;
    const FrameBuffer fb = frameOf(scene, view, unlitNearest(), &sorted);
    CHECK(columns(fb, view) == std::vector<Pixel>{red, packBgra(128, 0, 127), packBgra(64, 0, 191), blue});
    CHECK(sorted == 2);
    // No depth written: the depth buffer is the blue square's alone.
    const FrameBuffer blueOnly = behindAlone(scene, view, unlitNearest());
    int depthDiffers = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) depthDiffers += fb.depth(x, y) != blueOnly.depth(x, y);
    CHECK(depthDiffers == 0);
    // The factor multiplies: 0.5 x 64/255 = 0.12549 -> r 32, b 223.
    CHECK(columns(frameOf(texelAlphaScene(AlphaMode::Blend, 0.5f, 0.5f, ramp), view, unlitNearest()), view)[2] ==
          packBgra(32, 0, 223));
    // Scalar loop, two threads, 4 samples (alpha 64/255 is exact in 8 bits): the same colours.
    for (int variant = 0; variant < 3; ++variant) {
        INFO("variant " << variant);
        RenderSettings s = unlitNearest();
        FrameBuffer other(kSize, kSize);
        RenderContext c(other);
        if (variant == 0) s.isa = Isa::Scalar;
        if (variant == 1) c.setThreads(2);
        if (variant == 2) s.antiAliasing = *AntiAliasing::multisample(4);
        renderSceneFrame(c, scene, view, s);
        CHECK(columns(other, view) == columns(fb, view));
    }
}

TEST_CASE("texel alpha needs a texture with alpha: an opaque texture keeps the constant rule and the kernels",
          "[render][transparency]") {
    Mesh mesh = texturedSquare(-1.0f);
    const std::uint8_t opaque[4] = {255, 255, 255, 255}, holes[4] = {255, 0, 255, 0};
    const Texture solid = alphaRamp(opaque), holed = alphaRamp(holes);
    SurfaceMaterial m;
    m.texelAlpha = {AlphaMode::Blend, 1.0f, 0.5f};
    CHECK(activeTexelAlpha(m, mesh).mode == AlphaMode::Off); // untextured
    m.texture = &solid;
    CHECK(activeTexelAlpha(m, mesh).mode == AlphaMode::Off); // every texel opaque
    CHECK_FALSE(drawsBlended(m, mesh));
    m.texture = &holed;
    CHECK(activeTexelAlpha(m, mesh).mode == AlphaMode::Blend);
    CHECK(drawsBlended(m, mesh));
    m.texelAlpha.mode = AlphaMode::Mask;
    CHECK_FALSE(drawsBlended(m, mesh));
    mesh.uvs.clear(); // no uvs: not textured
    CHECK(activeTexelAlpha(m, mesh).mode == AlphaMode::Off);
    CHECK(solid.hasAlpha() == false);
    CHECK(holed.hasAlpha() == true);
}
