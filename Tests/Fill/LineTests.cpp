// DDA lines: A->B == B->A, the documented endpoint rule, clipping of huge lines, NaN, depth, colour.
#include "TestFramework.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "Raster/Fill/Line.hpp"
#include "RasterTestUtil.hpp"

using namespace sr;
using namespace sr::test;

namespace {

using PixelSet = std::set<std::pair<int, int>>; // (x, y)
constexpr Pixel kWhite = packBgra(255, 255, 255), kBlack = packBgra(0, 0, 0);

LineVertex lv(float x, float y, float z = 0.5f, Pixel c = kWhite) {
    LineVertex v;
    v.x = x;
    v.y = y;
    v.z = z;
    v.colour = c;
    return v;
}

PixelSet drawn(int w, int h, LineVertex a, LineVertex b, const LineOptions& o = {}) {
    FrameBuffer fb(w, h);
    fb.clear(kBlack);
    drawLine(fb, a, b, o);
    PixelSet s;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (fb.pixel(x, y) != kBlack) s.insert({x, y});
    return s;
}

// The rule of Line.hpp evaluated the slow, obvious way: for every column between the endpoint
// columns, the row containing the exact line point at the clamped column centre (integers only).
PixelSet ruleSet(int w, int h, float ax, float ay, float bx, float by) {
    auto snap = [](float v) { return std::int64_t(std::floor(double(v) * 256.0 + 0.5)); };
    auto fdiv = [](std::int64_t a, std::int64_t b) { // floor for b > 0
        return a >= 0 ? a / b : -((-a + b - 1) / b);
    };
    std::int64_t X0 = snap(ax), Y0 = snap(ay), X1 = snap(bx), Y1 = snap(by);
    const bool yMajor = std::llabs(Y1 - Y0) > std::llabs(X1 - X0);
    if (yMajor) { std::swap(X0, Y0); std::swap(X1, Y1); }
    if (X1 < X0) { std::swap(X0, X1); std::swap(Y0, Y1); }
    PixelSet s;
    for (std::int64_t c = fdiv(X0, 256); c <= fdiv(X1, 256); ++c) {
        const std::int64_t m = std::clamp<std::int64_t>(c * 256 + 128, X0, X1);
        const std::int64_t row = X1 == X0 ? fdiv(Y0, 256) : fdiv(Y0 * (X1 - X0) + (m - X0) * (Y1 - Y0), 256 * (X1 - X0));
        const std::int64_t x = yMajor ? row : c, y = yMajor ? c : row;
        if (x >= 0 && x < w && y >= 0 && y < h) s.insert({int(x), int(y)});
    }
    return s;
}

bool eightConnected(const PixelSet& s) {
    if (s.empty()) return true;
    std::set<std::pair<int, int>> seen{*s.begin()};
    std::vector<std::pair<int, int>> stack{*s.begin()};
    while (!stack.empty()) {
        const auto p = stack.back();
        stack.pop_back();
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const std::pair<int, int> q{p.first + dx, p.second + dy};
                if (s.count(q) && seen.insert(q).second) stack.push_back(q);
            }
    }
    return seen.size() == s.size();
}

} // namespace

TEST_CASE("A->B and B->A draw the same pixels, and exactly the documented rule", "[raster][line]") {
    std::mt19937 rng(123);
    int mismatches = 0, ruleMismatches = 0, disconnected = 0;
    for (int i = 0; i < 20000; ++i) {
        float c[4];
        const int kind = i % 4;
        for (float& v : c) {
            if (kind == 0) v = uniform(rng, -10, 42);                                  // free floats
            else if (kind == 1) v = float(uniformInt(rng, -2, 33)) + 0.5f;              // pixel centres
            else if (kind == 2) v = float(uniformInt(rng, -600, 8800)) / 256.0f;        // sub-pixel grid
            else v = float(uniformInt(rng, -10, 42)) + float(uniformInt(rng, 0, 4)) * 0.25f; // quarters
        }
        if (i % 50 == 0) { c[2] = c[0]; }                 // vertical
        if (i % 50 == 1) { c[3] = c[1]; }                 // horizontal
        if (i % 50 == 2) { c[2] = c[0]; c[3] = c[1]; }    // single point
        if (i % 50 == 3) { c[3] = c[1] + (c[2] - c[0]); } // 45 degrees
        const PixelSet ab = drawn(32, 32, lv(c[0], c[1]), lv(c[2], c[3]));
        const PixelSet ba = drawn(32, 32, lv(c[2], c[3]), lv(c[0], c[1]));
        mismatches += ab != ba ? 1 : 0;
        ruleMismatches += ab != ruleSet(32, 32, c[0], c[1], c[2], c[3]) ? 1 : 0;
        disconnected += eightConnected(ab) ? 0 : 1; // clipping a line keeps one connected piece
    }
    CHECK(mismatches == 0);
    CHECK(ruleMismatches == 0);
    CHECK(disconnected == 0);
}

