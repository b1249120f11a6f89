// Scene loading (built-in, OBJ or glTF), the auto-fit camera and the per-frame view.
#include "Platform/App/SceneSetup.hpp"

#include <algorithm>
#include <chrono>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "Math/Conventions.hpp"
#include "Math/DoubleMath.hpp"
#include "Math/Transform.hpp"
#include "Raster/Frame/Msaa.hpp" // msaaFits
#include "Raster/Geometry/Camera.hpp"
#include "Resources/DefaultScene.hpp"
#include "Resources/Gltf/GltfLoader.hpp"
#include "Resources/Image.hpp"
#include "Resources/Skybox.hpp"

namespace sr::app {
namespace {

// A draw's colours, opacity and pbr input from its file material (under MaterialRule::Mtl).
void setDrawColours(SceneDraw& d, const Material& m) {
    // The reference's rule: a material with a map_Kd and a black Kd is "the texture alone".
    const bool black = m.kd.r == 0.0f && m.kd.g == 0.0f && m.kd.b == 0.0f;
    d.kd = m.hasMap && black ? Color{1.0f, 1.0f, 1.0f, 1.0f} : m.kd;
    d.tint = d.kd;
    d.specular = Specular{m.ks, m.shininess};
    d.alpha = m.alpha;
    d.texelAlpha = m.texelAlpha;
    d.pbr = m.pbr;
}

// Splits a model into at most two compact meshes: the vertices of its textured ranges and those
// of its untextured ones. Every draw of one mesh runs the same vertex program, so renderScene
// transforms each mesh once per frame whatever the number of materials (its draws share the
// vertex stage), and a vertex that two materials share (the corners of a checkerboard of
// materials) is stored and transformed once. Each mesh holds only the vertices its ranges use.
// One remap array serves both meshes (cleared after each).
// Each range is one draw with its material's values under `rule` (SceneOptions.hpp, MaterialRule),
// its opacity included (a range of opacity 0 is not drawn); a range without a material from the
// file (or under Fixed) gets kd = `kd`, the texel alone, ks 0.5, 32, opaque.
// `origins`, when not null, gets for each scene mesh the model vertex of each of its vertices;
// `drawMaterials`, when not null, each draw's file material (-1: none, or not the file's rule).
Scene sceneFromModel(Model&& model, Color kd, MaterialRule rule, std::vector<std::vector<std::uint32_t>>* origins = nullptr,
                     std::vector<int>* drawMaterials = nullptr) {
    Scene scene;
    for (const Image& img : model.textures)
        scene.textures.push_back(Texture::fromRgba8(img.width, img.height, img.rgba.data()));
    // A map read by its alpha (readsAlpha: a glTF specularTexture, a glossiness): a copy with the
    // alpha in RGB, once per image.
    std::vector<int> alphaCopy(model.textures.size(), -1);
    const auto alphaTexture = [&](int slot) {
        if (slot < 0 || std::size_t(slot) >= model.textures.size()) return -1;
        if (alphaCopy[std::size_t(slot)] < 0) {
            Image img = model.textures[std::size_t(slot)];
            for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) img.rgba[i] = img.rgba[i + 1] = img.rgba[i + 2] = img.rgba[i + 3];
            alphaCopy[std::size_t(slot)] = int(scene.textures.size());
            scene.textures.push_back(Texture::fromRgba8(img.width, img.height, img.rgba.data()));
        }
        return alphaCopy[std::size_t(slot)];
    };
    const Mesh& src = model.mesh;
    // A range reads uvs when it has a base colour texture or any other map of a glTF material.
    const auto usesUvs = [&](const DrawRange& range) {
        if (range.texture >= 0) return true;
        if (range.material < 0 || !model.hasUvs) return false;
        return model.materials[std::size_t(range.material)].maps.any();
    };
    std::vector<std::uint32_t> remap(src.vertexCount(), kNoVertex);
    std::vector<std::uint32_t> firstIndex(model.ranges.size(), 0);
    std::vector<int> meshOf(model.ranges.size(), -1);
    // The ranges from..to (exclusive) that `take` accepts, appended to one new mesh.
    const auto makeMesh = [&](std::size_t from, std::size_t to, const auto& take) {
        Mesh part;
        std::vector<std::uint32_t> partOrigins;
        for (std::size_t r = from; r < to; ++r) {
            const DrawRange& range = model.ranges[r];
            if (!take(range)) continue;
            firstIndex[r] = appendRange(part, src, range.firstIndex, range.indexCount, remap, origins ? &partOrigins : nullptr);
            meshOf[r] = int(scene.meshes.size());
        }
        for (std::size_t r = from; r < to; ++r)
            if (take(model.ranges[r])) clearRange(src, model.ranges[r].firstIndex, model.ranges[r].indexCount, remap);
        // Vertex colours that are all white change no base colour: the mesh drops them (its
        // draws then interpolate none).
        const auto white = [](const Color& c) { return c.r == 1.0f && c.g == 1.0f && c.b == 1.0f && c.a == 1.0f; };
        if (std::all_of(part.colours.begin(), part.colours.end(), white)) part.colours.clear();
        if (!part.indices.empty()) {
            scene.meshes.push_back(std::move(part));
            if (origins) origins->push_back(std::move(partOrigins));
        }
    };
    for (const bool textured : {true, false})
        makeMesh(0, model.ranges.size(), [&](const DrawRange& range) { return range.instances.empty() && usesUvs(range) == textured; });
    // An instanced mesh: a mesh of its own (its vertices are in its own space), shared by the
    // ranges of its vertex block (the faces kept and the faces reversed).
    for (std::size_t r = 0; r < model.ranges.size();) {
        std::size_t end = r + 1;
        if (!model.ranges[r].instances.empty()) {
            while (end < model.ranges.size() && !model.ranges[end].instances.empty() &&
                   model.ranges[end].firstVertex == model.ranges[r].firstVertex)
                ++end;
            makeMesh(r, end, [](const DrawRange&) { return true; });
        }
        r = end;
    }
    for (std::size_t r = 0; r < model.ranges.size(); ++r) {
        const DrawRange& range = model.ranges[r];
        if (range.indexCount == 0) continue;
        SceneDraw d;
        d.mesh = meshOf[r];
        d.firstIndex = firstIndex[r];
        d.indexCount = range.indexCount;
        d.texture = range.texture;
        d.kd = kd;
        const Material* m = range.material >= 0 ? &model.materials[std::size_t(range.material)] : nullptr;
        if (m) { // geometry and sampling, not colour: under either material rule
            d.doubleSided = m->doubleSided;
            d.wrap = m->wrap;
            d.filter = m->filter;
        }
        const bool fromFile = rule == MaterialRule::Mtl && m && m->fromFile;
        if (fromFile) {
            setDrawColours(d, *m);
            d.addressing = m->addressing;
            if (model.hasUvs) {
                for (const MapSlot s : kAllMapSlots) d.maps[s] = readsAlpha(s) ? alphaTexture(m->maps[s]) : m->maps[s];
            }
            // Fully transparent (glTF MASK below its cutoff): nothing to draw, unless an animation
            // may make it visible (renderScene skips it while it is not).
            if (!(d.alpha > 0.0f) && !(model.animation && model.animation->animatesMaterial(range.material))) continue;
        }
        // One draw per place of an instanced range.
        for (std::size_t k = 0; k < std::max<std::size_t>(range.instances.size(), 1); ++k) {
            if (!range.instances.empty()) d.placement = Placement::of(range.instances[k]);
            scene.draws.push_back(d);
            if (drawMaterials) drawMaterials->push_back(fromFile ? range.material : -1);
        }
    }
    // Lines and points: the flat colour of their material (kd; lines carry no normal), else kd.
    for (LineSet& l : model.lineSets) {
        SceneLines lines;
        lines.points = l.points;
        lines.colour = kd;
        const Material* m = l.material >= 0 ? &model.materials[std::size_t(l.material)] : nullptr;
        if (rule == MaterialRule::Mtl && m && m->fromFile) lines.colour = m->kd;
        lines.positions = std::move(l.positions);
        lines.indices = std::move(l.indices);
        scene.lines.push_back(std::move(lines));
    }
    scene.boundsMin = model.boundsMin;
    scene.boundsMax = model.boundsMax;
    return scene;
}

std::string formatVec(Vec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g", double(v.x), double(v.y), double(v.z));
    return buf;
}

// Camera's near-plane rule (Camera::kMinNear): the command line refuses a --near outside it; an
// auto-fitted or programmatic near (a tiny model, the flight's extreme poses) is clamped into it.
double usableNear(double nearZ) {
    return std::clamp(nearZ, double(Camera::kMinNear), double(Camera::kMaxCoordinate));
}

} // namespace

