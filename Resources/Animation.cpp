// Animation: keyframe interpolation, the node hierarchy at a time, morph targets and skinning into a mesh.
#include "Resources/Animation.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string>
#include <utility>

#include "Math/Conventions.hpp"

namespace sr {
namespace {

void normalizeQuaternion(double* q) {
    const double l = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (l > 0.0 && std::isfinite(l))
        for (int c = 0; c < 4; ++c) q[c] /= l;
    else
        q[0] = q[1] = q[2] = 0.0, q[3] = 1.0;
}

Vec3d transformPoint(const Mat4d& m, Vec3d p) {
    return {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3],
            m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3],
            m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]};
}

Vec3d transformDirection(const Mat4d& m, Vec3d d) {
    return {m.m[0][0] * d.x + m.m[0][1] * d.y + m.m[0][2] * d.z, m.m[1][0] * d.x + m.m[1][1] * d.y + m.m[1][2] * d.z,
            m.m[2][0] * d.x + m.m[2][1] * d.y + m.m[2][2] * d.z};
}

// The normal n through m: its upper 3x3's cofactor matrix (det x the inverse transpose), the
// sign of det undone, renormalised; (0, 0, 1) when that gives no direction.
Vec3 transformNormal(const Mat4d& m, Vec3d n) {
    const double (*a)[4] = m.m;
    const double cof[3][3] = {{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[1][2] * a[2][0] - a[1][0] * a[2][2], a[1][0] * a[2][1] - a[1][1] * a[2][0]},
                              {a[0][2] * a[2][1] - a[0][1] * a[2][2], a[0][0] * a[2][2] - a[0][2] * a[2][0], a[0][1] * a[2][0] - a[0][0] * a[2][1]},
                              {a[0][1] * a[1][2] - a[0][2] * a[1][1], a[0][2] * a[1][0] - a[0][0] * a[1][2], a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
    const double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
    Vec3d v = Vec3d{cof[0][0] * n.x + cof[0][1] * n.y + cof[0][2] * n.z, cof[1][0] * n.x + cof[1][1] * n.y + cof[1][2] * n.z,
                    cof[2][0] * n.x + cof[2][1] * n.y + cof[2][2] * n.z} *
              (det < 0 ? -1.0 : 1.0);
    const double l = length(v);
    v = l > 0.0 && std::isfinite(l) ? v / l : Vec3d{0, 0, 1};
    return {float(v.x), float(v.y), float(v.z)};
}

Vec3 toFloat(Vec3d v) { return {float(v.x), float(v.y), float(v.z)}; }

} // namespace

Mat4d trsMatrix(const std::array<double, 3>& t, const std::array<double, 4>& q, const std::array<double, 3>& s) {
    Mat4d m;
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double rot[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                              {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                              {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m.m[r][c] = rot[r][c] * s[std::size_t(c)];
        m.m[r][3] = t[std::size_t(r)];
    }
    m.m[3][3] = 1.0;
    return m;
}

void AnimationSampler::evaluate(double t, double* out) const {
    const std::size_t keys = times.size();
    const std::size_t c = std::size_t(components);
    const bool cubic = interpolation == Interpolation::CubicSpline;
    // The value element of key k (a cubic key stores in-tangent, value, out-tangent).
    const auto value = [&](std::size_t k) { return values.data() + (cubic ? (3 * k + 1) * c : k * c); };
    if (keys == 0) return;
    if (!(t > times.front()) || keys == 1) {
        std::copy(value(0), value(0) + c, out);
    } else if (t >= times.back()) {
        std::copy(value(keys - 1), value(keys - 1) + c, out);
    } else {
        // The last key at or before t.
        const std::size_t k = std::size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
        const double d = times[k + 1] - times[k];
        const double s = (t - times[k]) / d;
        const double* v0 = value(k);
        const double* v1 = value(k + 1);
        if (interpolation == Interpolation::Step) {
            std::copy(v0, v0 + c, out);
        } else if (cubic) {
            const double* b0 = values.data() + (3 * k + 2) * c; // out-tangent of key k
            const double* a1 = values.data() + (3 * (k + 1)) * c; // in-tangent of key k + 1
            const double s2 = s * s, s3 = s2 * s;
            for (std::size_t i = 0; i < c; ++i)
                out[i] = (2 * s3 - 3 * s2 + 1) * v0[i] + (s3 - 2 * s2 + s) * d * b0[i] + (-2 * s3 + 3 * s2) * v1[i] +
                         (s3 - s2) * d * a1[i];
        } else if (quaternion) {
            double cosHalf = v0[0] * v1[0] + v0[1] * v1[1] + v0[2] * v1[2] + v0[3] * v1[3];
            const double sign = cosHalf < 0.0 ? -1.0 : 1.0;
            cosHalf *= sign;
            double w0 = 1.0 - s, w1 = s;
            if (cosHalf < 1.0 - 1e-9) { // else nearly equal: the lerp is the slerp
                const double angle = std::acos(std::min(cosHalf, 1.0));
                const double sinAngle = std::sin(angle);
                w0 = std::sin((1.0 - s) * angle) / sinAngle;
                w1 = std::sin(s * angle) / sinAngle;
            }
            for (std::size_t i = 0; i < 4; ++i) out[i] = w0 * v0[i] + w1 * sign * v1[i];
        } else {
            for (std::size_t i = 0; i < c; ++i) out[i] = v0[i] + s * (v1[i] - v0[i]);
        }
    }
    if (quaternion) normalizeQuaternion(out);
}

void ModelAnimation::markMovingBlocks() {
    std::vector<std::uint8_t> movable(nodes.size(), 0), morphing(nodes.size(), 0);
    for (const AnimationClip& c : clips)
        for (const AnimationChannel& ch : c.channels) (ch.path == AnimationPath::Weights ? morphing : movable)[std::size_t(ch.node)] = 1;
    for (std::size_t n = 0; n < nodes.size(); ++n)
        for (int k = nodes[n].parent; k >= 0 && !movable[n]; k = nodes[std::size_t(k)].parent) movable[n] = movable[std::size_t(k)];
    for (AnimatedBlock& b : blocks) {
        b.moves = morphing[std::size_t(b.node)] != 0;
        if (b.skin >= 0)
            for (int j : skins[std::size_t(b.skin)].joints) b.moves = b.moves || movable[std::size_t(j)];
        else
            b.moves = b.moves || movable[std::size_t(b.node)];
    }
    for (LightSource& l : lights) l.moves = l.node >= 0 && std::size_t(l.node) < nodes.size() && movable[std::size_t(l.node)];
    for (CameraSource& c : cameras) c.moves = c.node >= 0 && std::size_t(c.node) < nodes.size() && movable[std::size_t(c.node)];
}

double ModelAnimation::duration(int clip) const {
    double d = 0.0;
    for (std::size_t i = 0; i < clips.size(); ++i)
        if (clip < 0 || std::size_t(clip) == i) d = std::max(d, clips[i].duration);
    return d;
}

void ModelAnimation::nodeWorlds(double t, int clip, bool restOnly, std::vector<Mat4d>& world, std::vector<std::vector<double>>& weights) const {
    // Local transforms and weights: the rest values, then the channels.
    std::vector<std::array<double, 3>> translation(nodes.size()), scale(nodes.size());
    std::vector<std::array<double, 4>> rotation(nodes.size());
    weights.assign(nodes.size(), {});
    std::vector<std::uint8_t> animated(nodes.size(), 0);
    for (std::size_t n = 0; n < nodes.size(); ++n) {
        translation[n] = nodes[n].translation;
        rotation[n] = nodes[n].rotation;
        scale[n] = nodes[n].scale;
        weights[n] = nodes[n].weights;
    }
    double buffer[4];
    for (std::size_t c = 0; c < clips.size() && !restOnly; ++c) {
        if (clip >= 0 && std::size_t(clip) != c) continue;
        const double duration = clips[c].duration;
        const double local = duration > 0.0 ? t - std::floor(t / duration) * duration : t; // looped, as viewers play
        for (const AnimationChannel& ch : clips[c].channels) {
            const AnimationSampler& s = clips[c].samplers[std::size_t(ch.sampler)];
            const std::size_t n = std::size_t(ch.node);
            if (ch.path == AnimationPath::Weights) {
                weights[n].resize(std::size_t(s.components));
                s.evaluate(local, weights[n].data());
                continue;
            }
            s.evaluate(local, buffer);
            animated[n] = 1;
            if (ch.path == AnimationPath::Translation) std::copy(buffer, buffer + 3, translation[n].begin());
            else if (ch.path == AnimationPath::Scale) std::copy(buffer, buffer + 3, scale[n].begin());
            else std::copy(buffer, buffer + 4, rotation[n].begin());
        }
    }
    // World transforms, parents first (the loader bounded the depth).
    world.assign(nodes.size(), Mat4d{});
    std::vector<std::uint8_t> done(nodes.size(), 0);
    std::vector<int> chain;
    for (std::size_t n = 0; n < nodes.size(); ++n) {
        for (int k = int(n); k >= 0 && !done[std::size_t(k)]; k = nodes[std::size_t(k)].parent) chain.push_back(k);
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const std::size_t k = std::size_t(*it);
            const AnimationNode& node = nodes[k];
            const Mat4d local = node.hasMatrix && !animated[k] ? node.matrix : trsMatrix(translation[k], rotation[k], scale[k]);
            if (node.parent >= 0) {
                world[k] = world[std::size_t(node.parent)] * local;
            } else {
                Mat4d identity;
                for (int i = 0; i < 4; ++i) identity.m[i][i] = 1.0;
                world[k] = identity * local; // as the loader composes from the identity
            }
            done[k] = 1;
        }
        chain.clear();
    }
}

void ModelAnimation::pose(double t, int clip, Mesh& mesh, bool restOnly) const {
    std::vector<Mat4d> world;
    std::vector<std::vector<double>> weights;
    nodeWorlds(t, clip, restOnly, world, weights);
    // Each skin's joint matrices.
    std::vector<std::vector<Mat4d>> jointMatrices(skins.size());
    for (std::size_t s = 0; s < skins.size(); ++s) {
        const AnimationSkin& skin = skins[s];
        jointMatrices[s].resize(skin.joints.size());
        for (std::size_t j = 0; j < skin.joints.size(); ++j)
            jointMatrices[s][j] = world[std::size_t(skin.joints[j])] * skin.inverseBind[j];
    }
    std::vector<Vec3d> objectPositions, objectNormals, objectTangents;
    for (const AnimatedBlock& b : blocks) {
        if (!restOnly && !b.moves) continue;
        // Morphed object-space attributes.
        const std::vector<double>& w = weights[std::size_t(b.node)];
        objectPositions.assign(b.count, Vec3d{});
        objectNormals.assign(b.flatNormals ? 0 : b.count, Vec3d{});
        for (std::size_t i = 0; i < b.count; ++i) {
            objectPositions[i] = Vec3d(b.positions[i]);
            if (!b.flatNormals) objectNormals[i] = Vec3d(b.normals[i]);
        }
        const bool hasTangents = !b.tangents.empty() && mesh.hasTangents();
        objectTangents.assign(hasTangents ? b.count : 0, Vec3d{});
        for (std::size_t i = 0; i < objectTangents.size(); ++i) objectTangents[i] = Vec3d{b.tangents[i].x, b.tangents[i].y, b.tangents[i].z};
        for (std::size_t k = 0; k < b.targetPositions.size(); ++k) {
            const double wk = k < w.size() ? w[k] : 0.0;
            if (wk == 0.0) continue;
            for (std::size_t i = 0; i < b.count; ++i) objectPositions[i] = objectPositions[i] + Vec3d(b.targetPositions[k][i]) * wk;
            if (!b.flatNormals && k < b.targetNormals.size() && !b.targetNormals[k].empty())
                for (std::size_t i = 0; i < b.count; ++i) objectNormals[i] = objectNormals[i] + Vec3d(b.targetNormals[k][i]) * wk;
            if (hasTangents && k < b.targetTangents.size() && !b.targetTangents[k].empty())
                for (std::size_t i = 0; i < b.count; ++i) objectTangents[i] = objectTangents[i] + Vec3d(b.targetTangents[k][i]) * wk;
        }
        for (std::size_t i = 0; i < b.count; ++i) {
            Mat4d m;
            if (b.skin >= 0) {
                const std::vector<Mat4d>& joints = jointMatrices[std::size_t(b.skin)];
                for (int k = 0; k < 8; ++k) {
                    const float wk = b.weights[i][std::size_t(k)];
                    if (wk == 0.0f) continue;
                    const Mat4d& j = joints[b.joints[i][std::size_t(k)]];
                    for (int r = 0; r < 4; ++r)
                        for (int c = 0; c < 4; ++c) m.m[r][c] += double(wk) * j.m[r][c];
                }
            } else {
                m = b.instanced ? world[std::size_t(b.node)] * b.instance : world[std::size_t(b.node)];
            }
            const std::size_t at = std::size_t(b.first) + i;
            mesh.positions[at] = toFloat(transformPoint(m, objectPositions[i]));
            if (!b.flatNormals) mesh.normals[at] = transformNormal(m, objectNormals[i]);
            if (hasTangents) {
                const Vec4 t = b.tangents[i];
                const Vec3d tObj = objectTangents[i];
                const Vec3d tw = transformDirection(m, tObj);
                const double l = length(tw);
                const Vec3d tn = l > 0.0 && std::isfinite(l) ? tw / l : Vec3d{1, 0, 0};
                const Vec3d bObj = cross(objectNormals[i], tObj) * (t.w < 0 ? -1.0 : 1.0);
                const double sign = dot(cross(Vec3d(mesh.normals[at]), tn), transformDirection(m, bObj)) < 0.0 ? -1.0 : 1.0;
                mesh.tangents[at] = Vec4{float(tn.x), float(tn.y), float(tn.z), float(sign)};
            }
        }
        if (b.flatNormals) {
            for (std::size_t v = 0; v + 2 < b.count; v += 3) {
                const std::size_t at = std::size_t(b.first) + v;
                const Vec3d p0(mesh.positions[at]), p1(mesh.positions[at + 1]), p2(mesh.positions[at + 2]);
                Vec3d fn = cross(p1 - p0, p2 - p0);
                if (b.mirrored) fn = fn * -1.0;
                const double l = length(fn);
                fn = l > 0.0 && std::isfinite(l) ? fn / l : Vec3d{0, 0, 1};
                for (std::size_t k = 0; k < 3; ++k) mesh.normals[at + k] = toFloat(fn);
            }
        }
    }
}

} // namespace sr

namespace sr {

PropertyOwner ownerOf(AnimatedProperty p) {
    if (p >= AnimatedProperty::CameraYfov) return PropertyOwner::Camera;
    if (p >= AnimatedProperty::LightColor) return PropertyOwner::Light;
    return PropertyOwner::Material;
}

int componentsOf(AnimatedProperty p) {
    switch (p) {
    case AnimatedProperty::BaseColor: return 4;
    case AnimatedProperty::Emissive:
    case AnimatedProperty::SpecularColor:
    case AnimatedProperty::SheenColor:
    case AnimatedProperty::LightColor: return 3;
    case AnimatedProperty::TextureOffset:
    case AnimatedProperty::TextureScale: return 2;
    default: return 1;
    }
}

namespace {

// "<texture reference>/extensions/KHR_texture_transform/<offset | rotation | scale>" under a
// material: the reference (0 the base colour texture, 1 + its MapSlot) and the property.
bool transformPointer(const std::string& rest, AnimatedProperty& property, int& reference) {
    static const std::pair<const char*, int> kReferences[] = {
        {"pbrMetallicRoughness/baseColorTexture", 0},
        {"pbrMetallicRoughness/metallicRoughnessTexture", 1 + int(MapSlot::MetallicRoughness)},
        {"emissiveTexture", 1 + int(MapSlot::Emissive)},
        {"normalTexture", 1 + int(MapSlot::Normal)},
        {"occlusionTexture", 1 + int(MapSlot::Occlusion)},
        {"extensions/KHR_materials_specular/specularTexture", 1 + int(MapSlot::Specular)},
        {"extensions/KHR_materials_specular/specularColorTexture", 1 + int(MapSlot::SpecularColour)},
        {"extensions/KHR_materials_clearcoat/clearcoatTexture", 1 + int(MapSlot::Clearcoat)},
        {"extensions/KHR_materials_clearcoat/clearcoatRoughnessTexture", 1 + int(MapSlot::ClearcoatRoughness)},
        {"extensions/KHR_materials_clearcoat/clearcoatNormalTexture", 1 + int(MapSlot::ClearcoatNormal)},
        {"extensions/KHR_materials_sheen/sheenColorTexture", 1 + int(MapSlot::SheenColour)},
        {"extensions/KHR_materials_sheen/sheenRoughnessTexture", 1 + int(MapSlot::SheenRoughness)},
    };
    static const std::pair<const char*, AnimatedProperty> kValues[] = {{"offset", AnimatedProperty::TextureOffset},
                                                                       {"rotation", AnimatedProperty::TextureRotation},
                                                                       {"scale", AnimatedProperty::TextureScale}};
    static const std::string kExtension = "/extensions/KHR_texture_transform/";
    for (const auto& [name, slot] : kReferences) {
        const std::string prefix = name + kExtension;
        if (rest.compare(0, prefix.size(), prefix) != 0) continue;
        for (const auto& [value, p] : kValues)
            if (rest.compare(prefix.size(), std::string::npos, value) == 0) {
                property = p;
                reference = slot;
                return true;
            }
        return false;
    }
    return false;
}

} // namespace

bool propertyPointer(const std::string& pointer, AnimatedProperty& property, int& target, int& reference) {
    reference = 0;
    struct Owner {
        const char* prefix;
        std::initializer_list<std::pair<const char*, AnimatedProperty>> paths;
    };
    using P = AnimatedProperty;
    static const Owner kOwners[] = {
        {"/materials/",
         {{"pbrMetallicRoughness/baseColorFactor", P::BaseColor},
          {"pbrMetallicRoughness/metallicFactor", P::Metallic},
          {"pbrMetallicRoughness/roughnessFactor", P::Roughness},
          {"emissiveFactor", P::Emissive},
          {"extensions/KHR_materials_emissive_strength/emissiveStrength", P::EmissiveStrength},
          {"normalTexture/scale", P::NormalScale},
          {"occlusionTexture/strength", P::OcclusionStrength},
          {"alphaCutoff", P::AlphaCutoff},
          {"extensions/KHR_materials_ior/ior", P::Ior},
          {"extensions/KHR_materials_specular/specularFactor", P::SpecularFactor},
          {"extensions/KHR_materials_specular/specularColorFactor", P::SpecularColor},
          {"extensions/KHR_materials_clearcoat/clearcoatFactor", P::Clearcoat},
          {"extensions/KHR_materials_clearcoat/clearcoatRoughnessFactor", P::ClearcoatRoughness},
          {"extensions/KHR_materials_clearcoat/clearcoatNormalTexture/scale", P::ClearcoatNormalScale},
          {"extensions/KHR_materials_sheen/sheenColorFactor", P::SheenColor},
          {"extensions/KHR_materials_sheen/sheenRoughnessFactor", P::SheenRoughness}}},
        {"/extensions/KHR_lights_punctual/lights/",
         {{"color", P::LightColor},
          {"intensity", P::LightIntensity},
          {"range", P::LightRange},
          {"spot/innerConeAngle", P::SpotInnerCone},
          {"spot/outerConeAngle", P::SpotOuterCone}}},
        {"/cameras/", {{"perspective/yfov", P::CameraYfov}, {"perspective/znear", P::CameraZnear}, {"perspective/zfar", P::CameraZfar}}},
    };
    for (const Owner& owner : kOwners) {
        const std::size_t n = std::char_traits<char>::length(owner.prefix);
        if (pointer.compare(0, n, owner.prefix) != 0) continue;
        std::size_t i = n;
        long long index = 0;
        while (i < pointer.size() && pointer[i] >= '0' && pointer[i] <= '9' && index <= 2147483647) index = index * 10 + (pointer[i++] - '0');
        if (i == n || i >= pointer.size() || pointer[i] != '/' || index > 2147483647) return false;
        const std::string rest = pointer.substr(i + 1);
        if (std::strcmp(owner.prefix, "/materials/") == 0 && transformPointer(rest, property, reference)) {
            target = int(index);
            return true;
        }
        for (const auto& [path, p] : owner.paths)
            if (rest == path) {
                property = p;
                target = int(index);
                return true;
            }
        return false;
    }
    return false;
}

bool ModelAnimation::animatesProperties() const {
    for (const AnimationClip& c : clips)
        if (!c.properties.empty()) return true;
    for (const LightSource& l : lights)
        if (l.moves) return true;
    for (const CameraSource& c : cameras)
        if (c.moves) return true;
    return false;
}

bool ModelAnimation::animatesMaterial(int material) const {
    for (const AnimationClip& c : clips)
        for (const PropertyChannel& ch : c.properties)
            if (ownerOf(ch.property) == PropertyOwner::Material && ch.target == material) return true;
    return false;
}

bool ModelAnimation::animatesTransforms(int material) const {
    for (const AnimationClip& c : clips)
        for (const PropertyChannel& ch : c.properties)
            if (isTextureTransform(ch.property) && ch.target == material) return true;
    return false;
}

PosedProperties ModelAnimation::poseProperties(double t, int clip) const {
    PosedProperties out;
    // The file's numbers, then the channels over them.
    std::vector<MaterialFactors> factors;
    std::vector<std::uint8_t> materialAnimated(materials.size(), 0), transformAnimated(materials.size(), 0);
    struct LightValues {
        std::array<double, 3> colour;
        double intensity, range, inner, outer;
    };
    std::vector<LightValues> lightValues; // per LightSource
    const auto restLights = [&] {
        std::vector<LightValues> rest;
        for (const LightSource& l : lights) rest.push_back({l.colour, l.intensity, l.range, l.innerCone, l.outerCone});
        return rest;
    };
    std::vector<CameraSource> cameraValues;
    double v[4];
    for (std::size_t c = 0; c < clips.size(); ++c) {
        if (clip >= 0 && std::size_t(clip) != c) continue;
        const double duration = clips[c].duration;
        const double local = duration > 0.0 ? t - std::floor(t / duration) * duration : t; // looped, as pose
        for (const PropertyChannel& ch : clips[c].properties) {
            clips[c].samplers[std::size_t(ch.sampler)].evaluate(local, v);
            const std::size_t target = std::size_t(ch.target);
            switch (ownerOf(ch.property)) {
            case PropertyOwner::Material: {
                if (target >= materials.size()) break;
                if (factors.empty()) factors = materials;
                materialAnimated[target] = 1;
                if (isTextureTransform(ch.property)) transformAnimated[target] = 1;
                MaterialFactors& f = factors[target];
                switch (ch.property) {
                case AnimatedProperty::BaseColor: std::copy(v, v + 4, f.baseColor.begin()); break;
                case AnimatedProperty::Metallic: f.metallic = v[0]; break;
                case AnimatedProperty::Roughness: f.roughness = v[0]; break;
                case AnimatedProperty::Emissive: std::copy(v, v + 3, f.emissive.begin()); break;
                case AnimatedProperty::EmissiveStrength: f.emissiveStrength = v[0]; break;
                case AnimatedProperty::NormalScale: f.normalScale = v[0]; break;
                case AnimatedProperty::OcclusionStrength: f.occlusionStrength = v[0]; break;
                case AnimatedProperty::AlphaCutoff: f.alphaCutoff = v[0]; break;
                case AnimatedProperty::Ior: f.ior = v[0], f.hasIor = true; break;
                case AnimatedProperty::SpecularFactor: f.specularFactor = v[0], f.hasSpecular = true; break;
                case AnimatedProperty::SpecularColor: std::copy(v, v + 3, f.specularColor.begin()), f.hasSpecular = true; break;
                case AnimatedProperty::Clearcoat: f.clearcoat = v[0], f.hasClearcoat = true; break;
                case AnimatedProperty::ClearcoatRoughness: f.clearcoatRoughness = v[0], f.hasClearcoat = true; break;
                case AnimatedProperty::ClearcoatNormalScale: f.clearcoatNormalScale = v[0], f.hasClearcoat = true; break;
                case AnimatedProperty::SheenColor: std::copy(v, v + 3, f.sheenColor.begin()), f.hasSheen = true; break;
                case AnimatedProperty::SheenRoughness: f.sheenRoughness = v[0], f.hasSheen = true; break;
                case AnimatedProperty::TextureOffset: std::copy(v, v + 2, f.transforms[std::size_t(ch.reference)].offset.begin()); break;
                case AnimatedProperty::TextureRotation: f.transforms[std::size_t(ch.reference)].rotation = v[0]; break;
                case AnimatedProperty::TextureScale: std::copy(v, v + 2, f.transforms[std::size_t(ch.reference)].scale.begin()); break;
                default: break;
                }
                break;
            }
            case PropertyOwner::Light:
                if (lightValues.empty()) lightValues = restLights();
                for (std::size_t k = 0; k < lights.size(); ++k) { // every placement of that light
                    if (lights[k].light != ch.target) continue;
                    LightValues& l = lightValues[k];
                    if (ch.property == AnimatedProperty::LightColor) std::copy(v, v + 3, l.colour.begin());
                    else if (ch.property == AnimatedProperty::LightIntensity) l.intensity = v[0];
                    else if (ch.property == AnimatedProperty::LightRange) l.range = v[0];
                    else if (ch.property == AnimatedProperty::SpotInnerCone) l.inner = v[0];
                    else l.outer = v[0];
                }
                break;
            case PropertyOwner::Camera:
                if (cameraValues.empty()) cameraValues = cameras;
                for (CameraSource& cam : cameraValues) {
                    if (cam.camera != ch.target) continue;
                    if (ch.property == AnimatedProperty::CameraYfov) cam.yfov = v[0];
                    else if (ch.property == AnimatedProperty::CameraZnear) cam.znear = v[0];
                    else cam.zfar = v[0];
                }
                break;
            }
        }
    }
    // Lights and cameras whose nodes move: every one posed (the still ones as loaded).
    const bool lightsMove = std::any_of(lights.begin(), lights.end(), [](const LightSource& l) { return l.moves; });
    const bool camerasMove = std::any_of(cameras.begin(), cameras.end(), [](const CameraSource& c) { return c.moves; });
    if (lightsMove && lightValues.empty()) lightValues = restLights();
    if (camerasMove && cameraValues.empty()) cameraValues = cameras;
    std::vector<Mat4d> world;
    if (lightsMove || camerasMove) {
        std::vector<std::vector<double>> weights;
        nodeWorlds(t, clip, false, world, weights);
    }
    // A node's origin, and its axis (0 x, 1 y, 2 z) normalised; false where the transform collapses it.
    const auto origin = [&](int node) {
        const Mat4d& w = world[std::size_t(node)];
        return Vec3(float(w.m[0][3]), float(w.m[1][3]), float(w.m[2][3]));
    };
    const auto axis = [&](int node, int a, Vec3& out) {
        const Mat4d& w = world[std::size_t(node)];
        const double x = w.m[0][a], y = w.m[1][a], z = w.m[2][a], l = std::sqrt(x * x + y * y + z * z);
        if (!(l > 0.0) || !std::isfinite(l)) return false;
        out = Vec3(float(x / l), float(y / l), float(z / l));
        return true;
    };
    for (std::size_t m = 0; m < factors.size(); ++m) {
        if (!materialAnimated[m]) continue;
        Material material;
        material.fromFile = true;
        applyFactors(factors[m], material);
        out.materials.push_back(int(m));
        out.values.push_back(std::move(material));
        if (!transformAnimated[m]) continue;
        PosedProperties::Transforms posed;
        posed.material = int(m);
        for (std::size_t k = 0; k < posed.m.size(); ++k) {
            float matrix[2][3];
            factors[m].transforms[k].storedMatrix(matrix);
            for (int r = 0; r < 2; ++r)
                for (int c = 0; c < 3; ++c) posed.m[k][std::size_t(r)][std::size_t(c)] = std::isfinite(matrix[r][c]) ? matrix[r][c] : 0.0f;
        }
        out.transforms.push_back(posed);
    }
    for (std::size_t k = 0; k < lightValues.size(); ++k) {
        const LightSource& s = lights[k];
        const LightValues& l = lightValues[k];
        const double intensity = std::isfinite(l.intensity) ? std::clamp(l.intensity, 0.0, 1e9) : s.intensity;
        const double range = std::isfinite(l.range) ? std::max(l.range, 0.0) : s.range;
        Color colour{0, 0, 0, 1};
        float* rgb[3] = {&colour.r, &colour.g, &colour.b};
        for (std::size_t c = 0; c < 3; ++c) *rgb[c] = float(std::clamp(l.colour[c], 0.0, 1.0) * intensity);
        Light light = s.placed;
        if (s.moves) { // shining down its node's -Z from its origin (the loader's addLight)
            Vec3 z;
            light.position = origin(s.node);
            if (axis(s.node, 2, z)) {
                if (light.type == LightType::Directional) light.toLight = z;
                else light.spotDirection = -z;
            }
        }
        light.colour = colour;
        if (light.type != LightType::Directional) light.range = float(range);
        if (light.type == LightType::Spot) {
            const double outer = std::clamp(l.outer, 1e-6, kPiD / 2.0);
            const double inner = std::clamp(l.inner, 0.0, outer);
            light = Light::spot(light.position, light.spotDirection, colour, float(inner), float(outer), float(range));
        }
        out.lights.push_back(light);
    }
    for (std::size_t k = 0; k < cameraValues.size(); ++k) {
        const CameraSource& rest = cameras[k];
        CameraSource c = cameraValues[k];
        if (!(c.yfov > 0.0 && c.yfov < kPiD)) c.yfov = rest.yfov;
        if (!(c.znear > 0.0) || !std::isfinite(c.znear)) c.znear = rest.znear;
        if (!(c.zfar == 0.0 || c.zfar > c.znear) || !std::isfinite(c.zfar)) c.zfar = rest.zfar > c.znear ? rest.zfar : 0.0;
        PosedProperties::Camera posed{c.yfov * 180.0 / kPiD, c.znear, c.zfar, rest.eye, rest.target, rest.up};
        Vec3 z, y;
        if (rest.moves && axis(rest.node, 2, z) && axis(rest.node, 1, y)) { // looking down its node's -Z, +Y up (addCamera)
            posed.eye = origin(rest.node);
            posed.target = posed.eye - z;
            posed.up = y;
        }
        out.cameras.push_back(posed);
    }
    return out;
}

} // namespace sr
