// Animation: glTF keyframe samplers, node channels, morph targets and skins, and the pose they give a model's mesh at a time.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "Math/DoubleMath.hpp"
#include "Math/Vec.hpp"
#include "Raster/Geometry/Mesh.hpp"
#include "Raster/Shade/Shading.hpp" // Light
#include "Resources/MaterialFactors.hpp"
#include "Resources/Model.hpp" // Material, for PosedProperties

namespace sr {

// A node's local transform T R S (glTF "Transformations"): a translation, a unit quaternion
// (x, y, z, w) and a scale, as a matrix (the loader's rest transforms and the animated ones alike).
Mat4d trsMatrix(const std::array<double, 3>& t, const std::array<double, 4>& q, const std::array<double, 3>& s);

// A keyframe sampler (glTF "animation.sampler"): key times (strictly increasing, finite) and
// `components` values per key (three elements per key for CUBICSPLINE: in-tangent, value,
// out-tangent, as the specification stores them).
struct AnimationSampler {
    enum class Interpolation { Linear, Step, CubicSpline };
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times;
    std::vector<double> values;
    int components = 1;
    bool quaternion = false; // a rotation: LINEAR is slerp along the shorter arc, every result normalised

    // The value at time t into out[0 .. components): before the first key the first value, after
    // the last the last; between keys k and k + 1 with s = (t - t_k) / (t_k+1 - t_k):
    //  STEP         v_k;
    //  LINEAR       v_k + s (v_k+1 - v_k); a quaternion slerps (q_k+1 negated when q_k . q_k+1 < 0,
    //               as three.js does, so it turns the short way), normalised;
    //  CUBICSPLINE  the Hermite spline (2s^3 - 3s^2 + 1) v_k + (s^3 - 2s^2 + s) d b_k +
    //               (-2s^3 + 3s^2) v_k+1 + (s^3 - s^2) d a_k+1, d = t_k+1 - t_k, b the out-tangent,
    //               a the in-tangent (glTF appendix C); a quaternion normalised.
    void evaluate(double t, double* out) const;
};

// What a channel drives: a node's translation, rotation, scale, or its mesh's morph weights.
enum class AnimationPath { Translation, Rotation, Scale, Weights };

struct AnimationChannel {
    int node = 0; // index into ModelAnimation::nodes
    AnimationPath path = AnimationPath::Translation;
    int sampler = 0; // index into its clip's samplers
};

// A KHR_animation_pointer target besides a node's transform and weights: a material's factor
// ("/materials/{m}/pbrMetallicRoughness/baseColorFactor", ...), a KHR_lights_punctual light's
// property ("/extensions/KHR_lights_punctual/lights/{l}/intensity", ...) or a perspective
// camera's ("/cameras/{c}/perspective/yfov", ...).
enum class AnimatedProperty : std::uint8_t {
    BaseColor, Metallic, Roughness, Emissive, EmissiveStrength, NormalScale, OcclusionStrength, AlphaCutoff,
    Ior, SpecularFactor, SpecularColor, Clearcoat, ClearcoatRoughness, ClearcoatNormalScale, SheenColor, SheenRoughness,
    TextureOffset, TextureRotation, TextureScale, // a texture reference's KHR_texture_transform
    LightColor, LightIntensity, LightRange, SpotInnerCone, SpotOuterCone,
    CameraYfov, CameraZnear, CameraZfar,
};
enum class PropertyOwner { Material, Light, Camera };
PropertyOwner ownerOf(AnimatedProperty p);
int componentsOf(AnimatedProperty p); // the values per key: 4 (base colour), 3 (colours), 2 (uv offset, scale), else 1
constexpr bool isTextureTransform(AnimatedProperty p) {
    return p == AnimatedProperty::TextureOffset || p == AnimatedProperty::TextureRotation || p == AnimatedProperty::TextureScale;
}

// The property a KHR_animation_pointer JSON pointer names, the index of its material, light
// (the file's KHR_lights_punctual.lights) or camera, and for a texture transform its reference
// (`reference`: 0 the base colour texture, 1 + a MapSlot); false for any other pointer (a
// node's, an extension SoftRaster does not read).
bool propertyPointer(const std::string& pointer, AnimatedProperty& property, int& target, int& reference);

struct PropertyChannel {
    AnimatedProperty property = AnimatedProperty::BaseColor;
    int target = 0;    // the material, light or camera (the file's numbering)
    int reference = 0; // a texture transform's texture reference (propertyPointer)
    int sampler = 0;   // index into its clip's samplers
};

struct AnimationClip {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
    std::vector<PropertyChannel> properties;
    double duration = 0.0; // the last key time of its samplers
};

// A node of the file: its parent (-1 for a root or a node outside the scene) and its rest
// transform, TRS (a node given by a matrix cannot be animated: glTF "Animations").
struct AnimationNode {
    int parent = -1;
    bool hasMatrix = false;
    Mat4d matrix;                                 // hasMatrix
    std::array<double, 3> translation{0, 0, 0};
    std::array<double, 4> rotation{0, 0, 0, 1};   // x, y, z, w
    std::array<double, 3> scale{1, 1, 1};
    std::vector<double> weights;                  // the rest morph weights: the node's, else its mesh's
};

struct AnimationSkin {
    std::vector<int> joints;         // nodes
    std::vector<Mat4d> inverseBind;  // one per joint (identity when the file gives none)
};

// One primitive's vertices in the model's mesh, [first, first + count), and what moves them.
struct AnimatedBlock {
    int node = 0;       // the node whose mesh it is
    int skin = -1;      // index into ModelAnimation::skins, or -1
    std::uint32_t first = 0, count = 0;
    bool mirrored = false;   // the rest transform mirrors: its triangles were stored reversed
    // One instance of an EXT_mesh_gpu_instancing node: its instance transform, applied before the
    // node's world transform (not for a skinned block).
    bool instanced = false;
    Mat4d instance;
    bool moves = true;        // some clip moves it (markMovingBlocks); false: pose leaves it at rest
    bool flatNormals = false; // no NORMAL: each vertex belongs to one triangle (first + 3t ..), the face normal
    std::vector<Vec3> positions, normals;         // object space, one per vertex (normals: when !flatNormals)
    std::vector<Vec4> tangents;                   // object space, when the mesh keeps tangents for this block
    // Morph target deltas, one list per target (normals and tangents may be empty: none).
    std::vector<std::vector<Vec3>> targetPositions, targetNormals, targetTangents;
    std::vector<std::array<std::uint16_t, 8>> joints;  // JOINTS_0 and _1 (indices into the skin's joints)
    std::vector<std::array<float, 8>> weights;         // WEIGHTS_0 and _1, normalised to sum 1
};

// A light of the scene (Model::lights, node order) as its file gives it, for animated lights: its
// KHR_lights_punctual light and that light's colour, intensity, range and cone angles (radians).
struct LightSource {
    int light = 0;
    int node = -1;      // the node that places it
    bool moves = false; // a clip moves that node or an ancestor (markMovingBlocks)
    Light placed; // the light as the loader placed it (position, direction, type)
    std::array<double, 3> colour{1, 1, 1};
    double intensity = 1.0, range = 0.0, innerCone = 0.0, outerCone = 0.7853981633974483;
};
// A camera of the scene (Model::cameras, node order) as its file gives it, for animated cameras.
struct CameraSource {
    int camera = 0;
    double yfov = 0.0, znear = 0.0, zfar = 0.0; // radians; zfar 0: infinite
    int node = -1;      // the node that places it
    bool moves = false; // a clip moves that node or an ancestor (markMovingBlocks)
    Vec3 eye, target, up; // as the loader placed it (ModelCamera)
};

// The animated materials, lights and cameras at one time (ModelAnimation::poseProperties).
struct PosedProperties {
    std::vector<int> materials;         // each material a clip animates (the file's numbering)
    std::vector<Material> values;       // its colours, opacity and pbr input at that time (applyFactors)
    std::vector<Light> lights;          // every light of the scene (Model::lights); empty: none animated or moved
    struct Camera {
        double yfovDegrees, znear, zfar; // zfar 0: infinite
        Vec3 eye, target, up;            // where its node is at that time
    };
    std::vector<Camera> cameras;        // every camera of the scene (Model::cameras); empty: none animated or moved
    // Each material whose texture transforms a clip animates: every reference's transform at that
    // time on stored uvs (MapAddress::m; the base colour texture's, then each MapSlot's).
    struct Transforms {
        int material = 0;
        std::array<std::array<std::array<float, 3>, 2>, 1 + kMapSlots> m;
    };
    std::vector<Transforms> transforms;
};

// Everything a glTF file animates, kept beside the model's mesh (Model::animation): null for a
// file without animations, skins or morph targets, so such a scene runs and allocates nothing for
// animation.
struct ModelAnimation {
    std::vector<AnimationNode> nodes;
    std::vector<AnimationClip> clips;
    std::vector<AnimationSkin> skins;
    std::vector<AnimatedBlock> blocks;
    // What property channels read: every material's numbers (the file's order; only when some
    // clip animates a material), every scene light's and perspective camera's source.
    std::vector<MaterialFactors> materials;
    std::vector<LightSource> lights;
    std::vector<CameraSource> cameras;