std::uint32_t appendRange(Mesh& part, const Mesh& src, std::uint32_t firstIndex, std::uint32_t indexCount,
                          std::vector<std::uint32_t>& remap, std::vector<std::uint32_t>* origins) {
    assert(remap.size() == src.vertexCount());
    assert(std::size_t(firstIndex) + indexCount <= src.indices.size());
    const auto first = std::uint32_t(part.indices.size());
    const std::uint32_t* indices = src.indices.data() + firstIndex;
    part.indices.reserve(part.indices.size() + indexCount);
    for (std::uint32_t k = 0; k < indexCount; ++k) {
        const std::uint32_t v = indices[k];
        assert(v < remap.size());
        if (remap[v] == kNoVertex) {
            remap[v] = std::uint32_t(part.positions.size());
            part.positions.push_back(src.positions[v]);
            if (src.hasNormals()) part.normals.push_back(src.normals[v]);
            if (src.hasUvs()) part.uvs.push_back(src.uvs[v]);
            if (src.hasTangents()) part.tangents.push_back(src.tangents[v]);
            if (src.hasColours()) part.colours.push_back(src.colours[v]);
            if (src.hasUvSets())
                for (int s = 0; s < 2; ++s) part.uvSets[s].push_back(src.uvSets[s][v]);
            if (origins) origins->push_back(v);
        }
        part.indices.push_back(remap[v]);
    }
    return first;
}

