// Model: a loaded OBJ (mesh, materials, textures, draw ranges) and the options/limits of its loader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "Math/Vec.hpp"
#include "Raster/Mesh.hpp"
#include "Resources/Image.hpp"

namespace sr {

// One OBJ material as the renderer uses it: only the diffuse map matters (MTL Kd/Ka/Ks/Ns are
// ignored, as in the llvmpipe reference; untextured faces use kd = 0.8 grey at render time).
struct Material {
    std::string name;
    int texture = -1; // index into Model::textures, or -1 = untextured
};

// The triangles of one texture: one draw call. Ranges are keyed by TEXTURE (as glref splits its
// runs), so `material` is the material of the range's first triangle in the file; every triangle
// in the range has a material whose texture equals `texture` (faces without a material count as
// texture -1). One range per texture, in the order of each texture's first face in the file,
// the faces of a range in file order (ObjLoader.hpp: "Draw order"); together the ranges cover
// Mesh::indices once, in order.
struct DrawRange {
    std::uint32_t firstIndex = 0, indexCount = 0; // into Mesh::indices (3 per triangle)
    int material = -1;                            // index into Model::materials, or -1
    int texture = -1; // == (material >= 0 ? materials[material].texture : -1), for convenience
};

struct Model {
    Mesh mesh; // normals always present (one per vertex); uvs only when hasUvs
    std::vector<DrawRange> ranges;
    std::vector<Material> materials;
    std::vector<Image> textures;           // top row first; OBJ v = 0 is the image's BOTTOM row
    std::vector<std::string> texturePaths; // resolved path of each texture (parallel to textures)
    Vec3 boundsMin, boundsMax; // AABB of ALL 'v' entries (used or not), for the auto-fit camera
    bool hasUvs = false;          // the OBJ has at least one 'vt'
    bool normalsFromFile = false; // every face-vertex had a 'vn' (else some were computed)
    std::vector<std::string> warnings; // one line each, naming the file
};

// Resource limits for files from untrusted sources: exceeding one is a clear error, never an
// exhausted machine. The memory estimate covers tinyobjloader's temporary arrays plus ours.
struct ObjLimits {
    std::size_t maxFileBytes = std::size_t(256) << 20;     // the .obj itself
    std::size_t maxMtlBytes = std::size_t(16) << 20;       // each .mtl
    std::size_t maxMaterials = 65536;                      // over all .mtl files
    std::size_t maxVertices = std::size_t(1) << 24;        // each of v / vn / vt entries
    std::size_t maxTriangles = std::size_t(1) << 24;       // after triangulation
    std::size_t maxFaceVertices = 1024;                    // per polygon (ear clipping is O(n^2+))
    std::size_t maxPolygonWork = std::size_t(1) << 28;     // sum of n^2 over polygons with n > 4
    std::size_t maxMemoryBytes = std::size_t(4) << 30;     // estimated peak while loading (upper bound)
    std::size_t maxTextureBytes = std::size_t(1) << 30;    // decoded RGBA of all textures
};

struct ObjOptions {
    std::string textureOverride; // --texture PATH: replaces every material's map (error if unloadable)
    bool loadTextures = true;    // false: textures keep their slots and paths but stay 0x0, no decode
    ObjLimits limits;
};

// The default texture given to a material whose map is missing or cannot be decoded: an 8x8
// magenta/black checkerboard (one texel per square), visible on purpose.
Image defaultCheckerTexture();

} // namespace sr
