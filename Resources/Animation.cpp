// Animation: keyframe interpolation, the node hierarchy at a time, morph targets and skinning into a mesh.
#include "Resources/Animation.hpp"

#include <algorithm>
#include <cmath>

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
}

double ModelAnimation::duration(int clip) const {
    double d = 0.0;
    for (std::size_t i = 0; i < clips.size(); ++i)
        if (clip < 0 || std::size_t(clip) == i) d = std::max(d, clips[i].duration);
    return d;
}

void ModelAnimation::pose(double t, int clip, Mesh& mesh, bool restOnly) const {
    // Local transforms and weights: the rest values, then the channels.
    std::vector<std::array<double, 3>> translation(nodes.size()), scale(nodes.size());
    std::vector<std::array<double, 4>> rotation(nodes.size());
    std::vector<std::vector<double>> weights(nodes.size());
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
    std::vector<Mat4d> world(nodes.size());
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
                m = world[std::size_t(b.node)];
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
