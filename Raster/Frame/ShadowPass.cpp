// The shadow pass: the lights' frusta fitted to the scene, each map drawn depth-only through the
// rasterizer.
#include "Raster/Frame/ShadowPass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "Math/Transform.hpp"
#include "Raster/Frame/Scene.hpp"
#include "Raster/Pipeline.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define SR_SHADOW_SSE2 1
#else
#define SR_SHADOW_SSE2 0
#endif

namespace sr {

namespace {

// The nearer of each depth[x] and z0 + x' dz for x' = 0, 1, ... count - 1 (reversed-Z: the
// larger), in float: a shadow map's depths need only agree with the receiver test to within its
// bias, not bit for bit with the colour pass. Four lanes at a time where SSE2 is there.
void maxDepthRamp(float* depth, int count, float z0, float dz) {
    int x = 0;
#if SR_SHADOW_SSE2
    const __m128 step4 = _mm_set1_ps(4.0f * dz);
    __m128 z = _mm_add_ps(_mm_set1_ps(z0), _mm_mul_ps(_mm_set1_ps(dz), _mm_set_ps(3.0f, 2.0f, 1.0f, 0.0f)));
    for (; x + 4 <= count; x += 4) {
        _mm_storeu_ps(depth + x, _mm_max_ps(_mm_loadu_ps(depth + x), z));
        z = _mm_add_ps(z, step4);
    }
#endif
    for (; x < count; ++x) {
        const float z = z0 + dz * float(x);
        if (z > depth[x]) depth[x] = z;
    }
}

// The depth-only program: clip position only, no varyings; its "kernel" walks each span keeping
// the nearer depth (maxDepthRamp), no colour, into the map's tiles (ShadowMap::texelIndex): a
// span is cut at the tiles' edges, each piece's first depth computed as the span's.
struct DepthOnlyProgram {
    static constexpr int kVaryings = 0;
    const Mat4* viewProj;
    const Mesh* mesh;
    const Placement* placement; // an instance's place (null: the mesh is in world space)
    void vertex(std::size_t i, ClipVertex& out) const {
        const Vec3 p = placement ? placement->position(mesh->positions[i]) : mesh->positions[i];
        out.position = *viewProj * Vec4(p, 1.0f);
    }
    void triangle(std::size_t, const TriangleSetup&) const {}
    Pixel fragment(const Fragment<0>&) const { return 0; }
    bool fillKernel(const TriangleSetup& t, FrameBuffer& fb, const Scissor& s, std::uint64_t& shaded) const {
        const float dz = float(t.ddx[kPlaneZ]);
        const std::size_t tilesX = std::size_t(fb.width() / kShadowTile), tileSize = kShadowTile * kShadowTile;
        float* depth = fb.depthData();
        forEachSpan(t, s, [&](int y, int x0, int x1) {
            const double zy = t.value[kPlaneZ] + t.ddy[kPlaneZ] * ((y + 0.5) - t.originY);
            float* row = depth + std::size_t(y / kShadowTile) * tilesX * tileSize + std::size_t(y % kShadowTile * kShadowTile);
            for (int x = x0; x < x1;) {
                const int end = std::min(x1, (x / kShadowTile + 1) * kShadowTile);
                const double z0 = zy + t.ddx[kPlaneZ] * ((x + 0.5) - t.originX);
                maxDepthRamp(row + std::size_t(x / kShadowTile) * tileSize + std::size_t(x % kShadowTile), end - x, float(z0), dz);
                x = end;
            }
            shaded += std::uint64_t(x1 - x0);
        });
        return true;
    }
};

struct Bounds {
    Vec3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
    Vec3 hi{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(), -std::numeric_limits<float>::max()};
    void add(Vec3 p) {
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) return;
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    bool empty() const { return lo.x > hi.x; }
    std::array<Vec3, 8> corners() const {
        return {{{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z},
                 {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}}};
    }
};

// The bounds of what casts: every vertex the opaque draws use.
Bounds casterBounds(const Scene& scene) {
    Bounds b;
    for (const SceneDraw& d : scene.draws) {
        if (d.mesh < 0 || std::size_t(d.mesh) >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        if (std::size_t(d.firstIndex) + d.indexCount > mesh.indices.size() || d.alpha < 1.0f) continue;
        for (std::uint32_t k = 0; k < d.indexCount; ++k) b.add(drawnPosition(d, mesh.positions[mesh.indices[d.firstIndex + k]]));
    }
    return b;
}

Vec3 upFor(Vec3 axis) { return std::fabs(axis.y) < 0.99f ? Vec3{0, 1, 0} : Vec3{1, 0, 0}; }

// Sets `map`'s projection for a directional light shining along -toLight, fitted to the camera's
// view depths [tNear, tFar] (its pyramid slice) within the scene's bounds; false when there is
// nothing to fit.
bool fitDirectional(ShadowMap& map, Vec3 toLight, const Bounds& scene, const FrameView& view, float tNear, float tFar) {
    const Vec3 centre = (scene.lo + scene.hi) * 0.5f;
    const float radius = std::max(length(scene.hi - scene.lo) * 0.5f, 1e-3f);
    const Vec3 axis = normalize(toLight) * -1.0f;
    if (!(std::isfinite(axis.x) && std::isfinite(axis.y) && std::isfinite(axis.z))) return false;
    const float margin = radius * 0.05f;
    const Vec3 origin = centre - axis * (radius + margin);
    const Mat4 lightView = lookAt(origin, centre, upFor(axis));
    // Across the light: the bounds' extent, cut to the camera's view pyramid slice.
    float sx0 = std::numeric_limits<float>::max(), sy0 = sx0, sx1 = -sx0, sy1 = -sx0;
    for (const Vec3& c : scene.corners()) {
        const Vec4 q = lightView * Vec4(c, 1.0f);
        sx0 = std::min(sx0, q.x), sx1 = std::max(sx1, q.x), sy0 = std::min(sy0, q.y), sy1 = std::max(sy1, q.y);
    }
    const float forwardLength = length(view.rays.forward);
    if (tFar > 0.0f && forwardLength > 0.0f) {
        float fx0 = std::numeric_limits<float>::max(), fy0 = fx0, fx1 = -fx0, fy1 = -fx0;
        const auto addPoint = [&](Vec3 p) {
            const Vec4 q = lightView * Vec4(p, 1.0f);
            fx0 = std::min(fx0, q.x), fx1 = std::max(fx1, q.x), fy0 = std::min(fy0, q.y), fy1 = std::max(fy1, q.y);
        };
        for (const float t : {tNear, tFar})
            for (const double sx : {-1.0, 1.0})
                for (const double sy : {-1.0, 1.0}) addPoint(view.eye + view.rays.at(sx, sy) * (t / forwardLength));
        const float x0 = std::max(sx0, fx0), x1 = std::min(sx1, fx1), y0 = std::max(sy0, fy0), y1 = std::min(sy1, fy1);
        if (x0 < x1 && y0 < y1) sx0 = x0, sx1 = x1, sy0 = y0, sy1 = y1;
    }
    if (!(sx0 < sx1 && sy0 < sy1)) return false;
    const float pad = std::max(sx1 - sx0, sy1 - sy0) * 0.01f;
    sx0 -= pad, sx1 += pad, sy0 -= pad, sy1 += pad;
    map.perspective = false;
    map.nearZ = 0.0f;
    map.farZ = 2.0f * (radius + margin);
    map.origin = origin;
    map.axis = axis;
    map.viewProj = orthographic(sx0, sx1, sy0, sy1, map.nearZ, map.farZ) * lightView;
    map.texelWorld = std::max(sx1 - sx0, sy1 - sy0) / float(map.target.width());
    map.splitFar = tFar;
    return true;
}

// A spot light's cone as a perspective frustum from its position.
bool fitSpot(ShadowMap& map, const Light& light, const Bounds& scene) {
    const Vec3 axis = normalize(light.spotDirection);
    if (!(std::isfinite(axis.x) && std::isfinite(axis.y) && std::isfinite(axis.z))) return false;
    float farZ = 0.0f;
    for (const Vec3& c : scene.corners()) farZ = std::max(farZ, dot(c - light.position, axis));
    if (!(farZ > 0.0f)) return false;
    farZ *= 1.01f;
    const float nearZ = std::max(farZ * 1e-3f, 1e-4f);
    // cos(outer) = -coneOffset / coneScale (Light::spot); the frustum's half angle a little wider.
    const float cosOuter = light.coneScale > 0.0f ? std::clamp(-light.coneOffset / light.coneScale, -1.0f, 1.0f) : 0.5f;
    const float half = std::min(std::acos(cosOuter) * 1.05f + 0.01f, 1.48f); // at most about 85 degrees
    map.perspective = true;
    map.nearZ = nearZ;
    map.farZ = farZ;
    map.origin = light.position;
    map.axis = axis;
    map.viewProj = perspective(2.0f * half, 1.0f, nearZ, farZ) * lookAt(light.position, light.position + axis, upFor(axis));
    map.texelWorld = 2.0f * std::tan(half) / float(map.target.width());
    return true;
}

// A map's depth cleared to "nothing", split over the render threads by rows of its array (at
// 2048, 16 MiB a map; the tiles do not matter to a clear).
void clearMap(RenderContext& ctx, FrameBuffer& map) {
    const std::size_t width = std::size_t(map.width());
    ctx.forRows(map.height(), [&](int y0, int y1) {
        fillWords(map.depthData() + std::size_t(y0) * width, std::size_t(y1 - y0) * width, FrameBuffer::kFarDepth);
    });
}

} // namespace

void renderShadowMaps(RenderContext& ctx, const Scene& scene, const FrameView& view, const ShadowSettings& settings,
                      SceneShadows& out) {
    out.settings = settings;
    const std::vector<Light>& lights = view.lighting.lights;
    out.firstMap.assign(lights.size(), 0);
    out.mapCount.assign(lights.size(), 0);
    const Bounds bounds = casterBounds(scene);
    const int size = shadowMapSide(settings.size);
    // The camera's depth range over the scene: the cascades' splits.
    const float forwardLength = length(view.rays.forward);
    out.eye = view.eye;
    out.forward = forwardLength > 0.0f ? view.rays.forward * (1.0f / forwardLength) : Vec3{0, 0, -1};
    float reach = 0.0f;
    if (!bounds.empty())
        for (const Vec3& c : bounds.corners()) reach = std::max(reach, dot(c - out.eye, out.forward));
    const int cascades = std::clamp(settings.cascades, 1, kMaxCascades);
    const float start = reach * 1e-3f;
    std::array<float, kMaxCascades + 1> splits{};
    splits[0] = 0.0f;
    for (int k = 1; k <= cascades; ++k) {
        const float f = float(k) / float(cascades);
        const float logarithmic = start * std::pow(reach / std::max(start, 1e-30f), f);
        splits[std::size_t(k)] = k == cascades ? reach : 0.5f * (logarithmic + reach * f);
    }
    std::size_t used = 0;
    const RenderStats before = ctx.stats;
    FrameBuffer& screen = ctx.target();
    DrawState state;
    state.cull = CullMode::None;
    state.depth = DepthMode::TestWrite;
    for (std::size_t i = 0; i < lights.size() && !bounds.empty(); ++i) {
        const Light& light = lights[i];
        if (light.type == LightType::Point) continue;
        out.firstMap[i] = int(used);
        const int slices = light.type == LightType::Directional ? (reach > 0.0f ? cascades : 0) : 1;
        for (int k = 0; k < slices; ++k) {
            if (used == out.maps.size()) out.maps.emplace_back();
            ShadowMap& map = out.maps[used];
            if ((map.target.width() != size || map.target.height() != size) && !map.target.resize(size, size)) continue;
            const bool fitted = light.type == LightType::Directional
                                    ? fitDirectional(map, light.toLight, bounds, view, splits[std::size_t(k)],
                                                     splits[std::size_t(k) + 1])
                                    : fitSpot(map, light, bounds);
            if (!fitted) continue;
            map.light = int(i);
            clearMap(ctx, map.target);
            ctx.setTarget(map.target);
            for (const SceneDraw& d : scene.draws) {
                if (d.mesh < 0 || std::size_t(d.mesh) >= scene.meshes.size() || d.alpha < 1.0f) continue;
                const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
                if (std::size_t(d.firstIndex) + d.indexCount > mesh.indices.size()) continue;
                DepthOnlyProgram program{&map.viewProj, &mesh, d.placement ? &*d.placement : nullptr};
                drawProgram<0>(ctx, state, mesh.vertexCount(), mesh.indices.data() + d.firstIndex, d.indexCount, program);
            }
            ctx.setTarget(screen);
            ++out.mapCount[i];
            ++used;
        }
    }
    out.maps.resize(used); // fewer maps than last frame: the rest's memory goes
    ctx.stats = before;
}

} // namespace sr
