// Tests of the OBJ loader's draw ranges: one per texture whatever the material order, in a documented, deterministic order.
#include "TestFramework.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "ObjTestUtil.hpp"
#include "Resources/ObjLoader.hpp"

using namespace sr;
using namespace sr::objtest;

namespace {

// An n x n grid of unit quads in z = 0 (as scripts/make-grid.py writes it): vertex (col, row) with
// vt (col, row); quad (col, row) in row-major file order uses material "a" when `alternate` is
// false or col + row is even, else "b" (a usemtl before every quad: n*n - 1 material switches).
std::string gridObj(int n, bool alternate) {
    std::string s = "mtllib grid.mtl\n";
    const int side = n + 1;
    for (int row = 0; row < side; ++row)
        for (int col = 0; col < side; ++col) s += "v " + std::to_string(col) + " " + std::to_string(row) + " 0\n";
    for (int row = 0; row < side; ++row)
        for (int col = 0; col < side; ++col) s += "vt " + std::to_string(col) + " " + std::to_string(row) + "\n";
    char current = 0;
    for (int row = 0; row < n; ++row)
        for (int col = 0; col < n; ++col) {
            const char mat = !alternate || (col + row) % 2 == 0 ? 'a' : 'b';
            if (mat != current) s += std::string("usemtl ") + mat + "\n";
            current = mat;
            const int v0 = row * side + col + 1, v1 = v0 + 1, v2 = v0 + 1 + side, v3 = v0 + side;
            s += "f";
            for (int v : {v0, v1, v2, v3}) s += " " + std::to_string(v) + "/" + std::to_string(v);
            s += "\n";
        }
    return s;
}

std::string writeGrid(const std::string& dir, int n, bool alternate) {
    REQUIRE(writeImage(dir + "/a.png", rampImage(2, 2)).ok());
    REQUIRE(writeImage(dir + "/b.png", rampImage(3, 1)).ok());
    writeText(dir, "grid.mtl", "newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\n");
    return writeText(dir, alternate ? "alternate.obj" : "one.obj", gridObj(n, alternate));
}

// The quad (row-major number) a grid triangle lies in, from its centroid.
int quadOf(const Mesh& m, std::size_t triangle, int n) {
    Vec3 c{0, 0, 0};
    for (std::size_t k = 0; k < 3; ++k) c = c + m.positions[m.indices[3 * triangle + k]];
    return int(std::floor(c.y / 3.0f)) * n + int(std::floor(c.x / 3.0f));
}

} // namespace

TEST_CASE("OBJ alternating-material grid: one draw range per material, not one per switch", "[resources][obj][ranges]") {
    // 16 x 16 quads, a material switch before every quad (255 switches): the ranges must not
    // follow the switches (a range per switch would make 256 ranges of 2 triangles here).
    const int n = 16;
    const std::string dir = freshDir("grid-ranges");
    auto alt = loadObj(writeGrid(dir, n, true));
    REQUIRE(alt.ok());
    const Model& m = alt.value();
    REQUIRE(m.materials.size() == 2);
    REQUIRE(m.ranges.size() == m.materials.size());
    REQUIRE(m.mesh.triangleCount() == std::size_t(2 * n * n));
    // Order of first appearance: 'a' (quad 0) then 'b' (quad 1); together they cover the indices.
    CHECK(m.ranges[0].material == 0);
    CHECK(m.ranges[0].texture == m.materials[0].texture);
    CHECK(m.ranges[1].material == 1);
    CHECK(m.ranges[1].texture == m.materials[1].texture);
    CHECK(m.ranges[0].texture != m.ranges[1].texture);
    CHECK(m.ranges[0].firstIndex == 0);
    CHECK(m.ranges[0].indexCount == std::uint32_t(3 * n * n));
    CHECK(m.ranges[1].firstIndex == m.ranges[0].indexCount);
    CHECK(m.ranges[1].indexCount == std::uint32_t(3 * n * n));
    // Inside a range the faces keep their file order: the even quads, then the odd ones, each
    // in row-major order, two triangles per quad.
    for (std::size_t r = 0; r < 2; ++r) {
        std::vector<int> quads;
        const std::size_t first = m.ranges[r].firstIndex / 3, count = m.ranges[r].indexCount / 3;
        for (std::size_t t = first; t < first + count; ++t) quads.push_back(quadOf(m.mesh, t, n));
        std::vector<int> expected;
        for (int q = 0; q < n * n; ++q)
            if (std::size_t((q / n + q % n) % 2) == r) expected.insert(expected.end(), {q, q});
        CHECK(quads == expected);
    }
    // Vertices are shared across the ranges (numbered in file order of first use): one per grid point.
    CHECK(m.mesh.vertexCount() == std::size_t((n + 1) * (n + 1)));

    // The one-material grid: one range, and the very same vertices in the same order.
    auto one = loadObj(writeGrid(dir, n, false));
    REQUIRE(one.ok());
    REQUIRE(one.value().ranges.size() == 1);
    CHECK(one.value().ranges[0].indexCount == std::uint32_t(6 * n * n));
    REQUIRE(one.value().mesh.vertexCount() == m.mesh.vertexCount());
    for (std::size_t i = 0; i < m.mesh.vertexCount(); ++i) {
        CHECK(one.value().mesh.positions[i].x == m.mesh.positions[i].x);
        CHECK(one.value().mesh.positions[i].y == m.mesh.positions[i].y);
    }
}

