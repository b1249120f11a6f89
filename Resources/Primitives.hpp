// Procedural meshes (with normals and uvs) and textures for the built-in scene and the tests.
#pragma once

#include <cstdint>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Mat4.hpp"
#include "Raster/Geometry/Mesh.hpp"
#include "Resources/Image.hpp"

namespace sr {

// A quad in the XZ plane (y = 0) spanning [-halfX, halfX] x [-halfZ, halfZ], facing +Y, split
// into n x n cells; uv runs 0..uvScale across it.
Mesh makeGroundPlane(float halfX, float halfZ, int n, float uvScale);

// A unit quad in the XY plane ([-0.5, 0.5]^2, z = 0) facing +Z, uv 0..1.
Mesh makeQuad();

// An axis-aligned cube [-0.5, 0.5]^3: 24 vertices (flat normals per face), uv 0..1 per face.
Mesh makeCube();

// A UV sphere of radius 1: `rings` latitude bands x `segments` longitude slices, smooth normals.
Mesh makeSphere(int segments, int rings);

// A torus around +Y: major radius R, minor radius r, smooth normals, uv wrapping once.
Mesh makeTorus(float majorRadius, float minorRadius, int segments, int sides);

// Applies an affine transform to positions and (inverse-transpose) to normals, in place.
void transformMesh(Mesh& mesh, const Mat4& transform);

// Procedural textures (RGBA8, top row first, as decoded images are).
Image makeCheckerImage(int size, int cells, Color a, Color b);
Image makeBrickImage(int size);

} // namespace sr
