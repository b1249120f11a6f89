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

namespace {

std::string pointerChannel(int sampler, const std::string& pointer) {
    return "{\"sampler\":" + std::to_string(sampler) + ",\"target\":{\"path\":\"pointer\",\"extensions\":{\"KHR_animation_pointer\":{\"pointer\":\"" +
           pointer + "\"}}}}";
}

} // namespace

TEST_CASE("KHR_animation_pointer: a node's translation by pointer moves it as the core path does; a property SoftRaster does not read is named in a warning",
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
    a.extra = ",\"extensionsUsed\":[\"KHR_animation_pointer\"],\"extensionsRequired\":[\"KHR_animation_pointer\"],"
              "\"animations\":[{\"samplers\":[{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(moves) +
              "},{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(colours) + "}],\"channels\":[" +
              pointerChannel(0, "/nodes/0/translation") + "," + pointerChannel(1, "/materials/0/extensions/KHR_materials_transmission/transmissionFactor") + "]}]";
    auto r = loadGltf(writeText(dir, "pointer.gltf", a.embedded()));
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    Model m = std::move(r).value();
    REQUIRE(m.animation);
    REQUIRE(m.warnings.size() == 1);
    CHECK(m.warnings[0].find("KHR_animation_pointer '/materials/0/extensions/KHR_materials_transmission/transmissionFactor' is not animated") !=
          std::string::npos);
    m.animation->pose(0.5, -1, m.mesh);
    checkVec(m.mesh.positions[0], 1, 0, 0);
    checkVec(m.mesh.positions[1], 2, 0, 0);
    m.animation->pose(0.25, -1, m.mesh);
    checkVec(m.mesh.positions[2], 0.5, 1, 0);
}

namespace {

// A triangle with material 0 (animated), material 1 (MASK, its alpha animated), a point and a
// spot light and a camera: samplers over keys 0 and 1 s, each channel given by pointer.
Asset propertyAsset(const std::string& channels, const std::string& material0 = "{}") {
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int input = a.floats({0, 1}, "SCALAR");
    const int colours = a.floats({1, 0, 0, 1, 0, 0, 1, 1}, "VEC4");  // sampler 0: red -> blue
    const int ramp = a.floats({0, 1}, "SCALAR");                      // sampler 1: 0 -> 1
    const int intensity = a.floats({0, 10}, "SCALAR");                // sampler 2: 0 -> 10
    const int cone = a.floats({0.5f, 1.0f}, "SCALAR");                // sampler 3: 0.5 -> 1
    const int rgb = a.floats({1, 0.5f, 0, 1, 0.5f, 0}, "VEC3");       // sampler 4: (1, 0.5, 0)
    const int negative = a.floats({-1, -1}, "SCALAR");               // sampler 5: -1
    const int fade = a.floats({1, 1, 1, 0, 1, 1, 1, 1}, "VEC4");      // sampler 6: white, alpha 0 -> 1
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":0}," +
               "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":1}]}]";
    a.nodes = "[{\"mesh\":0},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}},\"translation\":[0,0,2]},"
              "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}},\"translation\":[0,0,3]},{\"camera\":0,\"translation\":[0,0,5]}]";
    a.scenes = "[{\"nodes\":[0,1,2,3]}]";
    a.materials = "[" + material0 + ",{\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5}]";
    std::string samplers;
    for (const int out : {colours, ramp, intensity, cone, rgb, negative, fade})
        samplers += std::string(samplers.empty() ? "" : ",") + "{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(out) + "}";
    a.extra = ",\"extensionsUsed\":[\"KHR_animation_pointer\",\"KHR_lights_punctual\"],"
              "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"intensity\":3},"
              "{\"type\":\"spot\",\"color\":[0,1,0],\"spot\":{\"innerConeAngle\":0.1,\"outerConeAngle\":0.4}}]}},"
              "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.5,\"znear\":0.1,\"zfar\":100}}],"
              "\"animations\":[{\"samplers\":[" + samplers + "],\"channels\":[" + channels + "]}]";
    return a;
}

} // namespace

