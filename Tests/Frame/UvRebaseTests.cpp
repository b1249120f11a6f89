// Texture coordinates far from 0: a receding textured wall renders the same picture
// whatever whole number of periods its uvs are offset by, on the scalar loop and every kernel ISA.
#include "TestFramework.hpp"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "Math/Transform.hpp"
#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Frame/MeshRenderer.hpp"
#include "Raster/Pipeline.hpp"

using namespace sr;

namespace {

constexpr int W = 160, H = 120;

// A wall receding from view depth 0.5 (left) to 200 (right), so every span is long and 1/w
// changes 400-fold along it; u runs from `offset` to `offset + 50` across it, v from `offset`
// to `offset + 1` up it. The bottom-left corner pokes through the near plane (depth 0.05 at
// z = 0.05 < near 0.1), so some triangles go through the clipper too.
Mesh wall(float offset) {
    Mesh m;
    m.positions = {{-0.6f, -0.5f, -0.05f}, {150.0f, -80.0f, -200.0f}, {150.0f, 80.0f, -200.0f}, {-0.6f, 0.5f, -0.5f}};
    m.uvs = {{offset, offset}, {offset + 50.0f, offset}, {offset + 50.0f, offset + 1.0f}, {offset, offset + 1.0f}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

Texture randomTexture(std::mt19937& rng, int w, int h) {
    std::vector<std::uint8_t> rgba(std::size_t(w) * std::size_t(h) * 4);
    for (auto& b : rgba) b = std::uint8_t(rng() & 0xFFu);
    return Texture::fromRgba8(w, h, rgba.data());
}

FrameView wallView() {
    FrameView view;
    view.viewProj = perspective(radians(90.0f), aspectRatio(W, H), 0.1f, 1000.0f);
    view.eye = {0.0f, 0.0f, 0.0f};
    return view;
}

std::vector<Pixel> render(const Mesh& mesh, const Texture& texture, const RenderSettings& settings) {
    FrameBuffer fb(W, H);
    fb.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
    RenderContext ctx(fb);
    const FrameView view = wallView();
    SurfaceMaterial material;
    material.texture = &texture;
    drawMesh(ctx, view, settings, mesh, mesh.indices.data(), mesh.indices.size(), material);
    std::vector<Pixel> pixels;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) pixels.push_back(fb.pixel(x, y));
    return pixels;
}

int differing(const std::vector<Pixel>& a, const std::vector<Pixel>& b) {
    int n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
    return n;
}

} // namespace

TEST_CASE("rebaseOffset: whole periods at or below the smallest value, nothing for Clamp or non-finite input", "[render][uv]") {
    CHECK(rebaseOffset(1024.25, 1030.0, 1074.5, 1.0) == 1024.0);
    CHECK(rebaseOffset(-3.5, 2.0, 0.0, 1.0) == -4.0);
    CHECK(rebaseOffset(1025.5, 1030.0, 1074.5, 2.0) == 1024.0); // Mirror: an even shift only
    CHECK(rebaseOffset(-3.5, 2.0, 0.0, 2.0) == -4.0);
    CHECK(rebaseOffset(0.25, 0.5, 0.75, 1.0) == 0.0);
    CHECK(rebaseOffset(1024.25, 1030.0, 1074.5, 0.0) == 0.0); // Clamp: not periodic
    CHECK(rebaseOffset(1024.25, std::nan(""), 1074.5, 1.0) == 0.0);
    CHECK(rebaseOffset(1024.25, INFINITY, 1074.5, 1.0) == 0.0);
    CHECK(rebaseOffset(1e300, -1e300, 0.0, 1.0) == -1e300);
    CHECK(rebaseOffset(-1.7e308, 1.7e308, 0.0, 1.0) == 0.0); // 1.7e308 + 1.7e308 overflows
}

TEST_CASE("a receding wall renders bit-identically for uv offsets of 1024, 16384 and 2^20 periods", "[render][uv][precision]") {
    // Repeat and Mirror are periodic and every input is exact, so the picture must not move.
    // Before the per-triangle rebase, 4,769 pixels differed at offset 1024 (nearest, 1024 x 768)
    // and 108,500 at 16,384: u * (1/w) and the recovered u kept too few fraction bits.
    std::mt19937 rng(14u);
    const Texture texture = randomTexture(rng, 64, 32);
    const Mesh base = wall(0.0f);
    std::vector<std::string> isas;
    for (Isa isa : {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        isas.push_back(isaName(isa));
        for (WrapMode wrap : {WrapMode::Repeat, WrapMode::Mirror})
            for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear})
                for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine}) {
                    RenderSettings settings;
                    settings.shading = ShadingMode::Unlit;
                    settings.wrap = wrap;
                    settings.filter = filter;
                    settings.perspective = persp;
                    settings.isa = isa;
                    const std::vector<Pixel> reference = render(base, texture, settings);
                    int textured = 0;
                    for (Pixel p : reference) textured += p != packBgra(0, 0, 0);
                    REQUIRE(textured > W * H / 4); // the wall fills a good part of the frame
                    for (float offset : {1024.0f, 16384.0f, 1048576.0f}) {
                        INFO(isaName(isa) << ", " << wrapName(wrap) << ", " << filterName(filter) << ", "
                                          << perspectiveModeName(persp) << ", offset " << offset);
                        CHECK(differing(render(wall(offset), texture, settings), reference) == 0);
                    }
                }
    }
    WARN("uv offsets checked on:" << [&] {
        std::string s;
        for (const auto& n : isas) s += " " + n;
        return s;
    }());
}

TEST_CASE("without the rebase the wall moves at offset 16384: the test scene sees the precision loss", "[render][uv][precision]") {
    // The same draw through drawIndexed with and without a VaryingRebase: the offset scene must
    // differ without it (otherwise the identity test above would prove nothing) and match with it.
    std::mt19937 rng(14u);
    const Texture texture = randomTexture(rng, 64, 32);
    const FrameView view = wallView();
    auto draw = [&](const Mesh& m, VaryingRebase rebase) {
        FrameBuffer fb(W, H);
        fb.clear(packBgra(0, 0, 0), FrameBuffer::kFarDepth);
        RenderContext ctx(fb);
        DrawState state;
        state.rebase = rebase;
        drawIndexed<2>(
            ctx, state, m.vertexCount(), m.indices.data(), m.indices.size(),
            [&](std::size_t i, ClipVertex& out) {
                out.position = view.viewProj * Vec4(m.positions[i], 1.0f);
                out.varyings[0] = m.uvs[i].x;
                out.varyings[1] = m.uvs[i].y;
            },
            [&](const Fragment<2>& f) {
                return packBgra8(texture.sample({f.varyings[0], f.varyings[1]}, 0.0f, TextureFilter::Nearest, WrapMode::Repeat));
            });
        std::vector<Pixel> pixels;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) pixels.push_back(fb.pixel(x, y));
        return pixels;
    };
    const VaryingRebase repeat{2, wrapPeriod(WrapMode::Repeat)};
    const auto reference = draw(wall(0.0f), repeat);
    CHECK(differing(draw(wall(16384.0f), repeat), reference) == 0);
    CHECK(differing(draw(wall(16384.0f), VaryingRebase{}), reference) > 100);
}