TEST_CASE("line endpoints, slopes and single points (hand-checked)", "[raster][line]") {
    // Horizontal: one pixel per column from the column of each endpoint.
    CHECK(drawn(8, 8, lv(0.2f, 3.7f), lv(5.9f, 3.7f)) == PixelSet{{0, 3}, {1, 3}, {2, 3}, {3, 3}, {4, 3}, {5, 3}});
    // Vertical, endpoint exactly on a pixel boundary: the pixel containing y = 6.0 is row 6.
    CHECK(drawn(8, 8, lv(2.5f, 1.5f), lv(2.5f, 6.0f)) == PixelSet{{2, 1}, {2, 2}, {2, 3}, {2, 4}, {2, 5}, {2, 6}});
    // 45 degrees through centres.
    CHECK(drawn(8, 8, lv(0.5f, 0.5f), lv(4.5f, 4.5f)) == PixelSet{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}});
    // Steep (y-major): x = 2.5 + (y - 0.5) / 8 at row centres, floor; x = 3.0 at row 4 is column 3.
    CHECK(drawn(8, 10, lv(2.5f, 0.5f), lv(3.5f, 8.5f)) ==
          PixelSet{{2, 0}, {2, 1}, {2, 2}, {2, 3}, {3, 4}, {3, 5}, {3, 6}, {3, 7}, {3, 8}});
    // End column whose centre the segment does not reach: evaluated at the endpoint itself.
    CHECK(drawn(8, 8, lv(0.9f, 0.9f), lv(3.2f, 2.1f)) == PixelSet{{0, 0}, {1, 1}, {2, 1}, {3, 2}});
    // A single point draws the pixel containing it; a point off screen draws nothing.
    CHECK(drawn(8, 8, lv(3.3f, 4.7f), lv(3.3f, 4.7f)) == PixelSet{{3, 4}});
    CHECK(drawn(8, 8, lv(-3.3f, 4.7f), lv(-3.3f, 4.7f)).empty());
    // Sub-pixel short line inside one pixel: that pixel.
    CHECK(drawn(8, 8, lv(5.1f, 5.1f), lv(5.8f, 5.3f)) == PixelSet{{5, 5}});
}