TEST_CASE("KHR_animation_pointer: material factors posed at a time are the material a file with those values loads",
          "[resources][animation][pointer]") {
    const std::string dir = freshDir("gltf-pointer-material");
    const std::string channels = pointerChannel(0, "/materials/0/pbrMetallicRoughness/baseColorFactor") + "," +
                                 pointerChannel(1, "/materials/0/pbrMetallicRoughness/metallicFactor") + "," +
                                 pointerChannel(1, "/materials/0/pbrMetallicRoughness/roughnessFactor") + "," +
                                 pointerChannel(4, "/materials/0/emissiveFactor") + "," +
                                 pointerChannel(2, "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength") + "," +
                                 pointerChannel(3, "/materials/0/extensions/KHR_materials_ior/ior") + "," +
                                 pointerChannel(1, "/materials/0/extensions/KHR_materials_clearcoat/clearcoatFactor") + "," +
                                 pointerChannel(4, "/materials/0/extensions/KHR_materials_sheen/sheenColorFactor") + "," +
                                 pointerChannel(1, "/materials/0/extensions/KHR_materials_sheen/sheenRoughnessFactor") + "," +
                                 pointerChannel(6, "/materials/1/pbrMetallicRoughness/baseColorFactor");
    auto r = loadGltf(writeText(dir, "animated.gltf", propertyAsset(channels, "{\"extensions\":{\"KHR_materials_clearcoat\":{}}}").embedded()));
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model m = std::move(r).value();
    REQUIRE(m.animation);
    CHECK(m.warnings.empty());
    CHECK(m.animation->animatesProperties());
    CHECK(m.animation->animatesMaterial(0));
    CHECK(m.animation->animatesMaterial(1));
    // At 0.25 s: base (0.75, 0, 0.25, 1), metallic = roughness = 0.25, emissive (1, 0.5, 0) x 2.5,
    // ior 0.625 (below 1: the extension's default 1.5, as a file's), clearcoat 0.25, sheen colour
    // (1, 0.5, 0) and roughness 0.25.
    const PosedProperties posed = m.animation->poseProperties(0.25, -1);
    REQUIRE(posed.materials.size() == 2);
    CHECK(posed.materials[0] == 0);
    CHECK(posed.materials[1] == 1);
    // The same numbers written in a file, loaded.
    Asset still;
    const int pos = still.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    still.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":0}]}]";
    still.nodes = "[{\"mesh\":0}]";
    still.materials = "[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.75,0,0.25,1],\"metallicFactor\":0.25,\"roughnessFactor\":0.25},"
                      "\"emissiveFactor\":[1,0.5,0],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":2.5},"
                      "\"KHR_materials_ior\":{\"ior\":0.625},\"KHR_materials_clearcoat\":{\"clearcoatFactor\":0.25},"
                      "\"KHR_materials_sheen\":{\"sheenColorFactor\":[1,0.5,0],\"sheenRoughnessFactor\":0.25}}}]";
    auto s = loadGltf(writeText(dir, "still.gltf", still.embedded()));
    INFO((s ? std::string() : s.error()));
    REQUIRE(s.ok());
    const Material& want = s.value().materials[0];
    const Material& got = posed.values[0];
    REQUIRE(got.pbr);
    REQUIRE(want.pbr);
    CHECK(got.pbr->baseColor.r == Approx(0.75));
    CHECK(got.pbr->baseColor.b == Approx(0.25));
    CHECK(got.pbr->metallic == Approx(0.25));
    CHECK(got.pbr->emissive.x == Approx(2.5));
    CHECK(got.pbr->emissive.y == Approx(1.25));
    CHECK(got.pbr->clearcoat == Approx(0.25));
    CHECK(got.kd.r == Approx(0.75 * 0.75)); // base x (1 - metallic)
    const auto same = [](const Color& a, const Color& b) { return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a; };
    CHECK(same(got.kd, want.kd));
    CHECK(same(got.ks, want.ks));
    CHECK(got.shininess == want.shininess);
    CHECK(same(got.pbr->baseColor, want.pbr->baseColor));
    CHECK(got.pbr->metallic == want.pbr->metallic);
    CHECK(got.pbr->roughness == want.pbr->roughness);
    CHECK(got.pbr->emissive == want.pbr->emissive);
    CHECK(got.pbr->dielectricF0 == want.pbr->dielectricF0);
    CHECK(got.pbr->clearcoat == want.pbr->clearcoat);
    CHECK(got.pbr->sheenColor.y == Approx(0.5));
    CHECK(got.pbr->sheenColor == want.pbr->sheenColor);
    CHECK(got.pbr->sheenRoughness == want.pbr->sheenRoughness);
    CHECK(got.alpha == want.alpha);
    // Material 1 (MASK, cutoff 0.5): its alpha 0.25 is below the cutoff (dropped), 0.75 above.
    CHECK(posed.values[1].alpha == 0.0f);
    CHECK(posed.values[1].texelAlpha.mode == AlphaMode::Mask);
    CHECK(m.animation->poseProperties(0.75, -1).values[1].alpha == 1.0f);
    // Looped as the node channels are: 1.25 s is 0.25 s.
    CHECK(m.animation->poseProperties(1.25, -1).values[0].pbr->metallic == got.pbr->metallic);
    // Nothing animates a light or a camera here: none is posed.
    CHECK(posed.lights.empty());
    CHECK(posed.cameras.empty());
}

