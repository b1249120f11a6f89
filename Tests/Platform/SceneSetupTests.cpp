// Tests of splitting a loaded model into per-range meshes: contents, and work bounded by the range.
#include "TestFramework.hpp"

#include "Platform/Demo/SceneSetup.hpp"

#include <cstdint>
#include <vector>

using namespace sr;
using namespace sr::demo;

namespace {

// A strip of `quads` unit quads along x (2 triangles each, 2 * (quads + 1) vertices), with
// normals and uvs that identify the vertex: normal.x = uv.x = its index.
Mesh strip(int quads) {
    Mesh m;
    for (int i = 0; i <= quads; ++i)
        for (int y = 0; y < 2; ++y) {
            const auto v = float(m.positions.size());
            m.positions.emplace_back(float(i), float(y), 0.0f);
            m.normals.emplace_back(v, 0.0f, 1.0f);
            m.uvs.emplace_back(v, 0.5f);
        }
    for (std::uint32_t i = 0; i < std::uint32_t(quads); ++i) {
        const std::uint32_t a = 2 * i, b = a + 2, c = a + 3, d = a + 1;
        for (std::uint32_t k : {a, b, c, a, c, d}) m.indices.push_back(k);
    }
    return m;
}

} // namespace

TEST_CASE("appendRange keeps the range's vertices in order of first use; clearRange resets the remap",
          "[platform][scene]") {
    const Mesh src = strip(3);
    std::vector<std::uint32_t> remap(src.vertexCount(), kNoVertex);
    // The second quad: source vertices 2, 4, 5, 2, 5, 3.
    Mesh part;
    appendRange(part, src, 6, 6, remap);
    clearRange(src, 6, 6, remap);
    REQUIRE(part.vertexCount() == 4);
    REQUIRE(part.hasNormals());
    REQUIRE(part.hasUvs());
    CHECK(part.indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
    const float expected[] = {2, 4, 5, 3};
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(part.positions[i].x == src.positions[std::size_t(expected[i])].x);
        CHECK(part.positions[i].y == src.positions[std::size_t(expected[i])].y);
        CHECK(part.normals[i].x == expected[i]);
        CHECK(part.uvs[i].x == expected[i]);
    }
    for (std::uint32_t r : remap) CHECK(r == kNoVertex);
}

// The work of a range is bounded by its size, not the model's: appendRange and clearRange touch
// only the remap entries of the range's own vertices. Every other entry holds a marker that a reset of
// the whole array per range (the old quadratic split: R ranges x V vertices) would overwrite.
TEST_CASE("appendRange and clearRange read and write only the remap entries of the range's vertices",
          "[platform][scene]") {
    const int quads = 500;
    const Mesh src = strip(quads);
    constexpr std::uint32_t kMarker = 0xC0FFEEu;
    std::vector<std::uint32_t> remap(src.vertexCount(), kMarker);
    std::size_t vertices = 0;
    for (int q = 0; q < quads; ++q) {
        // This quad's four vertices are clear on entry; every other entry keeps the marker.
        const std::uint32_t first = 2 * std::uint32_t(q);
        for (std::uint32_t v = first; v < first + 4; ++v) remap[v] = kNoVertex;
        Mesh part;
        appendRange(part, src, std::uint32_t(q) * 6, 6, remap);
        clearRange(src, std::uint32_t(q) * 6, 6, remap);
        REQUIRE(part.triangleCount() == 2);
        vertices += part.vertexCount();
        std::size_t markers = 0, clear = 0;
        for (std::uint32_t r : remap) {
            markers += r == kMarker;
            clear += r == kNoVertex;
        }
        REQUIRE(clear == 4);
        REQUIRE(markers == remap.size() - 4);
        for (std::uint32_t v = first; v < first + 4; ++v) remap[v] = kMarker;
    }
    CHECK(vertices == 4 * std::size_t(quads));
}
