// Tests of image decoding limits, the writers (PPM/PNG/BMP/PFM) and file errors.
#include "TestFramework.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "ObjTestUtil.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Resources/FileIO.hpp"
#include "Resources/Image.hpp"
#include "Resources/Skybox.hpp"

using namespace sr;

namespace {

std::string tempPath(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / "softraster-tests";
    std::filesystem::create_directories(dir);
    return (dir / name).u8string();
}

Image gradient(int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.rgba.resize(std::size_t(w) * std::size_t(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* t = img.texel(x, y);
            t[0] = std::uint8_t(x * 255 / (w - 1));
            t[1] = std::uint8_t(y * 255 / (h - 1));
            t[2] = std::uint8_t((x * 7 + y * 13) & 255);
            t[3] = 255;
        }
    return img;
}

// A PNG signature plus an IHDR chunk claiming width x height (RGBA8); no image data follows.
std::vector<unsigned char> pngHeaderClaiming(std::uint32_t width, std::uint32_t height) {
    std::vector<unsigned char> b = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    auto be32 = [&](std::uint32_t v) {
        for (int s = 24; s >= 0; s -= 8) b.push_back(std::uint8_t(v >> s));
    };
    be32(width);
    be32(height);
    b.insert(b.end(), {8, 6, 0, 0, 0}); // 8-bit, RGBA, deflate, no filter, no interlace
    be32(0);                            // CRC (stb_image does not check it)
    return b;
}

} // namespace

TEST_CASE("PNG, BMP and PPM round-trip exactly through write and decode", "[resources][image]") {
    const Image src = gradient(37, 21); // odd sizes: BMP rows need padding
    for (const char* ext : {".png", ".bmp", ".ppm"}) {
        const std::string path = tempPath(std::string("roundtrip") + ext);
        REQUIRE(writeImage(path, src).ok());
        auto back = loadImage(path);
        REQUIRE(back.ok());
        CHECK(back.value().width == src.width);
        CHECK(back.value().height == src.height);
        CHECK(back.value().rgba == src.rgba);
    }
}

TEST_CASE("a header claiming 100000 x 100000 pixels is refused before allocating", "[resources][image]") {
    const auto png = pngHeaderClaiming(100000, 100000); // stb_image's own limit refuses it
    auto r = decodeImage(png.data(), png.size(), "huge.png");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().find("huge.png: ") == 0);

    const auto tall = pngHeaderClaiming(10000, 17000); // within stb's limit, above ours
    auto t = decodeImage(tall.data(), tall.size(), "tall.png");
    REQUIRE_FALSE(t.ok());
    CHECK(t.error().find("tall.png: image is 10000x17000, above the limit") == 0);
}

TEST_CASE("image errors name the file and the reason", "[resources][image]") {
    auto missing = loadImage(tempPath("does-not-exist.png"));
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().find("does-not-exist.png: no such file") != std::string::npos);

    auto dir = loadImage(std::filesystem::temp_directory_path().u8string());
    REQUIRE_FALSE(dir.ok());
    CHECK(dir.error().find("is a directory") != std::string::npos);

    const std::string text = tempPath("not-an-image.png");
    REQUIRE(writeFileBytes(text, "hello, world\n", 13).ok());
    auto bad = loadImage(text);
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().find("not-an-image.png: not a decodable image") != std::string::npos);

    const std::string empty = tempPath("empty.png");
    REQUIRE(writeFileBytes(empty, "", 0).ok());
    auto none = loadImage(empty);
    REQUIRE_FALSE(none.ok());
    CHECK(none.error().find("empty file") != std::string::npos);

    CHECK_FALSE(writeImage(tempPath("x.tiff"), gradient(2, 2)).ok());
}

TEST_CASE("framebuffer to image keeps rows top first and channels in RGB order", "[resources][image]") {
    FrameBuffer fb(3, 2);
    fb.clear(packBgra(0, 0, 0));
    fb.setPixel(2, 0, packBgra(10, 20, 30)); // top-right
    const Image img = toImage(fb);
    CHECK(img.texel(2, 0)[0] == 10);
    CHECK(img.texel(2, 0)[1] == 20);
    CHECK(img.texel(2, 0)[2] == 30);
    CHECK(img.texel(2, 1)[0] == 0);
}

