// gltfimport animation clips: the nodes' rest transforms, the skins and the animation samplers of a file, checked against the specification.
#include <algorithm>
#include <cmath>

#include "Resources/Gltf/Import.hpp"

namespace sr::gltfimport {

namespace {

// A KHR_animation_pointer JSON pointer to a node's transform or weights ("/nodes/3/rotation"):
// its node and core path; false for any other target (materials, lights, cameras, ...).
bool nodePointer(const std::string& pointer, int& node, std::string& path) {
    static const std::string kPrefix = "/nodes/";
    if (pointer.compare(0, kPrefix.size(), kPrefix) != 0) return false;
    std::size_t i = kPrefix.size();
    long long index = 0;
    const std::size_t digits = i;
    while (i < pointer.size() && pointer[i] >= '0' && pointer[i] <= '9' && index < 2147483647) index = index * 10 + (pointer[i++] - '0');
    if (i == digits || i >= pointer.size() || pointer[i] != '/' || index > 2147483647) return false;
    const std::string rest = pointer.substr(i + 1);
    if (rest != "translation" && rest != "rotation" && rest != "scale" && rest != "weights") return false;
    node = int(index);
    path = rest;
    return true;
}

} // namespace

// The nodes' rest transforms and weights, the skins and the clips of an animated file, checked:
// key times finite and strictly increasing, values finite, counts as the specification says.
Status addAnimation(ModelAnimation& a, const gltf::Document& g, gltf::Accessors& accessors, std::vector<std::string>& warnings,
                    const std::string& path, const LoadLimits& limits) {
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
        const gltf::Node& node = g.nodes[n];
        AnimationNode& an = a.nodes[n];
        if (node.matrix.size() == 16) {
            an.hasMatrix = true;
            an.matrix = localMatrix(node);
        }
        if (node.translation.size() == 3) std::copy(node.translation.begin(), node.translation.end(), an.translation.begin());
        if (node.rotation.size() == 4) std::copy(node.rotation.begin(), node.rotation.end(), an.rotation.begin());
        if (node.scale.size() == 3) std::copy(node.scale.begin(), node.scale.end(), an.scale.begin());
        an.weights = node.weights;
        if (an.weights.empty() && node.mesh >= 0 && std::size_t(node.mesh) < g.meshes.size()) an.weights = g.meshes[std::size_t(node.mesh)].weights;
        for (double w : an.weights)
            if (!std::isfinite(w)) return Status::failure("node " + std::to_string(n) + ": a morph weight is not finite");
    }
    for (std::size_t k = 0; k < g.skins.size(); ++k) {
        const gltf::Skin& gs = g.skins[k];
        const std::string what = "skin " + std::to_string(k);
        if (gs.joints.size() > limits.maxJoints)
            return Status::failure(what + ": " + std::to_string(gs.joints.size()) + " joints, above the limit of " + std::to_string(limits.maxJoints));
        AnimationSkin skin;
        for (int j : gs.joints) {
            if (j < 0 || std::size_t(j) >= g.nodes.size()) return Status::failure(what + ": joint node " + std::to_string(j) + " does not exist");
            skin.joints.push_back(j);
        }
        Mat4d identity;
        for (int i = 0; i < 4; ++i) identity.m[i][i] = 1.0;
        skin.inverseBind.assign(gs.joints.size(), identity);
        if (gs.inverseBindMatrices >= 0) {
            auto v = accessors.view(gs.inverseBindMatrices, what + " inverseBindMatrices");
            if (!v) return Status::failure(v.error());
            if (v.value().components != 16 || v.value().componentType != gltf::kFloat || v.value().count < gs.joints.size())
                return Status::failure(what + " inverseBindMatrices: must be float MAT4, one per joint (" + std::to_string(gs.joints.size()) + ")");
            for (std::size_t j = 0; j < gs.joints.size(); ++j) {
                Mat4d m;
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) m.m[r][c] = readFloat(v.value(), j, c * 4 + r);
                const double (*e)[4] = m.m;
                const double det3 = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                                    e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
                if (!finite(m) || !(std::fabs(det3) > 0.0))
                    return Status::failure(what + " inverseBindMatrices: matrix " + std::to_string(j) + " is " +
                                           (finite(m) ? "singular (not invertible)" : "not finite"));
                skin.inverseBind[j] = m;
            }
        }
        a.skins.push_back(std::move(skin));
    }
    std::size_t totalKeys = 0;
    const auto targetsOf = [&](int node) -> std::size_t {
        const int mesh = g.nodes[std::size_t(node)].mesh;
        if (mesh < 0 || std::size_t(mesh) >= g.meshes.size() || g.meshes[std::size_t(mesh)].primitives.empty()) return 0;
        return g.meshes[std::size_t(mesh)].primitives.front().targets.size();
    };
    for (std::size_t k = 0; k < g.animations.size(); ++k) {
        const gltf::Animation& ga = g.animations[k];
        AnimationClip clip;
        clip.name = ga.name;
        const std::string what = "animation " + std::to_string(k);
        // What each sampler drives (the components of its values), from the channels.
        std::vector<int> components(ga.samplers.size(), 0);
        std::vector<std::uint8_t> rotation(ga.samplers.size(), 0);
        for (std::size_t c = 0; c < ga.channels.size(); ++c) {
            const gltf::AnimationChannel& gc = ga.channels[c];
            const std::string name = what + " channel " + std::to_string(c);
            int targetNode = gc.target_node;
            std::string targetPath = gc.target_path;
            AnimatedProperty property{};
            int target = 0, reference = 0;
            if (targetPath == "pointer" && propertyPointer(gc.pointer, property, target, reference)) {
                const PropertyOwner owner = ownerOf(property);
                const std::size_t count = owner == PropertyOwner::Material ? g.materials.size()
                                          : owner == PropertyOwner::Light  ? g.lights.size()
                                                                           : g.cameras.size();
                if (std::size_t(target) >= count)
                    return Status::failure(name + ": KHR_animation_pointer '" + gc.pointer + "' names a " +
                                           (owner == PropertyOwner::Material ? "material" : owner == PropertyOwner::Light ? "light" : "camera") +
                                           " that does not exist");
                if (gc.sampler < 0 || std::size_t(gc.sampler) >= ga.samplers.size())
                    return Status::failure(name + ": sampler " + std::to_string(gc.sampler) + " does not exist");
                const int n = componentsOf(property);
                int& have = components[std::size_t(gc.sampler)];
                if (have != 0 && have != n) return Status::failure(name + ": sampler " + std::to_string(gc.sampler) + " drives targets of different sizes");
                have = n;
                clip.properties.push_back({property, target, reference, gc.sampler});
                if (owner == PropertyOwner::Material && a.materials.empty())
                    for (const gltf::Material& gm : g.materials) a.materials.push_back(factorsOf(gm));
                continue;
            }
            if (targetPath == "pointer" && !nodePointer(gc.pointer, targetNode, targetPath)) {
                warnings.push_back(path + ": " + name + ": KHR_animation_pointer '" + gc.pointer +
                                   "' is not animated (node transforms and weights, material factors and texture transforms, "
                                   "light and camera properties are)");
                continue;
            }
            if (targetNode < 0) continue; // no target: ignored (glTF: an extension may define one)
            if (std::size_t(targetNode) >= g.nodes.size())
                return Status::failure(name + ": node " + std::to_string(targetNode) + " does not exist");
            if (gc.sampler < 0 || std::size_t(gc.sampler) >= ga.samplers.size())
                return Status::failure(name + ": sampler " + std::to_string(gc.sampler) + " does not exist");
            AnimationChannel ch;
            ch.node = targetNode;
            ch.sampler = gc.sampler;
            int n = 0;
            if (targetPath == "translation") ch.path = AnimationPath::Translation, n = 3;
            else if (targetPath == "rotation") ch.path = AnimationPath::Rotation, n = 4;
            else if (targetPath == "scale") ch.path = AnimationPath::Scale, n = 3;
            else if (targetPath == "weights") ch.path = AnimationPath::Weights, n = int(targetsOf(targetNode));
            else {
                warnings.push_back(path + ": " + name + ": path '" + targetPath + "' is not animated");
                continue;
            }
            if (n == 0) return Status::failure(name + ": animates the weights of node " + std::to_string(targetNode) + ", whose mesh has no morph targets");
            int& have = components[std::size_t(gc.sampler)];
            if (have != 0 && have != n) return Status::failure(name + ": sampler " + std::to_string(gc.sampler) + " drives targets of different sizes");
            have = n;
            rotation[std::size_t(gc.sampler)] = ch.path == AnimationPath::Rotation;
            clip.channels.push_back(ch);
        }
        for (std::size_t si = 0; si < ga.samplers.size(); ++si) {
            const gltf::AnimationSampler& gsm = ga.samplers[si];
            const std::string name = what + " sampler " + std::to_string(si);
            AnimationSampler sm;
            sm.components = std::max(components[si], 1);
            sm.quaternion = rotation[si] != 0;
            if (gsm.interpolation == "LINEAR") sm.interpolation = AnimationSampler::Interpolation::Linear;
            else if (gsm.interpolation == "STEP") sm.interpolation = AnimationSampler::Interpolation::Step;
            else if (gsm.interpolation == "CUBICSPLINE") sm.interpolation = AnimationSampler::Interpolation::CubicSpline;
            else return Status::failure(name + ": unknown interpolation '" + gsm.interpolation + "'");
            auto in = accessors.view(gsm.input, name + " input");
            if (!in) return Status::failure(in.error());
            if (in.value().components != 1 || in.value().componentType != gltf::kFloat || in.value().count == 0)
                return Status::failure(name + " input: must be float scalars, at least one");
            totalKeys += in.value().count;
            if (totalKeys > limits.maxAnimationKeys)
                return Status::failure("more than " + std::to_string(limits.maxAnimationKeys) + " animation keys");
            sm.times.resize(in.value().count);
            for (std::size_t i = 0; i < sm.times.size(); ++i) {
                sm.times[i] = readFloat(in.value(), i, 0);
                if (!std::isfinite(sm.times[i])) return Status::failure(name + " input: key " + std::to_string(i) + " time is not finite");
                if (i > 0 && !(sm.times[i] > sm.times[i - 1]))
                    return Status::failure(name + " input: key times are not increasing (key " + std::to_string(i) + ")");
            }
            auto out = accessors.view(gsm.output, name + " output");
            if (!out) return Status::failure(out.error());
            const View& o = out.value();
            const std::size_t perKey = sm.interpolation == AnimationSampler::Interpolation::CubicSpline ? 3 : 1;
            const std::size_t want = sm.times.size() * perKey * std::size_t(sm.components);
            const bool scalarsOk = o.components == 1 && o.count == want;                                         // weights
            const bool vectorsOk = o.components == sm.components && o.count * std::size_t(o.components) == want; // T, R, S
            const bool typeOk = o.componentType == gltf::kFloat || (o.normalized && o.componentType != gltf::kUnsignedInt);
            if (components[si] != 0 && (!typeOk || !(scalarsOk || vectorsOk)))
                return Status::failure(name + " output: " + std::to_string(o.count) + " elements of " + std::to_string(o.components) +
                                       " components, expected " + std::to_string(want) + " values (" +
                                       std::to_string(sm.components) + " per key" + (perKey == 3 ? ", three elements per cubic key" : "") + ")");
            sm.values.resize(components[si] != 0 ? want : 0);
            for (std::size_t i = 0; i < sm.values.size(); ++i) {
                const std::size_t e = i / std::size_t(o.components);
                sm.values[i] = readFloat(o, e, int(i % std::size_t(o.components)));
                if (!std::isfinite(sm.values[i])) return Status::failure(name + " output: value " + std::to_string(i) + " is not finite");
            }
            clip.duration = std::max(clip.duration, sm.times.back());
            clip.samplers.push_back(std::move(sm));
        }
        a.clips.push_back(std::move(clip));
    }
    return success();
}

} // namespace sr::gltfimport
