// Placement: where the vertices of a mesh drawn as one instance of many go in the world.
#pragma once

#include "Math/Mat4.hpp"
#include "Math/Vec.hpp"

namespace sr {

// A mesh stored once in its own space and drawn at several places (glTF EXT_mesh_gpu_instancing)
// is drawn once per place with that place's Placement: the vertex stage moves each vertex into
// the world (no copy of the mesh per place). Positions go through `toWorld`; normals through the
// cofactor matrix of its upper 3x3 (the inverse transpose times the determinant: the scale drops
// out with the renormalisation) times the determinant's sign, renormalised; tangents through the
// upper 3x3, renormalised, their handedness w times that sign (a mirror turns the bitangent).
// A mirroring placement (determinant below 0) also turns counter-clockwise faces clockwise: the
// draw's indices list its faces reversed (the glTF loader keeps a reversed copy of the indices).
struct Placement {
    Mat4 toWorld = Mat4::identity();
    Vec3 normalRows[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; // the normal matrix, row by row
    float handedness = 1.0f;                                // the sign of the determinant: -1 mirrors

    static Placement of(const Mat4& toWorld);
    bool mirrors() const { return handedness < 0.0f; }

    Vec3 position(Vec3 p) const { return (toWorld * Vec4(p, 1.0f)).xyz(); }
    Vec3 normal(Vec3 n) const {
        return normalize(Vec3{dot(normalRows[0], n), dot(normalRows[1], n), dot(normalRows[2], n)});
    }
    Vec4 tangent(Vec4 t) const {
        return Vec4(normalize((toWorld * Vec4(t.xyz(), 0.0f)).xyz()), t.w * handedness);
    }
};

} // namespace sr
