// Every span kernel x every ISA the CPU has against the scalar reference (fillTriangle + fragment()), bit for bit.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Math/Transform.hpp"
#include "Raster/Fill/Kernels/KernelTable.hpp"
#include "Raster/Fill/ScanlineFill.hpp" // fillTriangle, the reference
#include "Raster/Shade/MeshPrograms.hpp"
#include "Raster/Shade/Ibl.hpp"
#include "Raster/Shade/PbrProgram.hpp"
#include "Raster/Shade/Shadow.hpp"

using namespace sr;

namespace {

using namespace sr::programs;

// Random texels, RGBA8 top row first.
Texture randomTexture(std::mt19937& rng, int w, int h) {
    std::vector<std::uint8_t> rgba(std::size_t(w) * std::size_t(h) * 4);
    for (auto& b : rgba) b = std::uint8_t(rng() & 0xFFu);
    return Texture::fromRgba8(w, h, rgba.data());
}

// A varying value for the test triangles: mostly ordinary, sometimes far from 0, exactly 0,
// huge, or non-finite (NaN/Inf uvs take the samplers' scalar lanes; a zero normal takes the
// robust normalize), so every fallback of the kernels runs too.
float randomVarying(std::mt19937& rng, bool wild) {
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    if (!wild) return u(rng);
    switch (rng() % 24u) {
    case 0: return 0.0f;
    case 1: return std::numeric_limits<float>::quiet_NaN();
    case 2: return std::numeric_limits<float>::infinity();
    case 3: return 3.0e9f;                     // |u| >= 2^31: a scalar lane
    case 4: return 1.0e6f + 0.375f;            // far from 0, exact fraction
    case 5: return -1.0e-30f;                  // tiny negative
    default: return u(rng);
    }
}

// The reference: ScanlineFill.hpp's loop with the program's fragment(), counting like the pipeline.
template <class Prog, DepthMode kDepth, PerspectiveMode kPersp>
void referenceFill(const Prog& p, const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, std::uint64_t& shaded) {
    const float alpha = p.d->alpha;
    fillTriangle<kDepth, Prog::kVaryings, kPersp>(t, fb, s, [&](const Fragment<Prog::kVaryings>& f) {
        ++shaded;
        if (alpha < 1.0f) return blendOver(p.fragment(f), fb.colorRow(f.y)[f.x], alpha, p.d->linear); // the pipeline's `counted`
        return p.fragment(f);
    });
}
template <class Prog>
void referenceFill(const Prog& p, const KernelKey& key, const TriangleSetup& t, FrameBuffer& fb, const Scissor& s,
                   std::uint64_t& shaded) {
    auto persp = [&](auto depthTag) {
        constexpr DepthMode kDepth = decltype(depthTag)::value;
        if (key.perspective == PerspectiveMode::Affine) referenceFill<Prog, kDepth, PerspectiveMode::Affine>(p, t, fb, s, shaded);
        else referenceFill<Prog, kDepth, PerspectiveMode::Exact>(p, t, fb, s, shaded);
    };
    switch (key.depth) {
    case DepthMode::Off: persp(std::integral_constant<DepthMode, DepthMode::Off>{}); break;
    case DepthMode::Test: persp(std::integral_constant<DepthMode, DepthMode::Test>{}); break;
    case DepthMode::TestWrite: persp(std::integral_constant<DepthMode, DepthMode::TestWrite>{}); break;
    }
}

// The mesh the programs read: one triangle (flat's face normal), its normals and uvs.
Mesh oneTriangle() {
    Mesh mesh;
    mesh.positions = {{-1.0f, -0.5f, 0.2f}, {1.2f, -0.4f, -0.3f}, {0.1f, 1.1f, 0.4f}};
    mesh.normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
    mesh.uvs = {{0, 0}, {1, 0}, {0, 1}};
    mesh.indices = {0, 1, 2};
    return mesh;
}

struct Totals {
    long combinations = 0, pixels = 0;
};

// One program type, one key, one ISA: random triangles (tiny ones for the tail lanes and the
// queue, flat-depth ones for exact depth ties, random scissors) into two identical buffers.
template <class Prog, class Make>
void compareKernel(Isa isa, const KernelKey& key, Make&& make, std::mt19937& rng, Totals& totals) {
    const FillKernel<Prog> kernel = selectFillKernel<Prog>(isa, key);
    INFO("isa " << isaName(isa) << ", shading " << shadingModeName(Prog::kMode) << (Prog::kIsTextured ? " textured" : "")
                << ", depth " << int(key.depth) << ", " << perspectiveModeName(key.perspective) << ", "
                << filterName(key.filter) << ", " << wrapName(key.wrap));
    REQUIRE(kernel != nullptr);
    constexpr int kV = Prog::kVaryings;
    const int w = 61, h = 37; // odd sizes: groups that end past the row
    FrameBuffer ref(w, h), simd(w, h);
    std::uniform_real_distribution<float> pos(-12.0f, 72.0f), small(0.0f, 5.0f), unit(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::uint32_t r = rng() % 4u;
            ref.depthRow(y)[x] = simd.depthRow(y)[x] = r == 0 ? 0.0f : r == 1 ? 0.5f : unit(rng);
            ref.colorRow(y)[x] = simd.colorRow(y)[x] = 0x12345678u;
        }
    for (int tri = 0; tri < 12; ++tri) {
        ScreenVertex v[3];
        const bool tiny = rng() % 3u == 0, flatDepth = rng() % 6u == 0, wild = rng() % 3u == 0;
        const float cx = pos(rng), cy = pos(rng);
        for (auto& s : v) {
            s.x = tiny ? cx + small(rng) : pos(rng);
            s.y = tiny ? cy + small(rng) : pos(rng);
            s.z = flatDepth ? 0.5f : unit(rng);
            s.invW = std::exp2(std::uniform_real_distribution<float>(-6.0f, 2.0f)(rng));
            for (int k = 0; k < kV; ++k) s.varyings[std::size_t(k)] = randomVarying(rng, wild);
        }
        const auto setup = setupTriangle(v[0], v[1], v[2], kV, key.perspective != PerspectiveMode::Affine);
        if (!setup) continue;
        const Scissor sc = rng() % 2u ? Scissor{0, 0, w, h}
                                      : Scissor{int(rng() % 20u), int(rng() % 20u), 30 + int(rng() % 31u), 20 + int(rng() % 17u)};
        Prog p = make();
        p.triangle(0, *setup);
        std::uint64_t shadedRef = 0, shadedSimd = 0;
        referenceFill(p, key, *setup, ref, sc, shadedRef);
        kernel(p, *setup, simd, sc, shadedSimd);
        REQUIRE(shadedSimd == shadedRef);
        totals.pixels += long(shadedRef);
    }
    // The colours the kernel may still hold back for the draw's later triangles (the pipeline's
    // flush at the end of a draw); the triangles above overlap, so a queued colour written out of
    // order shows.
    const FlushKernel<Prog> flush = selectFlushKernel<Prog>(isa, key);
    REQUIRE(flush != nullptr);
    flush(make(), simd);
    for (int y = 0; y < h; ++y) {
        INFO("row " << y);
        REQUIRE(std::memcmp(ref.colorRow(y), simd.colorRow(y), sizeof(Pixel) * std::size_t(w)) == 0);
        REQUIRE(std::memcmp(ref.depthRow(y), simd.depthRow(y), sizeof(float) * std::size_t(w)) == 0);
    }
    ++totals.combinations;
}

} // namespace