    // Sets each block's `moves`: a channel of some clip on its node or an ancestor, on one of its
    // skin's joints or their ancestors, or on its node's weights; and each light's and camera's
    // (a channel on its node or an ancestor). Once, after loading.
    void markMovingBlocks();

    // The longest clip's duration (all clips: `clip` < 0), or clip `clip`'s.
    double duration(int clip = -1) const;

    // Writes the blocks' vertices (positions, normals, and tangents where the mesh has them) into
    // `mesh` (the model's mesh, numbered as loaded) posed at time t: the clips' channels (all of
    // them in file order, a later channel on the same target winning, or clip `clip` alone;
    // `clip` beyond the clips: none), each clip at t modulo its duration (looped, as viewers and
    // three.js play them; t = duration shows its first key), over the rest transforms, then each block's morph targets
    // (position and normal deltas weighted), its node's world transform (times its instance's
    // transform for an instanced block), or for a skinned block
    // sum_j w_j (world(joint j) x inverseBind_j) as the specification says (the mesh node's own
    // transform ignored), normals by the inverse transpose (renormalised), tangents by the
    // matrix (their morph deltas added first). A block that no clip
    // moves at any time (no channel on its node, an ancestor or a joint, no weights channel) is
    // left as it is: `mesh` must hold the rest pose there. `restOnly`: no clip, the rest
    // transforms and weights, every block written.
    void pose(double t, int clip, Mesh& mesh, bool restOnly = false) const;

    // Whether some clip animates a material, light or camera (a property channel, or the node of
    // a light or camera).
    bool animatesProperties() const;
    bool animatesMaterial(int material) const;
    // Whether some clip animates one of the material's texture transforms.
    bool animatesTransforms(int material) const;
    // The animated materials, lights and cameras at time t (clips as in pose; a later channel on
    // the same property wins; a light or camera whose node moves placed by its node's world
    // transform at t, as the loader places it). A value outside its property's range is treated as the loader
    // treats it in a file: clamped (factors, angles), a light's intensity and range at least 0,
    // a spot's inner cone kept below its outer; a camera's yfov outside (0, pi), znear <= 0 or a
    // zfar not beyond znear keep the file's value.
    PosedProperties poseProperties(double t, int clip) const;

    // Every node's world transform at time t (the rest transforms with `restOnly`), and its
    // morph weights: what pose and poseProperties place things by.
    void nodeWorlds(double t, int clip, bool restOnly, std::vector<Mat4d>& world, std::vector<std::vector<double>>& weights) const;
};

} // namespace sr
