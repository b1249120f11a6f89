// Model: a loaded OBJ (mesh, materials, textures, draw ranges) and the options/limits of its loader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Mat4.hpp"
#include "Math/Vec.hpp"
#include "Raster/Fill/Blend.hpp" // TexelAlpha
#include "Raster/Geometry/Mesh.hpp"
#include "Raster/Shade/Brdf.hpp"  // PbrFactors
#include "Raster/Shade/MaterialMaps.hpp"
#include "Raster/Shade/Shading.hpp" // Light
#include "Raster/Texture/Texture.hpp" // WrapMode, TextureFilter
#include "Resources/Image.hpp"

namespace sr {

struct ModelAnimation; // Resources/Animation.hpp

// One material as the renderer uses it: its diffuse map and the values the shading reads. From
// an MTL: Kd, Ks, Ns (Ka, Ke, d, illum and the rest are ignored, as in the llvmpipe reference),
// tinyobjloader's values with its defaults where a line is missing (Kd = Ks = 0, Ns = 1; a
// material with map_Kd and no Kd line gets Kd 0.6). From glTF: metallic-roughness mapped to
// these (GltfLoader.hpp). How they are used: sceneFromModel (Platform/App/SceneSetup.cpp) and
// README "Materials".
struct Material {
    std::string name;
    int texture = -1;      // index into Model::textures, or -1 = untextured
    bool fromFile = false; // read from the model's file (false: the --texture override's stand-in)
    bool hasMap = false;   // an MTL that names a map_Kd (whether or not it loads); false for glTF
    Color kd{0.0f, 0.0f, 0.0f, 1.0f}, ks{0.0f, 0.0f, 0.0f, 1.0f};
    float shininess = 1.0f;
    float alpha = 1.0f; // opacity: MTL d (or 1 - Tr); glTF baseColorFactor alpha under BLEND, 0 or 1 under MASK
    // glTF MASK / BLEND with a base colour texture: the per-fragment rule, used when the texture
    // has alpha (Raster/Fill/Blend.hpp; `alpha` above is then the rule for an opaque texture).
    TexelAlpha texelAlpha;
    bool doubleSided = true; // glTF doubleSided (its default: false, back faces culled whatever --cull says); OBJ: true
    // glTF: the sampler of its maps (its first map's, the base colour texture first), where it
    // says (the draw's wrap and filter unless --wrap / --filter chose them:
    // RenderSettings::wrapFromFile, filterFromFile). OBJ: unset.
    std::optional<WrapModes> wrap;
    std::optional<TextureFilter> filter;
    // glTF: the metallic-roughness material as the specification defines it (the pbr shading
    // model's input; kd, ks and shininess above are its Blinn-Phong mapping), and its other maps
    // (indices into Model::textures, -1 = none; sampled with the base colour texture's sampler).
    std::optional<PbrFactors> pbr;
    MaterialMaps<int> maps;
    // glTF: each map's own uv set, transform and sampler, for a material whose maps do not share
    // them (Mesh::uvSets then holds the raw sets); unset where they do (the maps read Mesh::uvs
    // with `wrap` and `filter`).
    std::optional<MapAddressing> addressing;
};

// The triangles of one material: one draw call. One range per material (faces without one form
// the material -1 range), in the order of each material's first face in the file, the faces of a
// range in file order (ObjLoader.hpp: "Draw order"); together the ranges cover Mesh::indices
// once, in order.
struct DrawRange {
    std::uint32_t firstIndex = 0, indexCount = 0; // into Mesh::indices (3 per triangle)
    int material = -1;                            // index into Model::materials, or -1
    int texture = -1; // == (material >= 0 && hasUvs ? materials[material].texture : -1), for convenience
    // glTF EXT_mesh_gpu_instancing: the range's vertices, Mesh::positions[firstVertex ..
    // firstVertex + vertexCount), are in the mesh's own space and the range is drawn once at each
    // of these places (mesh to world; Raster/Geometry/Placement.hpp). A range whose places mirror
    // lists its faces reversed. Empty: the range is in world space, drawn once.
    std::vector<Mat4> instances;
    std::uint32_t firstVertex = 0, vertexCount = 0;
};

// Line segments (index pairs) or points of the file (glTF POINTS / LINES / LINE_LOOP /
// LINE_STRIP), in world space, with their material (-1: none).
struct LineSet {
    std::vector<Vec3> positions;
    std::vector<std::uint32_t> indices; // 2 per segment, 1 per point; each < positions.size()
    bool points = false;
    int material = -1;
};

// A perspective camera of the file (glTF), in world space: it looks down its node's -Z with +Y up.
struct ModelCamera {
    std::string name;
    Vec3 eye{0, 0, 0}, target{0, 0, -1}, up{0, 1, 0};
    double yfovDegrees = 60.0;
    double znear = 0.1;
    double zfar = 0.0; // 0: none (infinite)
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
    std::vector<ModelCamera> cameras;  // glTF: the scene's perspective cameras, in node order
    std::vector<LineSet> lineSets;     // glTF: line and point primitives (OBJ 'l'/'p' are not read)
    std::vector<Light> lights;         // glTF KHR_lights_punctual: the scene's lights in world space, in node order
    std::vector<std::string> warnings; // one line each, naming the file
    // glTF KHR_materials_variants: the file's variant names, and the one drawn (-1: the
    // primitives' own materials).
    std::vector<std::string> variants;
    int variant = -1;
    // glTF animations, skins and morph targets (Animation.hpp): null when the file has none. The
    // mesh above is their rest pose.
    std::shared_ptr<const ModelAnimation> animation;
};

// Resource limits of both loaders (OBJ/MTL and glTF) for files from untrusted sources: exceeding
// one is a clear error, never an exhausted machine. The memory estimate covers tinyobjloader's
// temporary arrays plus ours.
struct LoadLimits {
    std::size_t maxFileBytes = std::size_t(256) << 20;     // the .obj, .gltf or .glb, and each file a glTF reads
    std::size_t maxMtlBytes = std::size_t(16) << 20;       // each .mtl
    std::size_t maxMaterials = 65536;                      // over all .mtl files, or in the glTF file
    std::size_t maxVertices = std::size_t(1) << 24;        // each of v / vn / vt entries; glTF: vertices
    std::size_t maxTriangles = std::size_t(1) << 24;       // after triangulation; glTF: as drawn, each instance's counted
    std::size_t maxFaceVertices = 1024;                    // per polygon (ear clipping is O(n^2+))
    std::size_t maxPolygonWork = std::size_t(1) << 28;     // sum of n^2 over polygons with n > 4
    std::size_t maxMemoryBytes = std::size_t(4) << 30;     // estimated peak while loading (upper bound)
    std::size_t maxTextureBytes = std::size_t(1) << 30;    // decoded RGBA of all textures
    std::size_t maxNodes = 65536;                          // glTF: nodes in the file
    std::size_t maxNodeDepth = 64;                         // glTF: levels of the node hierarchy
    std::size_t maxLights = 64;                            // glTF: lights placed in the scene (each costs per pixel)
    std::size_t maxAnimationKeys = std::size_t(1) << 22;   // glTF: key times over all samplers
    std::size_t maxJoints = 1024;                          // glTF: joints per skin
    std::size_t maxMorphTargets = 64;                      // glTF: morph targets per primitive
    std::size_t maxInstanceDraws = 65536;                  // glTF: draws of instanced meshes (instances x primitives)
};

// What loadModel, loadObj and loadGltf are asked to do: the texture override, whether to decode
// textures, and the limits.
struct LoadOptions {
    std::string textureOverride; // --texture PATH: replaces every material's map (error if unloadable)
    bool loadTextures = true;    // false: textures keep their slots and paths but stay 0x0, no decode
    std::string variant;         // glTF KHR_materials_variants: the variant to draw (empty: none; unknown: an error)
    LoadLimits limits;
};

// Every vertex position of the model in world space: the vertices of an instanced range once per
// place, every other vertex (used or not) as stored.
void forEachWorldPosition(const Model& model, const std::function<void(Vec3)>& visit);

// The model with its instanced ranges written out: each place's copy of the range's vertices,
// moved as the vertex stage moves them (Placement: position, normal, tangent), in one world-space
// range each. The reference the instanced draws are tested against.
void writeOutInstances(Model& model);

// The default texture given to a material whose map is missing or cannot be decoded: an 8x8
// magenta/black checkerboard (one texel per square), visible on purpose.
Image defaultCheckerTexture();

} // namespace sr