void clearRange(const Mesh& src, std::uint32_t firstIndex, std::uint32_t indexCount, std::vector<std::uint32_t>& remap) {
    // Only the entries this range set: the work is O(indexCount), not O(model) (a full reset per
    // range made a model of R ranges cost R x its vertex count).
    const std::uint32_t* indices = src.indices.data() + firstIndex;
    for (std::uint32_t k = 0; k < indexCount; ++k) remap[indices[k]] = kNoVertex;
}

Result<LoadedScene> loadScene(const SceneOptions& options) {
    LoadedScene out;
    if (options.obj.empty()) {
        out.scene = makeDefaultScene();
        out.builtIn = true;
        if (!options.texture.empty()) {
            auto img = loadImage(options.texture);
            if (!img) return Result<LoadedScene>::failure(img.error());
            out.textureOverride = Texture::fromRgba8(img.value().width, img.value().height, img.value().rgba.data());
        }
        out.description = "built-in scene: " + std::to_string(out.scene.triangleCount()) + " triangles";
        out.lights = {keyLight(options.light), defaultSceneFillLight()};
    } else {
        LoadOptions loadOptions;
        loadOptions.textureOverride = options.texture;
        loadOptions.variant = options.variant;
        if (!options.variant.empty() && !isGltfPath(options.obj))
            return Result<LoadedScene>::failure(options.obj + ": --variant: only glTF files have material variants");
        const auto loadStart = std::chrono::steady_clock::now();
        auto model = loadModel(options.obj, loadOptions); // .gltf / .glb or OBJ
        if (!model) return Result<LoadedScene>::failure(model.error());
        out.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loadStart).count();
        Model& m = model.value();
        out.loadedTriangles = m.mesh.triangleCount();
        for (const Image& image : m.textures) out.loadedTexels += std::size_t(image.width) * std::size_t(image.height);
        out.warnings = m.warnings;
        out.physical = isGltfPath(options.obj);
        // Bounding sphere: centre of the AABB of every 'v', radius = farthest vertex from it.
        out.centre = (m.boundsMin + m.boundsMax) * 0.5f;
        double r = 0.0;
        const auto reach = [&](Vec3 p) {
            const double dx = double(p.x) - out.centre.x, dy = double(p.y) - out.centre.y, dz = double(p.z) - out.centre.z;
            r = std::max(r, std::sqrt(dx * dx + dy * dy + dz * dz));
        };
        forEachWorldPosition(m, reach);
        for (const LineSet& l : m.lineSets) // glTF lines and points
            for (const Vec3& p : l.positions) reach(p);
        out.radius = r > 0.0 ? r : 1.0;
        // Instanced meshes are stored once and drawn at each place: the triangles drawn, and the
        // stored ones where they differ.
        std::size_t drawn = 0;
        for (const DrawRange& range : m.ranges) drawn += std::size_t(range.indexCount / 3) * std::max<std::size_t>(range.instances.size(), 1);
        const std::string instanced = drawn != m.mesh.triangleCount() && !m.animation
                                          ? " (" + std::to_string(m.mesh.triangleCount()) + " stored: instanced)"
                                          : std::string();
        out.description = options.obj + ": " + std::to_string(m.animation ? m.mesh.triangleCount() : drawn) + " triangles" + instanced + ", " +
                          std::to_string(m.textures.size()) + " textures, normals " +
                          (m.normalsFromFile ? "from the file" : out.physical ? "flat where the file has none" : "computed (area-weighted)");
        if (m.variant >= 0) out.description += ", material variant '" + m.variants[std::size_t(m.variant)] + "'";
        out.variants = m.variants;
        if (!m.lineSets.empty()) {
            std::size_t segments = 0, points = 0;
            for (const LineSet& l : m.lineSets) (l.points ? points : segments) += l.points ? l.indices.size() : l.indices.size() / 2;
            out.description += ", " + std::to_string(segments) + " line segments, " + std::to_string(points) + " points";
        }
        out.lights = m.lights;
        if (options.explicitLight && !out.lights.empty())
            out.warnings.push_back(options.obj + ": --light is ignored: the file has its own lights (" +
                                   std::to_string(out.lights.size()) + ")");
        for (const ModelCamera& mc : m.cameras) {
            CameraSetup c;
            c.eye = mc.eye;
            c.target = mc.target;
            c.up = mc.up;
            c.fovDegrees = mc.yfovDegrees;
            c.nearZ = mc.znear;
            c.farZ = mc.zfar > 0.0 ? mc.zfar : std::numeric_limits<double>::infinity();
            out.cameras.push_back(c);
        }
        if (m.animation) {
            out.animation = m.animation;
            out.posedModel.positions = m.mesh.positions;
            out.posedModel.normals = m.mesh.normals;
            out.posedModel.tangents = m.mesh.tangents;
        }
        const int clips = m.animation ? int(m.animation->clips.size()) : 0;
        const bool properties = m.animation && m.animation->animatesProperties();
        out.scene = sceneFromModel(std::move(m), options.kd, options.materials, out.animation ? &out.meshOrigins : nullptr,
                                   properties ? &out.drawMaterials : nullptr);
        if (options.animation && *options.animation >= clips)
            return Result<LoadedScene>::failure(options.obj + ": --animation " + std::to_string(*options.animation) + ": it has " +
                                                std::to_string(clips) + " animation(s)" + (clips == 0 ? "" : " (numbered from 0)"));
    }
    out.scene.sky.kind = options.sky;
    if (options.sky == Sky::Kind::Cube) {
        auto cube = loadSkybox(options.skybox);
        if (!cube) return Result<LoadedScene>::failure(cube.error());
        out.scene.sky.cube = std::make_shared<const CubeMap>(std::move(cube.value()));
    }
    // The sky's light: asked for, or by default wherever a glTF scene is drawn pbr in front of a sky
    // (what a glTF viewer shows); nothing is made for a scene that would not read it.
    const bool pbrDrawn = out.physical && (!options.explicitShading || options.shading == ShadingMode::Pbr);
    if (options.ibl.value_or(pbrDrawn) && out.scene.sky.on()) out.ibl = std::make_shared<const ImageLight>(out.scene.sky);
    if (options.camera && std::size_t(*options.camera) >= out.cameras.size())
        return Result<LoadedScene>::failure((options.obj.empty() ? std::string("the built-in scene") : options.obj) +
                                            ": --camera " + std::to_string(*options.camera) + ": it has " +
                                            std::to_string(out.cameras.size()) + " camera(s)" +
                                            (out.cameras.empty() ? "" : " (numbered from 0)"));
    return Result<LoadedScene>(std::move(out));
}

