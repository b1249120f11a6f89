// The fast paths against their references: per-vertex clip codes vs classify, cull-in-setup vs isCulled, inline and SSE2 shading vs scalar.
#include "TestFramework.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "Math/Vec.hpp"
#include "Raster/Clipper.hpp"
#include "Raster/Cull.hpp"
#include "Raster/ScanlineFill.hpp"
#include "Raster/ShadingSimd.hpp"
#include "Raster/TriangleSetup.hpp"

using namespace sr;

namespace {

// Random clip-space positions: mostly in and around the view volume, some behind the eye,
// some far outside the guard band, some exactly on planes, a few non-finite.
Vec4 randomPosition(std::mt19937& rng) {
    std::uniform_int_distribution<int> kind(0, 19);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f), w(0.01f, 5.0f), big(-1e6f, 1e6f);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float ww = w(rng);
    switch (kind(rng)) {
    case 0: return {big(rng), big(rng), u(rng), w(rng)};              // past the guard band
    case 1: return {u(rng), u(rng), u(rng), -ww};                     // behind the eye
    case 2: return {ww, -ww, ww, ww};                                 // on x = w, y = -w, z = w
    case 3: return {u(rng), u(rng), 0.0f, 0.0f};                      // w = 0
    case 4: return {u(rng), nan, u(rng), ww};                         // NaN
    case 5: return {inf, u(rng), u(rng), ww};                         // Inf
    case 6: return {u(rng) * ww, u(rng) * ww, -0.1f * ww, ww};        // past the far plane
    case 7: return {u(rng) * ww, u(rng) * ww, 1.0f * ww, ww};         // on the near plane
    case 8: return {u(rng) * 1e-13f, u(rng) * 1e-13f, 0.0f, 1e-13f};  // below kClipMinW
    default: return {u(rng) * ww, u(rng) * ww, std::fabs(u(rng)) * 0.7f * ww, ww};
    }
}

} // namespace

TEST_CASE("per-vertex clip codes classify exactly like the per-triangle classify", "[threads][clip]") {
    std::mt19937 rng(42);
    const int sizes[][2] = {{800, 600}, {1920, 1080}, {1, 1}, {0, 600}, {800, 0}, {8192, 17}};
    for (const auto& size : sizes) {
        for (bool clipFar : {false, true}) {
            ClipParams params;
            params.viewportWidth = size[0];
            params.viewportHeight = size[1];
            params.clipFar = clipFar;
            const Clipper clipper(params);
            int counts[3] = {};
            for (int i = 0; i < 20000; ++i) {
                ClipVertex a, b, c;
                a.position = randomPosition(rng);
                b.position = randomPosition(rng);
                c.position = randomPosition(rng);
                const ClipClass expected = clipper.classify(a, b, c);
                const ClipClass actual = clipper.classifyCodes(clipper.vertexCode(a.position), clipper.vertexCode(b.position),
                                                               clipper.vertexCode(c.position));
                if (expected != actual) {
                    INFO(size[0] << "x" << size[1] << " far " << clipFar << " triangle " << i);
                    REQUIRE(int(expected) == int(actual));
                }
                ++counts[int(expected)];
                // The non-finite bit is exactly "some component is NaN or Inf".
                CHECK(((clipper.vertexCode(a.position) & kCodeNonFinite) != 0) == !isFinite(a.position));
            }
            if (size[0] > 0 && size[1] > 0) {
                CHECK(counts[int(ClipClass::Accept)] > 100);
                CHECK(counts[int(ClipClass::Clip)] > 100);
            }
            CHECK(counts[int(ClipClass::Reject)] > 100);
        }
    }
}