TEST_CASE("huge coordinates finish fast and draw exactly the clipped segment", "[raster][line]") {
    const auto start = std::chrono::steady_clock::now();
    PixelSet row, diag, steep, half;
    for (int i = 0; i < 64; ++i) {
        row.insert({i, 10});
        diag.insert({i, i});
        steep.insert({5, i});
        if (i / 2 < 64) half.insert({i, i / 2});
    }
    for (int rep = 0; rep < 100; ++rep) {
        CHECK(drawn(64, 64, lv(-1e9f, 10.5f), lv(1e9f, 10.5f)) == row);
        CHECK(drawn(64, 64, lv(1e9f, 1e9f), lv(-1e9f, -1e9f)) == diag);
        CHECK(drawn(64, 64, lv(5.25f, -1e9f), lv(5.25f, 1e9f)) == steep);
        // y = x / 2 from -2^30 to 2^30: the clip points (-1, -0.5) and (65, 32.5) are exact.
        CHECK(drawn(64, 64, lv(-1073741824.0f, -536870912.0f), lv(1073741824.0f, 536870912.0f)) == half);
        CHECK(drawn(64, 64, lv(1e9f, -1e9f), lv(1e9f, 1e9f)).empty()); // entirely right of the screen
        CHECK(drawn(64, 64, lv(-3e38f, 5.5f), lv(3e38f, 5.5f)).size() == 64);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    CHECK(seconds < 5.0); // 600 huge lines: milliseconds natively (a billion steps would be minutes)
}

TEST_CASE("NaN or infinite endpoints draw nothing; an empty framebuffer is fine", "[raster][line]") {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    CHECK(drawn(16, 16, lv(nan, 3), lv(10, 3)).empty());
    CHECK(drawn(16, 16, lv(3, 3), lv(10, nan)).empty());
    CHECK(drawn(16, 16, lv(nan, nan), lv(nan, nan)).empty());
    CHECK(drawn(16, 16, lv(-inf, 3), lv(10, 3)).empty());
    FrameBuffer empty(0, 0);
    drawLine(empty, lv(0, 0), lv(10, 10)); // no write, no crash
    CHECK(empty.empty());
}

TEST_CASE("random lines never write out of bounds (ASan) and stay in the rule", "[raster][line]") {
    std::mt19937 rng(9);
    const int sizes[][2] = {{1, 1}, {7, 3}, {3, 7}, {64, 64}};
    int count = 0;
    for (int i = 0; i < 5000; ++i) {
        const auto& s = sizes[i % 4];
        const float r = i % 3 == 0 ? 1e6f : 40.0f;
        const float ax = uniform(rng, -r, r), ay = uniform(rng, -r, r), bx = uniform(rng, -r, r), by = uniform(rng, -r, r);
        const PixelSet p = drawn(s[0], s[1], lv(ax, ay), lv(bx, by));
        count += int(p.size());
        if (r < 100.0f) CHECK(p == ruleSet(s[0], s[1], ax, ay, bx, by));
    }
    CHECK(count > 0);
}

TEST_CASE("line depth test is GREATER-OR-EQUAL with optional write", "[raster][line]") {
    FrameBuffer fb(16, 4);
    fb.clear(kBlack, 0.5f);
    LineOptions test;
    test.depthTest = true;
    drawLine(fb, lv(0.5f, 1.5f, 0.4f), lv(15.5f, 1.5f, 0.4f), test); // behind: nothing
    CHECK(fb.pixel(7, 1) == kBlack);
    drawLine(fb, lv(0.5f, 1.5f, 0.5f), lv(15.5f, 1.5f, 0.5f), test); // equal: drawn (overlay)
    CHECK(fb.pixel(7, 1) == kWhite);
    CHECK(fb.depth(7, 1) == 0.5f);
    test.depthWrite = true;
    drawLine(fb, lv(0.5f, 2.5f, 0.0f), lv(15.5f, 2.5f, 1.0f), test); // crosses 0.5 halfway
    CHECK(fb.pixel(2, 2) == kBlack);
    CHECK(fb.pixel(13, 2) == kWhite);
    CHECK(fb.depth(13, 2) > 0.5f);
}

TEST_CASE("colour interpolation runs end to end and is the same in both directions", "[raster][line]") {
    LineOptions o;
    o.interpolateColour = true;
    const Pixel red = packBgra(255, 0, 0), blue = packBgra(0, 0, 255);
    FrameBuffer ab(32, 32), ba(32, 32);
    ab.clear(kBlack);
    ba.clear(kBlack);
    drawLine(ab, lv(0.5f, 3.5f, 0, red), lv(30.5f, 20.5f, 0, blue), o);
    drawLine(ba, lv(30.5f, 20.5f, 0, blue), lv(0.5f, 3.5f, 0, red), o);
    CHECK(std::equal(ab.colorData(), ab.colorData() + 32 * 32, ba.colorData()));
    CHECK(ab.pixel(0, 3) == red);
    CHECK(ab.pixel(30, 20) == blue);
    int lastRed = 256;
    for (int x = 0; x <= 30; ++x) { // red falls monotonically along the line
        for (int y = 0; y < 32; ++y)
            if (ab.pixel(x, y) != kBlack) {
                CHECK(int(pixelR(ab.pixel(x, y))) <= lastRed);
                lastRed = pixelR(ab.pixel(x, y));
            }
    }
    // Without interpolation the first endpoint's colour is used for every pixel.
    FrameBuffer flat(32, 32);
    flat.clear(kBlack);
    drawLine(flat, lv(0.5f, 3.5f, 0, red), lv(30.5f, 20.5f, 0, blue));
    CHECK(flat.pixel(30, 20) == red);
}