TEST_CASE("every span kernel on every ISA of this CPU is bit-identical to the scalar reference", "[threads][simd][kernels]") {
    std::mt19937 rng(18u);
    // A scene the programs read: two lights, an eye, a material, a triangle for flat's face normal.
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1))), Light::directional(normalize(Vec3(-0.3f, 0.2f, 1.0f)))};
    // The same with lights of every kind (RGB terms: lightsRgb, Gouraud's six varyings): a
    // coloured directional light, a point light with a range that cuts through the positions
    // (varyings in [-3, 3]), one without, and a spot whose cone edge crosses them.
    FrameView colouredView = view;
    colouredView.lighting.lights = {
        Light::directional(normalize(Vec3(1, 1, 1)), {1.0f, 0.5f, 0.25f, 1.0f}),
        Light::point({0.5f, 1.0f, 2.0f}, {4.0f, 3.0f, 1.0f, 1.0f}, 3.5f),
        Light::point({-2.0f, 0.0f, 1.0f}, {0.5f, 2.0f, 2.0f, 1.0f}),
        Light::spot({0.0f, 0.0f, 4.0f}, {0.1f, -0.2f, -1.0f}, {6.0f, 6.0f, 3.0f, 1.0f}, 0.2f, 0.6f, 9.0f)};
    REQUIRE(!colouredView.lighting.whiteDirectional());
    const Texture textures[] = {randomTexture(rng, 13, 7), randomTexture(rng, 32, 16)}; // non-power-of-two, power-of-two
    // Specular constants: the default (white 0.5, 32), an MTL-like coloured Ks with an odd
    // exponent, and none (Ks black: the kernels skip the half vector). Textured draws take one
    // per wrap mode (every filter, depth and perspective sees all three), untextured ones all.
    Specular coloured;
    coloured.ks = {0.3f, 0.6f, 0.1f};
    coloured.shininess = 7.0f;
    Specular none;
    none.ks = {0.0f, 0.0f, 0.0f};
    const Specular speculars[] = {Specular{}, coloured, none};
    std::vector<std::string> ran, skipped;
    Totals totals;
    int normalOnly = 0; // normal-only Phong programs compared (no specular term: `none`)
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) {
            skipped.push_back(isaName(isa));
            continue;
        }
        ran.push_back(isaName(isa));
        for (DepthMode depth : {DepthMode::Off, DepthMode::Test, DepthMode::TestWrite})
            for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
                for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear})
                    for (WrapMode wrap : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
                        RenderSettings settings;
                        settings.filter = filter;
                        settings.wrap = wrap;
                        settings.perspective = persp;
                        const KernelKey key{depth, persp, filter, wrap};
                        const Specular& specular = speculars[int(wrap)];
                        for (const Texture& texture : textures) {
                            // kd here is the texel's tint (an MTL Kd).
                            const DrawContext d{view,     settings, mesh, mesh.indices.data(), &texture, Color{0.7f, 0.4f, 0.2f, 1.0f},
                                                specular,
                                                1.0f, true, true, {}};
                            compareKernel<UnlitProgram<true>>(isa, key, [&] { return UnlitProgram<true>(&d, 0); }, rng, totals);
                            compareKernel<FlatProgram<true>>(isa, key, [&] { return FlatProgram<true>(&d); }, rng, totals);
                            compareKernel<GouraudProgram<true>>(isa, key, [&] { return GouraudProgram<true>(&d); }, rng, totals);
                            compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&d); }, rng, totals);
                            // Without a specular term under white directional lights, drawMesh's
                            // choice: the program without position varyings.
                            if (!phongReadsPosition(d)) {
                                compareKernel<PhongProgram<true, true>>(isa, key, [&] { return PhongProgram<true, true>(&d); }, rng, totals);
                                ++normalOnly;
                            }
                        }
                        if (depth == DepthMode::Test) {
                            // A transparent draw (alpha 0.4: every colour blended over the target),
                            // textured Phong and untextured flat (the constant-colour path); such
                            // draws are drawn with DepthMode::Test only (drawStateFor).
                            const DrawContext t{view, settings, mesh, mesh.indices.data(), &textures[1],
                                                Color{0.7f, 0.4f, 0.2f, 1.0f}, specular, 0.4f, true, true, {}};
                            compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&t); }, rng, totals);
                            const DrawContext u{view, settings, mesh, mesh.indices.data(), nullptr,
                                                Color{0.7f, 0.4f, 0.2f, 1.0f}, specular, 0.4f, true, true, {}};
                            compareKernel<FlatProgram<false>>(isa, key, [&] { return FlatProgram<false>(&u); }, rng, totals);
                        }
                        {
                            // Coloured, point and spot lights on the non-power-of-two texture.
                            const DrawContext d{colouredView, settings, mesh, mesh.indices.data(), &textures[0],
                                                Color{0.7f, 0.4f, 0.2f, 1.0f}, specular, 1.0f, false, true, {}};
                            compareKernel<FlatProgram<true>>(isa, key, [&] { return FlatProgram<true>(&d); }, rng, totals);
                            compareKernel<GouraudProgram<true, true>>(isa, key, [&] { return GouraudProgram<true, true>(&d); }, rng, totals);
                            compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&d); }, rng, totals);
                        }
                        // Untextured programs read neither filter nor wrap: once per depth and perspective.
                        if (filter != TextureFilter::Nearest || wrap != WrapMode::Repeat) continue;
                        for (const Specular& sp : speculars) {
                            const DrawContext d{view, settings, mesh, mesh.indices.data(), nullptr, Color{0.7f, 0.4f, 0.2f, 1.0f}, sp, 1.0f, true, true, {}};
                            compareKernel<UnlitProgram<false>>(isa, key, [&] { return UnlitProgram<false>(&d, packBgra8(d.kd)); }, rng, totals);
                            compareKernel<FlatProgram<false>>(isa, key, [&] { return FlatProgram<false>(&d); }, rng, totals);
                            compareKernel<GouraudProgram<false>>(isa, key, [&] { return GouraudProgram<false>(&d); }, rng, totals);
                            compareKernel<PhongProgram<false>>(isa, key, [&] { return PhongProgram<false>(&d); }, rng, totals);
                            if (!phongReadsPosition(d)) {
                                compareKernel<PhongProgram<false, true>>(isa, key, [&] { return PhongProgram<false, true>(&d); }, rng, totals);
                                ++normalOnly;
                            }
                            const DrawContext c{colouredView, settings, mesh, mesh.indices.data(), nullptr,
                                                Color{0.7f, 0.4f, 0.2f, 1.0f}, sp, 1.0f, false, true, {}};
                            compareKernel<FlatProgram<false>>(isa, key, [&] { return FlatProgram<false>(&c); }, rng, totals);
                            compareKernel<GouraudProgram<false, true>>(isa, key, [&] { return GouraudProgram<false, true>(&c); }, rng, totals);
                            compareKernel<PhongProgram<false>>(isa, key, [&] { return PhongProgram<false>(&c); }, rng, totals);
                        }
                    }
    }
    std::string ranList, skippedList;
    for (const auto& n : ran) ranList += " " + n;
    for (const auto& n : skipped) skippedList += " " + n;
    // The log names the ISAs that ran and those this CPU lacks (skipped by name).
    WARN("kernel ISAs tested:" << ranList << "; skipped (not on this CPU):" << (skippedList.empty() ? " none" : skippedList)
                               << "; " << totals.combinations << " kernel/key/texture combinations, " << totals.pixels
                               << " shaded pixels");
    REQUIRE(!ran.empty());
    CHECK(totals.pixels > 100000 * long(ran.size()));
    // Per ISA: 3 depth modes x 2 perspective modes x (3 filters x 2 textures, and one untextured draw).
    CHECK(normalOnly == 3 * 2 * (3 * 2 + 1) * int(ran.size()));
}

