// glTF animation: the samplers against hand-computed values, skins and morph targets posed by the loader's data, bad animated files.
#include "TestFramework.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "Math/Conventions.hpp"
#include "Resources/Animation.hpp"
#include "Resources/Gltf/GltfLoader.hpp"

#include "GltfTestUtil.hpp"
#include "ObjTestUtil.hpp"

using namespace sr;
using namespace sr::objtest;
using sr::gltftest::Asset;

namespace {

double at(const AnimationSampler& s, double t, int c = 0) {
    double out[4] = {0, 0, 0, 0};
    s.evaluate(t, out);
    return out[c];
}

void checkVec(Vec3 v, double x, double y, double z, double margin = 1e-6) {
    CHECK(v.x == Approx(x).margin(margin));
    CHECK(v.y == Approx(y).margin(margin));
    CHECK(v.z == Approx(z).margin(margin));
}

// Two joints: node 1 at the origin, node 2 one unit up (its child); node 0 holds the skinned
// triangle (and a translation the specification says a skinned mesh ignores). Vertex 0 (0, 2, 0)
// has weights 1 + 1 on joint 1 (a sum of 2), vertex 1 (0.1, 2, 0) weight 2 on joint 1, vertex 2
// (0, 2, 0.1) half on each joint. The clip turns joint node 2 by 90 degrees about Z over a second.
Asset skinAsset(std::uint8_t badJoint = 1) {
    Asset a;
    const int pos = a.floats({0, 2, 0, 0.1f, 2, 0, 0, 2, 0.1f}, "VEC3");
    const int joints = a.unsignedBytes({1, 1, 0, 0, badJoint, 0, 0, 0, 0, 1, 0, 0}, "VEC4");
    const int weights = a.floats({1, 1, 0, 0, 2, 0, 0, 0, 0.5f, 0.5f, 0, 0}, "VEC4");
    const int ibm = a.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, // joint node 1: identity
                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}, // node 2: translate(0, -1, 0), column-major
                             "MAT4");
    const float h = float(std::sqrt(0.5));
    const int input = a.floats({0, 1}, "SCALAR");
    const int output = a.floats({0, 0, 0, 1, 0, 0, h, h}, "VEC4");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"JOINTS_0\":" + std::to_string(joints) +
               ",\"WEIGHTS_0\":" + std::to_string(weights) + "}}]}]";
    a.nodes = "[{\"mesh\":0,\"skin\":0,\"translation\":[5,0,0]},{\"children\":[2]},{\"translation\":[0,1,0]}]";
    a.scenes = "[{\"nodes\":[0,1]}]";
    a.extra = ",\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":" + std::to_string(ibm) + "}]" +
              ",\"animations\":[{\"samplers\":[{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(output) +
              "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":2,\"path\":\"rotation\"}}]}]";
    return a;
}

} // namespace

TEST_CASE("animation samplers: LINEAR, STEP and CUBICSPLINE against hand-computed values; the ends hold", "[resources][animation]") {
    AnimationSampler linear;
    linear.times = {1, 3};
    linear.values = {10, 20};
    CHECK(at(linear, 0.0) == 10.0); // before the first key: the first value
    CHECK(at(linear, 1.0) == 10.0);
    CHECK(at(linear, 2.0) == 15.0);
    CHECK(at(linear, 2.5) == 17.5);
    CHECK(at(linear, 3.0) == 20.0);
    CHECK(at(linear, 9.0) == 20.0); // after the last: the last

    AnimationSampler step;
    step.interpolation = AnimationSampler::Interpolation::Step;
    step.times = {0, 1, 2};
    step.values = {1, 2, 3};
    CHECK(at(step, 0.99) == 1.0);
    CHECK(at(step, 1.0) == 2.0);
    CHECK(at(step, 1.5) == 2.0);
    CHECK(at(step, 2.5) == 3.0);

    // CUBICSPLINE: per key in-tangent a, value v, out-tangent b; the tangents scale by the key
    // interval d = 2: at s = 1/2, 0.5 v0 + 0.125 d b0 + 0.5 v1 - 0.125 d a1 = 0.5 + 0.75 + 2 - 1.25 = 2
    // (without d: 2.25).
    AnimationSampler cubic;
    cubic.interpolation = AnimationSampler::Interpolation::CubicSpline;
    cubic.times = {0, 2};
    cubic.values = {0, 1, 3, 5, 4, 0};
    CHECK(at(cubic, 1.0) == Approx(2.0).epsilon(1e-12));
    CHECK(at(cubic, 0.0) == 1.0);
    CHECK(at(cubic, 2.0) == 4.0);
    // s = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64.
    CHECK(at(cubic, 0.5) == Approx(27.0 / 32 + 9.0 / 64 * 2 * 3 + 5.0 / 32 * 4 - 3.0 / 64 * 2 * 5).epsilon(1e-12));
}

