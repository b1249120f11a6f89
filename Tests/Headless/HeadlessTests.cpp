// Tests of the headless command: flag parsing and error paths, bench's JSON, report's files.
#include "TestFramework.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "Platform/Headless/Commands.hpp"
#include "Raster/Frame/ThreadPool.hpp"
#include "Resources/FileIO.hpp"
#include "Resources/Image.hpp"
#include "Resources/GltfTestUtil.hpp"

using namespace sr;
using namespace sr::headless;

namespace {

struct Run {
    int rc = -1;
    std::string out, err;
};

Run run(std::vector<std::string> args) {
    std::ostringstream out, err;
    Run r;
    r.rc = runHeadless(args, Streams{out, err, false});
    r.out = out.str();
    r.err = err.str();
    return r;
}

std::string tempDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / "softraster-tests" / name;
    std::filesystem::create_directories(dir);
    return dir.u8string();
}

bool hasKey(const std::string& json, const std::string& key) { return json.find("\"" + key + "\":") != std::string::npos; }

// The number after "key": in a flat JSON line (enough for our own output).
double numberOf(const std::string& json, const std::string& key) {
    const auto at = json.find("\"" + key + "\":");
    REQUIRE(at != std::string::npos);
    return std::stod(json.substr(at + key.size() + 3));
}

// The "probed" list of --quality auto's JSON: each candidate's label, probed time and error.
struct Probed {
    std::string setting;
    double ms = 0.0, error = 0.0;
};
std::vector<Probed> probedList(const std::string& json) {
    std::vector<Probed> out;
    const auto at = json.find("\"probed\":[");
    if (at == std::string::npos) return out;
    const std::string list = json.substr(at, json.find(']', at) - at);
    for (auto item = list.find('{'); item != std::string::npos; item = list.find('{', item + 1)) {
        const std::string one = list.substr(item, list.find('}', item) - item + 1);
        const auto label = one.find("\"setting\":\"") + 11;
        out.push_back({one.substr(label, one.find('"', label) - label), numberOf(one, "ms"), numberOf(one, "error")});
    }
    return out;
}

} // namespace

TEST_CASE("usage and help", "[headless]") {
    const Run none = run({});
    CHECK(none.rc == kExitUsage);
    CHECK(none.err.find("usage: softraster <command>") != std::string::npos);
    for (const char* cmd : {"render", "bench", "report"}) {
        const Run help = run({cmd, "--help"});
        CHECK(help.rc == kExitOk);
        CHECK(help.out.find(std::string("usage: softraster ") + cmd) != std::string::npos);
        CHECK(help.out.find("--shading MODE") != std::string::npos);
    }
    CHECK(run({"--help"}).rc == kExitOk);
}

TEST_CASE("every bad flag or value gives one clear line and exit code 2", "[headless]") {
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"draw"}, "unknown command 'draw'"},
        {{"render", "--bogus"}, "unknown flag '--bogus'"},
        {{"render", "stray"}, "unexpected argument 'stray'"},
        {{"render", "--width"}, "missing value for --width"},
        {{"render", "--width", "0"}, "bad value for --width: '0'"},
        {{"render", "--width", "9000"}, "bad value for --width: '9000'"},
        {{"render", "--height", "12x"}, "bad value for --height: '12x'"},
        {{"render", "--fov", "180"}, "bad value for --fov: '180'"},
        {{"render", "--fov", "nan"}, "bad value for --fov: 'nan'"},
        {{"render", "--near", "-1"}, "bad value for --near: '-1'"},
        // Below Camera::kMinNear the depths would be subnormal (1e-40) or zero (1e-46: a blank image).
        {{"render", "--near", "1e-46"}, "bad value for --near: '1e-46' (expected a distance from 1e-06 to 1e+15)"},
        {{"render", "--near", "1e-40"}, "bad value for --near: '1e-40'"},
        {{"render", "--near", "9.9e-7"}, "bad value for --near: '9.9e-7'"},
        {{"render", "--near", "2e15"}, "bad value for --near: '2e15'"},
        {{"render", "--near", "2", "--far", "1"}, "--far (1.000000) must be greater than --near (2.000000)"},
        {{"render", "--eye", "1,2"}, "bad value for --eye: '1,2'"},
        {{"render", "--eye", "1,2,1e39"}, "bad value for --eye: '1,2,1e39'"},
        {{"render", "--light", "0,0,0"}, "--light must not be the zero vector"},
        {{"render", "--shading", "toon"}, "bad value for --shading: 'toon' (expected unlit, flat, gouraud, phong or pbr)"},
        {{"render", "--cull", "back"}, "bad value for --cull: 'back' (expected none, cw or ccw)"},
        {{"render", "--color", "srgb"}, "bad value for --color: 'srgb' (expected linear or gamma)"},
        {{"render", "--ibl"}, "--ibl lights the model from the sky: it needs --sky gradient or --skybox DIR"},
        {{"render", "--tonemap", "filmic"}, "bad value for --tonemap: 'filmic' (expected none, aces or neutral)"},
        {{"render", "--exposure", "40"}, "bad value for --exposure: '40'"},
        {{"render", "--filter", "aniso"}, "bad value for --filter: 'aniso'"},
        {{"render", "--persp", "span4"}, "bad value for --persp: 'span4' (expected exact or affine)"},
        // The retired span modes are named as such, with the modes that remain.
        {{"render", "--persp", "span16"}, "--persp span16: span subdivision was retired"},
        {{"bench", "--persp", "span8"}, "the modes that remain: exact, affine"},
        {{"render", "--threads", "-1"}, "bad value for --threads: '-1'"},
        {{"render", "--ssaa", "2"}, "bad value for --ssaa: '2' (expected 1, 4 or 16 samples per pixel)"},
        {{"bench", "--ssaa", "0"}, "bad value for --ssaa: '0'"},
        {{"render", "--msaa", "16"}, "bad value for --msaa: '16' (expected 1, 2, 4 or 8 samples per pixel)"},
        {{"bench", "--msaa", "3"}, "bad value for --msaa: '3'"},
        {{"render", "--msaa", "4", "--ssaa", "4"}, "--ssaa 4 and --msaa 4: choose one way of anti-aliasing"},
        {{"render", "--msaa", "8", "--width", "8192", "--height", "1025"}, "--msaa 8 at 8192x1025 needs more than"},
        // The sample target must fit FrameBuffer::kMaxDimension (8192) per side.
        {{"render", "--ssaa", "16", "--width", "2049"}, "--ssaa 16 renders 2049x600 at 4x4 the size"},
        {{"report", "--out-dir", "d", "--ssaa", "4", "--height", "4097"}, "at most 4096 per side"},
        {{"render", "--frames", "10"}, "unknown flag '--frames'"},
        {{"bench", "--frames", "0"}, "bad value for --frames: '0'"},
        {{"bench", "--warmup", "x"}, "bad value for --warmup: 'x'"},
        {{"report"}, "--out-dir DIR is required"},
        {{"report", "--out", "x.png", "--out-dir", "d"}, "unknown flag '--out'"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const Run r = run(c.args);
        CHECK(r.rc == kExitUsage);
        CHECK(r.err.find(c.message) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1); // one line
        CHECK(r.out.empty());
    }
}

