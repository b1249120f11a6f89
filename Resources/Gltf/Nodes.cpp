// gltfimport nodes: local transforms, GPU instancing, and what a node places besides meshes (cameras, KHR_lights_punctual lights).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "Math/Conventions.hpp"
#include "Resources/Gltf/Import.hpp"

namespace sr::gltfimport {

Mat4d localMatrix(const gltf::Node& n) {
    Mat4d m;
    if (n.matrix.size() == 16) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m.m[r][c] = n.matrix[std::size_t(c * 4 + r)];
        return m;
    }
    std::array<double, 3> t{0, 0, 0}, s{1, 1, 1};
    std::array<double, 4> q{0, 0, 0, 1};
    if (n.translation.size() == 3) std::copy(n.translation.begin(), n.translation.end(), t.begin());
    if (n.rotation.size() == 4) std::copy(n.rotation.begin(), n.rotation.end(), q.begin());
    if (n.scale.size() == 3) std::copy(n.scale.begin(), n.scale.end(), s.begin());
    return trsMatrix(t, q, s);
}

Mat4 toMat4(const Mat4d& m) {
    Mat4 r;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) r.m[col * 4 + row] = float(m.m[row][col]);
    return r;
}

bool finite(const Mat4d& m) {
    for (const auto& row : m.m)
        for (double v : row)
            if (!std::isfinite(v)) return false;
    return true;
}

Status addCamera(Builder& b, const gltf::Camera& c, const Mat4d& world, int index) {
    const std::string what = "camera " + std::to_string(index);
    if (c.type != "perspective") {
        b.model.warnings.push_back(b.path + ": " + what + " (" + c.type + ") skipped: only perspective cameras are used");
        return success();
    }
    const auto& p = c.perspective;
    if (!(p.yfov > 0.0 && p.yfov < kPiD) || !(p.znear > 0.0) || !(p.zfar == 0.0 || p.zfar > p.znear))
        return Status::failure(what + ": yfov must be in (0, pi), znear > 0 and zfar 0 or above znear");
    const auto apply3 = [&](double x, double y, double z) {
        return Vec3d{world.m[0][0] * x + world.m[0][1] * y + world.m[0][2] * z, world.m[1][0] * x + world.m[1][1] * y + world.m[1][2] * z,
                     world.m[2][0] * x + world.m[2][1] * y + world.m[2][2] * z};
    };
    const Vec3d eye{world.m[0][3], world.m[1][3], world.m[2][3]};
    const Vec3d forward = apply3(0, 0, -1), up = apply3(0, 1, 0);
    const double lf = length(forward), lu = length(up);
    if (!(lf > 0.0) || !(lu > 0.0) || !std::isfinite(lf) || !std::isfinite(lu))
        return Status::failure(what + ": its node's transform collapses the view direction");
    ModelCamera cam;
    cam.name = c.name;
    cam.eye = Vec3(float(eye.x), float(eye.y), float(eye.z));
    const Vec3d target = eye + forward / lf;
    cam.target = Vec3(float(target.x), float(target.y), float(target.z));
    cam.up = Vec3(float(up.x / lu), float(up.y / lu), float(up.z / lu));
    cam.yfovDegrees = p.yfov * 180.0 / kPiD;
    cam.znear = p.znear;
    cam.zfar = p.zfar;
    b.model.cameras.push_back(cam);
    if (b.animation) b.animation->cameras.push_back({index, p.yfov, p.znear, p.zfar, b.nodeIndex, false, cam.eye, cam.target, cam.up});
    return success();
}