std::optional<std::string> applySceneDefaults(SceneOptions& o, const LoadedScene& s) {
    if (!s.physical) {
        if (o.shading == ShadingMode::Pbr)
            return (s.builtIn ? std::string("the built-in scene") : o.obj) +
                   ": --shading pbr needs glTF metallic-roughness materials; OBJ/MTL and the built-in scene are "
                   "shaded phong at best";
        return std::nullopt;
    }
    if (!o.colour) o.colour = ColorMode::Linear;
    if (o.quality) {
        applyQuality(o, *o.quality, true); // the physical scene's preset
        if (!msaaFits(o.width, o.height, o.antiAliasing.msaaSamples()))
            return "--quality " + std::string(qualityName(*o.quality)) + " (MSAA " +
                   std::to_string(o.antiAliasing.msaaSamples()) + " in a glTF scene) at " +
                   std::to_string(o.width) + "x" + std::to_string(o.height) +
                   " needs more samples than the limit: use a smaller size or --ssaa";
    }
    if (!o.explicitShading && o.shading == ShadingMode::Phong) o.shading = ShadingMode::Pbr;
    return std::nullopt;
}

CameraSetup resolveCamera(const SceneOptions& o, const LoadedScene& s) {
    if (o.camera && std::size_t(*o.camera) < s.cameras.size()) {
        CameraSetup c = s.cameras[std::size_t(*o.camera)];
        if (o.eye) c.eye = *o.eye;
        if (o.target) c.target = *o.target;
        if (o.explicitUp) c.up = o.up;
        if (o.explicitFov) c.fovDegrees = o.fovDegrees;
        if (o.nearZ) c.nearZ = *o.nearZ;
        if (o.farZ) c.farZ = *o.farZ;
        return c;
    }
    CameraSetup c;
    c.up = o.up;
    c.fovDegrees = o.fovDegrees;
    if (s.builtIn && !o.eye) {
        const DefaultView v;
        c.eye = v.eye;
        c.target = o.target.value_or(v.target);
        c.fovDegrees = o.fovDegrees;
        c.nearZ = o.nearZ.value_or(v.nearZ);
        c.farZ = o.farZ.value_or(std::numeric_limits<double>::infinity());
        return c;
    }
    c.target = o.target.value_or(s.centre);
    if (o.eye) {
        c.eye = *o.eye;
        c.nearZ = o.nearZ.value_or(0.1);
        c.farZ = o.farZ.value_or(100.0);
        return c;
    }
    const double aspect = double(o.width) / double(o.height);
    const double halfV = o.fovDegrees * kPiD / 360.0;
    const double half = std::min(halfV, std::atan(std::tan(halfV) * aspect));
    const double dist = s.radius / std::sin(half);
    c.eye = c.target + Vec3(0.0f, 0.0f, float(dist));
    c.nearZ = o.nearZ.value_or(usableNear(std::max(dist - 1.01 * s.radius, 0.01 * s.radius)));
    c.farZ = o.farZ.value_or(dist + 1.01 * s.radius);
    return c;
}