TEST_CASE("Phong drops the position varyings only where nothing reads them", "[threads][kernels][shading]") {
    // phongReadsPosition: drawMesh's choice of PhongProgram<kTextured, true>, whose fragments carry
    // no position: only white directional lights, no specular term and no shadows.
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)))};
    Specular none;
    none.ks = {0.0f, 0.0f, 0.0f};
    Specular noExponent;
    noExponent.shininess = 0.0f;
    const RenderSettings settings;
    auto draw = [&](const FrameView& v, const Specular& sp, bool whiteLights) {
        return DrawContext{v, settings, mesh, mesh.indices.data(), nullptr, Color{0.7f, 0.4f, 0.2f, 1.0f}, sp, 1.0f, whiteLights, true, {}};
    };
    CHECK_FALSE(phongReadsPosition(draw(view, none, true)));
    CHECK_FALSE(phongReadsPosition(draw(view, noExponent, true)));
    CHECK(phongReadsPosition(draw(view, Specular{}, true)));  // the half vector needs the direction to the eye
    CHECK(phongReadsPosition(draw(view, none, false)));       // point, spot or coloured lights: the RGB path
    const SceneShadows shadows;
    FrameView shadowed = view;
    shadowed.shadows = &shadows;
    CHECK(phongReadsPosition(draw(shadowed, none, true)));    // the shadow maps are looked up at the position
    CHECK(PhongProgram<true, true>::kVaryings == PhongProgram<true>::kVaryings - 3);
    CHECK(PhongProgram<false, true>::kVaryings == 3);
}

TEST_CASE("in linear light every span kernel is bit-identical to the scalar reference", "[threads][simd][kernels][colour]") {
    // ColorMode::Linear: texels decoded from sRGB before filtering (nearest, the bilinear and
    // trilinear float blends), the colour encoded by the sRGB tables, blends in linear light.
    std::mt19937 rng(36u);
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1))), Light::directional(normalize(Vec3(-0.3f, 0.2f, 1.0f)))};
    FrameView colouredView = view;
    colouredView.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)), {1.0f, 0.5f, 0.25f, 1.0f}),
                                    Light::point({0.5f, 1.0f, 2.0f}, {4.0f, 3.0f, 1.0f, 1.0f}, 3.5f)};
    const Texture textures[] = {randomTexture(rng, 13, 7), randomTexture(rng, 32, 16)};
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (DepthMode depth : {DepthMode::Test, DepthMode::TestWrite})
            for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
                for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear})
                    for (WrapMode wrap : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror}) {
                        RenderSettings settings;
                        settings.filter = filter;
                        settings.wrap = wrap;
                        settings.perspective = persp;
                        settings.colour = ColorMode::Linear;
                        const KernelKey key{depth, persp, filter, wrap};
                        for (const Texture& texture : textures) {
                            DrawContext d{view, settings, mesh, mesh.indices.data(), &texture, Color{0.7f, 0.4f, 0.2f, 1.0f},
                                          Specular{}, 1.0f, true, true, {}};
                            d.linear = true;
                            compareKernel<UnlitProgram<true>>(isa, key, [&] { return UnlitProgram<true>(&d, 0); }, rng, totals);
                            compareKernel<FlatProgram<true>>(isa, key, [&] { return FlatProgram<true>(&d); }, rng, totals);
                            compareKernel<GouraudProgram<true>>(isa, key, [&] { return GouraudProgram<true>(&d); }, rng, totals);
                            compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&d); }, rng, totals);
                            DrawContext c{colouredView, settings, mesh, mesh.indices.data(), &texture, Color{0.7f, 0.4f, 0.2f, 1.0f},
                                          Specular{}, 1.0f, false, true, {}};
                            c.linear = true;
                            compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&c); }, rng, totals);
                        }
                        if (depth == DepthMode::Test) { // transparent: blended in linear light
                            DrawContext t{view, settings, mesh, mesh.indices.data(), &textures[1], Color{0.7f, 0.4f, 0.2f, 1.0f},
                                          Specular{}, 0.4f, true, true, {}};
                            t.linear = true;
                            compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&t); }, rng, totals);
                            DrawContext u{view, settings, mesh, mesh.indices.data(), nullptr, Color{0.7f, 0.4f, 0.2f, 1.0f},
                                          Specular{}, 0.4f, true, true, {}};
                            u.linear = true;
                            compareKernel<FlatProgram<false>>(isa, key, [&] { return FlatProgram<false>(&u); }, rng, totals);
                        }
                        if (filter != TextureFilter::Nearest || wrap != WrapMode::Repeat) continue;
                        DrawContext d{view, settings, mesh, mesh.indices.data(), nullptr, Color{0.7f, 0.4f, 0.2f, 1.0f}, Specular{},
                                      1.0f, true, true, {}};
                        d.linear = true;
                        compareKernel<UnlitProgram<false>>(isa, key, [&] { return UnlitProgram<false>(&d, encode(d, d.kd)); }, rng, totals);
                        compareKernel<GouraudProgram<false>>(isa, key, [&] { return GouraudProgram<false>(&d); }, rng, totals);
                        compareKernel<PhongProgram<false>>(isa, key, [&] { return PhongProgram<false>(&d); }, rng, totals);
                    }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 50000 * long(ran));
}

