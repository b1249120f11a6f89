// Blinn-Phong (Raster/Shade/Shading.hpp) against values worked out by hand, and one lit quad end to end.
#include "TestFramework.hpp"

#include <cmath>
#include <cstdint>

#include "Math/Transform.hpp"
#include "Raster/Frame/MeshRenderer.hpp"
#include "Raster/Shade/Shading.hpp"

using namespace sr;

// All cases use the reference constants unless stated: ambient 0.1, ks 0.5, shininess 32
// (shared/tools/llvmpipe-ref/README.md "Shading"):
//   diffuse  = 0.1 + sum_l max(N.L_l, 0)
//   specular = sum_l (N.L_l > 0 ? max(N.H_l, 0)^32 : 0),  H = normalize(L + V)
//   colour   = kd * diffuse + ks * specular (applyTerms)
// N = +Z throughout, so N.X is just X.z.
namespace {

Lighting oneLight(Vec3 toLight) {
    Lighting l;
    l.lights = {Light::directional(toLight)};
    return l;
}

constexpr Vec3 kN{0.0f, 0.0f, 1.0f};
const Specular kRef; // ks 0.5 white, shininess 32

Specular withShininess(float s) {
    Specular sp;
    sp.shininess = s;
    return sp;
}

// A unit quad at z = 0 facing +Z (two counter-clockwise triangles seen from +Z), normals +Z.
Mesh unitQuad() {
    Mesh quad;
    quad.positions = {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}};
    quad.normals.assign(4, {0.0f, 0.0f, 1.0f});
    quad.indices = {0, 1, 2, 0, 2, 3};
    return quad;
}

// The view from (0, 0, eyeZ) toward the origin with a 1.5 degree field of view (the unit quad
// fills most of a square target from |eyeZ| = 50), no far plane, the default lighting.
FrameView viewAlongZ(float eyeZ) {
    FrameView view;
    view.eye = {0.0f, 0.0f, eyeZ};
    view.viewProj = perspectiveInfinite(radians(1.5f), 1.0f, 1.0f) * lookAt(view.eye, {0, 0, 0}, {0, 1, 0});
    view.finiteFar = false;
    return view;
}

} // namespace

TEST_CASE("Blinn-Phong: light straight on, viewer straight on", "[render][shading]") {
    // L = V = N: N.L = 1, H = N, N.H = 1 -> diffuse 0.1 + 1 = 1.1, specular 1^32 = 1.
    const LightTerms t = blinnPhong(oneLight(kN), kRef, kN, kN);
    CHECK(t.diffuse == Approx(1.1f).margin(1e-7));
    CHECK(t.specular == 1.0f);
}

TEST_CASE("Blinn-Phong: grazing light, N.L = 1e-3 and exactly 0", "[render][shading]") {
    SECTION("N.L = 1e-3") {
        // L = (sqrt(1 - 1e-6), 0, 1e-3), V = N.
        // diffuse = 0.1 + 0.001 = 0.101.
        // L + V = (0.9999995, 0, 1.001); |L + V|^2 = (1 - 1e-6) + 1.002001 = 2.002 (exactly).
        // N.H^2 = 1.001^2 / 2.002 = 1.002001 / 2.002 = 0.5005, so N.H^32 = 0.5005^16
        //       = 2^-16 * 1.001^16 = 1.52587890625e-5 * 1.0160120... = 1.5504769e-5 = specular.
        const Vec3 l{std::sqrt(1.0f - 1e-6f), 0.0f, 1e-3f};
        const LightTerms t = blinnPhong(oneLight(l), kRef, kN, kN);
        CHECK(t.diffuse == Approx(0.101).epsilon(1e-6));
        // Relative 1e-4: float rounding of N.H (~1e-7 relative) grows 32x through the power.
        CHECK(t.specular == Approx(1.5504769e-5).epsilon(1e-4));
    }
    SECTION("N.L = 0 exactly: no diffuse and no specular, although N.H = 0.707") {
        // L = +X, V = N: N.L = 0 -> the one-sided rule drops the light entirely. Without it the
        // specular would be (1/sqrt 2)^32 = 2^-16 = 1.53e-5 (a non-zero value).
        const LightTerms t = blinnPhong(oneLight({1.0f, 0.0f, 0.0f}), kRef, kN, kN);
        CHECK(t.diffuse == 0.1f);
        CHECK(t.specular == 0.0f);
    }
}

