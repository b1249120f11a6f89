// From scene flags to something to draw: load the scene (built-in, OBJ or glTF), resolve the camera
// (the reference renderer's auto-fit rule), and build the frame view and render settings.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "Platform/App/SceneOptions.hpp"
#include "Raster/Frame/RenderScene.hpp"
#include "Raster/Frame/RenderSettings.hpp"
#include "Raster/Shade/Ibl.hpp"
#include "Resources/Animation.hpp"
#include "Resources/Result.hpp"

namespace sr::app {

struct CameraSetup {
    Vec3 eye, target, up;
    double fovDegrees = 60.0;
    double nearZ = 0.1;
    double farZ = 100.0; // +infinity: no far plane
};

struct LoadedScene {
    Scene scene;
    std::optional<Texture> textureOverride; // --texture on the built-in scene
    bool builtIn = false;
    Vec3 centre{0, 0, 0}; // bounding sphere of the model's vertices (auto-fit)
    double radius = 1.0;
    std::vector<CameraSetup> cameras; // the file's cameras (glTF), for --camera N and the demo's V key
    std::vector<Light> lights;        // the scene's own lights (glTF's; the built-in scene's key light from
                                      // --light and its fill light); none: --light's one alone
    std::vector<std::string> warnings;
    std::string description; // one line: what was loaded (triangles, textures, normals)
    // The model file's load (parse, decode, textures): wall time, and the decoded triangles and
    // texels (RGBA texels of every texture); zero for the built-in scene.
    double loadMs = 0.0;
    std::size_t loadedTriangles = 0, loadedTexels = 0;
    std::vector<std::string> variants; // glTF KHR_materials_variants: the file's variant names
    // A glTF scene: its materials are metallic-roughness (pbr), its colours linear and its
    // lights in physical units (Lighting::physical); the default light then has intensity pi.
    bool physical = false;
    // --ibl with a sky: the light it sends (made once, here); null otherwise.
    std::shared_ptr<const ImageLight> ibl;
    // A glTF file's animations, skins and morph targets (Resources/Animation.hpp); null without
    // them, and then nothing below is kept. The meshes hold the rest pose until poseScene.
    std::shared_ptr<const ModelAnimation> animation;
    Mesh posedModel;                                  // the model's vertices, posed (its numbering)
    std::vector<std::vector<std::uint32_t>> meshOrigins; // [mesh][k]: the model vertex of scene vertex k
    // With animated material properties (KHR_animation_pointer): each draw's file material (-1: none).
    std::vector<int> drawMaterials;
};

// Poses an animated scene at time t (seconds): clip `clip` alone, or every clip (clip < 0), as
// ModelAnimation::pose says; the scene's meshes take the posed positions, normals and tangents,
// and where KHR_animation_pointer animates them, the draws their materials' colours and pbr
// input, `lights` and `cameras` their properties (ModelAnimation::poseProperties): a frame view
// made afterwards sees them. Nothing for a scene without animation.
void poseScene(LoadedScene& scene, double t, int clip);

// Loads options.obj (or builds the default scene when empty). Errors name the file.
Result<LoadedScene> loadScene(const SceneOptions& options);

// The scene's own conventions where the flags left them open: a glTF scene is shaded pbr (when
// no --shading was given and no preset asked for less than Phong) in linear light (unless
// --color says otherwise); any other scene keeps gamma. --shading pbr on a scene without glTF
// materials is an error (its line returned).
std::optional<std::string> applySceneDefaults(SceneOptions& options, const LoadedScene& scene);

// Compacting ranges of a model's mesh into meshes of their own. appendRange appends the triangles
// indices[firstIndex .. firstIndex + indexCount) of `src` to `part`, with their vertices (normals
// and uvs too) in order of first use, and returns where they start in part.indices. `remap` maps
// a vertex of src to its index in `part`: it holds src.vertexCount() entries, kNoVertex for the
// range's vertices not yet in `part`; appendRange leaves the range's entries set, so that later
// ranges appended to the same `part` share those vertices, and clearRange resets them to
// kNoVertex. No other entry is read or written: splitting a model costs O(its indices) whatever
// the number of ranges (one remap serves them all).
inline constexpr std::uint32_t kNoVertex = UINT32_MAX;
// `origins`, when not null, gets the src index of each vertex appended to part.
std::uint32_t appendRange(Mesh& part, const Mesh& src, std::uint32_t firstIndex, std::uint32_t indexCount,
                          std::vector<std::uint32_t>& remap, std::vector<std::uint32_t>* origins = nullptr);
void clearRange(const Mesh& src, std::uint32_t firstIndex, std::uint32_t indexCount, std::vector<std::uint32_t>& remap);

// The camera the flags ask for. With --camera N: the file's camera N (loadScene checked that it
// exists), any of --eye, --target, --up, --fov, --near, --far given replacing its value.
// Without --eye: the built-in scene's own view, or for a model
// the reference's auto-fit: target = bounding-box centre (or --target), eye = target +
// (0, 0, r / sin(half)) with half the narrower half field of view, near = max(dist - 1.01 r,
// 0.01 r), far = dist + 1.01 r. With --eye: target defaults to the centre and near/far to
// 0.1 / 100. Explicit --near/--far always win.
CameraSetup resolveCamera(const SceneOptions& options, const LoadedScene& scene);

// "--eye x,y,z --target ... --near N --far F": the camera as flags for another renderer.
std::string cameraFlags(const CameraSetup& camera);

// The white directional light of --light (any non-zero direction, normalised in double).
Light keyLight(Vec3 direction);

// World -> clip for the camera (reversed-Z; MVP computed in double, rounded once to float, as
// the reference renderer does), the eye, and the lights: the scene's own (LoadedScene::lights)
// when it has any, else keyLight(light) alone.
// With `physical` (LoadedScene::physical) the lights are in KHR_lights_punctual's units, the
// default light has intensity pi (a white Lambertian surface facing it shows its albedo) and
// there is no ambient term (glTF has none).
FrameView makeFrameView(const CameraSetup& camera, int width, int height, Vec3 light,
                        const std::vector<Light>& sceneLights, bool physical = false, const ImageLight* ibl = nullptr);

RenderSettings makeRenderSettings(const SceneOptions& options);

// Renders one frame of the scene into ctx's target: clear (black, far depth) then draw,
// anti-aliased as settings.antiAliasing says (renderSceneFrame).
void renderFrame(RenderContext& ctx, const LoadedScene& scene, const FrameView& view, const RenderSettings& settings);

} // namespace sr::app
