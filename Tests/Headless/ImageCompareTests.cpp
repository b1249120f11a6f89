// The image metrics: SSIM against its closed form and an independent implementation, the heat map, and `softraster compare`.
#include "TestFramework.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "Platform/Headless/Commands.hpp"
#include "Platform/Headless/ImageCompare.hpp"
#include "Resources/Image.hpp"

using namespace sr;
using namespace sr::headless;
using sr::app::structuralSimilarity;

namespace {

// The synthetic pair also given to scikit-image below: a patterned ramp, and the same with a
// small periodic noise and its right half brighter by 12.
void syntheticPair(FrameBuffer& ref, FrameBuffer& test) {
    for (int y = 0; y < ref.height(); ++y)
        for (int x = 0; x < ref.width(); ++x) {
            int r[3], t[3];
            for (int c = 0; c < 3; ++c) {
                r[c] = (x * 5 + y * 3 + c * 40 + ((x * y) % 17) * 4) % 256;
                t[c] = std::clamp(r[c] + ((x * 7 + y * 11 + c * 3) % 9) - 4 + (x > 24 ? 12 : 0), 0, 255);
            }
            ref.colorRow(y)[x] = packBgra(std::uint8_t(r[0]), std::uint8_t(r[1]), std::uint8_t(r[2]));
            test.colorRow(y)[x] = packBgra(std::uint8_t(t[0]), std::uint8_t(t[1]), std::uint8_t(t[2]));
        }
}

void fill(FrameBuffer& fb, std::uint8_t v) {
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x) fb.colorRow(y)[x] = packBgra(v, v, v);
}

} // namespace