TEST_CASE("Blinn-Phong: light behind the surface gives ambient only", "[render][shading]") {
    SECTION("light straight behind (L + V = 0 never normalised)") {
        // L = -N, V = N: N.L = -1 -> diffuse 0.1, specular 0 (and no NaN from normalize(0)).
        const LightTerms t = blinnPhong(oneLight({0.0f, 0.0f, -1.0f}), kRef, kN, kN);
        CHECK(t.diffuse == 0.1f);
        CHECK(t.specular == 0.0f);
    }
    SECTION("light just behind, half vector well in front") {
        // L = normalize(1, 0, -0.01) = (0.99995, 0, -0.0099995): N.L = -0.0099995 < 0.
        // V = (-0.9, 0, sqrt(0.19)) = (-0.9, 0, 0.4358899).
        // L + V = (0.09995, 0, 0.4258904) -> N.H = 0.4258904 / 0.4374617 = 0.9735493, and
        // 0.9735493^32 = 0.424086: without the one-sided rule that would be the specular.
        const Vec3 l = normalize(Vec3{1.0f, 0.0f, -0.01f});
        const Vec3 v{-0.9f, 0.0f, std::sqrt(0.19f)};
        const LightTerms t = blinnPhong(oneLight(l), kRef, kN, v);
        CHECK(t.diffuse == 0.1f);
        CHECK(t.specular == 0.0f);
    }
}

TEST_CASE("Blinn-Phong: zero specular", "[render][shading]") {
    SECTION("N.H^32 underflows to 0 in float") {
        // e = 0.02, s = sqrt(1 - e^2) = 0.9997999: L = (s, 0, e), V = (0, s, e); N.L = 0.02 > 0.
        // L + V = (s, s, 2e); |L + V|^2 = 2 s^2 + 4 e^2 = 1.9992 + 0.0016 = 2.0008
        // N.H = 0.04 / sqrt(2.0008) = 0.04 / 1.4144964 = 0.0282786
        // N.H^32 = (N.H^2)^16 = (7.99680e-4)^16 = 2.8e-50 < 2^-149 (1.4e-45, the smallest float):
        // the repeated squaring underflows to exactly 0. diffuse = 0.1 + 0.02 = 0.12.
        const float e = 0.02f, s = std::sqrt(1.0f - e * e);
        const LightTerms t = blinnPhong(oneLight({s, 0.0f, e}), kRef, kN, {0.0f, s, e});
        CHECK(t.diffuse == Approx(0.12).epsilon(1e-6));
        CHECK(t.specular == 0.0f);
        // The same through std::pow (non-integer shininess): 0.0282786^31.5 = 1.7e-49 -> 0.
        CHECK(blinnPhong(oneLight({s, 0.0f, e}), withShininess(31.5f), kN, {0.0f, s, e}).specular == 0.0f);
    }
    SECTION("ks black: no specular term") {
        // L = V = N: diffuse 1.1 as before; N.H = 1 would give 1^32 = 1, but the term is off.
        Specular black;
        black.ks = {0.0f, 0.0f, 0.0f};
        CHECK_FALSE(black.on());
        const LightTerms t = blinnPhong(oneLight(kN), black, kN, kN);
        CHECK(t.diffuse == Approx(1.1f).margin(1e-7));
        CHECK(t.specular == 0.0f);
        // One channel of ks is enough to keep it (ks = (0, 0, 0.25): specular 1).
        black.ks.b = 0.25f;
        CHECK(blinnPhong(oneLight(kN), black, kN, kN).specular == 1.0f);
    }
    SECTION("shininess 0 or below (MTL Ns 0): no specular term, although x^0 = 1 everywhere") {
        // V far from H: N.H = 0.9 (as below), 0.9^0 = 1 would light the pixel with ks; the
        // reference draws no specular term for Ns <= 0.
        for (const float s : {0.0f, -3.0f}) {
            INFO("shininess " << s);
            CHECK_FALSE(withShininess(s).on());
            const LightTerms t = blinnPhong(oneLight(kN), withShininess(s), kN, {0.7846018f, 0.0f, 0.62f});
            CHECK(t.diffuse == Approx(1.1f).margin(1e-7));
            CHECK(t.specular == 0.0f);
        }
        CHECK(shininessPow(0.9f, 0.0f) == 1.0f); // what the rule avoids
    }
}