TEST_CASE("OBJ draw ranges come in order of each material's first face, faces in file order", "[resources][obj][ranges]") {
    const std::string dir = freshDir("range-order");
    REQUIRE(writeImage(dir + "/a.png", rampImage(2, 2)).ok());
    REQUIRE(writeImage(dir + "/b.png", rampImage(3, 1)).ok());
    writeText(dir, "m.mtl", "newmtl A\nmap_Kd a.png\nnewmtl B\nmap_Kd b.png\nnewmtl A2\nmap_Kd a.png\nnewmtl Plain\n");
    // Face k's first vertex is (k, 0, 0), so each triangle says which face it is.
    std::string obj = "mtllib m.mtl\nvt 0 0\n";
    for (int k = 1; k <= 7; ++k) obj += "v " + std::to_string(k) + " 0 0\n";
    obj += "v 0 1 0\nv 0 2 0\n";
    const char* materialOfFace[] = {"B", "A", "B", "Nope", "A2", "Plain", "A"}; // faces 1..7
    for (int k = 1; k <= 7; ++k)
        obj += std::string("usemtl ") + materialOfFace[k - 1] + "\nf " + std::to_string(k) + "/1 8/1 9/1\n";
    auto r = loadObj(writeText(dir, "m.obj", obj));
    REQUIRE(r.ok());
    const Model& m = r.value();
    // One range per material (A, B, A2, Plain = 0..3; an unknown name is no material, -1), in the
    // order of first use: B (face 1), A (face 2), none (face 4), A2 (face 5; the same texture as
    // A, but a material of its own: its Kd, Ks, Ns may differ), Plain (face 6, untextured).
    REQUIRE(m.ranges.size() == 5);
    const std::vector<std::vector<int>> expected{{1, 3}, {2, 7}, {4}, {5}, {6}};
    const int expectedMaterial[] = {1, 0, -1, 2, 3};
    const int expectedTexture[] = {1, 0, -1, 0, -1};
    for (std::size_t i = 0; i < 5; ++i) {
        INFO("range " << i);
        const DrawRange& d = m.ranges[i];
        CHECK(d.material == expectedMaterial[i]);
        CHECK(d.texture == expectedTexture[i]);
        CHECK(d.texture == (d.material >= 0 ? m.materials[std::size_t(d.material)].texture : -1));
        std::vector<int> faces;
        for (std::uint32_t k = 0; k < d.indexCount; k += 3)
            faces.push_back(int(m.mesh.positions[m.mesh.indices[d.firstIndex + k]].x));
        CHECK(faces == expected[i]);
    }
    // Vertices in file order of first use: face 1's three, then each later face's first vertex.
    REQUIRE(m.mesh.vertexCount() == 9);
    const float firstUse[] = {1, 0, 0, 2, 3, 4, 5, 6, 7};
    for (std::size_t i = 0; i < 9; ++i) CHECK(m.mesh.positions[i].x == firstUse[i]);
}