TEST_CASE("pbr needs glTF materials: the built-in scene refuses it in one line, exit code 1", "[headless][pbr]") {
    const Run r = run({"render", "--shading", "pbr", "--width", "32", "--height", "24", "--out", tempDir("h") + "/x.png"});
    CHECK(r.rc == kExitFailure);
    CHECK(r.err.find("--shading pbr needs glTF metallic-roughness materials") != std::string::npos);
    CHECK(r.out.empty());
}

TEST_CASE("an unreadable model or texture is named, exit code 1", "[headless]") {
    const Run missing = run({"render", "--obj", "no/such/model.obj", "--out", tempDir("h") + "/x.png"});
    CHECK(missing.rc == kExitFailure);
    CHECK(missing.err.find("no/such/model.obj") != std::string::npos);
    const Run tex = run({"render", "--texture", "no/such/texture.png", "--out", tempDir("h") + "/x.png"});
    CHECK(tex.rc == kExitFailure);
    CHECK(tex.err.find("no/such/texture.png") != std::string::npos);
    const Run badOut = run({"render", "--width", "32", "--height", "24", "--out", tempDir("h") + "/x.gif"});
    CHECK(badOut.rc == kExitFailure);
    CHECK(badOut.err.find("unknown image extension '.gif'") != std::string::npos);
}

TEST_CASE("render writes the image at the requested size and prints its path", "[headless]") {
    const std::string path = tempDir("render") + "/scene.png";
    const Run r = run({"render", "--width", "96", "--height", "64", "--out", path, "--quiet"});
    REQUIRE(r.rc == kExitOk);
    CHECK(r.out == path + "\n");
    CHECK(r.err.empty()); // --quiet
    auto img = loadImage(path);
    REQUIRE(img.ok());
    CHECK(img.value().width == 96);
    CHECK(img.value().height == 64);
    // The default scene is not blank: count distinct colours.
    std::vector<std::uint32_t> colours;
    for (std::size_t i = 0; i < img.value().rgba.size(); i += 4)
        colours.push_back(std::uint32_t(img.value().rgba[i]) << 16 | std::uint32_t(img.value().rgba[i + 1]) << 8 |
                          img.value().rgba[i + 2]);
    std::sort(colours.begin(), colours.end());
    CHECK(std::unique(colours.begin(), colours.end()) - colours.begin() > 50);
}

namespace {

// `softraster render` of the built-in scene at 96x64 with extra flags into dir/name; its RGBA bytes.
std::vector<std::uint8_t> renderBuiltIn96x64(const std::string& dir, const std::vector<std::string>& extra,
                                             const std::string& name) {
    std::vector<std::string> args{"render", "--width", "96", "--height", "64", "--quiet", "--out", dir + "/" + name};
    args.insert(args.end(), extra.begin(), extra.end());
    const Run r = run(args);
    REQUIRE(r.rc == kExitOk);
    auto img = loadImage(dir + "/" + name);
    REQUIRE(img.ok());
    return img.value().rgba;
}

} // namespace

TEST_CASE("--outline draws a band in the outline colour around the object at the centre, nothing else", "[headless][stencil]") {
    // The built-in scene at 96x64: with --outline only pixels that turn the outline colour
    // (1, 0.78, 0.1 -> 255, 199, 26) change, and there are some (a band around the object under
    // the image centre); --outline takes no value.
    const std::string dir = tempDir("outline");
    const auto plain = renderBuiltIn96x64(dir, {}, "plain.png");
    const auto outlined = renderBuiltIn96x64(dir, {"--outline"}, "outlined.png");
    REQUIRE(plain.size() == outlined.size());
    int changed = 0, other = 0;
    for (std::size_t i = 0; i < plain.size(); i += 4) {
        if (std::equal(plain.begin() + long(i), plain.begin() + long(i) + 3, outlined.begin() + long(i))) continue;
        ++changed;
        other += !(outlined[i] == 255 && outlined[i + 1] == 199 && outlined[i + 2] == 26);
    }
    CHECK(changed > 40);
    CHECK(other == 0);
    CHECK(run({"render", "--outline=3", "--quiet"}).rc == kExitUsage);
}