TEST_CASE("Blinn-Phong: very high and non-integer shininess", "[render][shading]") {
    SECTION("shininess 1000 (repeated squaring)") {
        // L = N and V at angle b from N: H = normalize(N + V) bisects them, N.H = cos(b / 2).
        // Choose cos(b/2) = 0.999: cos b = 2 * 0.999^2 - 1 = 0.996002,
        // sin b = 2 sin(b/2) cos(b/2) = 2 * sqrt(1 - 0.998001) * 0.999 = 2 * 0.0447102 * 0.999
        //       = 0.0893309. V = (0.0893309, 0, 0.996002).
        // 0.999^1000 = exp(1000 ln 0.999) = exp(1000 * -0.00100050033) = exp(-1.0005003) = 0.3676954
        // = specular; diffuse = 0.1 + 1 = 1.1.
        const LightTerms t = blinnPhong(oneLight(kN), withShininess(1000.0f), kN, {0.0893309f, 0.0f, 0.996002f});
        CHECK(t.diffuse == Approx(1.1f).margin(1e-7));
        // Relative 1e-3: an error of 1e-7 in N.H (float rounding of V, H) grows 1000x.
        CHECK(t.specular == Approx(0.3676954).epsilon(1e-3));
    }
    SECTION("shininess 31.5 (std::pow), between the 31st and 32nd powers") {
        // N.H = 0.9 exactly as in the 1000 case: cos(b/2) = 0.9 -> cos b = 2 * 0.81 - 1 = 0.62,
        // sin b = 2 * sqrt(0.19) * 0.9 = 2 * 0.4358899 * 0.9 = 0.7846018.
        // 0.9^31.5 = exp(31.5 * ln 0.9) = exp(31.5 * -0.1053605) = exp(-3.3188556) = 0.0361942
        // (between 0.9^32 = 0.0343368 and 0.9^31 = 0.0381520: neither truncated nor rounded).
        // = specular.
        const LightTerms t = blinnPhong(oneLight(kN), withShininess(31.5f), kN, {0.7846018f, 0.0f, 0.62f});
        CHECK(t.specular == Approx(0.0361942).epsilon(1e-4));
        CHECK(shininessPow(0.9f, 31.5f) == Approx(0.0361942).epsilon(1e-5));
        CHECK(shininessPow(0.9f, 31.5f) > shininessPow(0.9f, 32.0f));
        CHECK(shininessPow(0.9f, 31.5f) < shininessPow(0.9f, 31.0f));
    }
}

TEST_CASE("Blinn-Phong: several lights add up, and the pixel they make", "[render][shading]") {
    // V = N and three lights:
    //  L1 = N:            N.L = 1,   H = N, N.H = 1                        -> spec 1
    //  L2 = (0.6, 0, 0.8): N.L = 0.8, L2 + V = (0.6, 0, 1.8), N.H = 1.8 / sqrt(3.6) = 3 / sqrt 10,
    //                     N.H^2 = 0.9 -> N.H^32 = 0.9^16 = 0.1853020        -> spec 0.1853020
    //  L3 = -N:           behind                                           -> nothing
    // diffuse  = 0.1 + 1 + 0.8 = 1.9
    // specular = 1 + 0.1853020 = 1.1853020
    Lighting l;
    l.lights = {Light::directional(kN), Light::directional({0.6f, 0.0f, 0.8f}), Light::directional({0.0f, 0.0f, -1.0f})};
    const LightTerms t = blinnPhong(l, kRef, kN, kN);
    CHECK(t.diffuse == Approx(1.9).epsilon(1e-6));
    CHECK(t.specular == Approx(1.1853020).epsilon(1e-5));
    // kd = (0.1, 0.2, 0), ks 0.5: c = kd * 1.9 + 0.5 * 1.185302 = kd * 1.9 + 0.592651
    //   r = 0.19 + 0.592651 = 0.782651 -> * 255 = 199.576 -> 200
    //   g = 0.38 + 0.592651 = 0.972651 -> * 255 = 248.026 -> 248
    //   b = 0.00 + 0.592651 = 0.592651 -> * 255 = 151.126 -> 151
    const Pixel p = packBgra8(applyTerms({0.1f, 0.2f, 0.0f}, kRef.ks, t));
    CHECK(int(pixelR(p)) == 200);
    CHECK(int(pixelG(p)) == 248);
    CHECK(int(pixelB(p)) == 151);
    // A coloured ks (an MTL Ks) scales the specular per channel: ks = (0.2, 0, 0.4):
    //   r = 0.19 + 0.2 * 1.185302 = 0.19 + 0.2370604 = 0.4270604 -> * 255 = 108.90 -> 109
    //   g = 0.38 + 0                                 = 0.38      -> * 255 =  96.90 ->  97
    //   b = 0.00 + 0.4 * 1.185302 = 0.4741208        -> * 255 = 120.90 -> 121
    const Pixel q = packBgra8(applyTerms({0.1f, 0.2f, 0.0f}, {0.2f, 0.0f, 0.4f}, t));
    CHECK(int(pixelR(q)) == 109);
    CHECK(int(pixelG(q)) == 97);
    CHECK(int(pixelB(q)) == 121);
    // Clamping: kd = 1 gives 1.9 + 0.59 > 1 -> 255.
    CHECK(packBgra8(applyTerms({1.0f, 1.0f, 1.0f}, kRef.ks, t)) == packBgra(255, 255, 255));
}