TEST_CASE("cull in setup decides exactly like isCulled and builds the same record", "[threads][cull]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-40.0f, 840.0f), small(-2.0f, 2.0f), attr(0.0f, 1.0f);
    std::uniform_int_distribution<int> kind(0, 9);
    auto vertex = [&](float x, float y) {
        ScreenVertex v;
        v.x = x;
        v.y = y;
        v.z = attr(rng);
        v.invW = 0.5f + attr(rng);
        for (int k = 0; k < 4; ++k) v.varyings[std::size_t(k)] = attr(rng);
        return v;
    };
    int outcomes[3] = {};
    for (int i = 0; i < 60000; ++i) {
        ScreenVertex v[3];
        const int k = kind(rng);
        const float bx = coord(rng), by = coord(rng);
        for (auto& p : v) {
            if (k < 4) p = vertex(bx + small(rng), by + small(rng));               // tiny: often empty or degenerate
            else if (k == 4) p = vertex(std::round(bx), std::round(by) + small(rng)); // near-collinear
            else p = vertex(coord(rng), coord(rng));
        }
        if (k == 5) v[2] = v[1];                                                 // coincident
        if (k == 6) v[2].x = v[0].x + (v[1].x - v[0].x) * 2.0f, v[2].y = v[0].y + (v[1].y - v[0].y) * 2.0f;
        for (CullMode mode : {CullMode::None, CullMode::CW, CullMode::CCW}) {
            for (bool persp : {true, false}) {
                TriangleSetup record;
                const SetupOutcome outcome = setupTriangleCulled(record, v[0], v[1], v[2], mode, 4, persp);
                ++outcomes[int(outcome)];
                const bool culled = isCulled(mode, v[0], v[1], v[2]);
                REQUIRE((outcome == SetupOutcome::Culled) == culled);
                if (culled) continue;
                const auto reference = setupTriangle(v[0], v[1], v[2], 4, persp);
                REQUIRE(reference.has_value() == (outcome == SetupOutcome::Ready));
                if (!reference) continue;
                CHECK(record.doubleArea == reference->doubleArea);
                CHECK(record.firstRow == reference->firstRow);
                CHECK(record.midRow == reference->midRow);
                CHECK(record.endRow == reference->endRow);
                CHECK(record.minX == reference->minX);
                CHECK(record.maxX == reference->maxX);
                CHECK(record.longEdgeOnLeft == reference->longEdgeOnLeft);
                CHECK(std::memcmp(&record.longEdge, &reference->longEdge, sizeof(FixedEdge)) == 0);
                CHECK(std::memcmp(record.ddx, reference->ddx, sizeof record.ddx) == 0);
                CHECK(std::memcmp(record.ddy, reference->ddy, sizeof record.ddy) == 0);
                CHECK(std::memcmp(record.value, reference->value, sizeof record.value) == 0);
            }
        }
    }
    CHECK(outcomes[int(SetupOutcome::Ready)] > 1000);
    CHECK(outcomes[int(SetupOutcome::Culled)] > 1000);
    CHECK(outcomes[int(SetupOutcome::Empty)] > 100);
}

TEST_CASE("normalize's inline fast path is bit-identical to the robust path", "[threads][math]") {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_int_distribution<int> e(-60, 60);
    for (int i = 0; i < 200000; ++i) {
        const float s = std::ldexp(1.0f, e(rng));
        const Vec3 v{u(rng) * s, u(rng) * s, (i % 5 == 0) ? 0.0f : u(rng) * s};
        const Vec3 a = normalize(v), b = normalizeRobust(v);
        REQUIRE(std::memcmp(&a, &b, sizeof a) == 0);
    }
    const float inf = std::numeric_limits<float>::infinity();
    for (const Vec3 v : {Vec3{0, 0, 0}, Vec3{inf, 1, 0}, Vec3{3e38f, 3e38f, 3e38f}, Vec3{1e-45f, 0, 0}}) {
        const Vec3 a = normalize(v), b = normalizeRobust(v);
        CHECK(std::memcmp(&a, &b, sizeof a) == 0);
    }
}

#if SR_HAVE_SSE2
TEST_CASE("SSE2 Blinn-Phong of four pixels is bit-identical to the scalar shading", "[threads][simd]") {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_int_distribution<int> e(-40, 40), special(0, 15);
    Lighting lighting;
    lighting.toLight = {normalize(Vec3(1, 1, 1)), normalize(Vec3(-0.3f, 0.2f, 1.0f))};
    const Color kd{0.8f, 0.55f, 0.3f, 1.0f};
    int simdLanes = 0;
    for (int i = 0; i < 50000; ++i) {
        float nx[4], ny[4], nz[4], vx[4], vy[4], vz[4];
        for (int l = 0; l < 4; ++l) {
            const float s = std::ldexp(1.0f, e(rng));
            nx[l] = u(rng) * s, ny[l] = u(rng) * s, nz[l] = u(rng) * s;
            vx[l] = u(rng), vy[l] = u(rng), vz[l] = u(rng);
            if (special(rng) == 0) nx[l] = ny[l] = nz[l] = 0.0f; // zero normal: robust path
            if (special(rng) == 0) vx[l] = -lighting.toLight[0].x, vy[l] = -lighting.toLight[0].y,
                                   vz[l] = -lighting.toLight[0].z; // L + V = 0 before normalising v
        }
        __m128 ok = _mm_castsi128_ps(_mm_set1_epi32(-1));
        const simd::Vec3x4 n = simd::normalizeFast(simd::load3(nx, ny, nz), ok);
        const simd::Vec3x4 v = simd::normalizeFast(simd::load3(vx, vy, vz), ok);
        std::uint32_t out[4];
        REQUIRE(simd::shadeBlinnPhong(lighting, kd, n, v, ok, out));
        const int good = _mm_movemask_ps(ok);
        for (int l = 0; l < 4; ++l) {
            if (!(good & (1 << l))) continue;
            ++simdLanes;
            const LightTerms t = blinnPhong(lighting, normalize(Vec3{nx[l], ny[l], nz[l]}), normalize(Vec3{vx[l], vy[l], vz[l]}));
            REQUIRE(out[l] == packBgra8(applyTerms(kd, t)));
        }
    }
    CHECK(simdLanes > 150000);
}
#endif

