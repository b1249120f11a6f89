// Tests of malformed or hostile OBJ input: every case is a one-line error naming the file (and line), never a crash or hang.
#include "TestFramework.hpp"

#include <chrono>
#include <filesystem>
#include <vector>

#include "ObjTestUtil.hpp"
#include "Resources/FileIO.hpp"
#include "Resources/ObjLoader.hpp"

using namespace sr;
using namespace sr::objtest;

namespace {

const char* kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// Loads `text` written as `name` and returns the error (failing the test if it loaded).
std::string errorOf(const std::string& dir, const std::string& name, const std::string& text, const LoadOptions& o = {}) {
    const std::string path = writeText(dir, name, text);
    auto r = loadObj(path, o);
    REQUIRE_FALSE(r.ok());
    const std::string& e = r.error();
    CHECK(contains(e, path));
    CHECK(e.find('\n') == std::string::npos);
    return e;
}

} // namespace

TEST_CASE("OBJ file-level errors: missing, directory, empty, binary, image, UTF-16", "[resources][obj]") {
    const std::string dir = freshDir("errors-file");
    auto missing = loadObj(dir + "/nothere.obj");
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error() == dir + "/nothere.obj: no such file");
    auto directory = loadObj(dir);
    REQUIRE_FALSE(directory.ok());
    CHECK(contains(directory.error(), "is a directory"));

    CHECK(contains(errorOf(dir, "empty.obj", ""), "empty file (no triangles)"));
    CHECK(contains(errorOf(dir, "blank.obj", "\n  \n# nothing\n"), "no vertices"));
    CHECK(contains(errorOf(dir, "readme.obj", "This is a README.\nNot a model.\n"), "no vertices"));
    CHECK(contains(errorOf(dir, "points.obj", kTri), "no triangles"));
    CHECK(contains(errorOf(dir, "lines.obj", std::string(kTri) + "f 1 2\n"), "no triangles"));

    std::vector<unsigned char> png;
    REQUIRE(writeImage(dir + "/real.png", rampImage(2, 2)).ok());
    auto pngBytes = readFileBytes(dir + "/real.png");
    REQUIRE(pngBytes.ok());
    const std::string pngText(pngBytes.value().begin(), pngBytes.value().end());
    CHECK(contains(errorOf(dir, "image.obj", pngText), "PNG image, not a text file"));

    std::string garbage;
    for (int i = 0; i < 4096; ++i) garbage += char((i * 7919 + 13) % 256);
    CHECK(contains(errorOf(dir, "garbage.obj", garbage), "not a text file (binary byte"));
    CHECK(contains(errorOf(dir, "ctrl.obj", std::string(kTri) + "f 1 2 \x01" "3\n"), ".obj:4: not a text file"));

    // "v 0 0 0\n" as UTF-16LE with a BOM, and without one.
    std::string utf16;
    for (char c : std::string(kTri) + "f 1 2 3\n") utf16 += std::string(1, c) + '\0';
    CHECK(contains(errorOf(dir, "utf16bom.obj", "\xFF\xFE" + utf16), "UTF-16 text is not supported, save as UTF-8"));
    CHECK(contains(errorOf(dir, "utf16.obj", utf16), "UTF-16 text is not supported, save as UTF-8"));
    std::string utf16be;
    for (char c : std::string(kTri)) utf16be += std::string(1, '\0') + c;
    CHECK(contains(errorOf(dir, "utf16be.obj", "\xFE\xFF" + utf16be), "UTF-16 text is not supported"));
}

