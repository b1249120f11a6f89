// Builds the default scene's meshes, procedural textures and draws.
#include "Resources/DefaultScene.hpp"

#include "Math/Transform.hpp"
#include "Resources/Primitives.hpp"

namespace sr {
namespace {

Texture textureOf(const Image& img) { return Texture::fromRgba8(img.width, img.height, img.rgba.data()); }

void addObject(Scene& scene, Mesh mesh, const Mat4& transform, int texture, Color kd, float alpha = 1.0f) {
    transformMesh(mesh, transform);
    SceneDraw d;
    d.mesh = int(scene.meshes.size());
    d.indexCount = std::uint32_t(mesh.indices.size());
    d.texture = texture;
    d.kd = kd;
    d.alpha = alpha;
    scene.meshes.push_back(std::move(mesh));
    scene.draws.push_back(d);
}

} // namespace

Light defaultSceneFillLight() { return Light::point({-1.2f, 1.6f, 1.4f}, {2.4f, 1.5f, 0.7f, 1.0f}, 9.0f); }

Scene makeDefaultScene() {
    Scene scene;
    scene.textures.push_back(textureOf(makeCheckerImage(256, 8, {0.92f, 0.92f, 0.9f}, {0.25f, 0.27f, 0.3f})));
    scene.textures.push_back(textureOf(makeBrickImage(256)));
    scene.textures.push_back(textureOf(makeCheckerImage(64, 4, {0.95f, 0.8f, 0.1f}, {0.1f, 0.3f, 0.9f})));
    const int floorTex = 0, brickTex = 1, bannerTex = 2;
    const Color grey{0.8f, 0.8f, 0.8f};

    addObject(scene, makeGroundPlane(60.0f, 60.0f, 8, 30.0f), Mat4::identity(), floorTex, grey);
    addObject(scene, makeCube(), translate({-2.3f, 0.75f, 0.2f}) * rotate(radians(30.0f), {0, 1, 0}) * scale({1.5f, 1.5f, 1.5f}),
              brickTex, grey);
    addObject(scene, makeCube(), translate({2.5f, 0.5f, -1.2f}) * rotate(radians(-20.0f), {0, 1, 0}), brickTex, grey);
    addObject(scene, makeSphere(48, 24), translate({0.0f, 1.0f, -0.8f}), -1, {0.85f, 0.25f, 0.2f});
    addObject(scene, makeTorus(0.7f, 0.25f, 48, 16), translate({-0.3f, 0.25f, 2.0f}), -1, {0.9f, 0.7f, 0.2f});
    // The single-sided banner faces -Z (away from the default camera): its back face is visible.
    addObject(scene, makeQuad(),
              translate({3.0f, 1.6f, 1.2f}) * rotate(radians(180.0f + 20.0f), {0, 1, 0}) * scale({2.2f, 1.6f, 1.0f}),
              bannerTex, grey);
    // A block of tinted glass between the torus and the right cube: drawn after the opaque
    // draws, its back faces first (no culling), blended over what is behind it.
    addObject(scene, makeCube(), translate({1.25f, 0.45f, 1.7f}) * rotate(radians(25.0f), {0, 1, 0}) * scale({0.9f, 0.9f, 0.9f}),
              -1, {0.55f, 0.85f, 0.95f}, 0.45f);

    scene.boundsMin = {-60.0f, 0.0f, -60.0f};
    scene.boundsMax = {60.0f, 2.5f, 60.0f};
    return scene;
}

} // namespace sr
