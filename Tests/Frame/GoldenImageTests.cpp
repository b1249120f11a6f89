// Golden images of the default scene (160x120) in each shading mode, compared within a stated tolerance.
//
// The goldens live in Tests/Golden/default_<mode>_160x120.png and are produced by this test itself.
// To regenerate them after an intended change of the image (then look at them before committing):
//     SR_UPDATE_GOLDEN=1 build/native/bin/sr_frame_tests "[golden]"
// which writes the PNGs into the source tree (SR_TEST_DATA_DIR/../Golden) and passes.
#include "TestFramework.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "Platform/App/SceneSetup.hpp"
#include "Resources/Image.hpp"

using namespace sr;

namespace {

constexpr int kWidth = 160, kHeight = 120;

// Tolerance, per image:
//  - at most 0.5% of the pixels (96 of 19200) may differ at all, and
//  - at most 10 pixels (0.05%: edge pixels whose coverage flipped) may differ by more than 2 (of
//    255) in any channel; every other pixel is within 2.
// Why not bit-exact: the goldens are produced on one toolchain and checked on several (g++ with
// glibc, g++ with sanitizers, MinGW-w64 under Wine, MSVC on Windows, possibly ARM64). The shading
// is float arithmetic: std::sqrt is correctly rounded everywhere, but std::pow (non-integer
// shininess), std::sin/std::cos (the sphere and torus vertices) and std::tan (the projection) come
// from different libms (glibc, mingw-w64/msvcrt, the UCRT) that may differ by an ulp, and a
// compiler may contract a * b + c into one FMA (MSVC with /fp:fast, any ARM64 or -mfma build; not
// GCC's default x86-64 code). One ulp of a lit colour (~6e-8) moves a pixel by 1 level only when
// the value sits that close to a rounding boundary, and a vertex moved by an ulp changes the
// coverage of a pixel only when its centre is within ~1e-5 pixel of an edge. Both are rare and
// local: a handful of pixels, off by 1 (colour), or by an edge's contrast (coverage - hence a
// budget on the number of differing pixels, not only on the size of the difference). Against these
// goldens, glibc, ASan/UBSan and MinGW + Wine all give 0 differing pixels. A
// systematic change (texture orientation, a lighting term, a mode falling back to another, a
// winding error) moves thousands of pixels by far more than 2 and fails.
constexpr double kMaxDifferingShare = 0.005;
constexpr int kMaxChannelDiff = 2;
constexpr int kMaxCoverageFlips = 10;

std::string goldenPath(ShadingMode mode) {
    return std::string(SR_TEST_DATA_DIR) + "/../Golden/default_" + shadingModeName(mode) + "_160x120.png";
}

Image renderDefaultScene(ShadingMode mode) {
    app::SceneOptions options;
    options.width = kWidth;
    options.height = kHeight;
    options.shading = mode;
    auto scene = app::loadScene(options);
    REQUIRE(scene.ok());
    const app::CameraSetup camera = app::resolveCamera(options, scene.value());
    const FrameView view = app::makeFrameView(camera, kWidth, kHeight, options.light, scene.value().lights);
    const RenderSettings settings = app::makeRenderSettings(options);
    FrameBuffer fb(kWidth, kHeight);
    RenderContext ctx(fb);
    app::renderFrame(ctx, scene.value(), view, settings);
    return toImage(fb);
}

bool updating() {
    const char* v = std::getenv("SR_UPDATE_GOLDEN");
    return v && *v && std::string(v) != "0";
}

} // namespace

TEST_CASE("golden images of the default scene in each shading mode", "[render][golden]") {
    for (ShadingMode mode : {ShadingMode::Unlit, ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong}) {
        const std::string path = goldenPath(mode);
        INFO("mode " << shadingModeName(mode) << ", golden " << path);
        const Image actual = renderDefaultScene(mode);
        if (updating()) {
            const Status written = writeImage(path, actual);
            INFO((written.ok() ? std::string() : written.error()));
            REQUIRE(written.ok());
            WARN("SR_UPDATE_GOLDEN: wrote " << path);
            continue;
        }
        const auto golden = loadImage(path);
        INFO((golden.ok() ? std::string() : golden.error()) << " (regenerate with SR_UPDATE_GOLDEN=1)");
        REQUIRE(golden.ok());
        const Image& expected = golden.value();
        REQUIRE(expected.width == kWidth);
        REQUIRE(expected.height == kHeight);

        int differing = 0, beyond = 0, maxDiff = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const std::uint8_t* a = actual.texel(x, y);
                const std::uint8_t* e = expected.texel(x, y);
                int d = 0;
                for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a[c]) - int(e[c])));
                if (d > 0) ++differing;
                if (d > kMaxChannelDiff) ++beyond;
                maxDiff = std::max(maxDiff, d);
            }
        INFO("differing pixels " << differing << ", beyond " << kMaxChannelDiff << ": " << beyond
                                 << ", max channel difference " << maxDiff);
        CHECK(differing <= int(kMaxDifferingShare * kWidth * kHeight));
        CHECK(beyond <= kMaxCoverageFlips);
    }
}
