// Parsing and validation of the scene and quality flags.
#include "Platform/App/SceneOptions.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Frame/Msaa.hpp"
#include "Raster/Geometry/Camera.hpp"
#include "Raster/Texture/TextureLod.hpp" // kMaxAnisotropy

namespace sr::app {
namespace {

std::optional<double> parseNumber(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::optional<int> parseInt(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || errno == ERANGE || v < -2147483647L || v > 2147483647L)
        return std::nullopt;
    return int(v);
}

} // namespace

QualitySettings qualitySettings(Quality quality, bool physical) {
    if (physical) {
        switch (quality) {
        case Quality::Fast:
            return {AntiAliasing::none(), TextureFilter::Bilinear, ShadingMode::Pbr, PerspectiveMode::Exact};
        case Quality::Balanced:
            return {*AntiAliasing::multisample(4), TextureFilter::Trilinear, ShadingMode::Pbr, PerspectiveMode::Exact};
        case Quality::Accurate:
            return {*AntiAliasing::supersample(16), TextureFilter::Trilinear, ShadingMode::Pbr, PerspectiveMode::Exact, kMaxAnisotropy};
        }
    }
    switch (quality) {
    case Quality::Fast:
        return {AntiAliasing::none(), TextureFilter::Bilinear, ShadingMode::Gouraud, PerspectiveMode::Exact};
    case Quality::Balanced:
        return {*AntiAliasing::supersample(4), TextureFilter::Trilinear, ShadingMode::Phong, PerspectiveMode::Exact};
    case Quality::Accurate:
        return {*AntiAliasing::supersample(16), TextureFilter::Trilinear, ShadingMode::Phong, PerspectiveMode::Exact, kMaxAnisotropy};
    }
    return {};
}

const char* qualityName(Quality quality) {
    switch (quality) {
    case Quality::Fast: return "fast";
    case Quality::Balanced: return "balanced";
    case Quality::Accurate: return "accurate";
    }
    return "?";
}

std::optional<Quality> parseQuality(const std::string& text) {
    for (Quality q : {Quality::Fast, Quality::Balanced, Quality::Accurate})
        if (text == qualityName(q)) return q;
    return std::nullopt;
}

const char* materialRuleName(MaterialRule rule) { return rule == MaterialRule::Mtl ? "mtl" : "fixed"; }

std::optional<MaterialRule> parseMaterialRule(const std::string& text) {
    for (MaterialRule r : {MaterialRule::Mtl, MaterialRule::Fixed})
        if (text == materialRuleName(r)) return r;
    return std::nullopt;
}

std::optional<Vec3> parseVec3(const std::string& text) {
    double v[3];
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t comma = text.find(',', start);
        if ((k < 2) != (comma != std::string::npos)) return std::nullopt;
        const auto n = parseNumber(text.substr(start, k < 2 ? comma - start : std::string::npos));
        if (!n) return std::nullopt;
        v[k] = *n;
        start = comma + 1;
    }
    const Vec3 r{float(v[0]), float(v[1]), float(v[2])};
    if (!isFinite(r)) return std::nullopt; // e.g. 1e39 overflows float
    return r;
}