TEST_CASE("KHR_animation_pointer: light colour, intensity, range and spot cones, camera yfov; values out of range treated as a file's",
          "[resources][animation][pointer]") {
    const std::string dir = freshDir("gltf-pointer-lights");
    const std::string channels = pointerChannel(2, "/extensions/KHR_lights_punctual/lights/0/intensity") + "," +
                                 pointerChannel(4, "/extensions/KHR_lights_punctual/lights/0/color") + "," +
                                 pointerChannel(2, "/extensions/KHR_lights_punctual/lights/0/range") + "," +
                                 pointerChannel(3, "/extensions/KHR_lights_punctual/lights/1/spot/outerConeAngle") + "," +
                                 pointerChannel(3, "/cameras/0/perspective/yfov") + "," + pointerChannel(5, "/cameras/0/perspective/znear");
    auto r = loadGltf(writeText(dir, "lights.gltf", propertyAsset(channels).embedded()));
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model m = std::move(r).value();
    REQUIRE(m.animation);
    REQUIRE(m.lights.size() == 2);
    CHECK_FALSE(m.animation->animatesMaterial(0));
    const PosedProperties posed = m.animation->poseProperties(0.5, -1);
    CHECK(posed.materials.empty());
    REQUIRE(posed.lights.size() == 2);
    // The point light: intensity 5 (was 3), colour (1, 0.5, 0), range 5; its place kept.
    const Light& point = posed.lights[0];
    CHECK(point.type == LightType::Point);
    CHECK(point.colour.r == Approx(5.0));
    CHECK(point.colour.g == Approx(2.5));
    CHECK(point.colour.b == 0.0f);
    CHECK(point.range == Approx(5.0));
    CHECK(point.position.z == Approx(2.0));
    // The spot: outer cone 0.75 rad, inner 0.1 as the file says, green x 1.
    const Light& spot = posed.lights[1];
    const Light want = Light::spot(Vec3(0, 0, 3), Vec3(0, 0, -1), Color{0, 1, 0, 1}, 0.1f, 0.75f);
    CHECK(spot.type == LightType::Spot);
    CHECK(spot.coneScale == want.coneScale);
    CHECK(spot.coneOffset == want.coneOffset);
    CHECK(spot.coneScale != m.lights[1].coneScale);
    CHECK(spot.colour.g == 1.0f);
    // The camera: yfov 0.75 rad; znear animated to -1 is no znear: the file's 0.1 kept.
    REQUIRE(posed.cameras.size() == 1);
    CHECK(posed.cameras[0].yfovDegrees == Approx(0.75 * 180.0 / kPiD));
    CHECK(posed.cameras[0].znear == Approx(0.1));
    CHECK(posed.cameras[0].zfar == Approx(100.0));
    // At 0 s the intensity key is 0: the light is black (not the file's 3).
    CHECK(m.animation->poseProperties(0.0, -1).lights[0].colour.r == 0.0f);
}

TEST_CASE("KHR_animation_pointer: a pointer to a material, light or camera that does not exist, or a sampler of the wrong size, is an error",
          "[resources][animation][pointer][errors]") {
    const std::string dir = freshDir("gltf-pointer-bad");
    const auto fails = [&](const std::string& channels, const std::string& text) {
        auto r = loadGltf(writeText(dir, "bad.gltf", propertyAsset(channels).embedded()));
        REQUIRE_FALSE(r.ok());
        INFO(r.error());
        CHECK(r.error().find("bad.gltf") != std::string::npos);
        CHECK(r.error().find(text) != std::string::npos);
    };
    fails(pointerChannel(1, "/materials/7/pbrMetallicRoughness/metallicFactor"), "names a material that does not exist");
    fails(pointerChannel(2, "/extensions/KHR_lights_punctual/lights/2/intensity"), "names a light that does not exist");
    fails(pointerChannel(3, "/cameras/1/perspective/yfov"), "names a camera that does not exist");
    // Sampler 1 holds one value per key; a colour needs four.
    fails(pointerChannel(1, "/materials/0/pbrMetallicRoughness/baseColorFactor"), "expected 8 values (4 per key)");
}

