// The eight specialised mesh pipelines (shading mode x textured) behind drawMesh().
#include "Raster/MeshRenderer.hpp"

#include <cmath>
#include <type_traits>

#include "Raster/Pipeline.hpp"
#include "Raster/ShadingSimd.hpp"
#include "Raster/TextureLod.hpp"

namespace sr {
namespace {

// Face normal of triangle (p0, p1, p2): normalize((p1 - p0) x (p2 - p0)) in double, as the
// reference renderer computes it; not flipped toward the viewer. Zero area -> (0, 0, 1).
Vec3 faceNormal(Vec3 p0, Vec3 p1, Vec3 p2) {
    const double ax = double(p1.x) - p0.x, ay = double(p1.y) - p0.y, az = double(p1.z) - p0.z;
    const double bx = double(p2.x) - p0.x, by = double(p2.y) - p0.y, bz = double(p2.z) - p0.z;
    const double nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0.0) || !std::isfinite(len)) return {0.0f, 0.0f, 1.0f};
    return {float(nx / len), float(ny / len), float(nz / len)};
}

// The state every specialised pipeline shares; one instance per drawMesh call.
struct DrawContext {
    const FrameView& view;
    const RenderSettings& settings;
    const Mesh& mesh;
    const std::uint32_t* indices;
    const Texture* texture; // non-null only when the draw is textured
    Color kd;
};

// Diffuse colour at a fragment whose varyings 0 and 1 are (u, v). Trilinear filtering needs the
// screen-space uv derivatives, taken analytically from the triangle's planes (no quad shading).
template <int kVaryings>
Color sampleKd(const DrawContext& d, const TriangleSetup* setup, const Fragment<kVaryings>& f) {
    const Vec2 uv{f.varyings[0], f.varyings[1]};
    float lod = 0.0f;
    if (d.settings.filter == TextureFilter::Trilinear) {
        constexpr int kU = kPlaneVarying0, kV = kPlaneVarying0 + 1;
        const UvDerivatives g = d.settings.perspective == PerspectiveMode::Affine
                                    ? UvDerivatives{float(setup->ddx[kU]), float(setup->ddx[kV]), float(setup->ddy[kU]),
                                                    float(setup->ddy[kV])}
                                    : uvDerivatives(*setup, kU, kV, f.invW, uv.x, uv.y);
        lod = mipLevel(g.dudx, g.dvdx, g.dudy, g.dvdy, d.texture->width(), d.texture->height());
    }
    return d.texture->sample(uv, lod, d.settings.filter, d.settings.wrap);
}

DrawState drawStateFor(const DrawContext& d) {
    DrawState s;
    s.cull = d.settings.cull;
    s.clipFar = d.view.finiteFar;
    s.wireframe = d.settings.wireframe;
    s.stopAfter = d.settings.stopAfter;
    s.perspective = d.settings.perspective;
    return s;
}

// Writes the clip position and, when textured, the uv into varyings 0-1.
template <bool kTextured>
void transformVertex(const DrawContext& d, std::size_t i, ClipVertex& out) {
    out.position = d.view.viewProj * Vec4(d.mesh.positions[i], 1.0f);
    if constexpr (kTextured) {
        out.varyings[0] = d.mesh.uvs[i].x;
        out.varyings[1] = d.mesh.uvs[i].y;
    }
}

// The four shading programs (drawProgram's Program: vertex, triangle, fragment). Each render
// thread works on its own copy, so the per-triangle state (setup, terms) lives in the object.
template <bool kTextured>
struct UnlitProgram {
    static constexpr int kVaryings = kTextured ? 2 : 0;
    const DrawContext* d;
    Pixel flat;
    const TriangleSetup* setup = nullptr;
    UnlitProgram(const DrawContext* dc, Pixel colour) : d(dc), flat(colour) {}
    void vertex(std::size_t i, ClipVertex& out) const { transformVertex<kTextured>(*d, i, out); }
    void triangle(std::size_t, const TriangleSetup& s) { setup = &s; }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        if constexpr (kTextured) return packBgra8(sampleKd(*d, setup, f));
        else return flat;
    }
};

// Flat: lit ONCE per triangle (face normal, view vector at the centroid) in triangle().
template <bool kTextured>
struct FlatProgram {
    static constexpr int kVaryings = kTextured ? 2 : 0;
    const DrawContext* d;
    const TriangleSetup* setup = nullptr;
    LightTerms terms;
    Pixel flat = 0;
    explicit FlatProgram(const DrawContext* dc) : d(dc) {}
    void vertex(std::size_t i, ClipVertex& out) const { transformVertex<kTextured>(*d, i, out); }
    void triangle(std::size_t t, const TriangleSetup& s) {
        setup = &s;
        const Vec3 p0 = d->mesh.positions[d->indices[3 * t]], p1 = d->mesh.positions[d->indices[3 * t + 1]],
                   p2 = d->mesh.positions[d->indices[3 * t + 2]];
        const Vec3 centroid = (p0 + p1 + p2) / 3.0f;
        terms = blinnPhong(d->view.lighting, faceNormal(p0, p1, p2), normalize(d->view.eye - centroid));
        if constexpr (!kTextured) flat = packBgra8(applyTerms(d->kd, terms));
    }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        if constexpr (kTextured) return packBgra8(applyTerms(sampleKd(*d, setup, f), terms));
        else return flat;
    }
};