TEST_CASE("anisotropic filtering in the kernels is bit-identical to the scalar reference", "[threads][simd][kernels][aniso]") {
    // Trilinear with --aniso 2, 4, 16 (and 1 and affine, where it is plain trilinear): the taps along
    // the footprint's major axis, on display values and in linear light, every wrap, with random
    // perspective (invW over 2^-6 .. 2^2: footprints from round to needle-thin) and wild uvs (the
    // lanes redone by the scalar function).
    std::mt19937 rng(44u);
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)))};
    const Texture textures[] = {randomTexture(rng, 13, 7), randomTexture(rng, 64, 32)};
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
            for (int aniso : {1, 2, 4, 16})
                for (WrapMode wrap : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
                    for (bool linear : {false, true}) {
                        if (persp == PerspectiveMode::Affine && aniso != 16) continue;
                        RenderSettings settings;
                        settings.filter = TextureFilter::Trilinear;
                        settings.wrap = wrap;
                        settings.perspective = persp;
                        settings.aniso = aniso;
                        settings.colour = linear ? ColorMode::Linear : ColorMode::Gamma;
                        const KernelKey key{DepthMode::TestWrite, persp, TextureFilter::Trilinear, wrap};
                        for (const Texture& texture : textures) {
                            DrawContext d{view, settings, mesh, mesh.indices.data(), &texture, Color{0.7f, 0.4f, 0.2f, 1.0f},
                                          Specular{}, 1.0f, true, true, {}};
                            d.linear = linear;
                            compareKernel<UnlitProgram<true>>(isa, key, [&] { return UnlitProgram<true>(&d, 0); }, rng, totals);
                            compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&d); }, rng, totals);
                        }
                    }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 20000 * long(ran));
}

TEST_CASE("wrap modes apart on u and v in the kernels are bit-identical to the scalar reference", "[threads][simd][kernels][wrap]") {
    // A glTF sampler's wrapS and wrapT apart (RenderSettings::wrapV): every pair of different
    // modes, every filter, with and without anisotropy, on display values and in linear light,
    // for the textured unlit, Phong and pbr programs (wild uvs: the lanes redone by the scalar
    // sampler take the pair too).
    std::mt19937 rng(45u);
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)))};
    const Texture textures[] = {randomTexture(rng, 13, 7), randomTexture(rng, 32, 16)};
    PbrFactors factors;
    factors.baseColor = {0.8f, 0.5f, 0.3f, 1.0f};
    factors.metallic = 0.3f;
    factors.roughness = 0.6f;
    factors.emissive = {0.3f, 0.1f, 0.0f};
    const WrapMode modes[] = {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror};
    Totals totals;
    int ran = 0, pairs = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (WrapMode wu : modes)
            for (WrapMode wv : modes) {
                if (wu == wv) continue;
                ++pairs;
                for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
                    for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear})
                        for (int aniso : {1, 4})
                            for (bool linear : {false, true}) {
                                if (aniso > 1 && filter != TextureFilter::Trilinear) continue;
                                RenderSettings settings;
                                settings.filter = filter;
                                settings.wrap = wu;
                                settings.wrapV = wv;
                                settings.perspective = persp;
                                settings.aniso = aniso;
                                settings.colour = linear ? ColorMode::Linear : ColorMode::Gamma;
                                const KernelKey key{DepthMode::TestWrite, persp, filter, wu};
                                for (const Texture& texture : textures) {
                                    SurfaceMaterial material;
                                    material.pbr = &factors;
                                    material.texture = &texture;
                                    material.maps[MapSlot::Emissive] = &textures[0];
                                    DrawContext d{view, settings, mesh, mesh.indices.data(), &texture, Color{0.7f, 0.4f, 0.2f, 1.0f},
                                                  Specular{}, 1.0f, true, true, {}};
                                    d.linear = linear;
                                    d.material = &material;
                                    compareKernel<UnlitProgram<true>>(isa, key, [&] { return UnlitProgram<true>(&d, 0); }, rng, totals);
                                    compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&d); }, rng, totals);
                                    compareKernel<PbrProgram<true>>(isa, key, [&] { return PbrProgram<true>(&d); }, rng, totals);
                                }
                            }
            }
    }
    REQUIRE(ran > 0);
    CHECK(pairs == 6 * ran);
    CHECK(totals.pixels > 20000 * long(ran));
}

TEST_CASE("tone mapping and exposure in the kernels are bit-identical to the scalar encoder", "[threads][simd][kernels][colour]") {
    std::mt19937 rng(38u);
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.physical = true;
    view.lighting.ambient = 0.0f;
    // Bright enough that ACES saturates and PBR Neutral compresses its peaks (above 0.76).
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)), {6.0f, 4.0f, 2.0f, 1.0f}),
                            Light::point({0.5f, 1.0f, 2.0f}, {9.0f, 3.0f, 1.0f, 1.0f}, 0.0f)};
    const Texture texture = randomTexture(rng, 13, 7);
    PbrFactors factors;
    factors.baseColor = {0.9f, 0.6f, 0.3f, 1.0f};
    factors.metallic = 0.3f;
    factors.roughness = 0.4f;
    factors.emissive = {0.5f, 0.2f, 0.0f};
    SurfaceMaterial material;
    material.pbr = &factors;
    material.texture = &texture;
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (ToneMap op : {ToneMap::None, ToneMap::Aces, ToneMap::Neutral})
            for (float exposure : {1.0f, 0.35f, 3.0f}) {
                if (op == ToneMap::None && exposure == 1.0f) continue; // the plain encoder: the linear test's
                RenderSettings settings;
                settings.colour = ColorMode::Linear;
                settings.toneMap = op;
                const KernelKey key{DepthMode::TestWrite, PerspectiveMode::Exact, TextureFilter::Bilinear, WrapMode::Repeat};
                DrawContext d{view, settings, mesh, mesh.indices.data(), &texture, Color{0.9f, 0.7f, 0.5f, 1.0f}, Specular{},
                              1.0f, false, true, {}};
                d.linear = true;
                d.exposureScale = exposure;
                d.material = &material;
                compareKernel<PbrProgram<true>>(isa, key, [&] { return PbrProgram<true>(&d); }, rng, totals);
                compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&d); }, rng, totals);
                compareKernel<UnlitProgram<false>>(isa, key, [&] { return UnlitProgram<false>(&d, encode(d, d.kd)); }, rng, totals);
            }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 10000 * long(ran));
}

