// gltfimport tangents: per-vertex tangent frames generated from a primitive's uvs, for normal maps without a TANGENT attribute.
#include <cmath>

#include "Resources/Gltf/Import.hpp"

namespace sr::gltfimport {

// Per-vertex tangents of vertices [base, end) from their triangles `tris` (numbered from base),
// appended to mesh.tangents: each triangle's dp/du (Lengyel, "Computing Tangent Space Basis
// Vectors for an Arbitrary Mesh", 2001), summed per vertex (weighted by the triangle's uv area,
// as the unnormalised sum is), made orthogonal to the normal; w = +1 when n x t points along
// dp/dv (our v, which grows up the image: glTF's bitangent), else -1. A vertex whose triangles
// give no tangent (degenerate uvs) gets any unit vector orthogonal to its normal. The uvs are
// mesh.uvs, or `uvs` where given (a normal map read at its own address: MapAddressing).
void addTangents(Mesh& mesh, std::uint32_t base, const std::vector<std::uint32_t>& tris, const std::vector<Vec2>* uvs) {
    const std::size_t count = mesh.positions.size() - base;
    std::vector<Vec3d> tu(count, Vec3d{}), tv(count, Vec3d{});
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
        const std::uint32_t i[3] = {tris[t], tris[t + 1], tris[t + 2]};
        const Vec3d p0(mesh.positions[base + i[0]]), p1(mesh.positions[base + i[1]]), p2(mesh.positions[base + i[2]]);
        const auto uvAt = [&](std::uint32_t k) { return uvs ? (*uvs)[k] : mesh.uvs[base + k]; };
        const Vec2 w0 = uvAt(i[0]), w1 = uvAt(i[1]), w2 = uvAt(i[2]);
        const double du1 = double(w1.x) - w0.x, dv1 = double(w1.y) - w0.y, du2 = double(w2.x) - w0.x, dv2 = double(w2.y) - w0.y;
        const double det = du1 * dv2 - du2 * dv1;
        if (!(std::fabs(det) > 1e-20) || !std::isfinite(det)) continue;
        const Vec3d e1 = p1 - p0, e2 = p2 - p0;
        const Vec3d sdir = (e1 * dv2 - e2 * dv1) / det, tdir = (e2 * du1 - e1 * du2) / det;
        if (!std::isfinite(length(sdir)) || !std::isfinite(length(tdir))) continue;
        for (std::uint32_t k : i) {
            tu[k] = tu[k] + sdir;
            tv[k] = tv[k] + tdir;
        }
    }
    for (std::size_t k = 0; k < count; ++k) {
        const Vec3d n(mesh.normals[base + k]);
        Vec3d t = tu[k] - n * dot(n, tu[k]);
        double l = length(t);
        if (!(l > 1e-12) || !std::isfinite(l)) { // any vector orthogonal to n
            t = std::fabs(n.x) < 0.9 ? cross(n, Vec3d{1, 0, 0}) : cross(n, Vec3d{0, 1, 0});
            l = length(t);
        }
        t = t / l;
        const double w = dot(cross(n, t), tv[k]) < 0.0 ? -1.0 : 1.0;
        mesh.tangents.emplace_back(float(t.x), float(t.y), float(t.z), float(w));
    }
}

} // namespace sr::gltfimport
