// drawMesh's eight specialised pipelines against the general one-pipeline renderer (GeneralRenderer.hpp): same image, pixel for pixel.
#include "TestFramework.hpp"

#include "GeneralRenderer.hpp"
#include "Platform/Demo/SceneSetup.hpp"

using namespace sr;

TEST_CASE("specialised pipelines render the default scene exactly like the general path", "[render][shading][specialised]") {
    // Each varying is interpolated independently of how many others a draw carries, and each mode
    // does the same arithmetic in both renderers, so the images must be bit-identical; the
    // specialised ones only skip work (see Tests/Render/Bench/ShadingBench.cpp for the timing).
    demo::SceneOptions options;
    options.width = 160;
    options.height = 120;
    auto scene = demo::loadScene(options);
    REQUIRE(scene.ok());
    const FrameView view =
        demo::makeFrameView(demo::resolveCamera(options, scene.value()), options.width, options.height, options.light);
    for (ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong})
        for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Span8})
            for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Trilinear}) {
                INFO("mode " << shadingModeName(mode) << ", " << perspectiveModeName(persp) << ", " << filterName(filter));
                RenderSettings settings = demo::makeRenderSettings(options);
                settings.shading = mode;
                settings.perspective = persp;
                settings.filter = filter;
                FrameBuffer special(options.width, options.height), general(options.width, options.height);
                RenderContext cs(special), cg(general);
                demo::renderFrame(cs, scene.value(), view, settings);
                general.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
                test::renderSceneGeneral(cg, scene.value().scene, view, settings);
                int differing = 0;
                for (int y = 0; y < special.height(); ++y)
                    for (int x = 0; x < special.width(); ++x) differing += special.pixel(x, y) != general.pixel(x, y);
                CHECK(differing == 0);
                CHECK(cs.stats.fragmentsShaded == cg.stats.fragmentsShaded);
            }
}
