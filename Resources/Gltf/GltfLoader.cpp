// GltfLoader: the load of one glTF file, step by step: the document, its required extensions, the scene's node walk (meshes, instances, cameras, lights), animation, materials and textures, draw ranges and bounds.
#include "Resources/Gltf/GltfLoader.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include "Resources/FileIO.hpp"
#include "Resources/Gltf/Import.hpp"
#include "Resources/ObjLoader.hpp"

namespace sr {

namespace {

using R = Result<Model>;

// A message that quotes the file's own strings (property names, extension names), kept on one
// line: its control characters written as \n, \r, \t or \xNN.
std::string oneLine(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (const char ch : s) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else if (c < 0x20 || c == 0x7F) {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02X", unsigned(c));
            out += hex;
        } else {
            out += ch;
        }
    }
    return out;
}

Result<Model> loadFromMemory(const unsigned char* data, std::size_t size, const std::string& path, const LoadOptions& options);

// The extensions a file may require: those read here, and the image formats whose textures
// fall back to another image (Textures.cpp).
const std::set<std::string>& supportedExtensions() {
    static const std::set<std::string> kSupported = {
        "KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_lights_punctual", "KHR_mesh_quantization",
        "EXT_meshopt_compression", "KHR_meshopt_compression", "KHR_draco_mesh_compression", "EXT_texture_webp",
        "EXT_mesh_gpu_instancing", "KHR_texture_basisu", "EXT_texture_avif", "KHR_materials_unlit",
        "KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat", "KHR_materials_sheen",
        "KHR_materials_pbrSpecularGlossiness",
        "KHR_animation_pointer"}; // nodes, material factors, lights, cameras; other targets are named in a warning
    return kSupported;
}

// The material a primitive is drawn with under KHR_materials_variants' variant `variant` (-1:
// none): the mapping that lists the variant, else the primitive's own; -2: a malformed mapping.
int variantMaterial(const gltf::Primitive& prim, int variant) {
    if (variant < 0) return prim.material;
    const auto ext = prim.extensions.find("KHR_materials_variants");
    if (ext == prim.extensions.end()) return prim.material;
    const auto mappings = ext->find("mappings");
    if (mappings == ext->end() || !mappings->is_array()) return -2;
    for (const gltf::Json& m : *mappings) {
        const auto material = m.find("material"), variants = m.find("variants");
        if (!m.is_object() || material == m.end() || !material->is_number_integer() || variants == m.end() || !variants->is_array())
            return -2;
        for (const gltf::Json& v : *variants)
            if (v.is_number_integer() && v.get<long long>() == variant) return material->get<int>();
    }
    return prim.material;
}

gltf::Primitive withMaterial(gltf::Primitive prim, int material) {
    prim.material = material;
    return prim;
}

} // namespace

bool isGltfPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".gltf" || ext == ".glb";
}

Result<Model> loadModel(const std::string& utf8Path, const LoadOptions& options) {
    return isGltfPath(utf8Path) ? loadGltf(utf8Path, options) : loadObj(utf8Path, options);
}

Result<Model> loadGltf(const std::string& path, const LoadOptions& options) {
    auto bytes = readFileBytes(path, options.limits.maxFileBytes);
    if (!bytes) return R::failure(bytes.error());
    return loadGltfFromMemory(bytes.value().data(), bytes.value().size(), path, options);
}

Result<Model> loadGltfFromMemory(const unsigned char* data, std::size_t size, const std::string& path,
                                 const LoadOptions& options) {
    Result<Model> r = loadFromMemory(data, size, path, options);
    if (!r) return R::failure(oneLine(r.error()));
    for (std::string& w : r.value().warnings) w = oneLine(w);
    return r;
}