TEST_CASE("KHR_animation_pointer: an animated texture transform draws the material's maps at their own addresses, posed as a file's values",
          "[resources][animation][pointer]") {
    const std::string dir = freshDir("gltf-pointer-transform");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int uv = a.floats({0, 0, 1, 0, 0, 1}, "VEC2");
    const int input = a.floats({0, 1}, "SCALAR");
    const int offsets = a.floats({0, 0, 1, 0.5f}, "VEC2");
    const int angles = a.floats({0, 1}, "SCALAR");
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
               "},\"material\":0},{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
               "},\"material\":1},{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
               "},\"material\":2}]}]";
    a.nodes = "[{\"mesh\":0}]";
    // Material 0: base colour scaled by 2 (its offset animated), emissive untransformed (its
    // rotation animated); material 1: one map, its rotation animated; material 2: one map, still.
    a.materials = R"([{"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"scale":[2,2]}}}},)"
                  R"("emissiveTexture":{"index":0}},{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}},)"
                  R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}])";
    const std::string ppm = "P6\n1 1\n255\n\x40\x40\x40";
    const std::string base = "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/";
    a.extra = R"(,"textures":[{"source":0}],"images":[{"uri":"data:image/x-portable-pixmap;base64,)" +
              gltftest::base64(std::vector<unsigned char>(ppm.begin(), ppm.end())) + R"("}],)" +
              R"("extensionsUsed":["KHR_animation_pointer","KHR_texture_transform"],"animations":[{"samplers":[{"input":)" +
              std::to_string(input) + R"(,"output":)" + std::to_string(offsets) + R"(},{"input":)" + std::to_string(input) +
              R"(,"output":)" + std::to_string(angles) + R"(}],"channels":[)" + pointerChannel(0, base + "offset") + "," +
              pointerChannel(1, "/materials/0/emissiveTexture/extensions/KHR_texture_transform/rotation") + "," +
              pointerChannel(1, "/materials/1/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/rotation") + "]}]";
    auto r = loadGltf(writeText(dir, "transform.gltf", a.embedded()));
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model m = std::move(r).value();
    CHECK(m.warnings.empty());
    REQUIRE(m.animation);
    CHECK(m.animation->animatesTransforms(0));
    CHECK(m.animation->animatesTransforms(1));
    CHECK_FALSE(m.animation->animatesTransforms(2));
    // Material 1's one map shares its address with itself, but it moves: it has one all the
    // same (the raw sets are kept); material 2's does not.
    CHECK(m.materials[0].addressing.has_value());
    CHECK(m.materials[1].addressing.has_value());
    CHECK_FALSE(m.materials[2].addressing.has_value());
    CHECK(m.mesh.hasUvSets());
    // At 0.5 s: the base colour's offset (0.5, 0.25) over its scale 2, on stored uvs (u, 1 - v):
    // [[2, 0, 0.5], [0, 2, 1 - 2 - 0.25]]; the emissive map turned by 0.5 rad about the origin:
    // [[c, -s, s], [s, c, 1 - c]] with c = cos 0.5, s = sin 0.5.
    const PosedProperties posed = m.animation->poseProperties(0.5, -1);
    REQUIRE(posed.transforms.size() == 2);
    CHECK(posed.transforms[0].material == 0);
    CHECK(posed.transforms[1].material == 1);
    const auto& b = posed.transforms[0].m[0];
    CHECK(b[0][0] == 2.0f);
    CHECK(b[0][1] == Approx(0.0).margin(1e-7));
    CHECK(b[0][2] == Approx(0.5));
    CHECK(b[1][0] == Approx(0.0).margin(1e-7));
    CHECK(b[1][1] == 2.0f);
    CHECK(b[1][2] == Approx(-1.25));
    const auto& e = posed.transforms[0].m[1 + std::size_t(MapSlot::Emissive)];
    const double c = std::cos(0.5), s = std::sin(0.5);
    CHECK(e[0][0] == Approx(c));
    CHECK(e[0][1] == Approx(-s));
    CHECK(e[0][2] == Approx(s));
    CHECK(e[1][0] == Approx(s));
    CHECK(e[1][1] == Approx(c));
    CHECK(e[1][2] == Approx(1.0 - c));
    // At 0 s every transform is the file's: the matrices materialAddressing made at load.
    const PosedProperties rest = m.animation->poseProperties(0.0, -1);
    const MapAddressing& loaded = *m.materials[0].addressing;
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 3; ++col) {
            CHECK(rest.transforms[0].m[0][std::size_t(row)][std::size_t(col)] == loaded.base.m[row][col]);
            CHECK(rest.transforms[0].m[1 + std::size_t(MapSlot::Emissive)][std::size_t(row)][std::size_t(col)] ==
                  loaded[MapSlot::Emissive].m[row][col]);
        }
}

