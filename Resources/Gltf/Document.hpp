// gltf::Document: a glTF 2.0 asset's JSON as typed records (the specification's properties, defaults applied) and its buffers' bytes.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "Resources/Model.hpp" // LoadLimits
#include "Resources/Result.hpp"

namespace sr::gltf {

using Json = nlohmann::json;

// glTF constants (the glTF 2.0 specification, "Accessor", "Mesh").
inline constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
                     kFloat = 5126;
inline constexpr int kModePoints = 0, kModeLines = 1, kModeLineLoop = 2, kModeTriangles = 4, kModeStrip = 5, kModeFan = 6;

// Bytes of one component (0: not a glTF component type), components of one element (0: not a
// glTF element type; MAT2/MAT3 are not read).
int componentSize(int componentType);
int componentCount(const std::string& type);

// A texture reference of a material: the texture, its uv set, its scale (normal maps) or
// strength (occlusion), and its extensions (KHR_texture_transform).
struct TextureInfo {
    int index = -1;
    int texCoord = 0;
    double scale = 1.0, strength = 1.0;
    Json extensions = Json::object();
};

struct Material {
    std::string name;
    struct {
        std::vector<double> baseColorFactor{1, 1, 1, 1};
        double metallicFactor = 1.0, roughnessFactor = 1.0;
        TextureInfo baseColorTexture, metallicRoughnessTexture;
    } pbrMetallicRoughness;
    TextureInfo normalTexture, occlusionTexture, emissiveTexture;
    // KHR_materials_specular's maps (its specularTexture's alpha, its specularColorTexture's RGB).
    TextureInfo specularTexture, specularColorTexture;
    // KHR_materials_clearcoat's maps (the layer's weight in red, its roughness in green, its normal map).
    TextureInfo clearcoatTexture, clearcoatRoughnessTexture, clearcoatNormalTexture;
    // KHR_materials_sheen's maps (the sheen's colour in RGB, its roughness in alpha).
    TextureInfo sheenColorTexture, sheenRoughnessTexture;
    // KHR_materials_pbrSpecularGlossiness, where the material has it, in place of the metallic-
    // roughness block: its diffuse factor and texture are read as the base colour's (into
    // pbrMetallicRoughness), its specularGlossinessTexture as specularColorTexture (RGB) and
    // glossinessTexture (alpha).
    struct {
        bool present = false;
        std::vector<double> specularFactor{1, 1, 1};
        double glossinessFactor = 1.0;
    } specularGlossiness;
    TextureInfo glossinessTexture;
    std::vector<double> emissiveFactor{0, 0, 0};
    std::string alphaMode = "OPAQUE";
    double alphaCutoff = 0.5;
    bool doubleSided = false;
    Json extensions = Json::object();
};

// An accessor; `sparse` holds the substitutions of a sparse one (count 0: none).
struct Accessor {
    int bufferView = -1; // -1: the elements are zeros (before the sparse values), or decoded (Draco)
    std::size_t byteOffset = 0;
    int componentType = 0;
    bool normalized = false;
    std::size_t count = 0;
    std::string type;
    struct Sparse {
        std::size_t count = 0;
        int indicesBufferView = -1, indicesComponentType = 0, valuesBufferView = -1;
        std::size_t indicesByteOffset = 0, valuesByteOffset = 0;
    } sparse;
};

struct BufferView {
    int buffer = -1;
    std::size_t byteOffset = 0, byteLength = 0, byteStride = 0;
    Json extensions = Json::object(); // EXT_meshopt_compression / KHR_meshopt_compression
};

// A buffer's bytes: the GLB's BIN chunk, a data: URI, or an external file; empty when it has
// no uri and is not the GLB's first buffer (a meshopt fallback: nothing may read it).
struct Buffer {
    std::size_t byteLength = 0;
    std::vector<unsigned char> data;
    std::string source; // where the bytes came from, for messages
};

struct Image {
    std::string name, uri, mimeType;
    int bufferView = -1;
};

struct Sampler {
    int minFilter = -1, magFilter = -1, wrapS = 10497, wrapT = 10497;
};

struct Texture {
    int source = -1, sampler = -1;
    Json extensions = Json::object(); // EXT_texture_webp, KHR_texture_basisu, EXT_texture_avif
};

struct Primitive {
    std::map<std::string, int> attributes;
    int indices = -1, material = -1, mode = kModeTriangles;
    std::vector<std::map<std::string, int>> targets;
    Json extensions = Json::object(); // KHR_draco_mesh_compression, KHR_materials_variants
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    std::vector<double> weights;
};

struct Node {
    std::string name;
    int camera = -1, skin = -1, mesh = -1;
    std::vector<int> children;
    std::vector<double> rotation, scale, translation, matrix, weights; // as written (empty: absent)
    Json extensions = Json::object(); // KHR_lights_punctual, EXT_mesh_gpu_instancing
};

struct Skin {
    int inverseBindMatrices = -1;
    std::vector<int> joints;
};

struct AnimationChannel {
    int sampler = -1;
    int target_node = -1;
    std::string target_path;
    std::string pointer; // path "pointer": KHR_animation_pointer's JSON pointer (RFC 6901)
};

struct AnimationSampler {
    int input = -1, output = -1;
    std::string interpolation = "LINEAR";
};

struct Animation {
    std::string name;
    std::vector<AnimationChannel> channels;
    std::vector<AnimationSampler> samplers;
};

struct Camera {
    std::string name, type;
    struct {
        double yfov = 0.0, znear = 0.0, zfar = 0.0, aspectRatio = 0.0;
    } perspective;
};

// A KHR_lights_punctual light.
struct Light {
    std::string name, type;
    std::vector<double> color;
    double intensity = 1.0, range = 0.0;
    struct {
        double innerConeAngle = 0.0, outerConeAngle = 0.7853981633974483;
    } spot;
};

struct Scene {
    std::string name;
    std::vector<int> nodes;
};

struct Document {
    std::vector<Accessor> accessors;
    std::vector<BufferView> bufferViews;
    std::vector<Buffer> buffers;
    std::vector<Image> images;
    std::vector<Sampler> samplers;
    std::vector<Texture> textures;
    std::vector<Material> materials;
    std::vector<Mesh> meshes;
    std::vector<Node> nodes;
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    std::vector<Camera> cameras;
    std::vector<Light> lights;
    std::vector<Scene> scenes;
    int defaultScene = -1;
    std::vector<std::string> extensionsUsed, extensionsRequired;
    std::vector<std::string> variants; // KHR_materials_variants: the names, in order
    std::vector<std::string> warnings; // one line each, without the file's name
};

// Parses the asset (.glb when `data` starts with "glTF", else .gltf JSON) and reads its buffers:
// the GLB's BIN chunk, data: URIs (base64), external files relative to `dir` (each within
// limits.maxFileBytes, all together within limits.maxMemoryBytes). Property types are checked
// against the core schema (a wrong type is an error naming the property; an integer may be
// written as an integral number, "4.0"). A buffer without a uri other than the GLB's first is
// left empty. Errors are one line without the file's name.
Result<Document> parseDocument(const unsigned char* data, std::size_t size, const std::string& dir, const LoadLimits& limits);

// Percent-decoding of a relative URI (glTF: "URIs are relative to the .gltf file").
std::string decodeUri(const std::string& uri);

// The bytes of a data: URI's base64 payload, or a failure naming what is wrong with it.
Result<std::vector<unsigned char>> decodeDataUri(const std::string& uri);

} // namespace sr::gltf