TEST_CASE("PFM stores rows bottom-to-top, little-endian, scale -1", "[resources][image]") {
    const float values[6] = {1, 2, 3, 4, 5, 6}; // 3x2, top row first: {1,2,3} over {4,5,6}
    const std::string path = tempPath("depth.pfm");
    REQUIRE(writePfm(path, 3, 2, values).ok());
    auto bytes = readFileBytes(path);
    REQUIRE(bytes.ok());
    const std::string header = "Pf\n3 2\n-1.0\n";
    REQUIRE(bytes.value().size() == header.size() + 6 * sizeof(float));
    CHECK(std::string(bytes.value().begin(), bytes.value().begin() + long(header.size())) == header);
    float first;
    std::memcpy(&first, bytes.value().data() + header.size(), sizeof(float));
    CHECK(first == 4.0f); // the bottom row comes first
}

TEST_CASE("path helpers", "[resources][fileio]") {
    CHECK(parentDirectory("a/b/c.obj") == "a/b");
    CHECK(parentDirectory("a\\b\\c.obj") == "a\\b");
    CHECK(parentDirectory("c.obj") == ".");
    CHECK(lowerExtension("x/Y.PNG") == ".png");
    CHECK(lowerExtension("x.d/noext") == "");
}

TEST_CASE("--skybox DIR: six faces px .. nz of one square size; every problem names its file", "[resources][image][sky]") {
    const std::string dir = sr::objtest::freshDir("skybox");
    const char* names[] = {"px", "nx", "py", "ny", "pz", "nz"};
    const auto face = [](int size, int height, std::uint8_t shade) {
        Image img;
        img.width = size;
        img.height = height;
        img.rgba.assign(std::size_t(size) * std::size_t(height) * 4, 255);
        for (std::size_t i = 0; i < img.rgba.size(); i += 4) img.rgba[i] = shade; // red = the face's shade
        return img;
    };
    // Five faces: the sixth is missing.
    for (int f = 0; f < 5; ++f) REQUIRE(writeImage(dir + "/" + names[f] + (f % 2 ? ".bmp" : ".png"), face(4, 4, std::uint8_t(40 * f))).ok());
    auto missing = loadSkybox(dir);
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().find("'nz' is missing") != std::string::npos);
    CHECK(missing.error().find(dir) != std::string::npos);
    // All six: loaded in OpenGL's face order (the face each axis sees has that file's shade).
    REQUIRE(writeImage(dir + "/nz.ppm", face(4, 4, 200)).ok());
    auto cube = loadSkybox(dir);
    INFO((cube.ok() ? std::string() : cube.error()));
    REQUIRE(cube.ok());
    CHECK(cube.value().size() == 4);
    const Vec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const int shades[] = {0, 40, 80, 120, 160, 200};
    for (int f = 0; f < 6; ++f) CHECK(int(toUnorm8(cube.value().sample(axes[f]).r)) == shades[f]);
    // A face of another size, a face that is not square, a face that does not decode.
    REQUIRE(writeImage(dir + "/py.png", face(8, 8, 80)).ok());
    auto sizes = loadSkybox(dir);
    REQUIRE_FALSE(sizes.ok());
    CHECK(sizes.error().find("py.png: skybox faces differ in size") != std::string::npos);
    REQUIRE(writeImage(dir + "/py.png", face(4, 2, 80)).ok());
    auto square = loadSkybox(dir);
    REQUIRE_FALSE(square.ok());
    CHECK(square.error().find("py.png: a skybox face must be square") != std::string::npos);
    REQUIRE(writeFileBytes(dir + "/py.png", "not a png", 9).ok());
    auto broken = loadSkybox(dir);
    REQUIRE_FALSE(broken.ok());
    CHECK(broken.error().find("py.png") != std::string::npos);
    // Not a folder.
    auto none = loadSkybox(dir + "/no-such-folder");
    REQUIRE_FALSE(none.ok());
    CHECK(none.error().find("not a folder") != std::string::npos);
}