TEST_CASE("the pbr kernels (glTF BRDF, maps, physical lights) are bit-identical to the scalar program",
          "[threads][simd][kernels][pbr]") {
    std::mt19937 rng(37u);
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.physical = true;
    view.lighting.ambient = 0.0f;
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)), {kPiF, kPiF, kPiF, 1.0f}),
                            Light::point({0.5f, 1.0f, 2.0f}, {4.0f, 3.0f, 1.0f, 1.0f}, 3.5f),
                            Light::spot({0.0f, 0.0f, 4.0f}, {0.1f, -0.2f, -1.0f}, {6.0f, 6.0f, 3.0f, 1.0f}, 0.2f, 0.6f, 9.0f)};
    const Texture base = randomTexture(rng, 13, 7), mr = randomTexture(rng, 32, 16), emissive = randomTexture(rng, 8, 8);
    const Texture normals = randomTexture(rng, 16, 8);
    PbrFactors rough, polished;
    rough.baseColor = {0.8f, 0.5f, 0.3f, 1.0f};
    rough.metallic = 0.2f;
    rough.roughness = 0.9f;
    rough.emissive = {0.3f, 0.1f, 0.0f};
    rough.normalScale = 0.7f;
    polished.baseColor = {1.0f, 0.8f, 0.4f, 1.0f};
    polished.metallic = 1.0f;
    polished.roughness = 0.03f; // below the smallest roughness evaluated
    PbrFactors tinted = rough; // KHR_materials_ior / _specular: a tinted dielectric F0, a specular weight, their maps
    tinted.dielectricF0 = {0.11f, 0.06f, 0.3f};
    tinted.specularColorF0 = {0.11f, 0.06f, 3.0f};
    tinted.specularWeight = 0.55f;
    const Texture specularMap = randomTexture(rng, 8, 16), specularColour = randomTexture(rng, 16, 16);
    PbrFactors glossy = rough; // KHR_materials_pbrSpecularGlossiness with its texture (RGB and alpha)
    glossy.metallic = 0.0f;
    glossy.specularGlossiness = true;
    glossy.glossiness = 0.85f;
    glossy.dielectricF0 = glossy.specularColorF0 = {0.3f, 0.2f, 0.5f};
    const Texture glossiness = randomTexture(rng, 16, 8);
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (DepthMode depth : {DepthMode::Test, DepthMode::TestWrite})
            for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
                for (TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear, TextureFilter::Trilinear})
                    for (WrapMode wrap : {WrapMode::Repeat, WrapMode::Mirror})
                        for (const bool linear : {true, false}) {
                            RenderSettings settings;
                            settings.filter = filter;
                            settings.wrap = wrap;
                            settings.perspective = persp;
                            settings.shading = ShadingMode::Pbr;
                            settings.colour = linear ? ColorMode::Linear : ColorMode::Gamma;
                            const KernelKey key{depth, persp, filter, wrap};
                            for (const PbrFactors* factors : {&rough, &polished, &tinted, &glossy}) {
                                SurfaceMaterial material;
                                material.pbr = factors;
                                material.texture = &base;
                                material.maps[MapSlot::MetallicRoughness] = &mr;
                                material.maps[MapSlot::Emissive] = &emissive;
                                if (factors == &tinted) {
                                    material.maps[MapSlot::Specular] = &specularMap;
                                    material.maps[MapSlot::SpecularColour] = &specularColour;
                                }
                                if (factors == &glossy) {
                                    material.maps[MapSlot::MetallicRoughness] = nullptr;
                                    material.maps[MapSlot::SpecularColour] = &specularColour;
                                    material.maps[MapSlot::Glossiness] = &glossiness;
                                }
                                for (const bool doubleSided : {true, false}) {
                                    DrawContext d{view, settings, mesh, mesh.indices.data(), &base, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                                  Specular{}, 1.0f, false, doubleSided, {}};
                                    d.linear = linear;
                                    d.material = &material;
                                    compareKernel<PbrProgram<true>>(isa, key, [&] { return PbrProgram<true>(&d); }, rng, totals);
                                }
                                // Normal-mapped (random texels, random tangents and handedness among the varyings).
                                SurfaceMaterial mapped = material;
                                mapped.maps[MapSlot::Normal] = &normals;
                                DrawContext dn{view, settings, mesh, mesh.indices.data(), &base, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                               Specular{}, 1.0f, false, true, {}};
                                dn.linear = linear;
                                dn.material = &mapped;
                                compareKernel<PbrProgram<true, true>>(isa, key, [&] { return PbrProgram<true, true>(&dn); }, rng, totals);
                                if (filter != TextureFilter::Nearest || wrap != WrapMode::Repeat) continue;
                                SurfaceMaterial plain;
                                plain.pbr = factors;
                                DrawContext u{view, settings, mesh, mesh.indices.data(), nullptr, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                              Specular{}, depth == DepthMode::Test ? 0.4f : 1.0f, false, true, {}};
                                u.linear = linear;
                                u.material = &plain;
                                compareKernel<PbrProgram<false>>(isa, key, [&] { return PbrProgram<false>(&u); }, rng, totals);
                            }
                        }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 50000 * long(ran));
}

TEST_CASE("the pbr and unlit kernels with vertex colours (COLOR_0) are bit-identical to the scalar program",
          "[threads][simd][kernels][pbr]") {
    std::mt19937 rng(41u);
    const Mesh mesh = oneTriangle();
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.physical = true;
    view.lighting.ambient = 0.0f;
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)), {kPiF, kPiF, kPiF, 1.0f}),
                            Light::point({0.5f, 1.0f, 2.0f}, {4.0f, 3.0f, 1.0f, 1.0f}, 3.5f)};
    const Texture base = randomTexture(rng, 13, 7), mr = randomTexture(rng, 32, 16), normals = randomTexture(rng, 16, 8);
    PbrFactors factors;
    factors.baseColor = {0.8f, 0.5f, 0.3f, 1.0f};
    factors.metallic = 0.3f;
    factors.roughness = 0.6f;
    factors.normalScale = 0.8f;
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (DepthMode depth : {DepthMode::Test, DepthMode::TestWrite})
            for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
                for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Trilinear})
                    for (const bool linear : {true, false}) {
                        RenderSettings settings;
                        settings.filter = filter;
                        settings.perspective = persp;
                        settings.shading = ShadingMode::Pbr;
                        settings.colour = linear ? ColorMode::Linear : ColorMode::Gamma;
                        const KernelKey key{depth, persp, filter, WrapMode::Repeat};
                        SurfaceMaterial material;
                        material.pbr = &factors;
                        material.texture = &base;
                        material.maps[MapSlot::MetallicRoughness] = &mr;
                        DrawContext d{view, settings, mesh, mesh.indices.data(), &base, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                      Specular{}, 1.0f, false, true, {}};
                        d.linear = linear;
                        d.material = &material;
                        compareKernel<PbrProgram<true, false, true>>(isa, key, [&] { return PbrProgram<true, false, true>(&d); }, rng,
                                                                     totals);
                        SurfaceMaterial mapped = material;
                        mapped.maps[MapSlot::Normal] = &normals;
                        DrawContext dn = d;
                        dn.material = &mapped;
                        compareKernel<PbrProgram<true, true, true>>(isa, key, [&] { return PbrProgram<true, true, true>(&dn); }, rng,
                                                                    totals);
                        if (filter != TextureFilter::Bilinear) continue;
                        SurfaceMaterial plain;
                        plain.pbr = &factors;
                        DrawContext u{view, settings, mesh, mesh.indices.data(), nullptr, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                      Specular{}, depth == DepthMode::Test ? 0.4f : 1.0f, false, false, {}};
                        u.linear = linear;
                        u.material = &plain;
                        compareKernel<PbrProgram<false, false, true>>(isa, key, [&] { return PbrProgram<false, false, true>(&u); }, rng,
                                                                      totals);
                        // Unlit (KHR_materials_unlit, --shading unlit): kd x texel x colour, and kd x colour.
                        DrawContext lit = d;
                        lit.kd = {0.9f, 0.6f, 0.3f, 1.0f};
                        compareKernel<UnlitProgram<true, true>>(isa, key, [&] { return UnlitProgram<true, true>(&lit, 0); }, rng, totals);
                        compareKernel<UnlitProgram<false, true>>(isa, key, [&] { return UnlitProgram<false, true>(&u, 0); }, rng, totals);
                    }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 10000 * long(ran));
}

