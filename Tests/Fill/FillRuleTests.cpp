// Fill-rule ties: edges and vertices exactly on pixel centres follow the top-left rule (hand-checked).
#include "TestFramework.hpp"

#include <set>
#include <utility>
#include <vector>

#include "RasterTestUtil.hpp"
#include "ReferenceRasterizer.hpp"

using namespace sr;
using namespace sr::test;

namespace {

constexpr int kW = 8, kH = 8;
using PixelSet = std::set<std::pair<int, int>>; // (x, y)

PixelSet filled(ScreenVertex a, ScreenVertex b, ScreenVertex c) {
    PixelSet s;
    for (int p : scanCoverage(a, b, c, kW, kH)) s.insert({p % kW, p / kW});
    return s;
}

// Checks the expected set for both windings and all three rotations, and against the reference.
void checkTriangle(ScreenVertex a, ScreenVertex b, ScreenVertex c, const PixelSet& expected) {
    CHECK(filled(a, b, c) == expected);
    CHECK(filled(b, c, a) == expected);
    CHECK(filled(c, a, b) == expected);
    CHECK(filled(a, c, b) == expected);
    CHECK(filled(c, b, a) == expected);
    CHECK(filled(b, a, c) == expected);
    PixelSet r;
    for (int p : ref::coverage(a, b, c, kW, kH)) r.insert({p % kW, p / kW});
    CHECK(r == expected);
}

} // namespace

TEST_CASE("square with corners on pixel centres: left and top edges in, right and bottom out", "[raster][fillrule]") {
    // Corners (0.5, 0.5) and (2.5, 2.5): centres x, y in {0.5, 1.5, 2.5}; the 2.5 ones lie on the
    // right/bottom sides and are excluded; the top-left corner (0.5, 0.5) is on a left and a top
    // edge and is included.
    const PixelSet expected{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    PixelSet got = filled(vtx(0.5f, 0.5f), vtx(2.5f, 0.5f), vtx(2.5f, 2.5f));
    const PixelSet second = filled(vtx(0.5f, 0.5f), vtx(2.5f, 2.5f), vtx(0.5f, 2.5f));
    for (const auto& p : second) CHECK(got.insert(p).second); // no pixel in both halves
    CHECK(got == expected);
    // The other diagonal gives the same square.
    PixelSet other = filled(vtx(2.5f, 0.5f), vtx(2.5f, 2.5f), vtx(0.5f, 2.5f));
    const PixelSet otherSecond = filled(vtx(0.5f, 0.5f), vtx(2.5f, 0.5f), vtx(0.5f, 2.5f));
    for (const auto& p : otherSecond) CHECK(other.insert(p).second);
    CHECK(other == expected);
}

TEST_CASE("right triangle with top and left edges through centres", "[raster][fillrule]") {
    // (0.5,0.5) (4.5,0.5) (0.5,4.5): top edge y = 0.5 and left edge x = 0.5 are in; centres on the
    // hypotenuse x + y = 5 (a right edge) are out, so pixel (i, j) is in iff i + j < 4.
    PixelSet expected;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i + j < 4; ++i) expected.insert({i, j});
    REQUIRE(expected.size() == 10);
    checkTriangle(vtx(0.5f, 0.5f), vtx(4.5f, 0.5f), vtx(0.5f, 4.5f), expected);
}

TEST_CASE("right triangle with right and bottom edges through centres", "[raster][fillrule]") {
    // (4.5,0.5) (4.5,4.5) (0.5,4.5): the complement in the 4x4 block: the hypotenuse is now a
    // LEFT edge (interior at larger x) so its centres are in; x = 4.5 and y = 4.5 are out.
    PixelSet expected;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            if (i + j >= 4) expected.insert({i, j});
    REQUIRE(expected.size() == 6);
    checkTriangle(vtx(4.5f, 0.5f), vtx(4.5f, 4.5f), vtx(0.5f, 4.5f), expected);
}

TEST_CASE("apex on a centre and a horizontal bottom edge through centres", "[raster][fillrule]") {
    // (2.5,0.5) (4.5,2.5) (0.5,2.5): the apex lies on a left and a right edge (out); the bottom
    // edge y = 2.5 is not a top edge (out). Row y = 1.5 spans x in [1.5, 3.5): pixels 1 and 2.
    checkTriangle(vtx(2.5f, 0.5f), vtx(4.5f, 2.5f), vtx(0.5f, 2.5f), PixelSet{{1, 1}, {2, 1}});
}

TEST_CASE("horizontal top edge through centres and a bottom apex on a centre", "[raster][fillrule]") {
    // (0.5,0.5) (4.5,0.5) (2.5,2.5): the top edge is in from x = 0.5 up to (not incl.) 4.5; row
    // 1.5 spans [1.5, 3.5); the bottom apex is out.
    checkTriangle(vtx(0.5f, 0.5f), vtx(4.5f, 0.5f), vtx(2.5f, 2.5f),
                  PixelSet{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {1, 1}, {2, 1}});
}

TEST_CASE("a vertex exactly on a centre belongs to exactly one of the triangles sharing it", "[raster][fillrule]") {
    // Four triangles around (3.5, 3.5): only the one to the lower right (whose left and top
    // edges meet there) owns that centre.
    const ScreenVertex c = vtx(3.5f, 3.5f);
    const ScreenVertex n = vtx(3.5f, 0.5f), e = vtx(6.5f, 3.5f), s = vtx(3.5f, 6.5f), w = vtx(0.5f, 3.5f);
    const PixelSet quads[4] = {filled(c, n, e), filled(c, e, s), filled(c, s, w), filled(c, w, n)};
    int owners = 0;
    for (const auto& q : quads) owners += q.count({3, 3}) ? 1 : 0;
    CHECK(owners == 1);
    CHECK(quads[1].count({3, 3}) == 1); // c-e-s: the lower-right quadrant
}

TEST_CASE("a tiny triangle around one centre covers exactly that pixel", "[raster][fillrule]") {
    checkTriangle(vtx(2.4f, 5.4f), vtx(2.7f, 5.45f), vtx(2.5f, 5.7f), PixelSet{{2, 5}});
    // Same shape between centres: nothing.
    checkTriangle(vtx(2.6f, 5.6f), vtx(2.9f, 5.65f), vtx(2.7f, 5.9f), PixelSet{});
}