TEST_CASE("SSIM: 1 for identical images, the closed form for flat ones, scikit-image's value for a textured pair",
          "[headless][metrics]") {
    FrameBuffer a(48, 40), b(48, 40);
    syntheticPair(a, b);
    CHECK(structuralSimilarity(a, a) == Approx(1.0).epsilon(1e-12));
    // Two flat images of grey 100 and 150: no variance, so SSIM is the luminance term alone,
    // (2 mx my + C1) / (mx^2 + my^2 + C1), C1 = (0.01 x 255)^2.
    FrameBuffer g100(16, 16), g150(16, 16);
    fill(g100, 100);
    fill(g150, 150);
    const double c1 = (0.01 * 255.0) * (0.01 * 255.0);
    CHECK(structuralSimilarity(g100, g150) == Approx((2.0 * 100 * 150 + c1) / (100.0 * 100 + 150.0 * 150 + c1)).epsilon(1e-12));
    // An independent implementation (scikit-image 0.19.3, Debian python3-skimage):
    //   structural_similarity(ref, test, channel_axis=2, gaussian_weights=True, sigma=1.5,
    //                         use_sample_covariance=False, data_range=255)
    // on the same pair built with numpy gives 0.9893003707.
    CHECK(structuralSimilarity(a, b) == Approx(0.9893003707).epsilon(1e-9));
    // Worse with more noise, symmetric in its arguments.
    CHECK(structuralSimilarity(b, a) == Approx(structuralSimilarity(a, b)).epsilon(1e-12));
    FrameBuffer c = a;
    for (int y = 0; y < c.height(); ++y)
        for (int x = 0; x < c.width(); ++x)
            if ((x + y) % 3 == 0) c.colorRow(y)[x] = packBgra(0, 255, 0);
    CHECK(structuralSimilarity(a, c) < structuralSimilarity(a, b));
    // compareImages carries it only when asked.
    CHECK(compareImages(a, b, true).ssim == Approx(structuralSimilarity(a, b)).epsilon(1e-12));
    // Images under the window's size: a smaller window, still 1 for identical ones.
    FrameBuffer tiny(5, 3);
    fill(tiny, 30);
    CHECK(structuralSimilarity(tiny, tiny) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("the error heat map: black where equal, visible at one level, white from 64 levels", "[headless][metrics]") {
    FrameBuffer a(4, 2), b(4, 2);
    fill(a, 100);
    fill(b, 100);
    b.colorRow(0)[1] = packBgra(101, 100, 100); // one level in one channel
    b.colorRow(0)[2] = packBgra(100, 100, 164); // 64 levels
    b.colorRow(1)[3] = packBgra(100, 116, 100); // 16 levels: half-way up the ramp (sqrt(16 / 64))
    const Image map = errorHeatMap(a, b);
    REQUIRE(map.width == 4);
    REQUIRE(map.height == 2);
    const auto px = [&](int x, int y) { return &map.rgba[(std::size_t(y) * 4 + std::size_t(x)) * 4]; };
    CHECK((px(0, 0)[0] == 0 && px(0, 0)[1] == 0 && px(0, 0)[2] == 0));
    CHECK(int(px(1, 0)[0]) + px(1, 0)[1] + px(1, 0)[2] > 30); // one level shows
    CHECK(int(px(1, 0)[0]) + px(1, 0)[1] + px(1, 0)[2] < 200);
    CHECK((px(2, 0)[0] == 255 && px(2, 0)[1] == 255 && px(2, 0)[2] == 255));
    CHECK(px(3, 1)[0] > px(3, 1)[1]); // magenta: red and blue over green
    CHECK(px(3, 1)[2] > px(3, 1)[1]);
}

TEST_CASE("softraster compare: one JSON line of metrics, the heat map, clear errors", "[headless][metrics]") {
    const auto dir = std::filesystem::temp_directory_path() / "softraster-tests" / "compare";
    std::filesystem::create_directories(dir);
    const std::string refPath = (dir / "a.png").u8string(), testPath = (dir / "b.png").u8string(), mapPath = (dir / "map.png").u8string();
    FrameBuffer a(48, 40), b(48, 40);
    syntheticPair(a, b);
    REQUIRE(writeImage(refPath, toImage(a)).ok());
    REQUIRE(writeImage(testPath, toImage(b)).ok());
    const auto run = [](std::vector<std::string> args, std::string& out, std::string& err) {
        std::ostringstream o, e;
        args.insert(args.begin(), "compare");
        const int rc = runHeadless(args, Streams{o, e, false});
        out = o.str();
        err = e.str();
        return rc;
    };
    std::string out, err;
    std::filesystem::remove(mapPath);
    REQUIRE(run({refPath, testPath, "--map", mapPath}, out, err) == kExitOk);
    CHECK(std::count(out.begin(), out.end(), '\n') == 1);
    for (const char* key : {"\"width\":48", "\"height\":40", "\"mean_abs\":", "\"psnr_db\":", "\"max_abs\":", "\"differing_pixels\":",
                            "\"ssim\":0.989300"})
        CHECK(out.find(key) != std::string::npos);
    auto map = loadImage(mapPath);
    REQUIRE(map.ok());
    CHECK(map.value().width == 48);
    CHECK(map.value().height == 40);
    // The same file twice: no error at all.
    REQUIRE(run({refPath, refPath, "--quiet"}, out, err) == kExitOk);
    CHECK(out.find("\"mean_abs\":0.0000") != std::string::npos);
    CHECK(out.find("\"psnr_db\":null") != std::string::npos); // infinite
    CHECK(out.find("\"ssim\":1.000000") != std::string::npos);
    // Errors: a usage error (2) names what is wrong; a missing file or a size mismatch fails (1).
    CHECK(run({refPath}, out, err) == kExitUsage);
    CHECK(err.find("expected two images") != std::string::npos);
    CHECK(run({refPath, testPath, "--frobnicate"}, out, err) == kExitUsage);
    CHECK(run({refPath, (dir / "missing.png").u8string()}, out, err) == kExitFailure);
    CHECK(err.find("missing.png") != std::string::npos);
    FrameBuffer small(8, 8);
    const std::string smallPath = (dir / "small.png").u8string();
    REQUIRE(writeImage(smallPath, toImage(small)).ok());
    CHECK(run({refPath, smallPath}, out, err) == kExitFailure);
    CHECK(err.find("must be the same size") != std::string::npos);
    CHECK(run({"--help"}, out, err) == kExitOk);
    CHECK(out.find("usage: softraster compare") != std::string::npos);
}