TEST_CASE("drawMesh: a flat quad facing the light has the same colour in flat, Gouraud and Phong",
          "[render][shading]") {
    // A unit quad at z = 0 facing +Z, seen from (0, 0, 50) with a 1.5 degree field of view (it fills
    // most of a 64x64 target), one light along +Z. Per pixel, in every lit mode:
    //  - diffuse: N = (0, 0, 1) everywhere (face normal, vertex normals and their interpolation
    //    are all +Z) and L is directional, so diffuse = 0.1 + N.L = 1.1 in all three modes.
    //  - specular: only V differs. V makes at most theta = atan(0.5 sqrt 2 / 50) = 0.01414 rad
    //    with N over the quad; with L = N, H bisects N and V, so N.H = cos(theta / 2) and
    //    0.5 * cos(0.00707)^32 = 0.5 * (1 - 2.5e-5)^32 = 0.5 * (1 - 8.0e-4) = 0.4996.
    //    Phong evaluates it per pixel, flat at each triangle's centroid, Gouraud at the corners
    //    and interpolates: all three lie in [0.4996, 0.5], i.e. within 0.0004 * 255 = 0.10 LSB.
    // kd = (0.4, 0.3, 0.06), c = 1.1 kd + spec, spec in [0.4996, 0.5]:
    //   r = 0.44 + spec  = [0.9396, 0.94]  * 255 = [239.60, 239.70] -> 240
    //   g = 0.33 + spec  = [0.8296, 0.83]  * 255 = [211.55, 211.65] -> 212
    //   b = 0.066 + spec = [0.5656, 0.566] * 255 = [144.23, 144.33] -> 144
    // Every interval lies inside one rounding bin, so the bound is exact: all covered pixels of
    // all three modes are (240, 212, 144). Unlit is kd alone: (0.4, 0.3, 0.06) * 255 =
    // (102, 76.5 -> 76 (ties to even), 15.3 -> 15).
    const Mesh quad = unitQuad();

    FrameView view = viewAlongZ(50.0f);
    view.lighting.lights = {Light::directional({0.0f, 0.0f, 1.0f})};
    SurfaceMaterial material;
    material.kd = {0.4f, 0.3f, 0.06f};

    const Pixel background = packBgra(1, 2, 3);
    struct Case {
        ShadingMode mode;
        Pixel expected;
    };
    for (const Case& c : {Case{ShadingMode::Flat, packBgra(240, 212, 144)}, Case{ShadingMode::Gouraud, packBgra(240, 212, 144)},
                          Case{ShadingMode::Phong, packBgra(240, 212, 144)}, Case{ShadingMode::Unlit, packBgra(102, 76, 15)}}) {
        INFO("mode " << shadingModeName(c.mode));
        FrameBuffer fb(64, 64);
        fb.clear(background);
        RenderContext ctx(fb);
        RenderSettings settings;
        settings.shading = c.mode;
        drawMesh(ctx, view, settings, quad, material);
        int covered = 0, wrong = 0;
        for (int y = 0; y < fb.height(); ++y)
            for (int x = 0; x < fb.width(); ++x) {
                const Pixel p = fb.pixel(x, y);
                if (p == background) continue;
                ++covered;
                if (p != c.expected) ++wrong;
            }
        // The quad spans 1 / (2 * 50 * tan(0.75 deg)) = 0.764 of the view: ~49x49 pixels.
        CHECK(covered > 45 * 45);
        CHECK(covered < 53 * 53);
        CHECK(wrong == 0);
        CHECK(fb.pixel(32, 32) == c.expected);
    }
}