#if SR_HAVE_SSE2
namespace {

// A pixel value that depends on every bit a fragment carries (position, 1/w, each varying), so
// two fills agree on the colour buffer only if they hand identical fragments to the shader.
std::uint32_t mixBits(std::uint32_t h, std::uint32_t v) {
    h ^= v + 0x9E3779B9u + (h << 6) + (h >> 2);
    return h;
}
std::uint32_t bitsOf(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}
template <int kV>
struct HashProgram {
    std::uint32_t hash(int x, int y, float invW, const float* v, int stride) const {
        std::uint32_t h = mixBits(std::uint32_t(x), std::uint32_t(y));
        h = mixBits(h, bitsOf(invW));
        for (int k = 0; k < kV; ++k) h = mixBits(h, bitsOf(v[k * stride]));
        return h;
    }
    void fragment4(const FragmentBatch<kV>& b, Pixel out[4]) const {
        for (int i = 0; i < 4; ++i) out[i] = hash(b.x[i], b.y[i], b.invW[i], &b.v[0][i], 4);
    }
#if SR_HAVE_AVX2
    void fragment8(const FragmentBatch8<kV>& b, Pixel out[8]) const {
        for (int i = 0; i < 8; ++i) out[i] = hash(b.x[i], b.y[i], b.invW[i], &b.v[0][i], 8);
    }
#endif
};

template <DepthMode kDepth, PerspectiveMode kPersp>
void compareFills(std::mt19937& rng, long& pixels, bool eightWide = false) {
    constexpr int kV = 5;
    std::uniform_real_distribution<float> pos(-20.0f, 84.0f), small(0.0f, 4.0f), unit(0.0f, 1.0f), var(-50.0f, 50.0f);
    const int w = 64, h = 48;
    FrameBuffer ref(w, h), simd(w, h);
    for (int trial = 0; trial < 300; ++trial) {
        // Random depth already in the buffers (some fragments pass, some fail, some tie).
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::uint32_t r = rng() % 4u;
                const float d = r == 0 ? 0.0f : r == 1 ? 0.5f : unit(rng);
                ref.depthRow(y)[x] = simd.depthRow(y)[x] = d;
                ref.colorRow(y)[x] = simd.colorRow(y)[x] = 0x12345678u;
            }
        for (int tri = 0; tri < 8; ++tri) {
            ScreenVertex v[3];
            const bool tiny = rng() % 3u == 0; // spans of 1-3 pixels, the tail lanes
            const bool flat = rng() % 6u == 0; // z = 0.5 everywhere: exact ties with the buffer
            const float cx = pos(rng), cy = pos(rng);
            for (auto& p : v) {
                p.x = tiny ? cx + small(rng) : pos(rng);
                p.y = tiny ? cy + small(rng) : pos(rng);
                p.z = unit(rng);
                if (flat) p.z = 0.5f;
                p.invW = std::exp2(std::uniform_real_distribution<float>(-6.0f, 2.0f)(rng));
                for (int k = 0; k < kV; ++k) p.varyings[std::size_t(k)] = var(rng);
            }
            const auto setup = setupTriangle(v[0], v[1], v[2], kV, kPersp != PerspectiveMode::Affine);
            if (!setup) continue;
            const Scissor sc = rng() % 2u ? Scissor{0, 0, w, h}
                                          : Scissor{int(rng() % 20u), int(rng() % 20u), 30 + int(rng() % 34u), 25 + int(rng() % 23u)};
            HashProgram<kV> program;
            std::uint64_t shadedRef = 0, shadedSimd = 0;
            fillTriangle<kDepth, kV, kPersp>(*setup, ref, sc, [&](const Fragment<kV>& f) {
                ++shadedRef;
                return program.hash(f.x, f.y, f.invW, f.varyings.data(), 1);
            });
#if SR_HAVE_AVX2
            if (eightWide) fillTriangle8<kDepth, kV, kPersp>(*setup, simd, sc, program, shadedSimd);
            else
#endif
                fillTriangle4<kDepth, kV, kPersp>(*setup, simd, sc, program, shadedSimd);
            (void)eightWide;
            REQUIRE(shadedSimd == shadedRef);
            pixels += long(shadedRef);
        }
        for (int y = 0; y < h; ++y) {
            REQUIRE(std::memcmp(ref.colorRow(y), simd.colorRow(y), sizeof(Pixel) * std::size_t(w)) == 0);
            REQUIRE(std::memcmp(ref.depthRow(y), simd.depthRow(y), sizeof(float) * std::size_t(w)) == 0);
        }
    }
}

} // namespace

