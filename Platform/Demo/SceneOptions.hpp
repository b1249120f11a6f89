// The scene and quality flags shared by the headless command and SoftRaster.exe (same names,
// meanings and defaults as the llvmpipe reference renderer's, shared/tools/llvmpipe-ref).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"
#include "Raster/Kernels/Isa.hpp"
#include "Raster/Cull.hpp"
#include "Raster/Shading.hpp"
#include "Raster/Texture.hpp"
#include "Raster/PipelineModes.hpp" // PerspectiveMode

namespace sr::demo {

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
    WrapMode wrap = WrapMode::Repeat;
    PerspectiveMode perspective = PerspectiveMode::Exact;
    Isa isa = bestIsa(); // --isa: which span kernels fill (auto = the widest this CPU has)
    Color kd{0.8f, 0.8f, 0.8f, 1.0f};
    bool wireframe = false;
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

// Checks the combination (e.g. width/height limits); returns an error line or nullopt.
std::optional<std::string> validateSceneOptions(const SceneOptions& options);

// The flags' help text (lines end in '\n').
std::string sceneFlagsHelp();

// Parses "x,y,z" (three finite numbers) - the reference renderer's vector syntax.
std::optional<Vec3> parseVec3(const std::string& text);

} // namespace sr::demo