namespace {

// The error line for a value a flag does not take.
FlagResult bad(std::string& error, const std::string& flag, const std::string& value, const std::string& expected) {
    error = "bad value for " + flag + ": '" + value + "' (expected " + expected + ")";
    return FlagResult::Error;
}

// What a flag does with its value (empty for a flag that takes none): sets `o`, or words the error.
using FlagAction = FlagResult (*)(SceneOptions& o, const std::string& flag, const std::string& value, std::string& error);

// One scene or quality flag: its name, whether it takes a value, its action, and its lines in the
// help (null: the line of a flag before it describes it too); `section`, where not null, the
// heading printed before it.
struct SceneFlag {
    const char* name;
    bool takesValue;
    FlagAction action;
    const char* help;
    const char* section = nullptr;
};

FlagResult onModel(SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
    if (value.empty()) return bad(error, flag, value, "a file path");
    o.obj = value;
    return FlagResult::Consumed;
}

FlagResult onSize(SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
    const auto v = parseInt(value);
    if (!v || *v < 1 || *v > FrameBuffer::kMaxDimension)
        return bad(error, flag, value, "an integer from 1 to " + std::to_string(FrameBuffer::kMaxDimension));
    (flag == "--width" ? o.width : o.height) = *v;
    return FlagResult::Consumed;
}

FlagResult onVector(SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
    const auto v = parseVec3(value);
    if (!v) return bad(error, flag, value, "three finite numbers x,y,z");
    if (flag == "--eye") o.eye = *v;
    else if (flag == "--target") o.target = *v;
    else if (flag == "--up") o.up = *v, o.explicitUp = true;
    else if (flag == "--light") o.light = *v, o.explicitLight = true;
    else o.kd = Color{v->x, v->y, v->z, 1.0f};
    return FlagResult::Consumed;
}

FlagResult onSwitch(SceneOptions& o, const std::string& flag, const std::string&, std::string& error) {
    if (flag == "--fxaa") {
        // One way of anti-aliasing, as --ssaa and --msaa: an explicit other mode is refused.
        if ((o.explicitSsaa && o.antiAliasing.supersampled()) || (o.explicitMsaa && o.antiAliasing.multisampled())) {
            error = "--fxaa and --" + std::string(o.antiAliasing.supersampled() ? "ssaa " : "msaa ") +
                    std::to_string(o.antiAliasing.samples()) + ": choose one way of anti-aliasing";
            return FlagResult::Error;
        }
        o.antiAliasing = AntiAliasing::fxaa();
        o.explicitFxaa = true;
    } else if (flag == "--wireframe") o.wireframe = true;
    else if (flag == "--outline") o.outline = true;
    else if (flag == "--ibl" || flag == "--no-ibl") o.ibl = flag == "--ibl";
    else o.shadows.on = flag == "--shadows";
    return FlagResult::Consumed;
}

FlagResult onAntiAliasing(SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
    // One way of anti-aliasing: a flag replaces a preset's, and its value 1 turns off its own
    // mode only; the two modes explicitly on together are refused.
    const bool super = flag == "--ssaa";
    const auto v = parseInt(value);
    const std::optional<AntiAliasing> aa = !v ? std::nullopt : super ? AntiAliasing::supersample(*v) : AntiAliasing::multisample(*v);
    if (!aa) return bad(error, flag, value, super ? "1, 4 or 16 samples per pixel" : "1, 2, 4 or 8 samples per pixel");
    if (o.explicitFxaa && *aa != AntiAliasing::none()) {
        error = "--fxaa and " + flag + " " + value + ": choose one way of anti-aliasing";
        return FlagResult::Error;
    }
    const bool otherExplicit = super ? o.explicitMsaa : o.explicitSsaa;
    const bool otherOn = super ? o.antiAliasing.multisampled() : o.antiAliasing.supersampled();
    if (otherExplicit && otherOn) {
        if (*aa != AntiAliasing::none()) {
            const AntiAliasing ss = super ? *aa : o.antiAliasing, ms = super ? o.antiAliasing : *aa;
            error = "--ssaa " + std::to_string(ss.samples()) + " and --msaa " + std::to_string(ms.samples()) +
                    ": choose one way of anti-aliasing (the other must be 1)";
            return FlagResult::Error;
        }
    } else if (!o.explicitFxaa) {
        o.antiAliasing = *aa;
    }
    (super ? o.explicitSsaa : o.explicitMsaa) = true;
    return FlagResult::Consumed;
}

// The flags in the order of the help.
const SceneFlag kSceneFlags[] = {
    {"--model", true, onModel,
     "  --model PATH          model to render: Wavefront OBJ (+MTL), glTF 2.0 (.gltf, .glb);\n"
     "                        default: the built-in scene (--obj PATH: the same)\n",
     "scene (same flags and defaults as the llvmpipe reference renderer):\n"},
    {"--obj", true, onModel, nullptr},
    {"--width", true, onSize, "  --width N --height N  image size (default 800 x 600)\n"},
    {"--height", true, onSize, nullptr},
    {"--eye", true, onVector, "  --eye x,y,z           camera position (default: auto-fit the model's bounding sphere)\n"},
    {"--target", true, onVector, "  --target x,y,z        look-at point (default: the bounding box centre)\n"},
    {"--up", true, onVector, "  --up x,y,z            up vector (default 0,1,0)\n"},
    {"--camera", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseInt(value);
         if (!v || *v < 0 || *v > 65535) return bad(error, flag, value, "a camera number from 0 (the file's cameras, in node order)");
         o.camera = *v;
         return FlagResult::Consumed;
     },
     "  --camera N            view through the model's camera N (glTF, numbered from 0 in node\n"
     "                        order); --eye, --target, --up, --fov, --near, --far still override\n"},
    {"--variant", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         if (value.empty()) return bad(error, flag, value, "the name of one of the file's material variants (KHR_materials_variants)");
         o.variant = value;
         return FlagResult::Consumed;
     },
     "  --variant NAME        draw the glTF file's material variant NAME (KHR_materials_variants;\n"
     "                        an unknown name is an error listing the file's variants)\n"},
    {"--fov", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseNumber(value);
         if (!v || !(*v > 0.0 && *v < 180.0)) return bad(error, flag, value, "degrees in (0, 180)");
         o.fovDegrees = *v;
         o.explicitFov = true;
         return FlagResult::Consumed;
     },
     "  --fov DEG             vertical field of view in degrees (default 60)\n"},
    {"--near", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseNumber(value);
         if (!v || !(*v >= double(Camera::kMinNear) && *v <= double(Camera::kMaxCoordinate)))
             return bad(error, flag, value, "a distance from 1e-06 to 1e+15"); // Camera::kMinNear, kMaxCoordinate
         o.nearZ = *v;
         return FlagResult::Consumed;
     },
     "  --near Z --far Z      clip distances, near >= 1e-06 (default: auto-fitted, or 0.1 / 100\n"
     "                        with --eye)\n"},
    {"--far", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseNumber(value);
         if (!v || !(*v > 0.0)) return bad(error, flag, value, "a positive number");
         o.farZ = *v;
         return FlagResult::Consumed;
     },
     nullptr},
    {"--light", true, onVector, "  --light x,y,z         direction to the light (default 1,1,1)\n"},
    {"--shading", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseShadingMode(value);
         if (!m) return bad(error, flag, value, "unlit, flat, gouraud, phong or pbr");
         o.shading = *m;
         o.explicitShading = true;
         return FlagResult::Consumed;
     },
     "  --shading MODE        unlit | flat | gouraud | phong | pbr (default: pbr for glTF, the\n"
     "                        spec's metallic-roughness BRDF; phong otherwise; pbr needs glTF)\n"},
    {"--color", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseColorMode(value);
         if (!m) return bad(error, flag, value, "linear or gamma");
         o.colour = *m;
         return FlagResult::Consumed;
     },
     "  --color C             linear | gamma: colour arithmetic in linear light (sRGB textures\n"
     "                        decoded, the result sRGB-encoded; default for glTF) or on display\n"
     "                        values (default for OBJ and the built-in scene)\n"},
    {"--tonemap", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseToneMap(value);
         if (!m) return bad(error, flag, value, "none, aces or neutral");
         o.toneMap = *m;
         return FlagResult::Consumed;
     },
     "  --tonemap T           none (default: clamp) | aces | neutral (Khronos PBR Neutral); linear only\n"},
    {"--exposure", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseNumber(value);
         if (!v || !(*v >= -32.0 && *v <= 32.0)) return bad(error, flag, value, "a number of stops from -32 to 32");
         o.exposure = float(*v);
         return FlagResult::Consumed;
     },
     "  --exposure EV         scale the linear colour by 2^EV before tone mapping (default 0)\n"},
    {"--ibl", false, onSwitch,
     "  --ibl, --no-ibl       light glTF (pbr) surfaces from the sky too (diffuse irradiance and\n"
     "                        prefiltered specular, made once when the sky loads), or not;\n"
     "                        default: on when a glTF scene is drawn pbr in front of a sky\n"},
    {"--no-ibl", false, onSwitch, nullptr},
    {"--time", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseNumber(value);
         if (!v || !std::isfinite(*v) || *v < 0.0 || *v > 1e9) return bad(error, flag, value, "seconds from 0 (a finite number)");
         o.time = *v;
         return FlagResult::Consumed;
     },
     "  --time T              pose a glTF file's animations (node channels, morph targets, skins,\n"
     "                        KHR_animation_pointer's materials, lights and cameras) at T seconds\n"
     "                        (default: the rest pose; each clip loops)\n"},
    {"--animation", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         if (value == "all") {
             o.animation.reset();
             return FlagResult::Consumed;
         }
         const auto v = parseInt(value);
         if (!v || *v < 0 || *v > 65535) return bad(error, flag, value, "all, or an animation number from 0 (the file's, in order)");
         o.animation = *v;
         return FlagResult::Consumed;
     },
     "  --animation N|all     only animation N (numbered from 0), or all of them (default)\n"},
    {"--texture", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         if (value.empty()) return bad(error, flag, value, "a file path");
         o.texture = value;
         return FlagResult::Consumed;
     },
     "  --texture PATH        texture for every material (overrides map_Kd)\n"},
    {"--sky", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         if (value == "none") o.sky = Sky::Kind::None;
         else if (value == "gradient") o.sky = Sky::Kind::Gradient;
         else return bad(error, flag, value, "none or gradient; --skybox DIR for a cube map");
         o.skybox.clear();
         return FlagResult::Consumed;
     },
     "  --sky S               none (default: black) | gradient: what shows where nothing is drawn\n"},
    {"--skybox", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         if (value.empty()) return bad(error, flag, value, "a folder");
         o.skybox = value;
         o.sky = Sky::Kind::Cube;
         return FlagResult::Consumed;
     },
     "  --skybox DIR          cube-map sky: DIR holds px, nx, py, ny, pz, nz images (OpenGL's\n"
     "                        +X, -X, +Y, -Y, +Z, -Z faces, square, one size)\n"},
    {"--cull", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseCullMode(value);
         if (!m) return bad(error, flag, value, "none, cw or ccw");
         o.cull = *m;
         return FlagResult::Consumed;
     },
     "  --cull MODE           none | cw | ccw (default none; front faces are CCW)\n"},
    {"--threads", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseInt(value);
         if (!v || *v < 0 || *v > kMaxThreads) return bad(error, flag, value, "an integer from 0 to " + std::to_string(kMaxThreads));
         o.threads = *v;
         return FlagResult::Consumed;
     },
     "  --threads N           render threads (default 1)\n"},
    {"--filter", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseFilter(value);
         if (!m) return bad(error, flag, value, "nearest, bilinear or trilinear");
         o.filter = *m;
         o.explicitFilter = true;
         if (*m != TextureFilter::Trilinear && !o.explicitAniso) o.aniso = 1; // a preset's taps go with its filter
         return FlagResult::Consumed;
     },
     "  --filter F            nearest | bilinear | trilinear (default bilinear)\n", "quality:\n"},
    {"--aniso", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseInt(value);
         if (!v || (*v != 1 && *v != 2 && *v != 4 && *v != 8 && *v != 16)) return bad(error, flag, value, "1, 2, 4, 8 or 16 taps");
         o.aniso = *v;
         o.explicitAniso = true;
         // Anisotropic taps are trilinear ones: the flag brings the filter unless one was given.
         if (*v > 1 && !o.explicitFilter) {
             o.filter = TextureFilter::Trilinear;
             o.explicitFilter = true;
         }
         return FlagResult::Consumed;
     },
     "  --aniso N             anisotropic filtering: up to N trilinear taps along each pixel's\n"
     "                        footprint, 1 (off, default), 2, 4, 8 or 16; brings --filter trilinear\n"},
    {"--wrap", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseWrap(value);
         if (!m) return bad(error, flag, value, "repeat, clamp or mirror");
         o.wrap = *m;
         o.explicitWrap = true;
         return FlagResult::Consumed;
     },
     "  --wrap W              repeat | clamp | mirror (default repeat)\n"},
    {"--persp", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parsePerspectiveMode(value);
         if (!m && isRetiredPerspectiveMode(value)) {
             error = "--persp " + value +
                     ": span subdivision was retired (exact perspective now costs what affine costs; "
                     "docs/PERFORMANCE.md); the modes that remain: exact, affine";
             return FlagResult::Error;
         }
         if (!m) return bad(error, flag, value, "exact or affine");
         o.perspective = *m;
         o.explicitPerspective = true;
         return FlagResult::Consumed;
     },
     "  --persp P             exact | affine: perspective correction (default exact)\n"},
    {"--quality", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         if (value == "auto") {
             o.autoQuality = true;
             return FlagResult::Consumed;
         }
         const auto q = parseQuality(value);
         if (!q) return bad(error, flag, value, "fast, balanced, accurate or auto");
         o.autoQuality = false;
         applyQuality(o, *q);
         return FlagResult::Consumed;
     },
     "  --quality Q           fast | balanced | accurate: a preset of --ssaa, --filter, --shading\n"
     "                        and --persp (fast: 1, bilinear, gouraud, exact; balanced: 4,\n"
     "                        trilinear, phong, exact; accurate: 16, trilinear, --aniso 16, phong);\n"
     "                        those flags, given too, win. auto (render, bench): a short probe of\n"
     "                        the scene picks the most accurate setting within --budget-ms MS\n"
     "                        (default 16.7), or the cheapest within --max-error E (1 - SSIM)\n"},
    {"--budget-ms", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseNumber(value);
         if (!v || !(*v > 0.0 && *v <= 1e6)) return bad(error, flag, value, "milliseconds above 0");
         o.budgetMs = *v;
         return FlagResult::Consumed;
     },
     nullptr},
    {"--max-error", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseNumber(value);
         if (!v || !(*v >= 0.0 && *v <= 2.0)) return bad(error, flag, value, "an error from 0 (1 - SSIM against the ground truth)");
         o.maxError = *v;
         return FlagResult::Consumed;
     },
     nullptr},
    {"--ssaa", true, onAntiAliasing,
     "  --ssaa N              supersampling: 1 (off, default), 4 (2x2) or 16 (4x4) samples per pixel,\n"
     "                        each shaded, box-filtered; width and height at most 8192 / sqrt(N)\n"},
    {"--msaa", true, onAntiAliasing,
     "  --msaa N              multisampling: 1 (off, default), 2, 4 or 8 samples per pixel at the\n"
     "                        Direct3D positions, coverage and depth per sample, shaded once per\n"
     "                        pixel (centre, or centroid on edges), box-filtered; not with --ssaa\n"},
    {"--fxaa", false, onSwitch,
     "  --fxaa                one sample, then FXAA 3.11 (quality) over the finished image: edges\n"
     "                        smoothed for a fraction of a sample's cost; not with --ssaa or --msaa\n"},
    {"--isa", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseIsa(value);
         if (!m) return bad(error, flag, value, "auto, scalar, sse2, avx2 or avx512");
         if (!isaAvailable(*m)) {
             std::string have;
             for (Isa isa : kAllIsas)
                 if (isaAvailable(isa)) have += std::string(have.empty() ? "" : ", ") + isaName(isa);
             error = "--isa " + value + ": not available on this CPU or build (available: " + have + ")";
             return FlagResult::Error;
         }
         o.isa = *m;
         return FlagResult::Consumed;
     },
     "  --isa I               auto | scalar | sse2 | avx2 | avx512: span kernels (default auto, the\n"
     "                        widest this CPU has; scalar = the reference loop; same image for all)\n"},
    {"--kd", true, onVector, "  --kd r,g,b            colour of untextured surfaces without a material (default 0.8,0.8,0.8)\n"},
    {"--materials", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto m = parseMaterialRule(value);
         if (!m) return bad(error, flag, value, "mtl or fixed");
         o.materials = *m;
         return FlagResult::Consumed;
     },
     "  --materials M         mtl | fixed: use the MTL's Kd, Ks and Ns (default mtl), or kd = --kd\n"
     "                        or the texel, white ks 0.5 and shininess 32 everywhere (fixed)\n"},
    {"--wireframe", false, onSwitch, "  --wireframe           overlay triangle edges\n"},
    {"--shadows", false, onSwitch, "  --shadows             shadow maps for the directional and spot lights (--no-shadows: none)\n"},
    {"--no-shadows", false, onSwitch, nullptr},
    {"--shadow-size", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseInt(value);
         if (!v || *v < kMinShadowSize || *v > kMaxShadowSize)
             return bad(error, flag, value, "an integer from " + std::to_string(kMinShadowSize) + " to " + std::to_string(kMaxShadowSize));
         o.shadows.size = *v;
         return FlagResult::Consumed;
     },
     "  --shadow-size N       texels per side of each light's map, 16 to 8192 (default 2048),\n"
     "                        rounded up to a multiple of 32 (the map's tiles)\n"},
    {"--shadow-pcf", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const auto v = parseInt(value);
         if (!v || !validShadowPcf(*v)) return bad(error, flag, value, "1, 3 or 5");
         o.shadows.pcf = *v;
         return FlagResult::Consumed;
     },
     "  --shadow-pcf K        percentage-closer filter: K x K texel taps, 1, 3 or 5 (default 3)\n"},
    {"--shadow-bias", true,
     [](SceneOptions& o, const std::string& flag, const std::string& value, std::string& error) {
         const std::size_t comma = value.find(',');
         const auto c = comma == std::string::npos ? std::nullopt : parseNumber(value.substr(0, comma));
         const auto sl = comma == std::string::npos ? std::nullopt : parseNumber(value.substr(comma + 1));
         if (!c || !sl || !(*c >= 0.0 && *c <= 100.0 && *sl >= 0.0 && *sl <= 100.0))
             return bad(error, flag, value, "constant,slope: two numbers from 0 to 100 (texels)");
         o.shadows.constantBias = float(*c);
         o.shadows.slopeBias = float(*sl);
         return FlagResult::Consumed;
     },
     "  --shadow-bias C,S     depth bias in texels: C + S x tan(light angle) (default 1,1)\n"},
    {"--outline", false, onSwitch,
     "  --outline             selection outline (3 pixels, through the stencil buffer) around the\n"
     "                        opaque draw at the image centre; not drawn with --msaa\n"},
};

} // namespace