namespace {

// A cube-map sky of random 8 x 8 faces: every lookup of the image light's levels reads something different.
Sky randomCubeSky(std::mt19937& rng) {
    constexpr int kN = 8;
    std::vector<std::uint8_t> faces[kCubeFaces];
    for (auto& f : faces) {
        f.resize(std::size_t(kN) * kN * 4);
        for (auto& b : f) b = std::uint8_t(rng() & 0xFFu);
    }
    Sky sky;
    sky.kind = Sky::Kind::Cube;
    sky.cube = std::make_shared<const CubeMap>(CubeMap::fromRgba8(
        kN, {faces[0].data(), faces[1].data(), faces[2].data(), faces[3].data(), faces[4].data(), faces[5].data()}));
    return sky;
}

} // namespace

TEST_CASE("the pbr kernels with light from the sky (--ibl) and an occlusion map are bit-identical to the scalar program",
          "[threads][simd][kernels][pbr][ibl]") {
    std::mt19937 rng(41u);
    const Mesh mesh = oneTriangle();
    const ImageLight ibl(randomCubeSky(rng));
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.physical = true;
    view.lighting.ambient = 0.0f;
    view.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)), {kPiF, kPiF, kPiF, 1.0f})};
    view.ibl = &ibl;
    const Texture base = randomTexture(rng, 13, 7), mr = randomTexture(rng, 32, 16), occlusion = randomTexture(rng, 8, 4);
    const Texture normals = randomTexture(rng, 16, 8);
    PbrFactors rough, polished;
    rough.baseColor = {0.8f, 0.5f, 0.3f, 1.0f};
    rough.metallic = 0.2f;
    rough.roughness = 0.9f;
    rough.occlusionStrength = 0.6f;
    polished.baseColor = {1.0f, 0.8f, 0.4f, 1.0f};
    polished.metallic = 1.0f;
    polished.roughness = 0.03f;
    PbrFactors tinted = rough; // KHR_materials_ior / _specular, with their maps
    tinted.dielectricF0 = {0.11f, 0.06f, 0.3f};
    tinted.specularColorF0 = {0.11f, 0.06f, 3.0f};
    tinted.specularWeight = 0.55f;
    const Texture specularMap = randomTexture(rng, 8, 16), specularColour = randomTexture(rng, 16, 16);
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
            for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Trilinear})
                for (const bool linear : {true, false}) {
                    RenderSettings settings;
                    settings.filter = filter;
                    settings.perspective = persp;
                    settings.shading = ShadingMode::Pbr;
                    settings.colour = linear ? ColorMode::Linear : ColorMode::Gamma;
                    const KernelKey key{DepthMode::TestWrite, persp, filter, WrapMode::Repeat};
                    for (const PbrFactors* factors : {&rough, &polished, &tinted}) {
                        SurfaceMaterial material;
                        material.pbr = factors;
                        material.texture = &base;
                        material.maps[MapSlot::MetallicRoughness] = &mr;
                        material.maps[MapSlot::Occlusion] = &occlusion;
                        if (factors == &tinted) {
                            material.maps[MapSlot::Specular] = &specularMap;
                            material.maps[MapSlot::SpecularColour] = &specularColour;
                        }
                        DrawContext d{view, settings, mesh, mesh.indices.data(), &base, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                      Specular{}, 1.0f, false, true, {}};
                        d.linear = linear;
                        d.material = &material;
                        compareKernel<PbrProgram<true>>(isa, key, [&] { return PbrProgram<true>(&d); }, rng, totals);
                        SurfaceMaterial mapped = material;
                        mapped.maps[MapSlot::Normal] = &normals;
                        DrawContext dn = d;
                        dn.material = &mapped;
                        compareKernel<PbrProgram<true, true>>(isa, key, [&] { return PbrProgram<true, true>(&dn); }, rng, totals);
                        SurfaceMaterial plain;
                        plain.pbr = factors;
                        DrawContext u{view, settings, mesh, mesh.indices.data(), nullptr, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                      Specular{}, 1.0f, false, false, {}};
                        u.linear = linear;
                        u.material = &plain;
                        compareKernel<PbrProgram<false>>(isa, key, [&] { return PbrProgram<false>(&u); }, rng, totals);
                    }
                }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 20000 * long(ran));
}

TEST_CASE("the sRGB encoder's table: one midpoint per bucket at most, and the encoder exact for every float from 2^-13 to 1", "[threads][simd][colour]") {
    // The midpoints between bytes, as the piecewise curve defines them (srgbToLinear, ColorSpace.hpp).
    std::vector<float> mids(255);
    for (int k = 0; k < 255; ++k) mids[std::size_t(k)] = srgbToLinear(float((double(k) + 0.5) / 255.0));
    std::vector<int> perBucket(std::size_t(kSrgbEncodeBuckets), 0);
    for (float m : mids) {
        std::uint32_t bits;
        std::memcpy(&bits, &m, 4);
        REQUIRE(int(bits >> 16) >= kSrgbEncodeFirst); // every midpoint above 2^-13
        ++perBucket[std::size_t(int(bits >> 16) - kSrgbEncodeFirst)];
    }
    for (int i = 0; i < kSrgbEncodeBuckets; ++i) {
        INFO("bucket " << i);
        REQUIRE(perBucket[std::size_t(i)] <= 1);
    }
    // Exhaustive: every float in [2^-13, 1), walked in order with the count of midpoints below it
    // (the nearest byte; a float equal to a midpoint goes down), against encodeSrgb8.
    float l = std::ldexp(1.0f, -13);
    std::uint32_t bits;
    std::memcpy(&bits, &l, 4);
    std::size_t k = 0, wrong = 0;
    for (; l < 1.0f; ++bits, std::memcpy(&l, &bits, 4)) {
        while (k < mids.size() && mids[k] < l) ++k;
        if (encodeSrgb8(l) != k && wrong++ < 5) FAIL_CHECK("l " << l << " encodes to " << int(encodeSrgb8(l)) << ", not " << k);
    }
    REQUIRE(wrong == 0);
    REQUIRE(k == 255);
    // Below 2^-13: 0, at every power of two and a sample between.
    for (int e = -149; e < -13; ++e) {
        CHECK(encodeSrgb8(std::ldexp(1.0f, e)) == 0);
        CHECK(encodeSrgb8(std::ldexp(1.9f, e)) == 0);
    }
}

