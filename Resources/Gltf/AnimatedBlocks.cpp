// gltfimport animated blocks: what ModelAnimation::pose needs of a primitive in an animated file (object-space vertices, morph targets, skin joints and weights), checked.
#include <cmath>

#include "Resources/Gltf/Import.hpp"

namespace sr::gltfimport {

Status addAnimatedBlock(Builder& b, const gltf::Primitive& prim, const View& pos, const std::optional<View>& normals,
                        bool keepTangents, std::uint32_t first, std::size_t vertices, const std::vector<std::uint32_t>& source,
                        bool mirrored, const std::string& what, const LoadLimits& limits) {
    const gltf::Document& g = *b.doc;
    const auto src = [&](std::size_t k) { return source.empty() ? k : std::size_t(source[k]); };
    AnimatedBlock block;
    block.node = b.nodeIndex;
    block.first = first;
    block.count = std::uint32_t(vertices);
    block.mirrored = mirrored;
    if (b.instance) {
        block.instanced = true;
        block.instance = *b.instance;
    }
    block.flatNormals = !normals;
    const auto vec3 = [](const View& v, std::size_t i) { return Vec3{readFloat(v, i, 0), readFloat(v, i, 1), readFloat(v, i, 2)}; };
    const auto finite3 = [](Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    block.positions.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) block.positions[i] = vec3(pos, src(i));
    if (normals) {
        block.normals.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) block.normals[i] = vec3(*normals, src(i));
    }
    if (keepTangents) {
        const auto ti = prim.attributes.find("TANGENT");
        auto v = b.accessors->view(ti->second, what + " TANGENT");
        if (!v) return Status::failure(v.error());
        block.tangents.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i)
            block.tangents[i] = Vec4{readFloat(v.value(), src(i), 0), readFloat(v.value(), src(i), 1), readFloat(v.value(), src(i), 2),
                                     readFloat(v.value(), src(i), 3)};
    }
    if (prim.targets.size() > limits.maxMorphTargets)
        return Status::failure(what + ": " + std::to_string(prim.targets.size()) + " morph targets, above the limit of " +
                               std::to_string(limits.maxMorphTargets));
    for (std::size_t k = 0; k < prim.targets.size(); ++k) {
        const std::string name = what + " target " + std::to_string(k);
        std::vector<Vec3> dp(vertices, Vec3{0, 0, 0}), dn;
        for (const char* attribute : {"POSITION", "NORMAL"}) {
            const auto it = prim.targets[k].find(attribute);
            if (it == prim.targets[k].end()) continue;
            const bool isPosition = attribute[0] == 'P';
            if (!isPosition && !normals) continue; // flat normals are made from the morphed positions
            auto v = b.accessors->view(it->second, name + " " + attribute);
            if (!v) return Status::failure(v.error());
            if (v.value().components != 3 || v.value().count != pos.count)
                return Status::failure(name + " " + attribute + ": must be VEC3 with POSITION's count (" + std::to_string(pos.count) + ")");
            std::vector<Vec3>& out = isPosition ? dp : dn;
            out.resize(vertices);
            for (std::size_t i = 0; i < vertices; ++i) {
                out[i] = vec3(v.value(), src(i));
                if (!finite3(out[i])) return Status::failure(name + " " + attribute + ": vertex " + std::to_string(src(i)) + " is not finite");
            }
        }
        // TANGENT deltas, where the block keeps the file's tangents (a normal-mapped primitive).
        std::vector<Vec3> dt;
        if (const auto it = prim.targets[k].find("TANGENT"); keepTangents && it != prim.targets[k].end()) {
            auto v = b.accessors->view(it->second, name + " TANGENT");
            if (!v) return Status::failure(v.error());
            if (v.value().components != 3 || v.value().count != pos.count)
                return Status::failure(name + " TANGENT: must be VEC3 with POSITION's count (" + std::to_string(pos.count) + ")");
            dt.resize(vertices);
            for (std::size_t i = 0; i < vertices; ++i) {
                dt[i] = vec3(v.value(), src(i));
                if (!finite3(dt[i])) return Status::failure(name + " TANGENT: vertex " + std::to_string(src(i)) + " is not finite");
            }
        }
        block.targetPositions.push_back(std::move(dp));
        block.targetNormals.push_back(std::move(dn));
        block.targetTangents.push_back(std::move(dt));
    }
    const int skin = b.node->skin;
    const auto joints0 = prim.attributes.find("JOINTS_0");
    const auto weights0 = prim.attributes.find("WEIGHTS_0");
    if (skin >= 0 && joints0 != prim.attributes.end() && weights0 != prim.attributes.end()) {
        if (std::size_t(skin) >= g.skins.size()) return Status::failure("node " + std::to_string(b.nodeIndex) + ": skin " + std::to_string(skin) + " does not exist");
        const std::size_t jointCount = g.skins[std::size_t(skin)].joints.size();
        if (jointCount == 0) return Status::failure("skin " + std::to_string(skin) + " has no joints");
        block.skin = skin;
        block.joints.assign(vertices, {});
        block.weights.assign(vertices, {});
        for (int set = 0; set < 2; ++set) {
            const std::string suffix = "_" + std::to_string(set);
            const auto ji = prim.attributes.find("JOINTS" + suffix), wi = prim.attributes.find("WEIGHTS" + suffix);
            if (ji == prim.attributes.end() || wi == prim.attributes.end()) break;
            auto jv = b.accessors->view(ji->second, what + " JOINTS" + suffix);
            if (!jv) return Status::failure(jv.error());
            auto wv = b.accessors->view(wi->second, what + " WEIGHTS" + suffix);
            if (!wv) return Status::failure(wv.error());
            const View& J = jv.value();
            const View& W = wv.value();
            if (J.components != 4 || (J.componentType != gltf::kUnsignedByte && J.componentType != gltf::kUnsignedShort) || J.count != pos.count)
                return Status::failure(what + " JOINTS" + suffix + ": must be unsigned byte or short VEC4 with POSITION's count");
            if (W.components != 4 || W.count != pos.count ||
                !(W.componentType == gltf::kFloat || (W.normalized && (W.componentType == gltf::kUnsignedByte || W.componentType == gltf::kUnsignedShort))))
                return Status::failure(what + " WEIGHTS" + suffix + ": must be float or normalised unsigned byte/short VEC4 with POSITION's count");
            for (std::size_t i = 0; i < vertices; ++i)
                for (int c = 0; c < 4; ++c) {
                    const std::uint32_t joint = readIndexComponent(J, src(i), c);
                    const float weight = readFloat(W, src(i), c);
                    if (!std::isfinite(weight) || weight < 0.0f)
                        return Status::failure(what + " WEIGHTS" + suffix + ": vertex " + std::to_string(src(i)) + " has a weight that is negative or not finite");
                    if (weight > 0.0f && joint >= jointCount)
                        return Status::failure(what + " JOINTS" + suffix + ": vertex " + std::to_string(src(i)) + " names joint " +
                                               std::to_string(joint) + ", out of range (skin " + std::to_string(skin) + " has " +
                                               std::to_string(jointCount) + ")");
                    block.joints[i][std::size_t(4 * set + c)] = std::uint16_t(weight > 0.0f ? joint : 0u);
                    block.weights[i][std::size_t(4 * set + c)] = weight;
                }
        }
        // Weights that do not sum to 1 are normalised (glTF allows it); none at all: the first joint alone.
        for (auto& w : block.weights) {
            double sum = 0.0;
            for (float x : w) sum += x;
            if (sum > 0.0) {
                for (float& x : w) x = float(x / sum);
            } else {
                w = {};
                w[0] = 1.0f;
            }
        }
    }
    b.animation->blocks.push_back(std::move(block));
    return success();
}

} // namespace sr::gltfimport