TEST_CASE("animation samplers: rotations slerp the short way (a negated key turns no further) and stay unit", "[resources][animation]") {
    const double s45 = std::sin(kPiD / 4), c45 = std::cos(kPiD / 4);
    AnimationSampler r;
    r.quaternion = true;
    r.components = 4;
    r.times = {0, 1};
    r.values = {0, 0, 0, 1, 0, 0, -s45, -c45}; // 90 degrees about Z, written as its negation
    double q[4];
    r.evaluate(0.5, q);
    // 45 degrees about Z (w > 0): the short way; the long way would give 135 degrees about -Z.
    CHECK(q[0] == Approx(0.0).margin(1e-12));
    CHECK(q[2] == Approx(std::sin(kPiD / 8)).epsilon(1e-12));
    CHECK(q[3] == Approx(std::cos(kPiD / 8)).epsilon(1e-12));
    r.evaluate(0.25, q); // slerp: constant angular speed, 22.5 degrees
    CHECK(q[2] == Approx(std::sin(kPiD / 16)).epsilon(1e-12));
    // A cubic rotation is normalised.
    r.interpolation = AnimationSampler::Interpolation::CubicSpline;
    r.values = {0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, /* key 1 */ 0, 0, 0, 0, 0, 0, s45, c45, 0, 0, 0, 0};
    r.evaluate(0.5, q);
    CHECK(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("skins: a two-joint skin bent by 90 degrees moves its vertices where hand computation puts them", "[resources][animation][skin]") {
    const std::string dir = freshDir("gltf-skin");
    auto r = loadGltf(writeText(dir, "skin.gltf", skinAsset().embedded()));
    REQUIRE(r.ok());
    Model m = std::move(r).value();
    REQUIRE(m.animation);
    REQUIRE(m.mesh.positions.size() == 3);
    // The rest pose: the joints' rest transforms times their inverse bind matrices are the
    // identity, and the skinned mesh's node translation is ignored (glTF "Skins").
    checkVec(m.mesh.positions[0], 0, 2, 0);
    checkVec(m.mesh.positions[1], 0.1, 2, 0);
    checkVec(m.mesh.positions[2], 0, 2, 0.1);
    // t = 1: joint 2 turned 90 degrees about Z around (0, 1, 0): (x, y) -> (-(y - 1), 1 + x).
    // Vertex 0's weights 1 + 1 on joint 2 are normalised (a sum of 2 would double it), vertex 1's
    // single 2 likewise; vertex 2 is half on each joint.
    m.animation->pose(1.0 - 1e-12, -1, m.mesh);
    checkVec(m.mesh.positions[0], -1, 1, 0, 1e-5);
    checkVec(m.mesh.positions[1], -1, 1.1, 0, 1e-5);
    checkVec(m.mesh.positions[2], -0.5, 1.5, 0.1, 1e-5);
    // Half way: 45 degrees.
    m.animation->pose(0.5, -1, m.mesh);
    const double h = std::sqrt(0.5);
    checkVec(m.mesh.positions[0], -h, 1 + h, 0, 1e-5);
    // The flat normal of the posed triangle is unit.
    CHECK(length(m.mesh.normals[0]) == Approx(1.0f).epsilon(1e-5));
    // Clip 0 alone gives the same; a clip number beyond the file's animates nothing (the rest pose).
    m.animation->pose(0.5, 0, m.mesh);
    checkVec(m.mesh.positions[0], -h, 1 + h, 0, 1e-5);
    m.animation->pose(0.5, 7, m.mesh);
    checkVec(m.mesh.positions[0], 0, 2, 0);
    CHECK(m.animation->duration() == 1.0);
}

TEST_CASE("morph targets: weights 0 and 1 give the base and the target exactly; the mesh's weights are the rest pose",
          "[resources][animation][morph]") {
    const std::string dir = freshDir("gltf-morph");
    Asset a;
    const int pos = a.floats({1, 0, 0, 2, 0, 0, 1, 1, 0}, "VEC3");
    const int delta = a.floats({0, 4, 0, 0, 4, 0, 0, 4, 0}, "VEC3");
    const int input = a.floats({0, 1, 2}, "SCALAR");
    const int output = a.floats({0, 1, 1}, "SCALAR");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"targets\":[{\"POSITION\":" +
               std::to_string(delta) + "}]}],\"weights\":[0.25]}]";
    a.nodes = "[{\"mesh\":0}]";
    const std::string animation = ",\"animations\":[{\"samplers\":[{\"input\":" + std::to_string(input) + ",\"output\":" +
                                  std::to_string(output) + ",\"interpolation\":\"STEP\"}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"weights\"}}]}]";
    a.extra = animation;
    auto r = loadGltf(writeText(dir, "morph.gltf", a.embedded()));
    REQUIRE(r.ok());
    Model m = std::move(r).value();
    REQUIRE(m.animation);
    CHECK(m.mesh.positions[0] == Vec3(1, 1, 0)); // the rest pose: 0.25 x (0, 4, 0)
    m.animation->pose(0.5, -1, m.mesh);          // STEP: weight 0
    CHECK(m.mesh.positions[0] == Vec3(1, 0, 0));
    CHECK(m.mesh.positions[2] == Vec3(1, 1, 0));
    m.animation->pose(1.5, -1, m.mesh); // weight 1
    CHECK(m.mesh.positions[0] == Vec3(1, 4, 0));
    CHECK(m.mesh.positions[1] == Vec3(2, 4, 0));
    m.animation->pose(0.0, -1, m.mesh, true); // the rest pose again
    CHECK(m.mesh.positions[0] == Vec3(1, 1, 0));

    // A normal-mapped primitive with its own tangents: a TANGENT target moves them too.
    Asset t;
    const int tp = t.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int tn = t.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int tt = t.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4");
    const int tuv = t.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    const int td = t.floats({0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
    const int tdt = t.floats({-1, 1, 0, -1, 1, 0, -1, 1, 0}, "VEC3");
    const int tin = t.floats({0, 1, 2}, "SCALAR");
    const int tout = t.floats({0, 1, 1}, "SCALAR");
    t.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(tp) + ",\"NORMAL\":" + std::to_string(tn) +
               ",\"TANGENT\":" + std::to_string(tt) + ",\"TEXCOORD_0\":" + std::to_string(tuv) + "},\"material\":0,\"targets\":[{\"POSITION\":" +
               std::to_string(td) + ",\"TANGENT\":" + std::to_string(tdt) + "}]}]}]";
    t.nodes = "[{\"mesh\":0}]";
    t.materials = "[{\"normalTexture\":{\"index\":0}}]";
    t.extra = ",\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"none.png\"}],\"animations\":[{\"samplers\":[{\"input\":" +
              std::to_string(tin) + ",\"output\":" + std::to_string(tout) +
              ",\"interpolation\":\"STEP\"}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"weights\"}}]}]";
    auto tr = loadGltf(writeText(dir, "tangents.gltf", t.embedded()));
    REQUIRE(tr.ok());
    Model tm = std::move(tr).value();
    REQUIRE(tm.mesh.hasTangents());
    CHECK(tm.mesh.tangents[0] == Vec4(1, 0, 0, 1)); // weight 0 at rest
    tm.animation->pose(1.5, -1, tm.mesh);           // weight 1: (1, 0, 0) + (-1, 1, 0)
    CHECK(tm.mesh.tangents[0].x == Approx(0.0f).margin(1e-7));
    CHECK(tm.mesh.tangents[0].y == Approx(1.0f));
    CHECK(tm.mesh.tangents[0].w == 1.0f);

    // A file without animations, skins or morph targets keeps nothing for them.
    Asset plain;
    const int p2 = plain.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    plain.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(p2) + "}}]}]";
    plain.nodes = "[{\"mesh\":0}]";
    auto still = loadGltf(writeText(dir, "still.gltf", plain.embedded()));
    REQUIRE(still.ok());
    CHECK_FALSE(still.value().animation);
}

TEST_CASE("animated files with bad data are one-line errors naming the file and the problem", "[resources][animation][errors]") {
    const std::string dir = freshDir("gltf-animation-errors");
    const auto errorOf = [&](const std::string& name, const std::string& text) {
        auto r = loadGltf(writeText(dir, name, text));
        REQUIRE_FALSE(r.ok());
        INFO(r.error());
        CHECK(contains(r.error(), name));
        CHECK(r.error().find('\n') == std::string::npos);
        return r.error();
    };
    // A joint index beyond the skin's joints.
    CHECK(contains(errorOf("joint.gltf", skinAsset(9).embedded()), "names joint 9, out of range"));
    // Key times that do not increase, and a NaN key.
    {
        Asset a = skinAsset();
        const int bad = a.floats({1, 1}, "SCALAR");
        a.extra.replace(a.extra.find("\"input\":") + 8, 1, std::to_string(bad));
        CHECK(contains(errorOf("times.gltf", a.embedded()), "key times are not increasing"));
        Asset n = skinAsset();
        const int nan = n.floats({0, std::nanf("")}, "SCALAR");
        n.extra.replace(n.extra.find("\"input\":") + 8, 1, std::to_string(nan));
        CHECK(contains(errorOf("nan.gltf", n.embedded()), "is not finite"));
    }
    // An output of the wrong count (one rotation for two keys).
    {
        Asset a = skinAsset();
        const int bad = a.floats({0, 0, 0, 1}, "VEC4");
        a.extra.replace(a.extra.find("\"output\":") + 9, 1, std::to_string(bad));
        CHECK(contains(errorOf("count.gltf", a.embedded()), "expected 8 values"));
    }
    // A singular inverse bind matrix.
    {
        Asset a = skinAsset();
        const int zero = a.floats(std::vector<float>(32, 0.0f), "MAT4");
        const auto at = a.extra.find("\"inverseBindMatrices\":") + 22;
        a.extra.replace(at, a.extra.find('}', at) - at, std::to_string(zero));
        CHECK(contains(errorOf("singular.gltf", a.embedded()), "singular"));
    }
    // A skin without joints (the schema asks for at least one).
    {
        Asset a = skinAsset();
        a.extra.replace(a.extra.find("\"joints\":[1,2]"), 14, "\"joints\":[]");
        CHECK(contains(errorOf("nojoints.gltf", a.embedded()), "has no joints"));
    }
    // Weights animated on a mesh without morph targets.
    {
        Asset a = skinAsset();
        a.extra.replace(a.extra.find("\"rotation\""), 10, "\"weights\"");
        CHECK(contains(errorOf("weights.gltf", a.embedded()), "no morph targets"));
    }
}

TEST_CASE("an animation sampler's output as a sparse accessor over zeros drives the weights as the dense one would",
          "[resources][animation][sparse]") {
    const std::string dir = freshDir("gltf-sparse-output");
    Asset a;
    const int pos = a.floats({1, 0, 0, 2, 0, 0, 1, 1, 0}, "VEC3");
    const int delta = a.floats({0, 4, 0, 0, 4, 0, 0, 4, 0}, "VEC3");
    const int input = a.floats({0, 1, 2}, "SCALAR");
    // The output (0, 1, 0): no buffer view (zeros), key 1 set to 1 by the sparse substitution.
    const std::vector<std::uint8_t> index{1};
    const std::vector<float> value{1.0f};
    const int iv = a.view(index.data(), 1);
    const int vv = a.view(value.data(), 4);
    const int output = a.rawAccessor("{\"componentType\":5126,\"count\":3,\"type\":\"SCALAR\",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" +
                                     std::to_string(iv) + ",\"componentType\":5121},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}}");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"targets\":[{\"POSITION\":" +
               std::to_string(delta) + "}]}]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.extra = ",\"animations\":[{\"samplers\":[{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(output) +
              "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"weights\"}}]}]";
    auto r = loadGltf(writeText(dir, "sparse-output.gltf", a.embedded()));
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    Model m = std::move(r).value();
    REQUIRE(m.animation);
    m.animation->pose(0.5, -1, m.mesh); // weight 0.5
    checkVec(m.mesh.positions[0], 1, 2, 0);
    m.animation->pose(1.0, -1, m.mesh); // weight 1
    checkVec(m.mesh.positions[0], 1, 4, 0);
    m.animation->pose(2.0, -1, m.mesh); // weight 0
    checkVec(m.mesh.positions[0], 1, 0, 0);
}

TEST_CASE("KHR_animation_pointer: a node's translation by pointer moves it as the core path does; other targets are named in a warning",
          "[resources][animation][pointer]") {
    const std::string dir = freshDir("gltf-pointer");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int input = a.floats({0, 1}, "SCALAR");
    const int moves = a.floats({0, 0, 0, 2, 0, 0}, "VEC3");
    const int colours = a.floats({1, 0, 0, 1, 0, 0, 1, 1}, "VEC4");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":0}]}]";
    a.nodes = "[{\"mesh\":0}]";
    a.materials = "[{}]";
    const auto pointerChannel = [](int sampler, const std::string& pointer) {
        return "{\"sampler\":" + std::to_string(sampler) + ",\"target\":{\"path\":\"pointer\",\"extensions\":{\"KHR_animation_pointer\":{\"pointer\":\"" +
               pointer + "\"}}}}";
    };
    a.extra = ",\"extensionsUsed\":[\"KHR_animation_pointer\"],\"extensionsRequired\":[\"KHR_animation_pointer\"],"
              "\"animations\":[{\"samplers\":[{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(moves) +
              "},{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(colours) + "}],\"channels\":[" +
              pointerChannel(0, "/nodes/0/translation") + "," + pointerChannel(1, "/materials/0/pbrMetallicRoughness/baseColorFactor") + "]}]";
    auto r = loadGltf(writeText(dir, "pointer.gltf", a.embedded()));
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    Model m = std::move(r).value();
    REQUIRE(m.animation);
    REQUIRE(m.warnings.size() == 1);
    CHECK(m.warnings[0].find("KHR_animation_pointer '/materials/0/pbrMetallicRoughness/baseColorFactor' is not animated") != std::string::npos);
    m.animation->pose(0.5, -1, m.mesh);
    checkVec(m.mesh.positions[0], 1, 0, 0);
    checkVec(m.mesh.positions[1], 2, 0, 0);
    m.animation->pose(0.25, -1, m.mesh);
    checkVec(m.mesh.positions[2], 0.5, 1, 0);
}