std::string cameraFlags(const CameraSetup& c) {
    char buf[128];
    std::snprintf(buf, sizeof buf, " --fov %.9g --near %.9g --far %.9g", c.fovDegrees, c.nearZ, c.farZ);
    return "--eye " + formatVec(c.eye) + " --target " + formatVec(c.target) + " --up " + formatVec(c.up) + buf;
}

Light keyLight(Vec3 light) {
    // The direction is normalised in double, as the reference does.
    const double lx = light.x, ly = light.y, lz = light.z, l = std::sqrt(lx * lx + ly * ly + lz * lz);
    return Light::directional(l > 0 ? Vec3(float(lx / l), float(ly / l), float(lz / l)) : Vec3(0, 0, 1));
}

FrameView makeFrameView(const CameraSetup& c, int width, int height, Vec3 light, const std::vector<Light>& sceneLights,
                        bool physical, const ImageLight* ibl) {
    const double aspect = (width > 0 && height > 0) ? double(width) / double(height) : 1.0;
    // As Camera::setNearFar: near clamped into Camera's range, a far not beyond it is infinite.
    const double nearZ = usableNear(c.nearZ);
    const double farZ = c.farZ > nearZ ? c.farZ : std::numeric_limits<double>::infinity();
    const Mat4d view = lookAtD(c.eye, c.target, c.up);
    const Mat4d mvp = perspectiveD(c.fovDegrees * kPiD / 180.0, aspect, nearZ, farZ) * view;
    FrameView v;
    for (int r = 0; r < 4; ++r)
        for (int col = 0; col < 4; ++col) v.viewProj(r, col) = float(mvp.m[r][col]);
    v.eye = c.eye;
    v.finiteFar = !std::isinf(farZ);
    // The eye rays for the sky: the view's basis (its rows are side, up and -forward), scaled to
    // the frustum's half extents (vertical fov, the image's aspect).
    {
        const double ty = std::tan(c.fovDegrees * kPiD / 360.0), tx = ty * aspect;
        const double(&m)[4][4] = view.m;
        v.rays.forward = Vec3(float(-m[2][0]), float(-m[2][1]), float(-m[2][2]));
        v.rays.right = Vec3(float(m[0][0] * tx), float(m[0][1] * tx), float(m[0][2] * tx));
        v.rays.up = Vec3(float(m[1][0] * ty), float(m[1][1] * ty), float(m[1][2] * ty));
    }
    v.lighting.physical = physical;
    v.ibl = ibl;
    if (physical) v.lighting.ambient = 0.0f;
    if (!sceneLights.empty()) {
        v.lighting.lights = sceneLights; // the scene's own lights; --light is for scenes without
        return v;
    }
    v.lighting.lights = {keyLight(light)};
    if (physical) v.lighting.lights[0].colour = {kPiF, kPiF, kPiF, 1.0f};
    return v;
}