namespace {

// A shadow map whose depths are random, texel by texel (a quarter of them empty: kFarDepth),
// seen through `viewProj`, from `origin` along `axis`; `size` a whole number of tiles, as
// renderShadowMaps makes them (shadowMapSide).
ShadowMap randomMap(std::mt19937& rng, int size, const Mat4& viewProj, Vec3 origin, Vec3 axis, bool perspective, float nearZ,
                    float farZ, float texelWorld, float splitFar) {
    ShadowMap m;
    m.viewProj = viewProj;
    m.origin = origin;
    m.axis = axis;
    m.perspective = perspective;
    m.nearZ = nearZ;
    m.farZ = farZ;
    m.texelWorld = texelWorld;
    m.splitFar = splitFar;
    REQUIRE(size == shadowMapSide(size));
    m.target = FrameBuffer(size, size);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    float* depth = m.target.depthData(); // in tiles (ShadowMap::texelIndex): random either way
    for (std::size_t i = 0; i < std::size_t(size) * std::size_t(size); ++i) depth[i] = rng() % 4u == 0 ? FrameBuffer::kFarDepth : unit(rng);
    return m;
}

} // namespace

TEST_CASE("the pbr kernels with a clear coat (KHR_materials_clearcoat) are bit-identical to the scalar program",
          "[threads][simd][kernels][pbr][clearcoat]") {
    std::mt19937 rng(43u);
    const Mesh mesh = oneTriangle();
    const ImageLight ibl(randomCubeSky(rng));
    FrameView lightsOnly;
    lightsOnly.eye = {0.3f, 0.4f, 3.0f};
    lightsOnly.lighting.physical = true;
    lightsOnly.lighting.ambient = 0.0f;
    lightsOnly.lighting.lights = {Light::directional(normalize(Vec3(1, 1, 1)), {kPiF, kPiF, kPiF, 1.0f}),
                                  Light::point({0.5f, 1.0f, 2.0f}, {4.0f, 3.0f, 1.0f, 1.0f}, 3.5f),
                                  Light::spot({0.0f, 0.0f, 4.0f}, {0.1f, -0.2f, -1.0f}, {6.0f, 6.0f, 3.0f, 1.0f}, 0.2f, 0.6f, 9.0f)};
    FrameView withSky = lightsOnly;
    withSky.ibl = &ibl;
    const Texture base = randomTexture(rng, 13, 7), mr = randomTexture(rng, 32, 16), occlusion = randomTexture(rng, 8, 4);
    const Texture normals = randomTexture(rng, 16, 8), coatNormals = randomTexture(rng, 8, 16);
    const Texture coatMap = randomTexture(rng, 16, 4), coatRoughnessMap = randomTexture(rng, 4, 16);
    PbrFactors lacquer; // a coat over a rough coloured dielectric
    lacquer.baseColor = {0.8f, 0.1f, 0.1f, 1.0f};
    lacquer.metallic = 0.0f;
    lacquer.roughness = 0.7f;
    lacquer.emissive = {0.2f, 0.1f, 0.0f};
    lacquer.occlusionStrength = 0.6f;
    lacquer.clearcoat = 0.9f;
    lacquer.clearcoatRoughness = 0.15f;
    lacquer.clearcoatNormalScale = 0.6f;
    PbrFactors carPaint = lacquer; // a polished coat over a metal with KHR_materials_specular values
    carPaint.metallic = 0.8f;
    carPaint.roughness = 0.4f;
    carPaint.clearcoat = 1.0f;
    carPaint.clearcoatRoughness = 0.01f; // below the smallest roughness evaluated
    carPaint.dielectricF0 = {0.11f, 0.06f, 0.3f};
    carPaint.specularWeight = 0.55f;
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine})
            for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Trilinear})
                for (const bool linear : {true, false})
                    for (const FrameView* view : {&lightsOnly, &withSky}) {
                        RenderSettings settings;
                        settings.filter = filter;
                        settings.perspective = persp;
                        settings.shading = ShadingMode::Pbr;
                        settings.colour = linear ? ColorMode::Linear : ColorMode::Gamma;
                        const KernelKey key{DepthMode::TestWrite, persp, filter, WrapMode::Repeat};
                        for (const PbrFactors* factors : {&lacquer, &carPaint}) {
                            SurfaceMaterial material;
                            material.pbr = factors;
                            material.texture = &base;
                            material.maps[MapSlot::MetallicRoughness] = &mr;
                            material.maps[MapSlot::Occlusion] = &occlusion;
                            material.maps[MapSlot::Clearcoat] = &coatMap;
                            material.maps[MapSlot::ClearcoatRoughness] = &coatRoughnessMap;
                            DrawContext d{*view, settings, mesh, mesh.indices.data(), &base, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                          Specular{}, 1.0f, false, true, {}};
                            d.linear = linear;
                            d.material = &material;
                            compareKernel<PbrProgram<true>>(isa, key, [&] { return PbrProgram<true>(&d); }, rng, totals);
                            // The coat's own normal map, alone and over the base's.
                            SurfaceMaterial coatMapped = material;
                            coatMapped.maps[MapSlot::ClearcoatNormal] = &coatNormals;
                            DrawContext dc = d;
                            dc.material = &coatMapped;
                            compareKernel<PbrProgram<true, true>>(isa, key, [&] { return PbrProgram<true, true>(&dc); }, rng, totals);
                            SurfaceMaterial bothMapped = coatMapped;
                            bothMapped.maps[MapSlot::Normal] = &normals;
                            DrawContext db = d;
                            db.material = &bothMapped;
                            compareKernel<PbrProgram<true, true>>(isa, key, [&] { return PbrProgram<true, true>(&db); }, rng, totals);
                            SurfaceMaterial plain;
                            plain.pbr = factors;
                            DrawContext u{*view, settings, mesh, mesh.indices.data(), nullptr, Color{1.0f, 1.0f, 1.0f, 1.0f},
                                          Specular{}, 1.0f, false, false, {}};
                            u.linear = linear;
                            u.material = &plain;
                            compareKernel<PbrProgram<false>>(isa, key, [&] { return PbrProgram<false>(&u); }, rng, totals);
                        }
                    }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 20000 * long(ran));
}

