// The draw order of a loaded OBJ (one draw per texture, ObjLoader.hpp): what it means for exact depth ties.
#include "TestFramework.hpp"

#include <string>

#include "Platform/App/SceneSetup.hpp"
#include "Resources/Image.hpp"
#include "Resources/ObjTestUtil.hpp" // Tests/Resources: the OBJ tests' temporary files

using namespace sr;
using namespace sr::objtest;

namespace {

Image solid(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    Image img;
    img.width = img.height = 1;
    img.rgba = {r, g, b, 255};
    return img;
}

} // namespace

TEST_CASE("OBJ draw order: at an exact depth tie the face whose material appears first in the file wins",
          "[render][obj][ranges]") {
    // File order: red (a small triangle at the side), green (the big triangle), red again (the
    // SAME big triangle: every pixel of it ties in depth). The loader draws one range per
    // material, red first (face 1, then face 3), then green: the depth test (GREATER) keeps the
    // first write, so the tie shows red. Drawn in file order (as glref's material runs) it would
    // show green. Faces that do not tie look the same in either order. (Neither material has a Kd
    // line: tinyobjloader gives a material with map_Kd Kd 0.6, so red is 0.6 x 255 = 153.)
    const std::string dir = freshDir("draw-order-tie");
    REQUIRE(writeImage(dir + "/red.png", solid(255, 0, 0)).ok());
    REQUIRE(writeImage(dir + "/green.png", solid(0, 255, 0)).ok());
    writeText(dir, "tie.mtl", "newmtl red\nmap_Kd red.png\nnewmtl green\nmap_Kd green.png\n");
    writeText(dir, "tie.obj", "mtllib tie.mtl\n"
                              "v -3 -1 0\nv -2 -1 0\nv -2.5 0 0\n"
                              "v -1 -1 0\nv 1 -1 0\nv 0 1 0\n"
                              "vt 0.5 0.5\n"
                              "usemtl red\nf 1/1 2/1 3/1\n"
                              "usemtl green\nf 4/1 5/1 6/1\n"
                              "usemtl red\nf 4/1 5/1 6/1\n");
    app::SceneOptions options;
    options.obj = dir + "/tie.obj";
    options.width = 64;
    options.height = 64;
    options.shading = ShadingMode::Unlit;
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    REQUIRE(scene.value().scene.draws.size() == 2); // one per material, not one per switch (3)
    CHECK(scene.value().scene.draws[0].texture != scene.value().scene.draws[1].texture);
    CHECK(scene.value().scene.draws[0].indexCount == 6); // faces 1 and 3
    const FrameView view =
        app::makeFrameView(app::resolveCamera(options, scene.value()), options.width, options.height, options.light,
                            scene.value().lights);
    FrameBuffer fb(options.width, options.height);
    RenderContext ctx(fb);
    for (int threads : {1, 2}) {
        INFO(threads << " thread(s)");
        ctx.setThreads(threads);
        ctx.stats = {};
        app::renderFrame(ctx, scene.value(), view, app::makeRenderSettings(options));
        int red = 0, green = 0;
        for (int y = 0; y < fb.height(); ++y)
            for (int x = 0; x < fb.width(); ++x) {
                const Pixel p = fb.pixel(x, y);
                red += pixelR(p) == 153 && pixelG(p) == 0;
                green += pixelG(p) != 0;
            }
        CHECK(red > 100);
        CHECK(green == 0);
        // The green face's fragments all fail the test: shaded = the red faces' pixels only.
        CHECK(ctx.stats.fragmentsShaded == std::uint64_t(red));
    }
}