TEST_CASE("OBJ index errors name the file, line and the bad index", "[resources][obj]") {
    const std::string dir = freshDir("errors-index");
    const std::string t = kTri;
    CHECK(contains(errorOf(dir, "big.obj", t + "f 1 2 4\n"), "big.obj:4: face vertex '4': vertex index 4 is out of range (only 3 defined"));
    CHECK(contains(errorOf(dir, "zero.obj", t + "f 0 1 2\n"), "zero.obj:4: face vertex '0': vertex index 0 is invalid"));
    CHECK(contains(errorOf(dir, "neg.obj", t + "f -1 -2 -4\n"), "neg.obj:4: face vertex '-4': relative vertex index -4 points before the first one"));
    CHECK(contains(errorOf(dir, "huge.obj", t + "f 1 2 99999999999999999999\n"), "huge.obj:4:"));
    CHECK(contains(errorOf(dir, "word.obj", t + "f 1 2 three\n"), "word.obj:4: face vertex 'three': vertex index 0 is invalid"));
    CHECK(contains(errorOf(dir, "fwd.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n"), "fwd.obj:2:"));
    CHECK(contains(errorOf(dir, "vn.obj", t + "vn 0 0 1\nf 1//1 2//2 3//1\n"), "vn.obj:5: face vertex '2//2': normal index 2 is out of range (only 1 defined"));
    CHECK(contains(errorOf(dir, "vt.obj", t + "vt 0 0\nf 1/1 2/1 3/-2\n"), "vt.obj:5: face vertex '3/-2': relative texture coordinate index -2"));
    CHECK(contains(errorOf(dir, "vtn.obj", t + "vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/7\n"), "vtn.obj:6: face vertex '3/1/7': normal index 7"));
    CHECK(contains(errorOf(dir, "quad.obj", t + "f 1 2 3 5\n"), "quad.obj:4:"));
    // Lines and points are parsed (not drawn): a zero index there is tinyobjloader's own error.
    CHECK(contains(errorOf(dir, "line.obj", t + "f 1 2 3\nl 0 1\n"), "line 5"));
}

