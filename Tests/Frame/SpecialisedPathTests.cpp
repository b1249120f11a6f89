// drawMesh's specialised pipelines against the general one-pipeline renderer (GeneralRenderer.hpp), and every ISA's kernels against the scalar loop: same image, pixel for pixel.
#include "TestFramework.hpp"

#include "GeneralRenderer.hpp"
#include "Platform/App/SceneSetup.hpp"

using namespace sr;

TEST_CASE("specialised pipelines render the default scene exactly like the general path", "[render][shading][specialised]") {
    // Each varying is interpolated independently of how many others a draw carries, and each mode
    // does the same arithmetic in both renderers, so the images must be bit-identical; the
    // specialised ones only skip work (see Tests/Frame/Bench/ShadingBench.cpp for the timing).
    app::SceneOptions options;
    options.width = 160;
    options.height = 120;
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    scene.value().scene = test::opaqueOnly(std::move(scene.value().scene)); // the general renderer draws opaque draws only
    const FrameView sceneView =
        app::makeFrameView(app::resolveCamera(options, scene.value()), options.width, options.height, options.light,
                            scene.value().lights);
    // Then under the white key light alone and without a specular term on any draw: Phong draws
    // take the program without position varyings (nothing reads them; phongReadsPosition).
    for (bool specular : {true, false}) {
        FrameView view = sceneView;
        if (!specular) {
            for (SceneDraw& d : scene.value().scene.draws) d.specular.ks = {0.0f, 0.0f, 0.0f};
            view.lighting.lights.resize(1); // the key light (the built-in scene's fill light is a point light)
            REQUIRE(view.lighting.whiteDirectional());
        }
        for (ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong})
            for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
                for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Trilinear}) {
                    INFO("mode " << shadingModeName(mode) << ", " << perspectiveModeName(persp) << ", " << filterName(filter)
                                 << (specular ? "" : ", no specular"));
                    RenderSettings settings = app::makeRenderSettings(options);
                    settings.shading = mode;
                    settings.perspective = persp;
                    settings.filter = filter;
                    FrameBuffer special(options.width, options.height), general(options.width, options.height);
                    RenderContext cs(special), cg(general);
                    app::renderFrame(cs, scene.value(), view, settings);
                    general.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
                    test::renderSceneGeneral(cg, scene.value().scene, view, settings);
                    int differing = 0;
                    for (int y = 0; y < special.height(); ++y)
                        for (int x = 0; x < special.width(); ++x) differing += special.pixel(x, y) != general.pixel(x, y);
                    CHECK(differing == 0);
                    CHECK(cs.stats.fragmentsShaded == cg.stats.fragmentsShaded);
                }
    }
}

TEST_CASE("drawMesh renders the same image with every ISA's kernels and with the scalar loop", "[render][shading][kernels]") {
    // End to end through drawMesh's per-draw kernel choice, including a non-integer shininess:
    // Phong then falls back to the scalar loop, while flat and Gouraud (lit per triangle / per
    // vertex, outside the kernels) keep their kernels; every image equals the scalar one.
    app::SceneOptions options;
    options.width = 160;
    options.height = 120;
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    FrameView view =
        app::makeFrameView(app::resolveCamera(options, scene.value()), options.width, options.height, options.light,
                            scene.value().lights);
    // With the wireframe overlay too: an edge drawn after its triangle's fill must not be covered
    // by fill colours the kernel still had queued (fillSpans defers them; the pipeline flushes
    // before each edge). Shininess 0 (no specular term) under the key light alone: Phong's
    // program without position varyings.
    for (float shininess : {32.0f, 12.5f, 0.0f}) {
        for (SceneDraw& d : scene.value().scene.draws) d.specular.shininess = shininess;
        if (shininess == 0.0f) view.lighting.lights.resize(1);
        for (ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong})
            for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear})
            for (bool wireframe : {false, true}) {
                RenderSettings settings = app::makeRenderSettings(options);
                settings.shading = mode;
                settings.filter = filter;
                settings.wireframe = wireframe;
                settings.isa = Isa::Scalar;
                FrameBuffer reference(options.width, options.height);
                RenderContext cr(reference);
                app::renderFrame(cr, scene.value(), view, settings);
                for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
                    if (!isaAvailable(isa)) continue;
                    INFO("shininess " << shininess << ", " << shadingModeName(mode) << ", " << filterName(filter) << ", "
                                      << isaName(isa) << (wireframe ? ", wireframe" : ""));
                    settings.isa = isa;
                    FrameBuffer fb(options.width, options.height);
                    RenderContext c(fb);
                    app::renderFrame(c, scene.value(), view, settings);
                    int differing = 0;
                    for (int y = 0; y < fb.height(); ++y)
                        for (int x = 0; x < fb.width(); ++x) differing += fb.pixel(x, y) != reference.pixel(x, y);
                    CHECK(differing == 0);
                    CHECK(c.stats.fragmentsShaded == cr.stats.fragmentsShaded);
                }
            }
    }
}