// A KHR_lights_punctual light placed by a node: the light shines down its node's -Z from its
// origin. colour = color x intensity, used as it is (a directional light's lux and a point or
// spot light's candela over the squared distance land on the same scale: 1 lights a surface
// with its full diffuse colour); range 0 or absent: unlimited.
Status addLight(Builder& b, const gltf::Light& l, const Mat4d& world, int index) {
    const std::string what = "light " + std::to_string(index);
    double rgb[3] = {1.0, 1.0, 1.0};
    if (!l.color.empty()) {
        if (l.color.size() != 3) return Status::failure(what + ": color must have 3 components");
        for (int k = 0; k < 3; ++k) rgb[k] = l.color[std::size_t(k)];
    }
    for (double c : rgb)
        if (!(c >= 0.0 && c <= 1.0)) return Status::failure(what + ": color components must be in [0, 1]");
    if (!(l.intensity >= 0.0 && l.intensity <= 1e9)) return Status::failure(what + ": intensity must be in [0, 1e9]");
    if (!(l.range >= 0.0 && l.range <= 1e30)) return Status::failure(what + ": range must be positive (or absent)");
    const Color colour{float(rgb[0] * l.intensity), float(rgb[1] * l.intensity), float(rgb[2] * l.intensity), 1.0f};
    const Vec3d origin{world.m[0][3], world.m[1][3], world.m[2][3]};
    const Vec3d forward{-world.m[0][2], -world.m[1][2], -world.m[2][2]}; // the node's -Z
    const double lf = length(forward);
    const Vec3 position(float(origin.x), float(origin.y), float(origin.z));
    const Vec3 direction = lf > 0.0 && std::isfinite(lf) ? Vec3(float(forward.x / lf), float(forward.y / lf), float(forward.z / lf))
                                                         : Vec3(0.0f, 0.0f, 0.0f);
    if (l.type == "directional") {
        if (direction == Vec3(0.0f, 0.0f, 0.0f)) return Status::failure(what + ": its node's transform collapses the light's direction");
        b.model.lights.push_back(Light::directional(-direction, colour));
    } else if (l.type == "point") {
        b.model.lights.push_back(Light::point(position, colour, float(l.range)));
    } else if (l.type == "spot") {
        if (direction == Vec3(0.0f, 0.0f, 0.0f)) return Status::failure(what + ": its node's transform collapses the light's direction");
        const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
        if (!(inner >= 0.0 && inner < outer && outer <= kPiD / 2.0))
            return Status::failure(what + ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
        b.model.lights.push_back(Light::spot(position, direction, colour, float(inner), float(outer), float(l.range)));
    } else {
        return Status::failure(what + ": type '" + l.type + "' is not directional, point or spot");
    }
    if (b.animation)
        b.animation->lights.push_back({index, b.nodeIndex, false, b.model.lights.back(), {rgb[0], rgb[1], rgb[2]}, l.intensity, l.range,
                                       l.spot.innerConeAngle, l.spot.outerConeAngle});
    return success();
}

Result<int> nodeLight(const gltf::Node& node, std::size_t lightCount) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return Result<int>(-1);
    const gltf::Json& v = *ext;
    if (!v.is_object() || !v.contains("light") || !v["light"].is_number())
        return Result<int>::failure("KHR_lights_punctual must name a light by its index");
    const double index = v["light"].get<double>();
    if (!(index >= 0.0 && index < double(lightCount)) || index != double(int(index))) {
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", index);
        return Result<int>::failure(std::string("KHR_lights_punctual: light ") + text + " does not exist");
    }
    return Result<int>(int(index));
}


// EXT_mesh_gpu_instancing ("Instancing"): TRANSLATION (float VEC3), ROTATION (float or
// normalised byte/short VEC4, a unit quaternion) and SCALE (float VEC3), each optional, with
// one element per instance; instance k's transform is T_k R_k S_k, applied before the node's.
Result<std::vector<Mat4d>> instanceMatrices(Builder& b, const gltf::Node& node, int nodeIndex) {
    using R = Result<std::vector<Mat4d>>;
    const auto ext = node.extensions.find("EXT_mesh_gpu_instancing");
    if (ext == node.extensions.end()) return R(std::vector<Mat4d>{});
    const std::string what = "node " + std::to_string(nodeIndex) + " EXT_mesh_gpu_instancing";
    const auto attributes = ext->find("attributes");
    if (attributes == ext->end() || !attributes->is_object() || attributes->empty())
        return R::failure(what + ": needs attributes (TRANSLATION, ROTATION or SCALE)");
    std::optional<View> views[3];
    const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    std::size_t count = 0;
    bool first = true;
    for (int k = 0; k < 3; ++k) {
        const auto it = attributes->find(names[k]);
        if (it == attributes->end()) continue;
        if (!it->is_number_integer()) return R::failure(what + ": " + names[k] + " must name an accessor");
        auto v = b.accessors->view(it->get<int>(), what + " " + names[k]);
        if (!v) return R::failure(v.error());
        const View& view = v.value();
        const int want = k == 1 ? 4 : 3;
        const bool typeOk = view.componentType == gltf::kFloat ||
                            (k == 1 && view.normalized && (view.componentType == gltf::kByte || view.componentType == gltf::kShort));
        if (view.components != want || !typeOk)
            return R::failure(what + " " + names[k] + (k == 1 ? ": must be float or normalised byte/short VEC4" : ": must be float VEC3"));
        if (!first && view.count != count) return R::failure(what + ": its attributes count different numbers of instances");
        count = view.count;
        first = false;
        views[k] = view;
    }
    std::vector<Mat4d> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        std::array<double, 3> t{0, 0, 0}, s{1, 1, 1};
        std::array<double, 4> q{0, 0, 0, 1};
        for (int c = 0; c < 3; ++c) {
            if (views[0]) t[std::size_t(c)] = readFloat(*views[0], i, c);
            if (views[2]) s[std::size_t(c)] = readFloat(*views[2], i, c);
        }
        if (views[1]) {
            double l = 0.0;
            for (int c = 0; c < 4; ++c) l += double(readFloat(*views[1], i, c)) * readFloat(*views[1], i, c);
            l = std::sqrt(l);
            if (!(l > 0.0) || !std::isfinite(l)) return R::failure(what + " ROTATION: instance " + std::to_string(i) + " is not a rotation");
            for (int c = 0; c < 4; ++c) q[std::size_t(c)] = readFloat(*views[1], i, c) / l;
        }
        const Mat4d m = trsMatrix(t, q, s);
        if (!finite(m)) return R::failure(what + ": instance " + std::to_string(i) + " has a transform that is not finite");
        out.push_back(m);
    }
    return R(std::move(out));
}

} // namespace sr::gltfimport