TEST_CASE("the Phong kernels' shadow-map test is bit-identical to the scalar program's", "[threads][simd][kernels][shadow]") {
    std::mt19937 rng(17u);
    const Mesh mesh = oneTriangle();
    // Lights: a white directional light with three cascades of different sizes, a spot with a
    // perspective map, a point light (no map) and a coloured directional light with one map. The
    // varyings' positions in [-3, 3] fall on and off the maps, in front of and behind their
    // random casters.
    const Vec3 sun = normalize(Vec3(1, 1, 1)), sky = normalize(Vec3(-0.3f, 0.2f, 1.0f));
    const Vec3 spotAt{0.0f, 0.0f, 4.0f}, spotDir = normalize(Vec3(0.1f, -0.2f, -1.0f));
    FrameView view;
    view.eye = {0.3f, 0.4f, 3.0f};
    view.lighting.lights = {Light::directional(sun), Light::spot(spotAt, spotDir, {6.0f, 6.0f, 3.0f, 1.0f}, 0.2f, 0.6f, 9.0f),
                            Light::point({0.5f, 1.0f, 2.0f}, {4.0f, 3.0f, 1.0f, 1.0f}, 3.5f),
                            Light::directional(sky, {1.0f, 0.5f, 0.25f, 1.0f})};
    FrameView whiteView = view; // one white directional light: the kernels' white path must not be taken
    whiteView.lighting.lights = {Light::directional(sun)};
    REQUIRE(whiteView.lighting.whiteDirectional());

    SceneShadows shadows;
    shadows.eye = view.eye;
    shadows.forward = normalize(Vec3(-0.1f, -0.1f, -1.0f));
    auto directional = [&](Vec3 toLight, float extent, int size, float splitFar) {
        const Vec3 origin = toLight * 6.0f;
        const Mat4 vp = orthographic(-extent, extent, -extent, extent, 0.0f, 12.0f) * lookAt(origin, Vec3{}, Vec3(0, 1, 0));
        return randomMap(rng, size, vp, origin, toLight * -1.0f, false, 0.0f, 12.0f, 2.0f * extent / float(size), splitFar);
    };
    shadows.maps.push_back(directional(sun, 2.0f, 32, 1.5f));
    shadows.maps.push_back(directional(sun, 3.0f, 64, 3.5f));
    shadows.maps.push_back(directional(sun, 4.5f, 96, 1e30f));
    shadows.maps.push_back(randomMap(rng, 32, perspective(1.2f, 1.0f, 0.5f, 20.0f) * lookAt(spotAt, spotAt + spotDir, Vec3(0, 1, 0)),
                                     spotAt, spotDir, true, 0.5f, 20.0f, 2.0f * std::tan(0.6f) / 32.0f, 0.0f));
    shadows.maps.push_back(directional(sky, 3.5f, 64, 0.0f));
    shadows.firstMap = {0, 3, 0, 4};
    shadows.mapCount = {3, 1, 0, 1};
    view.shadows = &shadows;
    whiteView.shadows = &shadows;

    // The maps shadow some points fully, some partly (PCF) and leave some lit: the test sees all three.
    {
        std::uniform_real_distribution<float> coord(-3.0f, 3.0f);
        int none = 0, partial = 0, full = 0;
        for (int i = 0; i < 4000; ++i) {
            const Vec3 p{coord(rng), coord(rng), coord(rng)}, n = normalize(Vec3{coord(rng), coord(rng), coord(rng)});
            for (std::size_t light : {std::size_t(0), std::size_t(1), std::size_t(3)}) {
                const Vec3 l = light == 1 ? normalize(spotAt - p) : view.lighting.lights[light].toLight;
                const float seen = shadows.visibility(light, p, n, l);
                (seen == 0.0f ? none : seen == 1.0f ? full : partial) += 1;
            }
        }
        INFO("unlit " << none << ", partly lit " << partial << ", lit " << full);
        CHECK(none > 20);
        CHECK(partial > 500);
        CHECK(full > 500);
    }

    Specular coloured;
    coloured.ks = {0.3f, 0.6f, 0.1f};
    coloured.shininess = 7.0f;
    const Texture texture = randomTexture(rng, 13, 7);
    struct Variant {
        int pcf;
        float constantBias, slopeBias;
    };
    Totals totals;
    int ran = 0;
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        ++ran;
        for (const Variant& variant : {Variant{1, 1.0f, 1.0f}, Variant{3, 0.5f, 2.0f}, Variant{5, 0.0f, 0.0f}}) {
            shadows.settings.pcf = variant.pcf;
            shadows.settings.constantBias = variant.constantBias;
            shadows.settings.slopeBias = variant.slopeBias;
            for (DepthMode depth : {DepthMode::Test, DepthMode::TestWrite})
                for (PerspectiveMode persp : {PerspectiveMode::Exact, PerspectiveMode::Affine}) {
                    RenderSettings settings;
                    settings.perspective = persp;
                    const KernelKey key{depth, persp, TextureFilter::Bilinear, WrapMode::Repeat};
                    for (const Specular& specular : {Specular{}, coloured}) {
                        const DrawContext lit{view, settings, mesh, mesh.indices.data(), &texture, Color{0.7f, 0.4f, 0.2f, 1.0f},
                                              specular, 1.0f, false, true, {}};
                        compareKernel<PhongProgram<true>>(isa, key, [&] { return PhongProgram<true>(&lit); }, rng, totals);
                        compareKernel<PhongProgram<false>>(isa, key, [&] { return PhongProgram<false>(&lit); }, rng, totals);
                        const DrawContext white{whiteView, settings, mesh, mesh.indices.data(), nullptr,
                                                Color{0.7f, 0.4f, 0.2f, 1.0f}, specular, 1.0f, true, true, {}};
                        compareKernel<PhongProgram<false>>(isa, key, [&] { return PhongProgram<false>(&white); }, rng, totals);
                    }
                }
        }
    }
    REQUIRE(ran > 0);
    CHECK(totals.pixels > 10000 * long(ran));
}

TEST_CASE("the scalar ISA has no kernel: the reference loop fills", "[threads][simd][kernels]") {
    const KernelKey exact{DepthMode::TestWrite, PerspectiveMode::Exact, TextureFilter::Bilinear, WrapMode::Repeat};
    CHECK(selectFillKernel<PhongProgram<true>>(Isa::Scalar, exact) == nullptr);
    for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
        if (!isaAvailable(isa)) continue;
        CHECK(selectFillKernel<PhongProgram<true>>(isa, exact) != nullptr);
    }
}

TEST_CASE("ISA names parse and print; auto is the best available one", "[threads][simd][kernels]") {
    for (Isa isa : kAllIsas) CHECK(parseIsa(isaName(isa)) == isa);
    CHECK(parseIsa("auto") == bestIsa());
    CHECK(!parseIsa("AVX2").has_value());
    CHECK(!parseIsa("neon").has_value());
    CHECK(isaAvailable(bestIsa()));
    CHECK(isaAvailable(Isa::Scalar));
}