TEST_CASE("--shadows darkens the built-in scene's floor; bench times the shadow pass; bad values exit 2", "[headless][shadow]") {
    // Shadows only take light away: with --shadows no pixel is brighter in any channel, and many
    // are darker. bench's stage breakdown gains shadow_pass (and not without --shadows).
    const std::string dir = tempDir("shadows");
    const auto plain = renderBuiltIn96x64(dir, {}, "plain.png");
    const auto shadowed = renderBuiltIn96x64(dir, {"--shadows", "--shadow-size", "512", "--shadow-pcf", "1"}, "shadowed.png");
    REQUIRE(plain.size() == shadowed.size());
    int darker = 0, brighter = 0;
    for (std::size_t i = 0; i < plain.size(); i += 4) {
        bool less = false, more = false;
        for (std::size_t k = 0; k < 3; ++k) {
            less |= shadowed[i + k] < plain[i + k];
            more |= shadowed[i + k] > plain[i + k];
        }
        darker += less;
        brighter += more;
    }
    CHECK(darker > 100);
    CHECK(brighter == 0);
    CHECK(renderBuiltIn96x64(dir, {"--shadows", "--no-shadows"}, "off.png") == plain);
    const Run b = run({"bench", "--width", "64", "--height", "48", "--frames", "2", "--warmup", "0", "--quiet", "--shadows",
                       "--shadow-size", "256"});
    REQUIRE(b.rc == kExitOk);
    CHECK(numberOf(b.out, "shadow_pass") > 0.0);
    const Run nb = run({"bench", "--width", "64", "--height", "48", "--frames", "2", "--warmup", "0", "--quiet"});
    CHECK(!hasKey(nb.out, "shadow_pass"));
    CHECK(run({"render", "--shadow-size", "8", "--quiet"}).rc == kExitUsage);
    CHECK(run({"render", "--shadow-size", "9000", "--quiet"}).rc == kExitUsage);
    CHECK(run({"render", "--shadow-pcf", "2", "--quiet"}).rc == kExitUsage);
    CHECK(run({"render", "--shadows=1", "--quiet"}).rc == kExitUsage);
    CHECK(run({"render", "--shadow-bias", "1", "--quiet"}).rc == kExitUsage);
    CHECK(run({"render", "--shadow-bias", "1,-1", "--quiet"}).rc == kExitUsage);
}

TEST_CASE("--ssaa 1 is today's image; --ssaa 4 and 16 change only edge pixels, a little", "[headless][ssaa]") {
    const std::string dir = tempDir("ssaa");
    auto render = [&](const std::vector<std::string>& extra, const std::string& name) {
        return renderBuiltIn96x64(dir, extra, name);
    };
    const auto plain = render({}, "plain.png");
    CHECK(render({"--ssaa", "1"}, "ssaa1.png") == plain);
    const auto aa4 = render({"--ssaa", "4"}, "ssaa4.png");
    const auto aa16 = render({"--ssaa", "16"}, "ssaa16.png");
    REQUIRE(aa4.size() == plain.size());
    REQUIRE(aa16.size() == plain.size());
    // Mean absolute difference per channel, and the pixels that differ at all.
    auto distance = [](const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, std::size_t& differing) {
        double sum = 0;
        differing = 0;
        for (std::size_t i = 0; i < a.size(); i += 4) {
            int d = 0;
            for (std::size_t c = 0; c < 3; ++c) {
                d = std::max(d, std::abs(int(a[i + c]) - int(b[i + c])));
                sum += std::abs(int(a[i + c]) - int(b[i + c]));
            }
            differing += d > 0;
        }
        return sum / double(a.size() / 4 * 3);
    };
    std::size_t differing = 0;
    const std::size_t pixels = plain.size() / 4;
    const double plainTo16 = distance(plain, aa16, differing);
    CHECK(differing > pixels / 50); // edges and texture detail are smoothed
    const double fourTo16 = distance(aa4, aa16, differing);
    CHECK(fourTo16 < 0.75 * plainTo16); // more samples: closer to the 16-sample image
    CHECK(distance(plain, aa4, differing) > 0.0);
    const Run b = run({"bench", "--width", "64", "--height", "48", "--frames", "1", "--warmup", "0", "--quiet", "--ssaa", "4"});
    REQUIRE(b.rc == kExitOk);
    CHECK(numberOf(b.out, "ssaa") == 4);
    CHECK(numberOf(b.out, "pixels_covered") <= 64 * 48);
}

TEST_CASE("--msaa 1 is today's image; --msaa 2, 4, 8 come closer to the 16-sample image", "[headless][msaa]") {
    const std::string dir = tempDir("msaa");
    auto render = [&](const std::vector<std::string>& extra, const std::string& name) {
        return renderBuiltIn96x64(dir, extra, name);
    };
    auto distance = [](const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
        double sum = 0;
        for (std::size_t i = 0; i < a.size(); i += 4)
            for (std::size_t c = 0; c < 3; ++c) sum += std::abs(int(a[i + c]) - int(b[i + c]));
        return sum / double(a.size() / 4 * 3);
    };
    // The built-in scene at the default settings against its SSAA 16 image: the edges come closer
    // (the texture detail, which multisampling shades once per pixel, does not).
    const auto plain = render({}, "plain.png");
    CHECK(render({"--msaa", "1"}, "msaa1.png") == plain);
    const auto truth = render({"--ssaa", "16"}, "ssaa16.png");
    const double one = distance(plain, truth);
    for (const char* n : {"2", "4", "8"}) {
        CAPTURE(n);
        const auto aa = render({"--msaa", n}, std::string("msaa") + n + ".png");
        REQUIRE(aa.size() == plain.size());
        CHECK(distance(aa, truth) < 0.97 * one);
        CHECK(distance(aa, plain) > 0.0);
    }
    const Run b = run({"bench", "--width", "64", "--height", "48", "--frames", "1", "--warmup", "0", "--quiet", "--msaa", "8"});
    REQUIRE(b.rc == kExitOk);
    CHECK(numberOf(b.out, "msaa") == 8);
    CHECK(numberOf(b.out, "ssaa") == 1);
    CHECK(numberOf(b.out, "pixels_shaded") > 0);
}