TEST_CASE("lights and cameras on animated nodes move with them; those on still nodes stay as loaded", "[resources][animation][pointer]") {
    const std::string dir = freshDir("gltf-moving-lights");
    Asset a;
    const int pos = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int input = a.floats({0, 1}, "SCALAR");
    const int moves = a.floats({0, 0, 5, 0, 4, 5}, "VEC3");               // (0, 0, 5) -> (0, 4, 5)
    const float h = float(std::sqrt(0.5));
    const int turns = a.floats({0, 0, 0, 1, 0, h, 0, h}, "VEC4");         // 0 -> 90 degrees about +Y
    a.meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}]";
    // Node 1: a camera and its child node 2 a point light, moved; node 3 a directional light,
    // turned; node 4 a spot light, still.
    a.nodes = "[{\"mesh\":0},{\"camera\":0,\"translation\":[0,0,5],\"children\":[2]},"
              "{\"translation\":[1,0,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
              "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
              "{\"translation\":[0,3,0],\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}}]";
    a.scenes = "[{\"nodes\":[0,1,3,4]}]";
    a.extra = ",\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{\"lights\":"
              "[{\"type\":\"point\"},{\"type\":\"directional\"},{\"type\":\"spot\"}]}},"
              "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}}],"
              "\"animations\":[{\"samplers\":[{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(moves) +
              "},{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(turns) +
              "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"translation\"}},"
              "{\"sampler\":1,\"target\":{\"node\":3,\"path\":\"rotation\"}}]}]";
    auto r = loadGltf(writeText(dir, "moving.gltf", a.embedded()));
    INFO((r ? std::string() : r.error()));
    REQUIRE(r.ok());
    const Model m = std::move(r).value();
    REQUIRE(m.animation);
    CHECK(m.animation->animatesProperties());
    REQUIRE(m.lights.size() == 3);
    REQUIRE(m.cameras.size() == 1);
    const PosedProperties posed = m.animation->poseProperties(0.5, -1);
    REQUIRE(posed.lights.size() == 3);
    REQUIRE(posed.cameras.size() == 1);
    // The camera at (0, 2, 5), still looking down -Z; its child light at (1, 2, 5).
    checkVec(posed.cameras[0].eye, 0, 2, 5);
    checkVec(posed.cameras[0].target, 0, 2, 4);
    checkVec(posed.cameras[0].up, 0, 1, 0);
    CHECK(posed.cameras[0].yfovDegrees == Approx(0.8 * 180.0 / kPiD));
    checkVec(posed.lights[0].position, 1, 2, 5);
    // The directional light turned 45 degrees about +Y at 0.5 s: toward (sin 45, 0, cos 45).
    checkVec(posed.lights[1].toLight, std::sqrt(0.5), 0, std::sqrt(0.5), 1e-5);
    // The still spot light: exactly as loaded.
    CHECK(posed.lights[2].position == m.lights[2].position);
    CHECK(posed.lights[2].spotDirection == m.lights[2].spotDirection);
    CHECK(posed.lights[2].coneScale == m.lights[2].coneScale);
    // At 0 s everything is where the loader put it.
    const PosedProperties rest = m.animation->poseProperties(0.0, -1);
    checkVec(rest.cameras[0].eye, m.cameras[0].eye.x, m.cameras[0].eye.y, m.cameras[0].eye.z);
    checkVec(rest.lights[0].position, m.lights[0].position.x, m.lights[0].position.y, m.lights[0].position.z);
    checkVec(rest.lights[1].toLight, m.lights[1].toLight.x, m.lights[1].toLight.y, m.lights[1].toLight.z);
}