// Gouraud: Blinn-Phong per vertex; the diffuse and specular terms are interpolated
// (perspective-correct) and combined per pixel, so a texture still modulates per pixel.
template <bool kTextured>
struct GouraudProgram {
    static constexpr int kT = kTextured ? 2 : 0; // first varying of the lighting terms
    static constexpr int kVaryings = kT + 2;
    const DrawContext* d;
    const TriangleSetup* setup = nullptr;
    explicit GouraudProgram(const DrawContext* dc) : d(dc) {}
    void vertex(std::size_t i, ClipVertex& out) const {
        transformVertex<kTextured>(*d, i, out);
        const Vec3 p = d->mesh.positions[i];
        const LightTerms t = blinnPhong(d->view.lighting, normalize(d->mesh.normals[i]), normalize(d->view.eye - p));
        out.varyings[kT] = t.diffuse;
        out.varyings[kT + 1] = t.specular;
    }
    void triangle(std::size_t, const TriangleSetup& s) { setup = &s; }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        const LightTerms t{f.varyings[kT], f.varyings[kT + 1]};
        if constexpr (kTextured) return packBgra8(applyTerms(sampleKd(*d, setup, f), t));
        else return packBgra8(applyTerms(d->kd, t));
    }
};

// Phong shading: world position and normal interpolated (perspective-correct), the normal
// renormalised and Blinn-Phong evaluated per pixel.
template <bool kTextured>
struct PhongProgram {
    static constexpr int kP = kTextured ? 2 : 0; // position varyings kP..kP+2, normal kP+3..kP+5
    static constexpr int kVaryings = kP + 6;
    const DrawContext* d;
    const TriangleSetup* setup = nullptr;
    explicit PhongProgram(const DrawContext* dc) : d(dc) {}
    void vertex(std::size_t i, ClipVertex& out) const {
        transformVertex<kTextured>(*d, i, out);
        const Vec3 p = d->mesh.positions[i], n = d->mesh.normals[i];
        out.varyings[kP] = p.x;
        out.varyings[kP + 1] = p.y;
        out.varyings[kP + 2] = p.z;
        out.varyings[kP + 3] = n.x;
        out.varyings[kP + 4] = n.y;
        out.varyings[kP + 5] = n.z;
    }
    void triangle(std::size_t, const TriangleSetup& s) { setup = &s; }
    Pixel fragment(const Fragment<kVaryings>& f) const {
        const Vec3 p{f.varyings[kP], f.varyings[kP + 1], f.varyings[kP + 2]};
        const Vec3 n = normalize(Vec3{f.varyings[kP + 3], f.varyings[kP + 4], f.varyings[kP + 5]});
        const LightTerms t = blinnPhong(d->view.lighting, n, normalize(d->view.eye - p));
        if constexpr (kTextured) return packBgra8(applyTerms(sampleKd(*d, setup, f), t));
        else return packBgra8(applyTerms(d->kd, t));
    }
#if SR_HAVE_SSE2
    // Four pixels at once (ShadingSimd.hpp): the same operations lane by lane, so the same bits;
    // lanes off the fast normalize path are redone by fragment(). Bilinear textures are sampled
    // four lanes at once, other filters lane by lane (kdLanes).
    void fragment4(const FragmentBatch<kVaryings>& b, Pixel out[4]) const {
        __m128 ok = _mm_castsi128_ps(_mm_set1_epi32(-1));
        Texture::ColorLanes kd;
        kdLanes<4>(b, kd, [&] { d->texture->sampleBilinear4(b.v[0], b.v[1], d->settings.wrap, kd, false); });
        const simd::Vec3x4 n = simd::normalizeFast(simd::load3(b.v[kP + 3], b.v[kP + 4], b.v[kP + 5]), ok);
        const Vec3 eye = d->view.eye;
        const simd::Vec3x4 toEye{_mm_sub_ps(_mm_set1_ps(eye.x), _mm_loadu_ps(b.v[kP])),
                                 _mm_sub_ps(_mm_set1_ps(eye.y), _mm_loadu_ps(b.v[kP + 1])),
                                 _mm_sub_ps(_mm_set1_ps(eye.z), _mm_loadu_ps(b.v[kP + 2]))};
        const simd::Vec3x4 v = simd::normalizeFast(toEye, ok);
        const bool simdDone = simd::shadeBlinnPhong(d->view.lighting, _mm_load_ps(kd.r), _mm_load_ps(kd.g),
                                                    _mm_load_ps(kd.b), n, v, ok, out);
        const int good = simdDone ? _mm_movemask_ps(ok) : 0;
        if (good == 0xF) return;
        for (int i = 0; i < 4; ++i)
            if (!(good & (1 << i))) out[i] = fragment(laneFragment(b, i));
    }
#endif
#if SR_HAVE_AVX2
    // Eight pixels at once (AVX2), as fragment4.
    SR_TARGET_AVX2 void fragment8(const FragmentBatch8<kVaryings>& b, Pixel out[8]) const {
        __m256 ok = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
        Texture::ColorLanes8 kd;
        kdLanes<8>(b, kd, [&] { d->texture->sampleBilinear8(b.v[0], b.v[1], d->settings.wrap, kd, false); });
        const simd8::Vec3x8 n = simd8::normalizeFast(
            {_mm256_load_ps(b.v[kP + 3]), _mm256_load_ps(b.v[kP + 4]), _mm256_load_ps(b.v[kP + 5])}, ok);
        const Vec3 eye = d->view.eye;
        const simd8::Vec3x8 toEye{_mm256_sub_ps(_mm256_set1_ps(eye.x), _mm256_load_ps(b.v[kP])),
                                  _mm256_sub_ps(_mm256_set1_ps(eye.y), _mm256_load_ps(b.v[kP + 1])),
                                  _mm256_sub_ps(_mm256_set1_ps(eye.z), _mm256_load_ps(b.v[kP + 2]))};
        const simd8::Vec3x8 v = simd8::normalizeFast(toEye, ok);
        const bool simdDone = simd8::shadeBlinnPhong(d->view.lighting, _mm256_load_ps(kd.r), _mm256_load_ps(kd.g),
                                                     _mm256_load_ps(kd.b), n, v, ok, out);
        const int good = simdDone ? _mm256_movemask_ps(ok) : 0;
        if (good == 0xFF) return;
        for (int i = 0; i < 8; ++i)
            if (!(good & (1 << i))) out[i] = fragment(laneFragment(b, i));
    }
#endif
    // Lane i of a FragmentBatch / FragmentBatch8 as a Fragment (for the per-lane fallbacks).
    template <class Batch>
    static Fragment<kVaryings> laneFragment(const Batch& b, int i) {
        Fragment<kVaryings> f;
        f.x = b.x[i];
        f.y = b.y[i];
        f.invW = b.invW[i];
        for (int k = 0; k < kVaryings; ++k) f.varyings[std::size_t(k)] = b.v[k][i];
        return f;
    }
    // The diffuse colour of kLanes fragments into kd's r/g/b lanes: the material's, or the
    // texture's (bilinearLanes samples all lanes at once; other filters go lane by lane, exactly
    // as sampleKd).
    template <int kLanes, class Batch, class Lanes, class BilinearLanes>
    void kdLanes(const Batch& b, Lanes& kd, BilinearLanes&& bilinearLanes) const {
        if constexpr (kTextured) {
            if (d->settings.filter == TextureFilter::Bilinear) {
                bilinearLanes(); // == sampleKd per lane
                return;
            }
        }
        for (int i = 0; i < kLanes; ++i) {
            Color c = d->kd;
            if constexpr (kTextured) c = sampleKd(*d, setup, laneFragment(b, i));
            kd.r[i] = c.r;
            kd.g[i] = c.g;
            kd.b[i] = c.b;
        }
    }
};