namespace {

Result<Model> loadFromMemory(const unsigned char* data, std::size_t size, const std::string& path, const LoadOptions& options) {
    using namespace gltfimport;
    const LoadLimits& limits = options.limits;
    if (size > limits.maxFileBytes)
        return R::failure(path + ": " + std::to_string(size) + " bytes, above the limit of " + std::to_string(limits.maxFileBytes));
    const std::string dir = parentDirectory(path);
    auto parsed = gltf::parseDocument(data, size, dir, limits);
    if (!parsed) return R::failure(path + ": " + parsed.error());
    const gltf::Document& g = parsed.value();
    for (const std::string& ext : g.extensionsRequired)
        if (!supportedExtensions().count(ext))
            return R::failure(path + ": requires the extension " + ext + ", which SoftRaster does not support");
    const int sceneIndex = g.defaultScene >= 0 ? g.defaultScene : 0;
    if ((g.defaultScene >= 0 || !g.scenes.empty()) && std::size_t(sceneIndex) >= g.scenes.size())
        return R::failure(path + ": scene " + std::to_string(sceneIndex) + " does not exist");
    if (g.nodes.size() > limits.maxNodes)
        return R::failure(path + ": " + std::to_string(g.nodes.size()) + " nodes, above the limit of " + std::to_string(limits.maxNodes));
    if (g.materials.size() > limits.maxMaterials)
        return R::failure(path + ": " + std::to_string(g.materials.size()) + " materials, above the limit of " +
                          std::to_string(limits.maxMaterials));

    // KHR_materials_variants: the variant asked for, by name.
    int variant = -1;
    if (!options.variant.empty()) {
        const auto found = std::find(g.variants.begin(), g.variants.end(), options.variant);
        if (found == g.variants.end()) {
            std::string names;
            for (const std::string& v : g.variants) names += (names.empty() ? "" : ", ") + v;
            return R::failure(path + ": no material variant '" + options.variant + "' (" +
                              (names.empty() ? std::string("the file has none") : "its variants: " + names) + ")");
        }
        variant = int(found - g.variants.begin());
    }

    gltf::Accessors accessors(g);
    Builder b;
    b.path = path;
    b.doc = &g;
    b.accessors = &accessors;
    b.trianglesOf.resize(g.materials.size() + 2); // [material + 1]; the last slot: the override stand-in
    bool morphs = false;
    for (const gltf::Mesh& gm : g.meshes)
        for (const gltf::Primitive& prim : gm.primitives) morphs |= !prim.targets.empty();
    if (!g.animations.empty() || !g.skins.empty() || morphs) {
        b.animation = std::make_shared<ModelAnimation>();
        b.animation->nodes.resize(g.nodes.size());
    }
    // Materials whose texture transforms a clip moves, known before their primitives are read.
    b.animatedTransforms.assign(g.materials.size(), 0);
    for (const gltf::Animation& ga : g.animations)
        for (const gltf::AnimationChannel& gc : ga.channels) {
            AnimatedProperty property{};
            int material = 0, reference = 0;
            if (gc.target_path == "pointer" && propertyPointer(gc.pointer, property, material, reference) && isTextureTransform(property) &&
                std::size_t(material) < g.materials.size())
                b.animatedTransforms[std::size_t(material)] = 1;
        }
    // Depth-first over the scene's node trees; a node met twice makes the graph not a tree.
    std::vector<std::uint8_t> seen(g.nodes.size(), 0);
    struct Item {
        int node;
        Mat4d parent;
        std::size_t depth;
    };
    Mat4d identity;
    for (int i = 0; i < 4; ++i) identity.m[i][i] = 1.0;
    std::vector<Item> stack;
    if (!g.scenes.empty()) {
        const auto& roots = g.scenes[std::size_t(sceneIndex)].nodes;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, identity, 1});
    }
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        if (item.node < 0 || std::size_t(item.node) >= g.nodes.size())
            return R::failure(path + ": node " + std::to_string(item.node) + " does not exist");
        if (seen[std::size_t(item.node)])
            return R::failure(path + ": node " + std::to_string(item.node) +
                              " is reached twice (the node graph must be a tree: recursive or shared nodes)");
        seen[std::size_t(item.node)] = 1;
        if (item.depth > limits.maxNodeDepth)
            return R::failure(path + ": the node hierarchy is deeper than " + std::to_string(limits.maxNodeDepth) + " levels");
        const gltf::Node& node = g.nodes[std::size_t(item.node)];
        const Mat4d world = item.parent * localMatrix(node);
        if (!finite(world)) return R::failure(path + ": node " + std::to_string(item.node) + " has a transform that is not finite");
        b.node = &node;
        b.nodeIndex = item.node;
        if (node.mesh >= 0) {
            if (std::size_t(node.mesh) >= g.meshes.size())
                return R::failure(path + ": node " + std::to_string(item.node) + ": mesh " + std::to_string(node.mesh) + " does not exist");
            const auto instances = instanceMatrices(b, node, item.node);
            if (!instances) return R::failure(path + ": " + instances.error());
            // Instances of a skinned mesh: the skin places every vertex by its joints (the node's
            // own transform ignored), and the extension leaves open where an instance would go.
            if (!instances.value().empty() && node.skin >= 0)
                return R::failure(path + ": node " + std::to_string(item.node) + ": EXT_mesh_gpu_instancing on a skinned mesh is not supported");
            const gltf::Mesh& gm = g.meshes[std::size_t(node.mesh)];
            const auto add = [&](std::size_t p, const Mat4d& placed) {
                const std::string what = "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p);
                const int material = variantMaterial(gm.primitives[p], variant);
                if (material < -1) return Status::failure(what + ": KHR_materials_variants: a mapping is malformed");
                return material == gm.primitives[p].material ? addPrimitive(b, gm.primitives[p], placed, what, limits)
                                                             : addPrimitive(b, withMaterial(gm.primitives[p], material), placed, what, limits);
            };
            // Instances of a static mesh: its triangles stored once in its own space, drawn at
            // each place (DrawRange::instances). Lines and points, and the instances in an
            // animated file (each follows its node: AnimatedBlock::instance), are written out.
            std::vector<Mat4> places;
            if (!b.animation)
                for (const Mat4d& instance : instances.value()) places.push_back(toMat4(world * instance));
            const std::size_t copies = std::max<std::size_t>(instances.value().size(), 1);
            for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
                if (!places.empty() && gm.primitives[p].mode >= gltf::kModeTriangles) {
                    b.placing = true;
                    const std::size_t first = b.placed.size();
                    const Status s = add(p, identity);
                    b.placing = false;
                    if (!s) return R::failure(path + ": " + s.error());
                    for (std::size_t k = first; k < b.placed.size(); ++k) {
                        b.placed[k].places = places;
                        b.instanceDraws += places.size();
                        b.instancedTriangles += (places.size() - 1) * (b.placed[k].triangles.size() / 3);
                    }
                    if (b.instanceDraws > limits.maxInstanceDraws)
                        return R::failure(path + ": more than " + std::to_string(limits.maxInstanceDraws) +
                                          " draws of instanced meshes (EXT_mesh_gpu_instancing: instances x primitives)");
                    if (b.triangles + b.instancedTriangles > limits.maxTriangles)
                        return R::failure(path + ": more than " + std::to_string(limits.maxTriangles) + " triangles (each instance's counted)");
                    continue;
                }
                for (std::size_t k = 0; k < copies; ++k) {
                    b.instance = instances.value().empty() ? nullptr : &instances.value()[k];
                    const Status s = add(p, instances.value().empty() ? world : world * instances.value()[k]);
                    b.instance = nullptr;
                    if (!s) return R::failure(path + ": " + s.error());
                }
            }
        }
        if (node.camera >= 0) {
            if (std::size_t(node.camera) >= g.cameras.size())
                return R::failure(path + ": node " + std::to_string(item.node) + ": camera " + std::to_string(node.camera) + " does not exist");
            const Status s = addCamera(b, g.cameras[std::size_t(node.camera)], world, node.camera);
            if (!s) return R::failure(path + ": " + s.error());
        }
        const Result<int> light = nodeLight(node, g.lights.size());
        if (!light) return R::failure(path + ": node " + std::to_string(item.node) + ": " + light.error());
        if (light.value() >= 0) {
            if (b.model.lights.size() >= limits.maxLights)
                return R::failure(path + ": more than " + std::to_string(limits.maxLights) + " lights in the scene");
            const Status s = addLight(b, g.lights[std::size_t(light.value())], world, light.value());
            if (!s) return R::failure(path + ": " + s.error());
        }
        for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
            stack.push_back({*it, world, item.depth + 1});
            if (b.animation && *it >= 0 && std::size_t(*it) < g.nodes.size()) b.animation->nodes[std::size_t(*it)].parent = item.node;
        }
    }
    if (b.animation) {
        const Status s = addAnimation(*b.animation, g, accessors, b.model.warnings, path, limits);
        if (!s) return R::failure(path + ": " + s.error());
        b.animation->markMovingBlocks();
    }
    Model& model = b.model;
    model.variants = g.variants;
    model.variant = variant;
    model.normalsFromFile = b.anyFileNormal && !b.anyComputedNormal;

    // Materials and their textures.
    for (std::size_t i = 0; i < g.materials.size(); ++i) {
        model.materials.push_back(materialFrom(g.materials[i]));
        std::string problem;
        materialAddressing(g, g.materials[i], &problem, b.transformsMove(int(i)));
        if (!problem.empty()) model.warnings.push_back(path + ": material " + std::to_string(i) + ": " + problem);
    }
    const Status textures = addTextures(b, options, dir);
    if (!textures) return R::failure(textures.error());

    // One range per material in order of first use.
    for (const int key : b.firstUse) {
        std::vector<std::uint32_t>& list = b.trianglesOf[std::size_t(key)];
        DrawRange r;
        r.firstIndex = std::uint32_t(model.mesh.indices.size());
        r.indexCount = std::uint32_t(list.size());
        r.material = key - 1;
        r.texture = model.hasUvs && r.material >= 0 ? model.materials[std::size_t(r.material)].texture : -1;
        model.mesh.indices.insert(model.mesh.indices.end(), list.begin(), list.end());
        model.ranges.push_back(r);
    }
    // The instanced primitives: a range for their places that keep the winding, and one with the
    // faces reversed for those that mirror, each after the world-space ranges.
    for (const Builder::PlacedPrimitive& placed : b.placed) {
        for (const bool mirrors : {false, true}) {
            DrawRange r;
            for (const Mat4& place : placed.places)
                if ((determinant(place) < 0.0f) == mirrors) r.instances.push_back(place);
            if (r.instances.empty() || placed.triangles.empty()) continue;
            r.firstIndex = std::uint32_t(model.mesh.indices.size());
            r.indexCount = std::uint32_t(placed.triangles.size());
            r.material = placed.material;
            r.texture = model.hasUvs && r.material >= 0 ? model.materials[std::size_t(r.material)].texture : -1;
            r.firstVertex = placed.firstVertex;
            r.vertexCount = placed.vertexCount;
            for (std::size_t t = 0; t + 2 < placed.triangles.size(); t += 3) {
                const std::uint32_t* v = placed.triangles.data() + t;
                if (mirrors) model.mesh.indices.insert(model.mesh.indices.end(), {v[0], v[2], v[1]});
                else model.mesh.indices.insert(model.mesh.indices.end(), v, v + 3);
            }
            model.ranges.push_back(std::move(r));
        }
    }
    // Primitives without a material get the specification's default one (every property at its
    // default: white, metallic 1, roughness 1, opaque, single-sided), not an OBJ face's grey.
    int defaultMaterial = -1;
    for (DrawRange& r : model.ranges) {
        if (r.material >= 0 || !options.textureOverride.empty()) continue;
        if (defaultMaterial < 0) {
            model.materials.push_back(materialFrom(gltf::Material{}));
            model.materials.back().name = "(the glTF default material)";
            defaultMaterial = int(model.materials.size()) - 1;
        }
        r.material = defaultMaterial;
    }
    // An animated file's rest pose: skins bound by their joints' rest transforms and the default
    // morph weights (the specification's pose without a clip); the bounds are the rest pose's.
    if (b.animation) {
        b.animation->pose(0.0, -1, model.mesh, true);
        model.animation = std::move(b.animation);
    }
    // Nothing to draw: a valid file all the same (every viewer shows an empty frame).
    if (b.triangles == 0 && model.lineSets.empty()) {
        model.warnings.push_back(path + ": " +
                                 (g.scenes.empty() ? std::string("the file defines no scene: nothing to draw")
                                                   : "scene " + std::to_string(sceneIndex) + " has nothing to draw"));
        model.boundsMin = Vec3(-1.0f, -1.0f, -1.0f);
        model.boundsMax = Vec3(1.0f, 1.0f, 1.0f);
        return R(std::move(model));
    }
    // Bounds of the drawn vertices (world space), triangles' (each instance's), lines' and points'.
    bool first = true;
    const auto grow = [&](Vec3 p) {
        model.boundsMin = first ? p : Vec3(std::min(model.boundsMin.x, p.x), std::min(model.boundsMin.y, p.y), std::min(model.boundsMin.z, p.z));
        model.boundsMax = first ? p : Vec3(std::max(model.boundsMax.x, p.x), std::max(model.boundsMax.y, p.y), std::max(model.boundsMax.z, p.z));
        first = false;
    };
    forEachWorldPosition(model, grow);
    for (const LineSet& l : model.lineSets)
        for (const Vec3& p : l.positions) grow(p);
    return R(std::move(model));
}

} // namespace

} // namespace sr
