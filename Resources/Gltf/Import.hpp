// gltfimport: the steps that turn a gltf::Document into a Model (nodes, primitives, materials, textures, animation), and the state they share while walking the scene.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "Math/DoubleMath.hpp"
#include "Resources/Animation.hpp"
#include "Resources/Gltf/Accessors.hpp"
#include "Resources/Gltf/Document.hpp"
#include "Resources/MaterialFactors.hpp"
#include "Resources/Model.hpp"

namespace sr::gltfimport {

using gltf::readFloat;
using gltf::readIndex;
using gltf::readIndexComponent;
using gltf::View;

// Everything gathered while walking the scene: vertices in world space, triangles per material.
struct Builder {
    std::string path; // the file, for warnings
    const gltf::Document* doc = nullptr;
    gltf::Accessors* accessors = nullptr;
    Model model;
    // A file with animations, skins or morph targets: what moves (null otherwise: nothing kept).
    std::shared_ptr<ModelAnimation> animation;
    const gltf::Node* node = nullptr; // the node whose primitives are being added
    int nodeIndex = -1;
    const Mat4d* instance = nullptr;  // its EXT_mesh_gpu_instancing instance being added, if any
    std::vector<std::vector<std::uint32_t>> trianglesOf; // [material + 1] -> indices
    std::vector<int> firstUse;                           // materials (+1) in order of first use
    std::size_t lineElements = 0, lineVertices = 0; // in model.lineSets, for the limits
    std::size_t triangles = 0; // in trianglesOf (the mesh's indices are filled at the end)
    bool anyComputedNormal = false, anyFileNormal = false;
    // An instanced node's triangle primitives are added once, in the mesh's own space (`placing`),
    // each kept here with its material, vertex block and triangles, drawn at the node's places
    // (DrawRange::instances).
    struct PlacedPrimitive {
        int material = -1;
        std::uint32_t firstVertex = 0, vertexCount = 0;
        std::vector<std::uint32_t> triangles; // counter-clockwise, into the mesh
        std::vector<Mat4> places;             // mesh to world, one per instance
    };
    bool placing = false;
    std::vector<PlacedPrimitive> placed;
    std::size_t instanceDraws = 0;     // places over all placed primitives (LoadLimits::maxInstanceDraws)
    std::size_t instancedTriangles = 0; // the triangles their places draw beyond the stored ones
    // [material]: an animation moves one of its texture transforms (KHR_animation_pointer): its
    // maps are drawn at their own addresses from the raw uv sets (materialAddressing's `force`).
    std::vector<std::uint8_t> animatedTransforms;
    bool transformsMove(int material) const {
        return material >= 0 && std::size_t(material) < animatedTransforms.size() && animatedTransforms[std::size_t(material)] != 0;
    }
};

// Nodes.cpp: the node's local transform (glTF: matrix, column-major, or T * R * S).
Mat4d localMatrix(const gltf::Node& n);
bool finite(const Mat4d& m);
// The matrix in single precision (Mat4d is row by row, Mat4 column by column).
Mat4 toMat4(const Mat4d& m);
// A camera node: eye = the node's origin, forward = its -Z, up = its +Y (glTF "Cameras").
Status addCamera(Builder& b, const gltf::Camera& c, const Mat4d& world, int index);
// A KHR_lights_punctual light placed by a node.
Status addLight(Builder& b, const gltf::Light& l, const Mat4d& world, int index);
// The KHR_lights_punctual light a node places (-1: none); a malformed reference is an error.
Result<int> nodeLight(const gltf::Node& node, std::size_t lightCount);
// EXT_mesh_gpu_instancing: the node's instance transforms (TRANSLATION, ROTATION, SCALE
// accessors, one element per instance), each to be applied before the node's world transform;
// empty when the node is not instanced.
Result<std::vector<Mat4d>> instanceMatrices(Builder& b, const gltf::Node& node, int nodeIndex);

// Materials.cpp: the metallic-roughness material and its Blinn-Phong mapping (GltfLoader.hpp):
// the material's numbers as the file gives them, and the Material they make (applyFactors).
MaterialFactors factorsOf(const gltf::Material& gm);
Material materialFrom(const gltf::Material& gm);

// The reference of a material's map in a slot: its texture, uv set and transform.
const gltf::TextureInfo& textureInfoOf(const gltf::Material& gm, MapSlot slot);
// A glTF sampler as SoftRaster's wrap modes and filter (see Materials.cpp).
struct SamplerModes {
    WrapModes wrap;
    std::optional<TextureFilter> filter;
    std::string problem;
};
SamplerModes samplerModes(const gltf::Sampler& s);
// KHR_texture_transform of one texture reference, as the 2x3 matrix uv' = M (u, v, 1) in glTF's
// uv space (v down the image): translation x rotation x scale, the extension's order. `found`:
// the reference carries the extension.
struct UvTransform {
    double m[2][3] = {{1, 0, 0}, {0, 1, 0}};
    bool found = false;
    bool operator==(const UvTransform& o) const;
};
UvTransform uvTransformOf(const gltf::Json& extensions);
struct UvSource {
    int texCoord = 0; // TEXCOORD_<texCoord>
    UvTransform transform;
};
UvSource materialUvSource(const gltf::Material& gm);
SamplerModes materialSampler(const gltf::Document& g, const gltf::Material& gm);
// `force`: an address for each map even where they share one (a material whose transforms move).
std::optional<MapAddressing> materialAddressing(const gltf::Document& g, const gltf::Material& gm, std::string* problem, bool force = false);

// Tangents.cpp: per-vertex tangents of vertices [base, end) from their triangles, along the
// mesh's uvs or `uvs` (vertex base + k reads (*uvs)[k]: a normal map's own).
void addTangents(Mesh& mesh, std::uint32_t base, const std::vector<std::uint32_t>& tris, const std::vector<Vec2>* uvs = nullptr);

// Primitives.cpp: one primitive of a node, its triangles (or lines and points) in world space.
Status addPrimitive(Builder& b, const gltf::Primitive& prim, const Mat4d& world, const std::string& what, const LoadLimits& limits);

// AnimatedBlocks.cpp: a primitive of an animated file: its object-space vertices (vertex i
// reads accessor element source[i], or i when `source` is empty), morph targets and skin
// attributes, for ModelAnimation::pose.
Status addAnimatedBlock(Builder& b, const gltf::Primitive& prim, const View& pos, const std::optional<View>& normals,
                        bool keepTangents, std::uint32_t first, std::size_t vertices, const std::vector<std::uint32_t>& source,
                        bool mirrored, const std::string& what, const LoadLimits& limits);

// AnimationClips.cpp: the nodes' rest transforms and weights, the skins and the clips.
Status addAnimation(ModelAnimation& a, const gltf::Document& g, gltf::Accessors& accessors, std::vector<std::string>& warnings,
                    const std::string& path, const LoadLimits& limits);

// Textures.cpp: the materials' texture slots and their decoded images (one slot per image),
// the samplers of the base colour textures; errors are one line naming the file.
Status addTextures(Builder& b, const LoadOptions& options, const std::string& dir);

} // namespace sr::gltfimport
