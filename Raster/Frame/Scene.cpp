// Scene: its statistics, a draw's material, picking.
#include "Raster/Frame/Scene.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace sr {

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const SceneDraw& d : draws) n += d.indexCount / 3;
    return n;
}

SurfaceMaterial materialOf(const Scene& scene, const SceneDraw& d, const Texture* textureOverride) {
    SurfaceMaterial material;
    material.kd = d.kd;
    material.tint = d.tint;
    material.specular = d.specular;
    material.alpha = d.alpha;
    material.texelAlpha = d.texelAlpha;
    material.doubleSided = d.doubleSided;
    material.wrap = d.wrap;
    material.filter = d.filter;
    if (textureOverride) material.texture = textureOverride;
    else if (d.texture >= 0) material.texture = &scene.textures[std::size_t(d.texture)];
    if (d.pbr) {
        material.pbr = &*d.pbr;
        if (d.addressing) material.addressing = &*d.addressing;
        for (const MapSlot slot : kAllMapSlots)
            if (d.maps.has(slot)) material.maps[slot] = &scene.textures[std::size_t(d.maps[slot])];
    }
    return material;
}

namespace {

// Whether the ray o + t d (t > 0) meets triangle (a, b, c), and at which t (Moeller-Trumbore, in double).
bool rayHits(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c, double& tHit) {
    const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    const double dd[3] = {d.x, d.y, d.z};
    const double p[3] = {dd[1] * e2[2] - dd[2] * e2[1], dd[2] * e2[0] - dd[0] * e2[2], dd[0] * e2[1] - dd[1] * e2[0]};
    const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (!(std::fabs(det) > 0.0)) return false; // parallel, degenerate or NaN
    const double s[3] = {double(o.x) - a.x, double(o.y) - a.y, double(o.z) - a.z};
    const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    if (!(u >= 0.0 && u <= 1.0)) return false;
    const double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
    const double v = (dd[0] * q[0] + dd[1] * q[1] + dd[2] * q[2]) / det;
    if (!(v >= 0.0 && u + v <= 1.0)) return false;
    tHit = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return tHit > 0.0;
}

} // namespace

int pickDraw(const Scene& scene, Vec3 origin, Vec3 dir) {
    int best = -1;
    double bestT = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < scene.draws.size(); ++i) {
        const SceneDraw& d = scene.draws[i];
        if (d.mesh < 0 || std::size_t(d.mesh) >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
        if (std::size_t(d.firstIndex) + d.indexCount > mesh.indices.size()) continue;
        if (drawsBlended(materialOf(scene, d, nullptr), mesh)) continue;
        const std::uint32_t* idx = mesh.indices.data() + d.firstIndex;
        const auto at = [&](std::uint32_t v) { return drawnPosition(d, mesh.positions[v]); };
        for (std::uint32_t k = 0; k + 2 < d.indexCount; k += 3) {
            double t = 0.0;
            if (rayHits(origin, dir, at(idx[k]), at(idx[k + 1]), at(idx[k + 2]), t) && t < bestT) {
                bestT = t;
                best = int(i);
            }
        }
    }
    return best;
}

} // namespace sr