template <class Program>
void drawWith(RenderContext& ctx, const DrawContext& d, std::size_t indexCount, Program program) {
    drawProgram<Program::kVaryings>(ctx, drawStateFor(d), d.mesh.vertexCount(), d.indices, indexCount, program);
}

template <bool kTextured>
void drawShaded(RenderContext& ctx, const DrawContext& d, ShadingMode mode, std::size_t indexCount) {
    switch (mode) {
    case ShadingMode::Unlit: drawWith(ctx, d, indexCount, UnlitProgram<kTextured>(&d, packBgra8(d.kd))); break;
    case ShadingMode::Flat: drawWith(ctx, d, indexCount, FlatProgram<kTextured>(&d)); break;
    case ShadingMode::Gouraud: drawWith(ctx, d, indexCount, GouraudProgram<kTextured>(&d)); break;
    case ShadingMode::Phong: drawWith(ctx, d, indexCount, PhongProgram<kTextured>(&d)); break;
    }
}

} // namespace

void drawMesh(RenderContext& ctx, const FrameView& view, const RenderSettings& settings, const Mesh& mesh,
              const std::uint32_t* indices, std::size_t indexCount, const SurfaceMaterial& material) {
    const bool textured = material.texture != nullptr && mesh.hasUvs();
    ShadingMode mode = settings.shading;
    if (!mesh.hasNormals() && (mode == ShadingMode::Gouraud || mode == ShadingMode::Phong)) mode = ShadingMode::Flat;
    const DrawContext d{view, settings, mesh, indices, textured ? material.texture : nullptr, material.kd};
    if (textured) drawShaded<true>(ctx, d, mode, indexCount);
    else drawShaded<false>(ctx, d, mode, indexCount);
}

} // namespace sr
