// The scene and quality flags shared by the headless command and SoftRaster.exe. The scene flags
// have the names, meanings and defaults of the llvmpipe reference renderer's
// (shared/tools/llvmpipe-ref); the quality flags (--filter, --wrap, --persp, --ssaa, --quality,
// --isa) are ours.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"
#include "Raster/Fill/Kernels/Isa.hpp"
#include "Raster/Frame/AntiAliasing.hpp"
#include "Raster/Frame/Sky.hpp"
#include "Raster/Geometry/Cull.hpp"
#include "Raster/Setup/PipelineModes.hpp" // PerspectiveMode
#include "Raster/Shade/ColorSpace.hpp"
#include "Raster/Shade/Shading.hpp"
#include "Raster/Shade/Shadow.hpp"
#include "Raster/Texture/Texture.hpp"

namespace sr::app {

// Three points on the speed/accuracy front that `softraster report` measures (docs/reports),
// selected by --quality on the command line and in the demo. Explicit --ssaa, --msaa, --filter,
// --shading and --persp flags override the preset's value, in any order (an explicit --msaa
// replaces the preset's supersampling, an explicit --ssaa its multisampling).
enum class Quality { Fast, Balanced, Accurate };

struct QualitySettings {
    AntiAliasing antiAliasing;
    TextureFilter filter = TextureFilter::Bilinear;
    ShadingMode shading = ShadingMode::Phong;
    PerspectiveMode perspective = PerspectiveMode::Exact;
    int aniso = 1; // anisotropic taps with the trilinear filter
};

// fast: 1 sample, bilinear, Gouraud, exact. balanced: 4 samples (2x2), trilinear, Phong, exact.
// accurate: 16 samples (4x4), trilinear with 16 anisotropic taps, Phong, exact - the report's
// ground truth. In a physical (glTF) scene, whose model is pbr in linear light: fast: 1 sample,
// bilinear, pbr, exact; balanced: MSAA 4, trilinear, pbr, exact; accurate: 16 samples, trilinear
// with 16 anisotropic taps, pbr, exact. Each is on
// or next to the measured Pareto front of docs/reports (docs/PERFORMANCE.md says where and why).
QualitySettings qualitySettings(Quality quality, bool physical = false);
const char* qualityName(Quality quality);
std::optional<Quality> parseQuality(const std::string& text);

// How an OBJ's MTL values are used (the reference renderer's --materials). Mtl: kd = Kd (times
// the texel when textured; a textured material with a black Kd counts as Kd 1), ks = Ks,
// shininess = Ns, no specular term when Ks is black or Ns <= 0, opacity = d (1 - Tr). Fixed:
// every material is kd = --kd or the texel alone, white ks 0.5, shininess 32, opaque. glTF
// materials (GltfLoader.hpp) follow the same two rules.
// Faces without a material use the fixed values under both.
enum class MaterialRule { Mtl, Fixed };
const char* materialRuleName(MaterialRule rule);
std::optional<MaterialRule> parseMaterialRule(const std::string& text);

struct SceneOptions {
    std::string obj;                 // empty: the built-in default scene
    int width = 800, height = 600;
    std::optional<Vec3> eye, target; // unset: auto-fit (see resolveCamera)
    Vec3 up{0.0f, 1.0f, 0.0f};
    double fovDegrees = 60.0;
    std::optional<double> nearZ, farZ;
    Vec3 light{1.0f, 1.0f, 1.0f};    // direction TO the light
    ShadingMode shading = ShadingMode::Phong;
    std::string texture;             // overrides every material's texture
    CullMode cull = CullMode::None;
    int threads = 1;
    // Quality knobs.
    TextureFilter filter = TextureFilter::Bilinear;
    int aniso = 1; // --aniso: trilinear taps along the footprint (RenderSettings::aniso)
    WrapMode wrap = WrapMode::Repeat;
    PerspectiveMode perspective = PerspectiveMode::Exact;
    AntiAliasing antiAliasing; // --ssaa 1|4|16, --msaa 1|2|4|8 or --fxaa (Raster/Frame/AntiAliasing.hpp)
    Isa isa = bestIsa(); // --isa: which span kernels fill (auto = the widest this CPU has)
    Color kd{0.8f, 0.8f, 0.8f, 1.0f};
    MaterialRule materials = MaterialRule::Mtl; // --materials
    std::optional<int> camera;                  // --camera N: the file's camera N (glTF)
    std::string variant;                        // --variant NAME: a KHR_materials_variants variant (glTF)
    // --time T: pose a glTF file's animations at T seconds (unset: the rest pose; the demo plays
    // from 0); --animation N: only clip N (unset, or "all": every clip, as viewers play them).
    std::optional<double> time;
    std::optional<int> animation;
    bool explicitUp = false, explicitFov = false; // --up / --fov given (they override --camera's)
    bool wireframe = false;
    bool outline = false; // --outline: the selection outline of the draw at the image centre
    // --shadows / --no-shadows, --shadow-size N, --shadow-pcf K, --shadow-bias C,S (Raster/Shade/Shadow.hpp)
    ShadowSettings shadows;
    std::optional<Quality> quality; // --quality, if given (its values are already in the fields above)
    // --quality auto (the headless command): a setting chosen by a short probe of the scene, the
    // most accurate within --budget-ms MS, or the cheapest within --max-error E (1 - SSIM against
    // the ground truth); neither given: a budget of 16.7 ms.
    bool autoQuality = false;
    std::optional<double> budgetMs, maxError;
    // Which of the preset-covered knobs a flag set explicitly (they win over --quality).
    bool explicitSsaa = false, explicitMsaa = false, explicitFxaa = false, explicitAniso = false, explicitFilter = false, explicitShading = false, explicitPerspective = false;
    bool explicitWrap = false; // --wrap given (a glTF sampler's wrap applies otherwise)
    bool explicitLight = false; // --light given (ignored, with a warning, by a file with its own lights)
    // The sky behind the scene: --sky none (default: the black clear colour) | gradient (the
    // procedural SkyGradient), or --skybox DIR (six cube-map faces: Resources/Skybox.hpp).
    Sky::Kind sky = Sky::Kind::None;
    std::string skybox;
    // --color linear|gamma (unset: the scene's own convention, applySceneDefaults), --tonemap,
    // --exposure EV (linear only: Raster/Shade/ColorSpace.hpp).
    std::optional<ColorMode> colour;
    // --ibl / --no-ibl: the sky lights pbr surfaces (Raster/Shade/Ibl.hpp), or not; unset: it does
    // when a glTF scene is drawn pbr in front of a sky (as glTF viewers light a model by its
    // environment), and not otherwise (loadScene).
    std::optional<bool> ibl;
    ToneMap toneMap = ToneMap::None;
    float exposure = 0.0f;
};

// Largest accepted --width / --height and --threads.
inline constexpr int kMaxThreads = 64;

// Outcome of offering one argument to the scene-flag parser.
enum class FlagResult { Consumed, NotMine, Error };

// Tries to parse args[i] (and its value args[i + 1]) as a scene or quality flag. On Consumed,
// i is advanced past the value. On Error, `error` holds one line naming the flag and value.
// Both "--flag value" and "--flag=value" are accepted.
FlagResult parseSceneFlag(const std::vector<std::string>& args, std::size_t& i, SceneOptions& options,
                          std::string& error);

// Sets the preset's knobs in `options`, except those a flag set explicitly; records the preset.
// `physical`: the physical scene's preset (applySceneDefaults applies it once the scene is known).
void applyQuality(SceneOptions& options, Quality quality, bool physical = false);

// Checks the combination (e.g. width/height limits); returns an error line or nullopt.
std::optional<std::string> validateSceneOptions(const SceneOptions& options);

// The flags' help text (lines end in '\n'), and their names (parseSceneFlag's, in the help's
// order): one table holds each flag's name, arity, action and help.
std::string sceneFlagsHelp();
std::vector<std::string> sceneFlagNames();

// Parses "x,y,z" (three finite numbers) - the reference renderer's vector syntax.
std::optional<Vec3> parseVec3(const std::string& text);

} // namespace sr::app