TEST_CASE("bench prints one JSON line with the documented fields", "[headless]") {
    const Run r = run({"bench", "--width", "64", "--height", "48", "--frames", "3", "--warmup", "1", "--quiet"});
    REQUIRE(r.rc == kExitOk);
    REQUIRE(std::count(r.out.begin(), r.out.end(), '\n') == 1);
    const std::string& j = r.out;
    for (const char* key : {"width", "height", "triangles", "frames", "threads", "ms_per_frame_median",
                            "ms_per_frame_min", "mpix_per_s", "stages_ms", "clear", "transform_clip_cull", "setup",
                            "fill_shade", "counters", "vertices_transformed", "triangles_in", "clipped", "culled",
                            "rasterized", "triangles_set_up", "pixels_shaded", "overdraw", "triangles_sorted"})
        CHECK(hasKey(j, key));
    CHECK(numberOf(j, "width") == 64);
    CHECK(numberOf(j, "frames") == 3);
    CHECK(numberOf(j, "ms_per_frame_min") <= numberOf(j, "ms_per_frame_median"));
    CHECK(numberOf(j, "triangles_in") > 1000);
    CHECK(numberOf(j, "rasterized") <= numberOf(j, "triangles_in"));
    CHECK(numberOf(j, "triangles_set_up") == numberOf(j, "rasterized")); // one thread: each set up once
    // Counted, and indexed: the built-in scene's triangles share vertices, so fewer vertex-stage
    // runs than triangle corners (the sharing between draws is tested in SharedVertexStageTests).
    CHECK(numberOf(j, "vertices_transformed") > 0);
    CHECK(numberOf(j, "vertices_transformed") < 3 * numberOf(j, "triangles_in"));
    CHECK(numberOf(j, "pixels_shaded") >= numberOf(j, "pixels_covered"));
    CHECK(numberOf(j, "pixels_covered") <= 64 * 48);
    CHECK(numberOf(j, "overdraw") >= 1.0);
    CHECK(numberOf(j, "triangles_sorted") == 12); // the built-in scene's glass block (12 triangles), sorted every frame
}

TEST_CASE("bench counters follow the cull mode", "[headless]") {
    const Run none = run({"bench", "--width", "64", "--height", "48", "--frames", "1", "--warmup", "0", "--quiet"});
    const Run cw = run({"bench", "--width", "64", "--height", "48", "--frames", "1", "--warmup", "0", "--quiet",
                        "--cull", "cw"});
    REQUIRE(none.rc == kExitOk);
    REQUIRE(cw.rc == kExitOk);
    CHECK(numberOf(cw.out, "culled") > numberOf(none.out, "culled") + 100);
    CHECK(numberOf(cw.out, "rasterized") < numberOf(none.out, "rasterized"));
}

TEST_CASE("report: every combination against the SSAA 16 ground truth, the front and the presets", "[headless][report]") {
    const std::string dir = tempDir("report");
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const Run r = run({"report", "--out-dir", dir, "--width", "48", "--height", "32", "--frames", "2", "--warmup",
                       "0", "--rounds", "2", "--quiet"});
    REQUIRE(r.rc == kExitOk);
    auto csv = readFileBytes(dir + "/report.csv");
    REQUIRE(csv.ok());
    const std::string text(csv.value().begin(), csv.value().end());
    CHECK(text.rfind("ssaa,msaa,fxaa,filter,shading,persp,ms_median,ms_min,ms_max,mean_abs,psnr_db,ssim,max_abs,differing_share,"
                     "pareto,preset,truth\n", 0) == 0);
    // The built-in scene is textured: the truth + {1 sample, FXAA, MSAA 4, SSAA 4} x 3 filters
    // (bilinear, trilinear, trilinear with 16 anisotropic taps) x 2 shadings (Gouraud, Phong) +
    // MSAA 8; nearest, affine and flat are not rungs.
    CHECK(std::count(text.begin(), text.end(), '\n') == 1 + 1 + 4 * 3 * 2 + 1);
    CHECK(text.find(",nearest,") == std::string::npos);
    CHECK(text.find(",affine,") == std::string::npos);
    CHECK(text.find(",flat,") == std::string::npos);
    auto row = [&](const std::string& prefix) {
        const auto at = text.find("\n" + prefix);
        REQUIRE(at != std::string::npos);
        return text.substr(at + 1, text.find('\n', at + 1) - at - 1);
    };
    auto field = [](const std::string& line, int k) {
        std::size_t at = 0;
        for (int i = 0; i < k; ++i) at = line.find(',', at) + 1;
        return line.substr(at, line.find(',', at) - at);
    };
    // The truth against itself: no error; it is the accurate preset.
    const std::string truth = row("16,1,0,trilinear+aniso16,phong,exact,");
    CHECK(field(truth, 9) == "0.0000");
    CHECK(field(truth, 10) == "inf");
    CHECK(field(truth, 11) == "1.000000"); // SSIM
    CHECK(field(truth, 15) == "accurate");
    CHECK(field(truth, 16) == "1");
    // One sample per pixel is not the truth; four samples (MSAA or SSAA) are closer to it than one,
    // and so are eight multisamples (on this textured scene most of the error left is the
    // texture's, which multisampling does not touch: 8 is not reliably closer than 4 here).
    const double mae1 = std::stod(field(row("1,1,0,trilinear,phong,exact,"), 9));
    const double mae4 = std::stod(field(row("4,1,0,trilinear,phong,exact,"), 9));
    const double msaa4 = std::stod(field(row("1,4,0,trilinear,phong,exact,"), 9));
    const double msaa8 = std::stod(field(row("1,8,0,trilinear+aniso16,phong,exact,"), 9));
    CHECK(mae1 > 0.0);
    CHECK(mae4 < mae1);
    CHECK(msaa4 < mae1);
    CHECK(msaa8 < mae1);
    // SSIM agrees: below 1 with one sample, closer to 1 with four supersamples.
    const double ssim1 = std::stod(field(row("1,1,0,trilinear,phong,exact,"), 11));
    CHECK(ssim1 < 1.0);
    CHECK(std::stod(field(row("4,1,0,trilinear,phong,exact,"), 11)) > ssim1);
    CHECK(std::stod(field(row("1,1,0,trilinear,phong,exact,"), 7)) <= std::stod(field(row("1,1,0,trilinear,phong,exact,"), 6)));
    CHECK(field(row("4,1,0,trilinear,phong,exact,"), 15) == "balanced");
    CHECK(field(row("1,1,0,bilinear,gouraud,exact,"), 15) == "fast");
    // FXAA: one sample with its edges filtered, another image (whether closer to the truth depends
    // on the scene and size: Tests/Frame/FxaaTests.cpp measures edges).
    CHECK(std::stod(field(row("1,1,1,trilinear,phong,exact,"), 9)) != mae1);
    // The truth is on the Pareto front: nothing else has zero error.
    CHECK(field(truth, 14) == "1");
    auto md = readFileBytes(dir + "/report.md");
    REQUIRE(md.ok());
    const std::string mdText(md.value().begin(), md.value().end());
    CHECK(mdText.find("measured against the ground truth") != std::string::npos);
    CHECK(mdText.find("| ssaa | msaa | fxaa | filter | shading | persp | ms/frame median [min, max] | mean abs") != std::string::npos);
    CHECK(mdText.find("2 interleaved rounds") != std::string::npos);
    // A heat map per setting on the front (the truth aside), shown in report.md, of the image's size.
    CHECK(mdText.find("## Where the error is") != std::string::npos);
    int maps = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::u8path(dir))) {
        const std::string name = entry.path().filename().u8string();
        if (name.rfind("report-map-", 0) != 0) continue;
        ++maps;
        CHECK(mdText.find("](" + name + ")") != std::string::npos);
        auto map = loadImage(entry.path().u8string());
        REQUIRE(map.ok());
        CHECK(map.value().width == 48);
        CHECK(map.value().height == 32);
    }
    int frontRows = 0; // on the front and not the truth
    for (std::size_t at = text.find('\n'); at != std::string::npos && at + 1 < text.size(); at = text.find('\n', at + 1)) {
        const std::string line = text.substr(at + 1, text.find('\n', at + 1) - at - 1);
        frontRows += field(line, 14) == "1" && field(line, 16) == "0";
    }
    CHECK(maps >= 1);
    CHECK(maps == frontRows);
    auto svg = readFileBytes(dir + "/report.svg");
    REQUIRE(svg.ok());
    const std::string s(svg.value().begin(), svg.value().end());
    CHECK(s.rfind("<svg", 0) == 0);
    CHECK(s.find("Pareto") != std::string::npos);
    CHECK(s.find("[balanced]") != std::string::npos);
    CHECK(std::count(s.begin(), s.end(), '\n') > 40);
}