TEST_CASE("the four-pixel span loop hands fragment4 exactly the one-pixel loop's fragments", "[threads][simd][fill]") {
    std::mt19937 rng(8u);
    long pixels = 0;
    compareFills<DepthMode::TestWrite, PerspectiveMode::Exact>(rng, pixels);
    compareFills<DepthMode::Test, PerspectiveMode::Exact>(rng, pixels);
    compareFills<DepthMode::Off, PerspectiveMode::Exact>(rng, pixels);
    compareFills<DepthMode::TestWrite, PerspectiveMode::Affine>(rng, pixels);
    compareFills<DepthMode::Off, PerspectiveMode::Affine>(rng, pixels);
    CHECK(pixels > 100000);
}
#endif

#if SR_HAVE_AVX2
TEST_CASE("the eight-pixel AVX2 span loop hands fragment8 exactly the one-pixel loop's fragments", "[threads][simd][fill][avx2]") {
    if (!cpuHasAvx2()) {
        WARN("no AVX2 on this CPU (or SR_NO_AVX2 set): not tested");
        return;
    }
    std::mt19937 rng(9u);
    long pixels = 0;
    compareFills<DepthMode::TestWrite, PerspectiveMode::Exact>(rng, pixels, true);
    compareFills<DepthMode::Test, PerspectiveMode::Exact>(rng, pixels, true);
    compareFills<DepthMode::Off, PerspectiveMode::Exact>(rng, pixels, true);
    compareFills<DepthMode::TestWrite, PerspectiveMode::Affine>(rng, pixels, true);
    compareFills<DepthMode::Off, PerspectiveMode::Affine>(rng, pixels, true);
    CHECK(pixels > 100000);
}

TEST_CASE("AVX2 Blinn-Phong of eight pixels is bit-identical to the scalar shading", "[threads][simd][avx2]") {
    if (!cpuHasAvx2()) {
        WARN("no AVX2 on this CPU (or SR_NO_AVX2 set): not tested");
        return;
    }
    std::mt19937 rng(2025);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), c(-0.2f, 1.2f);
    std::uniform_int_distribution<int> e(-40, 40), special(0, 15);
    Lighting lighting;
    lighting.toLight = {normalize(Vec3(1, 1, 1)), normalize(Vec3(-0.3f, 0.2f, 1.0f))};
    int simdLanes = 0;
    for (int i = 0; i < 30000; ++i) {
        alignas(32) float nx[8], ny[8], nz[8], vx[8], vy[8], vz[8], kr[8], kg[8], kb[8];
        for (int l = 0; l < 8; ++l) {
            const float s = std::ldexp(1.0f, e(rng));
            nx[l] = u(rng) * s, ny[l] = u(rng) * s, nz[l] = u(rng) * s;
            vx[l] = u(rng), vy[l] = u(rng), vz[l] = u(rng);
            kr[l] = c(rng), kg[l] = c(rng), kb[l] = c(rng);
            if (special(rng) == 0) nx[l] = ny[l] = nz[l] = 0.0f;
            if (special(rng) == 0) vx[l] = -lighting.toLight[0].x, vy[l] = -lighting.toLight[0].y,
                                   vz[l] = -lighting.toLight[0].z;
        }
        std::uint32_t out[8];
        int good = 0;
        [&]() SR_TARGET_AVX2 {
            __m256 ok = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
            const simd8::Vec3x8 n = simd8::normalizeFast({_mm256_load_ps(nx), _mm256_load_ps(ny), _mm256_load_ps(nz)}, ok);
            const simd8::Vec3x8 v = simd8::normalizeFast({_mm256_load_ps(vx), _mm256_load_ps(vy), _mm256_load_ps(vz)}, ok);
            REQUIRE(simd8::shadeBlinnPhong(lighting, _mm256_load_ps(kr), _mm256_load_ps(kg), _mm256_load_ps(kb), n, v, ok, out));
            good = _mm256_movemask_ps(ok);
        }();
        for (int l = 0; l < 8; ++l) {
            if (!(good & (1 << l))) continue;
            ++simdLanes;
            const LightTerms t = blinnPhong(lighting, normalize(Vec3{nx[l], ny[l], nz[l]}), normalize(Vec3{vx[l], vy[l], vz[l]}));
            REQUIRE(out[l] == packBgra8(applyTerms(Color{kr[l], kg[l], kb[l], 1.0f}, t)));
        }
    }
    CHECK(simdLanes > 150000);
}
#endif
