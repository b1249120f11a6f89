// GltfLoader: loads a glTF 2.0 scene (.gltf with external or embedded buffers, .glb; compressed, quantized or instanced) into a Model.
#pragma once

#include <cstddef>
#include <string>

#include "Resources/Model.hpp"
#include "Resources/Result.hpp"

namespace sr {

// Loads the default scene of a glTF 2.0 asset (its `scene`, or scene 0 when none is named) into
// the same Model an OBJ gives, in world space:
//  - the document (Resources/Gltf/Document.hpp): our own reader of the JSON (nlohmann-json) and
//    of the GLB container; buffers from the BIN chunk, data: URIs or files;
//  - accessors as the specification defines them (Accessors.hpp): byte strides, sparse
//    substitutions, accessors without a buffer view (zeros), normalised or plain integers;
//  - encodings, decoded once at load (Codecs.hpp): KHR_mesh_quantization (byte and short
//    positions, normals, tangents, uvs), EXT_meshopt_compression and KHR_meshopt_compression
//    (libmeshoptimizer), KHR_draco_mesh_compression (Draco), EXT_texture_webp (libwebp),
//    EXT_texture_avif (libavif, Linux build); KHR_texture_basisu images (and AVIF ones in a
//    build without libavif) fall back to the texture's own source;
//  - nodes: the hierarchy's TRS or matrix transforms, nested, applied to POSITION (in double,
//    rounded once to float); NORMAL by the inverse transpose, renormalised; a node whose
//    transform mirrors (negative determinant) has its triangles' winding reversed, so front
//    faces stay counter-clockwise; EXT_mesh_gpu_instancing: each instance's T R S before the
//    node's transform: a static mesh's triangles stored once in its own space, drawn at each
//    instance's place (DrawRange::instances; those that mirror from the faces reversed); in an
//    animated file, and for lines and points, written out one copy per instance;
//  - primitives: TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN, indexed (u8/u16/u32) or not;
//    POSITION, NORMAL (without it, flat normals), TEXCOORD_0 (v is flipped to OBJ's convention,
//    v = 0 the image's bottom row). POINTS and LINES primitives become line sets;
//  - materials (pbrMetallicRoughness mapped to Blinn-Phong; README "Materials"): with base =
//    baseColorFactor, m = metallicFactor, r = roughnessFactor: kd = base x (1 - m) (times the
//    baseColorTexture texel when textured), ks = 0.04 (1 - m) + base x m, shininess =
//    2 / r^4 - 2 rounded and clamped to [1, 1024]. Primitives without a material get the fixed
//    values of OBJ faces without one;
//  - one draw range per material, in order of first use (node order, depth first; primitives in
//    order);
//  - animations (KHR_animation_pointer's node targets too; its others: a warning), skins and
//    morph targets (Resources/Animation.hpp) into Model::animation, the
//    mesh then holding the rest pose (skins bound by their joints' rest transforms, the default
//    morph weights); null for a file without any.
// A valid file with nothing to draw (no scenes, or a scene without triangles, lines or points)
// loads as an empty Model with a warning saying so.
// Errors (one line, "PATH: problem", exit 1 at the command line): JSON that is not glTF,
// properties of the wrong type, accessors or buffer views out of their buffers, compressed
// streams that do not decode or disagree with their accessors, indices out of range, a missing
// .bin that an accessor reads (one nothing reads, or a URI not fetched, http:, is left
// alone), node graphs that are not trees (recursive or shared nodes), a hierarchy deeper than
// limits.maxNodeDepth, positions that are not finite, animation data against the specification
// (key times not finite or not increasing, values not finite, outputs of the wrong count or
// type, joint indices beyond their skin, singular inverse bind matrices), a required extension
// we do not support, a texture whose only image is in a format we cannot decode, and the limits
// of LoadLimits (file, buffer, triangle, vertex, node, texture sizes). A texture image that
// cannot be decoded is a warning and the checkerboard.
Result<Model> loadGltf(const std::string& utf8Path, const LoadOptions& options = {});

// The same from the file's bytes already in memory (.glb when they start with "glTF", else
// .gltf JSON); external buffers and images are still read relative to utf8Path's directory.
Result<Model> loadGltfFromMemory(const unsigned char* data, std::size_t size, const std::string& utf8Path,
                                 const LoadOptions& options = {});

// True when the path ends in .gltf or .glb (ASCII case-insensitive).
bool isGltfPath(const std::string& path);

// loadGltf for .gltf / .glb, loadObj otherwise.
Result<Model> loadModel(const std::string& utf8Path, const LoadOptions& options = {});

} // namespace sr