std::vector<std::string> sceneFlagNames() {
    std::vector<std::string> out;
    for (const SceneFlag& f : kSceneFlags) out.push_back(f.name);
    return out;
}

FlagResult parseSceneFlag(const std::vector<std::string>& args, std::size_t& i, SceneOptions& o, std::string& error) {
    std::string flag = args[i];
    std::optional<std::string> inlineValue;
    if (const auto eq = flag.find('='); flag.rfind("--", 0) == 0 && eq != std::string::npos) {
        inlineValue = flag.substr(eq + 1);
        flag = flag.substr(0, eq);
    }
    const SceneFlag* f = nullptr;
    for (const SceneFlag& candidate : kSceneFlags)
        if (flag == candidate.name) f = &candidate;
    if (!f) return FlagResult::NotMine;
    if (!f->takesValue) {
        if (inlineValue) {
            error = flag + " takes no value";
            return FlagResult::Error;
        }
        return f->action(o, flag, std::string(), error);
    }
    std::string value;
    if (inlineValue) {
        value = *inlineValue;
    } else {
        if (i + 1 >= args.size()) {
            error = "missing value for " + flag;
            return FlagResult::Error;
        }
        value = args[++i];
    }
    return f->action(o, flag, value, error);
}

void applyQuality(SceneOptions& o, Quality quality, bool physical) {
    o.quality = quality;
    const QualitySettings p = qualitySettings(quality, physical);
    if (!o.explicitSsaa && !o.explicitMsaa && !o.explicitFxaa) o.antiAliasing = p.antiAliasing;
    if (!o.explicitFilter) o.filter = p.filter;
    if (!o.explicitAniso && o.filter == TextureFilter::Trilinear) o.aniso = p.aniso;
    if (!o.explicitShading) o.shading = p.shading;
    if (!o.explicitPerspective) o.perspective = p.perspective;
}

