// Non-ASCII (UTF-8) paths through our file APIs: images and OBJ/MTL/textures in a folder named with accents and CJK, natively and under Wine.
#include "TestFramework.hpp"

#include <filesystem>
#include <string>

#include "ObjTestUtil.hpp"
#include "Resources/FileIO.hpp"
#include "Resources/Image.hpp"
#include "Resources/ObjLoader.hpp"

using namespace sr;
using namespace sr::objtest;

namespace {
// "tëst-模型" in UTF-8 (escapes: the source stays ASCII for every compiler's default charset).
const std::string kName = "t\xC3\xABst-\xE6\xA8\xA1\xE5\x9E\x8B";

// True if `dir` holds an entry whose UTF-8 name is exactly `name` (not "t?st-??" from an ANSI API).
bool listed(const std::string& dir, const std::string& name) {
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::u8path(dir)))
        if (e.path().filename().u8string() == name) return true;
    return false;
}
} // namespace

TEST_CASE("images write and read back under a non-ASCII path", "[resources][unicode]") {
    const std::string dir = freshDir(kName);
    for (const char* ext : {".png", ".bmp", ".ppm"}) {
        const std::string path = dir + "/" + kName + ext;
        REQUIRE(writeImage(path, rampImage(3, 2)).ok());
        CHECK(listed(dir, kName + ext));
        auto img = loadImage(path);
        REQUIRE(img.ok());
        CHECK(img.value().width == 3);
        CHECK(img.value().rgba == rampImage(3, 2).rgba);
    }
    const float depth[2] = {0.25f, 0.75f};
    REQUIRE(writePfm(dir + "/" + kName + ".pfm", 2, 1, depth).ok());
    auto bytes = readFileBytes(dir + "/" + kName + ".pfm");
    REQUIRE(bytes.ok());
    CHECK(bytes.value().size() == std::string("Pf\n2 1\n-1.0\n").size() + 8);
}

TEST_CASE("an OBJ, its MTL and texture load from non-ASCII paths; errors name them intact", "[resources][unicode]") {
    const std::string dir = freshDir(kName + "-obj");
    REQUIRE(writeImage(dir + "/" + kName + ".png", rampImage(2, 2)).ok());
    writeText(dir, kName + ".mtl", "newmtl A\nmap_Kd " + kName + ".png\n");
    const std::string obj = writeText(dir, kName + ".obj",
                                      "mtllib " + kName + ".mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl A\nf 1/1 2/1 3/1\n");
    CHECK(listed(dir, kName + ".obj"));
    auto r = loadObj(obj);
    REQUIRE(r.ok());
    CHECK(r.value().warnings.empty());
    REQUIRE(r.value().textures.size() == 1);
    CHECK(r.value().textures[0].width == 2);
    CHECK(r.value().texturePaths[0] == dir + "/" + kName + ".png");

    auto missing = loadObj(dir + "/" + kName + "-missing.obj");
    REQUIRE_FALSE(missing.ok());
    CHECK(contains(missing.error(), kName + "-missing.obj: no such file"));
}