// --- Coloured, point and spot lights (lightTerms) ----------------------------------------------
// N = +Z at the origin and V = N unless stated; the one light's factor a and direction L follow
// Shading.hpp's lightAt: a = 1 / d^2 for point and spot lights, times the range window
// 1 - (d / range)^4 and the cone factor clamp((cos - cos outer) / (cos inner - cos outer), 0, 1)^2.

namespace {
Lighting only(const Light& light) {
    Lighting l;
    l.lights = {light};
    return l;
}
constexpr Vec3 kOrigin{0.0f, 0.0f, 0.0f};
} // namespace

TEST_CASE("Lights: a coloured directional light scales both terms per channel", "[render][shading][lights]") {
    // L = V = N: N.L = 1, N.H = 1 -> diffuse = 0.1 + colour, specular = colour.
    const RgbTerms t = lightTerms(only(Light::directional(kN, {0.5f, 1.0f, 2.0f})), kRef, kN, kOrigin, kN);
    CHECK(t.diffuse.r == Approx(0.6f));
    CHECK(t.diffuse.g == Approx(1.1f));
    CHECK(t.diffuse.b == Approx(2.1f));
    CHECK(t.specular.r == 0.5f);
    CHECK(t.specular.g == 1.0f);
    CHECK(t.specular.b == 2.0f);
}

TEST_CASE("Lights: a point light falls off with the square of the distance", "[render][shading][lights]") {
    SECTION("straight above at distance 2, colour (8, 4, 2): a = 1/4") {
        // diffuse = 0.1 + colour * 1 * 0.25 = (2.1, 1.1, 0.6); specular = colour * 1^32 * 0.25 = (2, 1, 0.5).
        const RgbTerms t = lightTerms(only(Light::point({0, 0, 2}, {8.0f, 4.0f, 2.0f})), kRef, kN, kOrigin, kN);
        CHECK(t.diffuse.r == Approx(2.1f));
        CHECK(t.diffuse.g == Approx(1.1f));
        CHECK(t.diffuse.b == Approx(0.6f));
        CHECK(t.specular.r == 2.0f);
        CHECK(t.specular.g == 1.0f);
        CHECK(t.specular.b == 0.5f);
    }
    SECTION("oblique: at (3, 0, 4), white") {
        // d^2 = 25, a = 0.04, L = (0.6, 0, 0.8): diffuse = 0.1 + 0.8 * 0.04 = 0.132;
        // N.H = 3 / sqrt 10 (as above), N.H^32 = 0.9^16 = 0.1853020 -> specular 0.04 * 0.1853020 = 0.00741208.
        const RgbTerms t = lightTerms(only(Light::point({3, 0, 4}, {1, 1, 1})), kRef, kN, kOrigin, kN);
        CHECK(t.diffuse.g == Approx(0.132f).epsilon(1e-6));
        CHECK(t.specular.g == Approx(0.00741208f).epsilon(1e-5));
    }
    SECTION("the light moves with the surface point: p = (0, 0, -2) sees it at distance 4") {
        const RgbTerms t = lightTerms(only(Light::point({0, 0, 2}, {8.0f, 8.0f, 8.0f})), kRef, kN, {0, 0, -2}, kN);
        CHECK(t.diffuse.r == Approx(0.1f + 8.0f / 16.0f)); // 0.6
    }
    SECTION("range: the window 1 - (d / range)^4") {
        // d = 2, range 4: (1/2)^4 = 0.0625 -> a = 0.25 * 0.9375 = 0.234375; 0.1 + 8 * 0.234375 = 1.975.
        const RgbTerms t = lightTerms(only(Light::point({0, 0, 2}, {8.0f, 8.0f, 8.0f}, 4.0f)), kRef, kN, kOrigin, kN);
        CHECK(t.diffuse.r == Approx(1.975f));
        CHECK(t.specular.r == Approx(8.0f * 0.234375f));
        // At or beyond the range: no light at all (ambient only, no specular).
        for (float range : {2.0f, 1.0f}) {
            const RgbTerms off = lightTerms(only(Light::point({0, 0, 2}, {8.0f, 8.0f, 8.0f}, range)), kRef, kN, kOrigin, kN);
            CHECK(off.diffuse.r == 0.1f);
            CHECK(off.specular.r == 0.0f);
        }
    }
    SECTION("behind the surface: nothing") {
        const RgbTerms t = lightTerms(only(Light::point({0, 0, -2}, {8.0f, 8.0f, 8.0f})), kRef, kN, kOrigin, kN);
        CHECK(t.diffuse.r == 0.1f);
        CHECK(t.specular.r == 0.0f);
    }
    SECTION("at the surface point itself: capped, finite") {
        // d = 0: L = normalize(0) (no direction, N.L not > 0): no light, and no NaN.
        const RgbTerms t = lightTerms(only(Light::point(kOrigin, {1, 1, 1})), kRef, kN, kOrigin, kN);
        CHECK(t.diffuse.r == 0.1f);
        CHECK(t.specular.r == 0.0f);
    }
}