RenderSettings makeRenderSettings(const SceneOptions& o) {
    RenderSettings s;
    s.shading = o.shading;
    s.cull = o.cull;
    s.filter = o.filter;
    s.aniso = o.aniso;
    s.wrap = o.wrap;
    s.filterFromFile = !o.explicitFilter; // a --quality preset's filter yields to the file's sampler
    s.wrapFromFile = !o.explicitWrap;
    s.perspective = o.perspective;
    s.isa = o.isa;
    s.wireframe = o.wireframe;
    s.outline.pickCentre = o.outline;
    s.shadows = o.shadows;
    s.antiAliasing = o.antiAliasing;
    s.colour = o.colour.value_or(ColorMode::Gamma);
    s.toneMap = o.toneMap;
    s.exposure = o.exposure;
    return s;
}

namespace {

// A draw whose material's texture transforms move: each map's address takes its transform at
// this time, and the uvs the draw reads where its maps share one address (and the shading
// models that read the base colour texture alone) are its first map's set through it again.
void moveTransforms(Scene& scene, SceneDraw& d, const PosedProperties::Transforms& moved) {
    if (!d.addressing) return;
    MapAddressing& a = *d.addressing;
    const auto set = [&](MapAddress& address, std::size_t k) {
        for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 3; ++c) address.m[r][c] = moved.m[k][std::size_t(r)][std::size_t(c)];
    };
    set(a.base, 0);
    for (const MapSlot s : kAllMapSlots) set(a[s], 1 + std::size_t(s));
    const MapAddress* first = d.texture >= 0 ? &a.base : nullptr;
    for (const MapSlot s : kAllMapSlots)
        if (!first && d.maps.has(s)) first = &a[s];
    Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
    if (!first || !mesh.hasUvs() || !mesh.hasUvSets()) return;
    const std::vector<Vec2>& raw = mesh.uvSets[std::size_t(first->uvSet)];
    for (std::uint32_t i = d.firstIndex; i < d.firstIndex + d.indexCount; ++i) {
        const std::uint32_t v = mesh.indices[i];
        mesh.uvs[v] = first->apply(raw[v]);
    }
}

} // namespace