TEST_CASE("--aniso: on the built-in scene's receding floor, closer to the 16-sample truth than trilinear", "[headless][aniso]") {
    // The truth is 4x4 supersampling with plain trilinear (no anisotropic taps of its own: the
    // check must not grade the filter by itself); at one sample the floor near the horizon is
    // where trilinear's level, set by the footprint's long axis, greys the checkerboard.
    const std::string dir = tempDir("aniso");
    auto render = [&](const std::string& name, std::vector<std::string> extra) {
        std::vector<std::string> args{"render", "--width", "200", "--height", "150", "--out", dir + "/" + name, "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        REQUIRE(run(args).rc == kExitOk);
        return dir + "/" + name;
    };
    const std::string truth = render("truth.png", {"--ssaa", "16", "--filter", "trilinear"});
    const std::string tri = render("tri.png", {"--filter", "trilinear"});
    const std::string an4 = render("an4.png", {"--aniso", "4"});
    const std::string an16 = render("an16.png", {"--aniso", "16"});
    auto error = [&](const std::string& image) {
        const Run r = run({"compare", image, truth});
        REQUIRE(r.rc == kExitOk);
        return numberOf(r.out, "mean_abs");
    };
    const double eTri = error(tri), e4 = error(an4), e16 = error(an16);
    INFO("mean abs error against the truth: trilinear " << eTri << ", aniso 4 " << e4 << ", aniso 16 " << e16);
    // (16 taps need not beat 4 here: the truth's own samples still blur the far floor, as
    // trilinear does, a quarter as much.)
    CHECK(e4 < 0.7 * eTri);
    CHECK(e16 < 0.7 * eTri);
    const Run bench = run({"bench", "--width", "32", "--height", "24", "--frames", "1", "--warmup", "0", "--quiet", "--aniso", "8"});
    REQUIRE(bench.rc == kExitOk);
    CHECK(numberOf(bench.out, "aniso") == 8);
}

TEST_CASE("--quality selects a preset; explicit flags win in any order", "[headless][quality]") {
    auto bench = [](std::vector<std::string> extra) {
        std::vector<std::string> args{"bench", "--width", "32", "--height", "24", "--frames", "1", "--warmup", "0", "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        const Run r = run(args);
        REQUIRE(r.rc == kExitOk);
        return r.out;
    };
    auto str = [](const std::string& json, const std::string& key) {
        const auto at = json.find("\"" + key + "\":\"");
        REQUIRE(at != std::string::npos);
        const auto from = at + key.size() + 4;
        return json.substr(from, json.find('"', from) - from);
    };
    const std::string fast = bench({"--quality", "fast"});
    CHECK(numberOf(fast, "ssaa") == 1);
    CHECK(str(fast, "filter") == "bilinear");
    CHECK(str(fast, "shading") == "gouraud");
    CHECK(str(fast, "persp") == "exact");
    const std::string balanced = bench({"--quality", "balanced"});
    CHECK(numberOf(balanced, "ssaa") == 4);
    CHECK(str(balanced, "filter") == "trilinear");
    CHECK(str(balanced, "shading") == "phong");
    CHECK(str(balanced, "persp") == "exact");
    const std::string accurate = bench({"--quality=accurate"});
    CHECK(numberOf(accurate, "ssaa") == 16);
    CHECK(str(accurate, "filter") == "trilinear");
    for (const auto& order : {std::vector<std::string>{"--shading", "flat", "--quality", "accurate", "--ssaa", "1"},
                              std::vector<std::string>{"--ssaa", "1", "--quality", "accurate", "--shading", "flat"}}) {
        CAPTURE(order);
        const std::string mixed = bench(order);
        CHECK(numberOf(mixed, "ssaa") == 1);
        CHECK(str(mixed, "shading") == "flat");
        CHECK(str(mixed, "filter") == "trilinear");
        CHECK(str(mixed, "persp") == "exact");
    }
    // An explicit --msaa replaces the preset's supersampling (and the other way round).
    const std::string multi = bench({"--quality", "balanced", "--msaa", "4"});
    CHECK(numberOf(multi, "msaa") == 4);
    CHECK(numberOf(multi, "ssaa") == 1);
    CHECK(str(multi, "filter") == "trilinear");
    const Run bad = run({"render", "--quality", "ultra"});
    CHECK(bad.rc == kExitUsage);
    CHECK(bad.err.find("bad value for --quality: 'ultra' (expected fast, balanced, accurate or auto)") != std::string::npos);
}

TEST_CASE("render of the default scene matches its golden image", "[headless][golden]") {
    // Same tolerance as the frame suite's golden test (Tests/Frame/GoldenImageTests.cpp):
    // at most 0.5% of the pixels differ, at most 10 of them by more than 2 levels.
    for (const char* mode : {"unlit", "phong"}) {
        CAPTURE(mode);
        const std::string path = tempDir("golden") + "/default_" + mode + ".png";
        const Run r = run({"render", "--width", "160", "--height", "120", "--shading", mode, "--out", path, "--quiet"});
        REQUIRE(r.rc == kExitOk);
        auto actual = loadImage(path);
        auto golden = loadImage(std::string(SR_TEST_DATA_DIR) + "/../Golden/default_" + mode + "_160x120.png");
        REQUIRE(actual.ok());
        REQUIRE(golden.ok());
        REQUIRE(actual.value().width == golden.value().width);
        REQUIRE(actual.value().height == golden.value().height);
        int differing = 0, large = 0;
        for (std::size_t i = 0; i < actual.value().rgba.size(); i += 4) {
            int m = 0;
            for (std::size_t c = 0; c < 3; ++c)
                m = std::max(m, std::abs(int(actual.value().rgba[i + c]) - int(golden.value().rgba[i + c])));
            differing += m > 0;
            large += m > 2;
        }
        CHECK(differing <= 160 * 120 / 200);
        CHECK(large <= 10);
    }
}

TEST_CASE("--threads beyond the CPUs this process may use starts only as many, and says so", "[headless][threads]") {
    const int usable = ThreadPool::usableHardwareThreads();
    const Run many = run({"bench", "--width", "64", "--height", "48", "--frames", "1", "--warmup", "0", "--threads", "64"});
    REQUIRE(many.rc == kExitOk);
    if (usable > 0 && usable < 64) {
        CHECK(numberOf(many.out, "threads") == usable);
        CHECK(many.err.find("--threads 64: this process may run on " + std::to_string(usable)) != std::string::npos);
    } else {
        CHECK(numberOf(many.out, "threads") == 64);
    }
    // Within the CPUs: as asked, without a note.
    const Run one = run({"bench", "--width", "64", "--height", "48", "--frames", "1", "--warmup", "0", "--threads", "1"});
    REQUIRE(one.rc == kExitOk);
    CHECK(numberOf(one.out, "threads") == 1);
    CHECK(one.err.find("may run on") == std::string::npos);
}

#ifndef _WIN32 // Debian's assimp-testmodels: natively
TEST_CASE("--time poses a glTF file's animation; the kernels equal the scalar path at every time; bench --time-step",
          "[headless][animation]") {
    const std::string skin = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
    const std::string dir = tempDir("animation");
    const std::vector<std::string> view = {"--width", "96", "--height", "72", "--eye", "0,1,4", "--target", "0,1,0", "--quiet"};
    const auto render = [&](std::vector<std::string> flags, const std::string& name) {
        std::vector<std::string> args = {"render", "--model", skin, "--out", dir + "/" + name};
        args.insert(args.end(), view.begin(), view.end());
        args.insert(args.end(), flags.begin(), flags.end());
        const Run r = run(args);
        INFO(r.err);
        REQUIRE(r.rc == kExitOk);
        auto img = loadImage(dir + "/" + name);
        REQUIRE(img.ok());
        return img.value().rgba;
    };
    const auto rest = render({}, "rest.png");
    // The strip bends left at 1.25 s and right at 4.25 s (joint 2 turns +-90 degrees): three
    // different images, each the same through the span kernels and the scalar reference.
    std::vector<std::vector<std::uint8_t>> posed;
    for (const char* t : {"0", "1.25", "4.25"}) {
        const auto kernels = render({"--time", t}, std::string("t") + t + ".png");
        const auto scalar = render({"--time", t, "--isa", "scalar"}, std::string("t") + t + "_scalar.png");
        CHECK(kernels == scalar);
        posed.push_back(kernels);
    }
    CHECK(posed[0] == rest); // the clip's first key is the rest pose
    CHECK(posed[1] != rest);
    CHECK(posed[2] != rest);
    CHECK(posed[1] != posed[2]);
    // --animation N beyond the file's clips, and --time on a file without animation (a note).
    const Run bad = run({"render", "--model", skin, "--animation", "3", "--out", dir + "/x.png"});
    CHECK(bad.rc == kExitFailure);
    CHECK(bad.err.find("--animation 3: it has 1 animation(s)") != std::string::npos);
    const Run still = run({"render", "--time", "1", "--width", "32", "--height", "24", "--out", dir + "/still.png"});
    CHECK(still.rc == kExitOk);
    CHECK(still.err.find("has no animation") != std::string::npos);
    // bench --time-step: the posing stage in the JSON; a file without animation has none.
    const Run b = run({"bench", "--model", skin, "--width", "64", "--height", "48", "--frames", "3", "--warmup", "0", "--time-step",
                       "0.1", "--quiet"});
    REQUIRE(b.rc == kExitOk);
    CHECK(hasKey(b.out, "animate"));
    const Run plain = run({"bench", "--width", "64", "--height", "48", "--frames", "1", "--warmup", "0", "--time-step", "0.1", "--quiet"});
    REQUIRE(plain.rc == kExitOk);
    CHECK_FALSE(hasKey(plain.out, "animate"));
}
#endif

TEST_CASE("--quality auto: a probe chooses by --budget-ms or --max-error and says what it chose", "[headless][auto]") {
    // 160x120, not smaller: the candidates' probed times must differ by more than a loaded host's
    // noise, or the "fastest" below is any of the one-sample, FXAA, MSAA 4 and SSAA 4 settings.
    const std::vector<std::string> small = {"--width", "160", "--height", "120", "--frames", "1", "--warmup", "0"};
    const auto bench = [&](std::vector<std::string> flags) {
        std::vector<std::string> args = {"bench"};
        args.insert(args.end(), small.begin(), small.end());
        args.insert(args.end(), flags.begin(), flags.end());
        const Run r = run(args);
        INFO(r.err);
        REQUIRE(r.rc == kExitOk);
        return r;
    };
    // A budget nothing meets: the fastest candidate as probed (which cheap setting that is, is
    // timing: one sample, FXAA, MSAA 4 and SSAA 4 have each been it on a loaded host), checked
    // against the probe's own list of times; an unlimited one: the truth.
    const Run tight = bench({"--quality", "auto", "--budget-ms", "0.000001"});
    CHECK(tight.err.find("quality auto (--budget-ms 1e-06): ") != std::string::npos);
    REQUIRE(hasKey(tight.out, "quality_auto"));
    const std::vector<Probed> probed = probedList(tight.out);
    REQUIRE(probed.size() == std::size_t(numberOf(tight.out, "candidates")));
    std::size_t fastest = 0;
    for (std::size_t k = 1; k < probed.size(); ++k)
        if (probed[k].ms < probed[fastest].ms || (probed[k].ms == probed[fastest].ms && probed[k].error < probed[fastest].error))
            fastest = k;
    CHECK(tight.out.find("\"quality_auto\":{\"setting\":\"" + probed[fastest].setting + "\"") != std::string::npos);
    CHECK(numberOf(tight.out, "probe_ms") == probed[fastest].ms);
    CHECK(probed.back().setting == "ssaa16 trilinear aniso16 phong exact"); // the truth is probed last,
    CHECK(probed.back().error == 0.0);                                      // its error 0,
    for (std::size_t k = 0; k + 1 < probed.size(); ++k) CHECK(probed[k].error > 0.0); // the others' not
    const Run loose = bench({"--quality", "auto", "--budget-ms", "1000000", "--quiet"});
    CHECK(numberOf(loose.out, "ssaa") == 16);
    CHECK(loose.out.find("\"setting\":\"ssaa16 trilinear aniso16 phong exact\"") != std::string::npos);
    CHECK(numberOf(loose.out, "error") == 0.0);
    CHECK(loose.err.empty()); // --quiet
    // An error bound of 0: only the truth; a bound of 1 (anything): the cheapest, one sample.
    const Run exact = bench({"--quality", "auto", "--max-error", "0"});
    CHECK(exact.err.find("ssaa16 trilinear aniso16 phong exact") != std::string::npos);
    const Run any = bench({"--quality", "auto", "--max-error", "1"});
    CHECK(numberOf(any.out, "ssaa") == 1);
    CHECK(numberOf(any.out, "msaa") == 1);
    CHECK(numberOf(any.out, "candidates") >= 9);
    // Usage errors: the bounds without auto, both at once, auto for report, and in the demo.
    CHECK(run({"render", "--budget-ms", "5"}).rc == kExitUsage);
    CHECK(run({"render", "--quality", "auto", "--budget-ms", "5", "--max-error", "0.1"}).rc == kExitUsage);
    CHECK(run({"render", "--quality", "auto", "--budget-ms", "-1"}).rc == kExitUsage);
    CHECK(run({"report", "--out-dir", tempDir("auto-report"), "--quality", "auto"}).rc == kExitUsage);
}

TEST_CASE("bench --flight with --quality auto reports the setting each frame was drawn with", "[headless][auto]") {
    // The labels of the probe's settings and the index each frame used.
    const auto flight = [&](const char* budget) {
        const Run r = run({"bench", "--width", "160", "--height", "120", "--frames", "6", "--flight", "3", "--quality", "auto",
                           "--budget-ms", budget, "--quiet"});
        INFO(r.err);
        REQUIRE(r.rc == kExitOk);
        const auto list = [&](const std::string& key) {
            const auto at = r.out.find("\"" + key + "\":[");
            REQUIRE(at != std::string::npos);
            const auto begin = at + key.size() + 4;
            std::vector<std::string> items;
            std::stringstream in(r.out.substr(begin, r.out.find(']', begin) - begin));
            for (std::string item; std::getline(in, item, ',');) items.push_back(item);
            return items;
        };
        std::vector<std::string> labels = list("settings");
        std::vector<std::string> used;
        for (const std::string& k : list("per_frame")) {
            const int i = std::stoi(k);
            REQUIRE(i >= 0);
            REQUIRE(i < int(labels.size()));
            used.push_back(labels[std::size_t(i)]);
        }
        return used;
    };
    // Nothing fits: every frame at the probe's fastest setting (which cheap one that is, is timing;
    // the frames' own times scale every prediction alike, so it stays the fastest and is never
    // left); everything fits: the truth.
    const auto tight = flight("0.000001");
    REQUIRE(tight.size() == 6);
    for (const std::string& l : tight) {
        CHECK(l == tight.front());
        CHECK(l != "\"ssaa16 trilinear aniso16 phong exact\"");
    }
    const auto loose = flight("1000000");
    REQUIRE(loose.size() == 6);
    for (const std::string& l : loose) CHECK(l == "\"ssaa16 trilinear aniso16 phong exact\"");
}

TEST_CASE("bench's stages: the SSAA, MSAA and FXAA resolve timed on its own, only where there is one; binning with threads", "[headless]") {
    const auto bench = [](std::vector<std::string> extra) {
        // 20 frames: the resolve's time is a mean over the warm-up and timed frames, checked against
        // the median frame below, and with 3 frames one slow frame on a loaded machine (a first
        // touch, a preemption) made it 3x the median (FXAA, 1 run in 40 beside a busy CPU).
        std::vector<std::string> args{"bench", "--width", "64", "--height", "48", "--frames", "20", "--warmup", "1", "--quiet"};
        args.insert(args.end(), extra.begin(), extra.end());
        const Run r = run(args);
        REQUIRE(r.rc == kExitOk);
        return r.out;
    };
    const std::string plain = bench({});
    CHECK_FALSE(hasKey(plain, "resolve"));
    CHECK_FALSE(hasKey(plain, "binning")); // one thread: nothing is binned
    for (const std::vector<std::string>& aa : {std::vector<std::string>{"--ssaa", "4"}, {"--msaa", "4"}, {"--fxaa"}}) {
        const std::string out = bench(aa);
        CHECK(hasKey(out, "resolve"));
        CHECK(numberOf(out, "resolve") > 0.0);
        CHECK(numberOf(out, "resolve") < numberOf(out, "ms_per_frame_median") * 2.0); // a part of the frame (a mean, so some slack)
    }
    // Two threads (where the process may use two CPUs): the binning stage of its own.
    const std::string two = bench({"--threads", "2"});
    if (numberOf(two, "threads") > 1) {
        CHECK(hasKey(two, "binning"));
        CHECK(numberOf(two, "binning") >= 0.0);
    }
}

TEST_CASE("bench reports the model's load: its time, decoded triangles and texels; none for the built-in scene", "[headless][bench]") {
    const std::string dir = tempDir("bench-load");
    // Two triangles and a 4x2 texture (8 texels).
    Image texture;
    texture.width = 4;
    texture.height = 2;
    texture.rgba.assign(4 * 2 * 4, 200);
    REQUIRE(writeImage(dir + "/t.png", texture).ok());
    const std::string mtl = "newmtl m\nKd 1 1 1\nmap_Kd t.png\n";
    const std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nusemtl m\nf 1/1 2/2 3/3\nf 2/2 4/4 3/3\n";
    REQUIRE(writeFileBytes(dir + "/m.mtl", mtl.data(), mtl.size()).ok());
    REQUIRE(writeFileBytes(dir + "/q.obj", obj.data(), obj.size()).ok());
    const Run b = run({"bench", "--obj", dir + "/q.obj", "--width", "32", "--height", "32", "--frames", "1", "--warmup", "0", "--quiet"});
    REQUIRE(b.rc == kExitOk);
    REQUIRE(hasKey(b.out, "load_ms"));
    CHECK(numberOf(b.out, "load_ms") > 0.0);
    CHECK(numberOf(b.out, "texels") == 8.0);
    CHECK(b.out.find("\"load\":{\"triangles\":2,") != std::string::npos);
    const Run builtIn = run({"bench", "--width", "32", "--height", "32", "--frames", "1", "--warmup", "0", "--quiet"});
    REQUIRE(builtIn.rc == kExitOk);
    CHECK(!hasKey(builtIn.out, "load_ms"));
}

TEST_CASE("report: a glTF scene's rungs without each material extension it has, measured against the truth with them",
          "[headless][report][pbr]") {
    const std::string dir = tempDir("report-extensions");
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    // A quad facing the camera, red, with a clear coat, a white sheen and KHR_materials_ior 2.5.
    gltftest::Asset a;
    const int pos = a.floats({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, 1, 0}, "VEC3");
    const int nrm = a.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm) +
               "},\"material\":0}]}]";
    a.nodes = R"([{"mesh":0}])";
    a.materials = R"([{"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.1,0.1,1],"metallicFactor":0,"roughnessFactor":0.6},)"
                  R"("extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":1},"KHR_materials_ior":{"ior":2.5},)"
                  R"("KHR_materials_sheen":{"sheenColorFactor":[1,1,1],"sheenRoughnessFactor":0.5}}}])";
    a.extra = R"(,"extensionsUsed":["KHR_materials_clearcoat","KHR_materials_ior","KHR_materials_sheen"])";
    const std::string text = a.embedded();
    REQUIRE(writeFileBytes(dir + "/coat.gltf", text.data(), text.size()).ok());
    const Run r = run({"report", "--model", dir + "/coat.gltf", "--out-dir", dir, "--width", "32", "--height", "24", "--light", "0,0.3,1",
                       "--frames", "1", "--warmup", "0", "--rounds", "1", "--quiet"});
    REQUIRE(r.rc == kExitOk);
    auto csv = readFileBytes(dir + "/report.csv");
    REQUIRE(csv.ok());
    const std::string table(csv.value().begin(), csv.value().end());
    // Untextured, physical: the truth + {1 sample, FXAA, MSAA 4, SSAA 4} x {Gouraud, Phong, pbr}
    // + MSAA 8 + pbr gamma + pbr without the coat, without the sheen, without the specular and
    // without all three.
    CHECK(std::count(table.begin(), table.end(), '\n') == 1 + 1 + 4 * 3 + 1 + 1 + 4);
    const auto meanAbs = [&](const std::string& shading) {
        const std::string key = "\n1,1,0,-," + shading + ",exact,";
        const auto at = table.find(key);
        REQUIRE(at != std::string::npos);
        std::string line = table.substr(at + key.size());
        for (int i = 0; i < 3; ++i) line = line.substr(line.find(',') + 1); // ms median, min, max
        return std::stod(line.substr(0, line.find(',')));
    };
    const double full = meanAbs("pbr"), noCoat = meanAbs("pbr without clearcoat"), noSpecular = meanAbs("pbr without specular"),
                 noSheen = meanAbs("pbr without sheen"), neither = meanAbs("pbr without clearcoat and sheen and specular");
    // Each dropped extension moves the image away from the truth drawn with it (most of the
    // error of one sample is the quad's aliased edges, the same in every such rung).
    CHECK(noCoat > full + 0.25);
    CHECK(noSpecular > full + 0.25);
    CHECK(noSheen > full + 0.25);
    CHECK(neither > full + 0.25);
}

TEST_CASE("--variant: an unknown name fails listing none for a file without variants; OBJ files have none", "[headless][variants]") {
    const std::string dir = tempDir("variant");
    const std::string gltf = "{\"asset\":{\"version\":\"2.0\"}}";
    REQUIRE(writeFileBytes(dir + "/plain.gltf", gltf.data(), gltf.size()).ok());
    const Run g = run({"render", "--model", dir + "/plain.gltf", "--variant", "gold", "--width", "16", "--height", "16",
                       "--out", dir + "/v.png", "--quiet"});
    CHECK(g.rc == kExitFailure);
    CHECK(g.err.find("no material variant 'gold' (the file has none)") != std::string::npos);
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    REQUIRE(writeFileBytes(dir + "/t.obj", obj.data(), obj.size()).ok());
    const Run o = run({"render", "--obj", dir + "/t.obj", "--variant", "gold", "--width", "16", "--height", "16", "--out", dir + "/o.png",
                       "--quiet"});
    CHECK(o.rc == kExitFailure);
    CHECK(o.err.find("only glTF files have material variants") != std::string::npos);
    CHECK(run({"render", "--variant=", "--quiet"}).rc == kExitUsage);
}