TEST_CASE("Lights: a spot light's cone", "[render][shading][lights]") {
    // At (0, 0, 2) pointing down -Z, inner 0.2 rad, outer 0.6 rad, colour 1.
    const Light spot = Light::spot({0, 0, 2}, {0, 0, -1}, {1, 1, 1}, 0.2f, 0.6f);
    SECTION("on the axis: the full light, a = 1/4") {
        const RgbTerms t = lightTerms(only(spot), kRef, kN, kOrigin, kN);
        CHECK(t.diffuse.r == Approx(0.35f));
        CHECK(t.specular.r == Approx(0.25f));
    }
    SECTION("0.4 rad off the axis: half-way through the falloff") {
        // p = (-2 tan 0.4, 0, 0) = (-0.8455864, 0, 0): L makes 0.4 rad with the axis and with N.
        // cone = ((cos 0.4 - cos 0.6) / (cos 0.2 - cos 0.6))^2 = (0.0957252 / 0.1547309)^2 = 0.3827364;
        // d^2 = 4 / cos^2 0.4 = 4.7150164 -> a = 0.3827364 / 4.7150164 = 0.0811739;
        // diffuse = 0.1 + cos 0.4 * a = 0.1 + 0.9210610 * 0.0811739 = 0.1747661;
        // H bisects L and V = N: N.H = cos 0.2 = 0.9800666, specular = 0.9800666^32 a = 0.0426182.
        const RgbTerms t = lightTerms(only(spot), kRef, kN, {-0.8455864f, 0.0f, 0.0f}, kN);
        CHECK(t.diffuse.r == Approx(0.1747661).epsilon(1e-5));
        CHECK(t.specular.r == Approx(0.0426182).epsilon(1e-4));
    }
    SECTION("inside the inner angle: the cone factor is 1") {
        // 0.1 rad off: p = (-2 tan 0.1, 0, 0); a = cos^2 0.1 / 4, diffuse = 0.1 + cos^3 0.1 / 4.
        const float x = -2.0f * std::tan(0.1f);
        const RgbTerms t = lightTerms(only(spot), kRef, kN, {x, 0.0f, 0.0f}, kN);
        CHECK(t.diffuse.r == Approx(0.1 + std::pow(std::cos(0.1), 3.0) / 4.0).epsilon(1e-5));
    }
    SECTION("outside the outer angle: dark") {
        const RgbTerms t = lightTerms(only(spot), kRef, kN, {-2.0f * std::tan(0.7f), 0.0f, 0.0f}, kN);
        CHECK(t.diffuse.r == 0.1f);
        CHECK(t.specular.r == 0.0f);
    }
}