void poseScene(LoadedScene& scene, double t, int clip) {
    if (!scene.animation) return;
    if (scene.animation->animatesProperties()) {
        const PosedProperties posed = scene.animation->poseProperties(t, clip);
        for (std::size_t k = 0; k < posed.materials.size(); ++k)
            for (std::size_t d = 0; d < scene.drawMaterials.size() && d < scene.scene.draws.size(); ++d)
                if (scene.drawMaterials[d] == posed.materials[k]) setDrawColours(scene.scene.draws[d], posed.values[k]);
        for (const PosedProperties::Transforms& moved : posed.transforms)
            for (std::size_t d = 0; d < scene.drawMaterials.size() && d < scene.scene.draws.size(); ++d)
                if (scene.drawMaterials[d] == moved.material) moveTransforms(scene.scene, scene.scene.draws[d], moved);
        if (posed.lights.size() == scene.lights.size()) scene.lights = posed.lights;
        for (std::size_t k = 0; k < posed.cameras.size() && k < scene.cameras.size(); ++k) {
            CameraSetup& c = scene.cameras[k];
            c.eye = posed.cameras[k].eye;
            c.target = posed.cameras[k].target;
            c.up = posed.cameras[k].up;
            c.fovDegrees = posed.cameras[k].yfovDegrees;
            c.nearZ = posed.cameras[k].znear;
            c.farZ = posed.cameras[k].zfar > 0.0 ? posed.cameras[k].zfar : std::numeric_limits<double>::infinity();
        }
    }
    Mesh& model = scene.posedModel;
    scene.animation->pose(t, clip, model);
    for (std::size_t m = 0; m < scene.scene.meshes.size() && m < scene.meshOrigins.size(); ++m) {
        Mesh& mesh = scene.scene.meshes[m];
        const std::vector<std::uint32_t>& origin = scene.meshOrigins[m];
        const bool normals = mesh.hasNormals() && model.hasNormals(), tangents = mesh.hasTangents() && model.hasTangents();
        for (std::size_t k = 0; k < origin.size(); ++k) {
            const std::uint32_t v = origin[k];
            mesh.positions[k] = model.positions[v];
            if (normals) mesh.normals[k] = model.normals[v];
            if (tangents) mesh.tangents[k] = model.tangents[v];
        }
    }
}

void renderFrame(RenderContext& ctx, const LoadedScene& scene, const FrameView& view, const RenderSettings& settings) {
    const Texture* texture = scene.textureOverride ? &*scene.textureOverride : nullptr;
    if (settings.outline.pickCentre) { // the draw at the image centre, this frame
        RenderSettings picked = settings;
        picked.outline.draw = pickDraw(scene.scene, view.eye, view.rays.forward);
        renderSceneFrame(ctx, scene.scene, view, picked, texture);
        return;
    }
    renderSceneFrame(ctx, scene.scene, view, settings, texture);
}

} // namespace sr::app