std::optional<std::string> validateSceneOptions(const SceneOptions& o) {
    if (o.nearZ && o.farZ && !(*o.farZ > *o.nearZ))
        return "--far (" + std::to_string(*o.farZ) + ") must be greater than --near (" + std::to_string(*o.nearZ) + ")";
    if (o.eye && o.target && *o.eye == *o.target) return "--eye and --target must differ";
    if (length(o.light) == 0.0f) return "--light must not be the zero vector";
    if (o.aniso > 1 && o.filter != TextureFilter::Trilinear)
        return "--aniso " + std::to_string(o.aniso) + " takes trilinear taps: not with --filter " + filterName(o.filter);
    if (o.aniso > 1 && o.perspective == PerspectiveMode::Affine)
        return "--aniso " + std::to_string(o.aniso) + " follows each pixel's footprint: not with --persp affine";
    if (o.ibl.value_or(false) && o.sky == Sky::Kind::None) return "--ibl lights the model from the sky: it needs --sky gradient or --skybox DIR";
    if ((o.budgetMs || o.maxError) && !o.autoQuality) return "--budget-ms and --max-error choose for --quality auto: give it too";
    if (o.budgetMs && o.maxError) return "--budget-ms and --max-error are two ways to choose: give one";
    const AntiAliasing aa = o.antiAliasing;
    if (!msaaFits(o.width, o.height, aa.msaaSamples()))
        return "--msaa " + std::to_string(aa.msaaSamples()) + " at " + std::to_string(o.width) + "x" +
               std::to_string(o.height) +
               " needs more than " + std::to_string(kMaxMsaaSamples) + " samples (the limit): use fewer samples or a "
               "smaller image";
    if (const int f = aa.gridSide(); f > 1 && (o.width > FrameBuffer::kMaxDimension / f ||
                                              o.height > FrameBuffer::kMaxDimension / f))
        return "--ssaa " + std::to_string(aa.samples()) + " renders " + std::to_string(o.width) + "x" +
               std::to_string(o.height) + " at " + std::to_string(f) + "x" + std::to_string(f) +
               " the size, above the " + std::to_string(FrameBuffer::kMaxDimension) +
               "-pixel limit: at most " + std::to_string(FrameBuffer::kMaxDimension / f) + " per side";
    return std::nullopt;
}

std::string sceneFlagsHelp() {
    std::string text;
    for (const SceneFlag& f : kSceneFlags) {
        if (f.section) text += f.section;
        if (f.help) text += f.help;
    }
    return text;
}

} // namespace sr::app