TEST_CASE("Lights: white directional lights give blinnPhong's terms bit for bit", "[render][shading][lights]") {
    // lightTerms with colour 1 and a = 1 multiplies by 1 only: the fast path (one-number terms)
    // and the general one agree exactly, so scenes without coloured lights keep their images.
    Lighting l;
    l.lights = {Light::directional(normalize(Vec3(1, 1, 1))), Light::directional(normalize(Vec3(-0.3f, 0.2f, 1.0f)))};
    REQUIRE(l.whiteDirectional());
    std::uint32_t state = 12345u;
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24) * 2.0f - 1.0f;
    };
    for (int i = 0; i < 2000; ++i) {
        const Vec3 n = normalize(Vec3(next(), next(), next())), v = normalize(Vec3(next(), next(), next()));
        const Vec3 p{next(), next(), next()};
        const LightTerms grey = blinnPhong(l, kRef, n, v);
        const RgbTerms rgb = lightTerms(l, kRef, n, p, v);
        REQUIRE(rgb.diffuse.r == grey.diffuse);
        REQUIRE(rgb.diffuse.b == grey.diffuse);
        REQUIRE(rgb.specular.g == grey.specular);
    }
    l.lights.push_back(Light::directional(kN, {1.0f, 0.9f, 1.0f}));
    CHECK(!l.whiteDirectional());
    l.lights.back() = Light::point({0, 0, 1}, {1, 1, 1});
    CHECK(!l.whiteDirectional());
}

TEST_CASE("drawMesh: a red light lights only the red channel, in flat, Gouraud and Phong", "[render][shading][lights]") {
    // The lit quad of the test above under one pure red light along +Z: green and blue keep the
    // ambient term alone, 0.1 kd (0.1 * 0.5 * 255 = 12.75 -> 13), red is lit as before
    // (kd 0.5: 0.55 + spec [0.4996, 0.5] -> 1.05: 255). Gouraud carries six terms here: with
    // its two grey ones, green would be lit too.
    const Mesh quad = unitQuad();
    FrameView view = viewAlongZ(50.0f);
    view.lighting.lights = {Light::directional({0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f})};
    SurfaceMaterial material;
    material.kd = {0.5f, 0.5f, 0.5f};
    for (ShadingMode mode : {ShadingMode::Flat, ShadingMode::Gouraud, ShadingMode::Phong}) {
        for (Isa isa : {Isa::Scalar, bestIsa()}) {
            INFO("mode " << shadingModeName(mode) << ", isa " << isaName(isa));
            FrameBuffer fb(64, 64);
            fb.clear(0);
            RenderContext ctx(fb);
            RenderSettings settings;
            settings.shading = mode;
            settings.isa = isa;
            drawMesh(ctx, view, settings, quad, material);
            CHECK(fb.pixel(32, 32) == packBgra(255, 13, 13));
        }
    }
}

TEST_CASE("drawMesh: a single-sided surface loses its back faces whatever the cull mode; a double-sided one follows it",
          "[render][cull][materials]") {
    // The quad faces +Z; seen from +Z its triangles are counter-clockwise (front faces), from -Z
    // clockwise (back faces). Covered pixels are counted at 64x64.
    const Mesh quad = unitQuad();
    auto covered = [&](float eyeZ, CullMode cull, bool doubleSided) {
        const FrameView view = viewAlongZ(eyeZ);
        SurfaceMaterial material;
        material.doubleSided = doubleSided;
        FrameBuffer fb(64, 64);
        fb.clear(0);
        RenderContext ctx(fb);
        RenderSettings settings;
        settings.cull = cull;
        drawMesh(ctx, view, settings, quad, material);
        int n = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) n += fb.pixel(x, y) != 0;
        return n;
    };
    const int full = covered(50.0f, CullMode::None, true);
    REQUIRE(full > 1000);
    for (CullMode cull : {CullMode::None, CullMode::CW, CullMode::CCW}) {
        INFO("cull " << cullModeName(cull));
        // Single-sided: front faces always drawn, back faces never.
        CHECK(covered(50.0f, cull, false) == full);
        CHECK(covered(-50.0f, cull, false) == 0);
        // Double-sided: the cull mode decides (CW culls back faces, CCW front faces).
        CHECK(covered(50.0f, cull, true) == (cull == CullMode::CCW ? 0 : full));
        CHECK(covered(-50.0f, cull, true) == (cull == CullMode::CW ? 0 : full));
    }
}