TEST_CASE("OBJ non-finite or overflowing coordinates name the vertex and line", "[resources][obj]") {
    const std::string dir = freshDir("errors-number");
    const std::string t = kTri;
    CHECK(contains(errorOf(dir, "nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), "nan.obj:2: vertex 2: coordinate 'nan' is not a number"));
    CHECK(contains(errorOf(dir, "inf.obj", "v 0 0 0\n# x\nv 1 0 -inf\n"), "inf.obj:3: vertex 2: coordinate '-inf'"));
    CHECK(contains(errorOf(dir, "msvc.obj", "v 1.#INF 0 0\n"), "msvc.obj:1: vertex 1"));
    CHECK(contains(errorOf(dir, "comma.obj", "v 0,5 0 0\n"), "comma.obj:1: vertex 1"));
    CHECK(contains(errorOf(dir, "big.obj", t + "v 1e39 0 0\nf 1 2 3\n"), "big.obj:4: vertex 4: coordinate is not finite as a float"));
    CHECK(contains(errorOf(dir, "bigvn.obj", t + "vn 0 -4e38 0\nf 1 2 3\n"), "bigvn.obj:4: normal 1: coordinate is not finite"));
    CHECK(contains(errorOf(dir, "nanvt.obj", t + "vt 0.5 NaN\nf 1 2 3\n"), "nanvt.obj:4: texture coordinate 1"));
    CHECK(contains(errorOf(dir, "e.obj", "v 1e 0 0\n"), "e.obj:1: vertex 1: coordinate '1e' is not a number"));
    // A third vt value and vertex colours are not geometry: not checked (tinyobjloader ignores them).
    const std::string ok = writeText(dir, "ok.obj", "v 0 0 0 1 0.5 0\nv 1 0 0\nv 0 1 0\nvt 0 0 w\nf 1/1 2/1 3/1\n");
    CHECK(loadObj(ok).ok());
    // Forms tinyobjloader parses (trailing junk after a number included) load as it reads them.
    auto forms = loadObj(writeText(dir, "forms.obj", "v +1. -.5 2.e1\nv 3.1+e2 1E2 -0\nv 0 1 0\nf 1 2 3\n"));
    REQUIRE(forms.ok());
    CHECK(forms.value().boundsMax.x == Approx(3.1f));
    CHECK(forms.value().boundsMax.y == 100.0f);
    CHECK(forms.value().boundsMax.z == 20.0f);
}

TEST_CASE("OBJ limits: counts, polygon size and memory estimate are clear errors", "[resources][obj]") {
    const std::string dir = freshDir("errors-limits");
    LoadOptions o;
    o.limits.maxVertices = 3;
    CHECK(contains(errorOf(dir, "v.obj", std::string(kTri) + "v 1 1 1\nf 1 2 3\n", o), "v.obj:4: more than 3 vertex entries"));
    o = {};
    o.limits.maxTriangles = 2;
    CHECK(contains(errorOf(dir, "t.obj", std::string(kTri) + "f 1 2 3\nf 1 2 3\nf 1 3 2\n", o), "t.obj:6: more than 2 triangles"));
    o = {};
    o.limits.maxMemoryBytes = 1000;
    CHECK(contains(errorOf(dir, "m.obj", std::string(kTri) + "f 1 2 3\nf 1 2 3\nf 1 3 2\n", o), "above the limit of 0 MiB"));
    o = {};
    o.limits.maxFileBytes = 10;
    CHECK(contains(errorOf(dir, "size.obj", std::string(kTri) + "f 1 2 3\n", o), "above the limit of 10 bytes"));

    std::string polygon = std::string(kTri) + "f";
    for (int i = 0; i < 2000; ++i) polygon += (i % 3 == 0) ? " 1" : (i % 3 == 1) ? " 2" : " 3";
    CHECK(contains(errorOf(dir, "poly.obj", polygon + "\n"), "poly.obj:4: face has more than 1024 vertices"));
}

TEST_CASE("OBJ with 10 MB single lines loads or fails fast", "[resources][obj]") {
    const std::string dir = freshDir("errors-longline");
    const auto start = std::chrono::steady_clock::now();
    // A 10 MB comment, a 10 MB vertex line and a 10 MB group name: harmless, the model loads.
    const std::string longText(10 << 20, 'x');
    std::string longVertex = "v 1 2 3";
    while (longVertex.size() < (10u << 20)) longVertex += " 0.25";
    auto r = loadObj(writeText(dir, "long.obj", "#" + longText + "\n" + kTri + longVertex + "\ng " + longText + "\nf 1 2 3\n"));
    REQUIRE(r.ok());
    CHECK(r.value().mesh.triangleCount() == 1);
    CHECK(r.value().boundsMax.z == 3.0f);
    // A 10 MB face line: refused by the polygon limit before tinyobjloader triangulates it.
    std::string longFace = std::string(kTri) + "f";
    while (longFace.size() < (10u << 20)) longFace += " 1 2 3";
    CHECK(contains(errorOf(dir, "longface.obj", longFace + "\n"), "face has more than"));
    // A 10 MB number: one huge mantissa becomes inf and is reported.
    CHECK(contains(errorOf(dir, "longnum.obj", std::string(kTri) + "v " + std::string(10 << 20, '9') + " 0 0\nf 1 2 3\n"),
                   "longnum.obj:4: vertex 4: coordinate is not finite"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    CHECK(seconds < 30.0);
}

TEST_CASE("OBJ with a bad MTL still loads: binary or UTF-16 material files are warnings", "[resources][obj]") {
    const std::string dir = freshDir("errors-mtl");
    writeText(dir, "bin.mtl", std::string("newmtl A\0\x01\x02", 11));
    writeText(dir, "u16.mtl", "\xFF\xFEn\0e\0w\0");
    auto r = loadObj(writeText(dir, "m.obj", std::string("mtllib bin.mtl\nmtllib u16.mtl\n") + kTri + "vt 0 0\nusemtl A\nf 1/1 2/1 3/1\n"));
    REQUIRE(r.ok());
    const auto& w = r.value().warnings;
    REQUIRE(w.size() >= 2);
    CHECK(contains(w[0], "bin.mtl:1: not a text file"));
    CHECK(contains(w[1], "u16.mtl: UTF-16 text is not supported"));
    CHECK(r.value().textures.empty());

    // Thousands of mtllib lines: at most 64 files are tried, warnings stay bounded.
    std::string flood;
    for (int i = 0; i < 5000; ++i) flood += "mtllib missing" + std::to_string(i) + ".mtl\n";
    auto f = loadObj(writeText(dir, "flood.obj", flood + kTri + "f 1 2 3\n"));
    REQUIRE(f.ok());
    CHECK(f.value().warnings.size() < 100);
}

TEST_CASE("OBJ, MTL and texture paths with non-ASCII UTF-8 names load", "[resources][obj]") {
    const std::string dir = freshDir("utf8-\xC3\xA9t\xC3\xA9");
    REQUIRE(writeImage(dir + "/t\xC3\xA9x.png", rampImage(2, 2)).ok());
    writeText(dir, "m\xC3\xA8.mtl", "newmtl A\nmap_Kd t\xC3\xA9x.png\n");
    auto r = loadObj(writeText(dir, "mod\xC3\xA8le.obj",
                               "mtllib m\xC3\xA8.mtl\n" + std::string(kTri) + "vt 0 0\nusemtl A\nf 1/1 2/1 3/1\n"));
    REQUIRE(r.ok());
    CHECK(r.value().warnings.empty());
    REQUIRE(r.value().textures.size() == 1);
    CHECK(r.value().textures[0].width == 2);
}
