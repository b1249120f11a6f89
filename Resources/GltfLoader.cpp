// GltfLoader: tinygltf parses (JSON, GLB chunks, buffers, data URIs) through our file callbacks; everything it hands over is validated here before use.
#include "Resources/GltfLoader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <system_error>

#include "Math/Conventions.hpp"
#include "Math/DoubleMath.hpp"
#include "Resources/Animation.hpp"
#include "Resources/FileIO.hpp"
#include "Resources/ObjLoader.hpp"
#include "Resources/TinyGltf.hpp"

#include <nlohmann/json.hpp>

namespace sr {

namespace {

using R = Result<Model>;

// glTF constants (the glTF 2.0 specification, "Accessor", "Mesh").
constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
constexpr int kModePoints = 0, kModeTriangles = 4, kModeStrip = 5, kModeFan = 6;

int componentSize(int componentType) {
    switch (componentType) {
    case kByte:
    case kUnsignedByte: return 1;
    case kShort:
    case kUnsignedShort: return 2;
    case kUnsignedInt:
    case kFloat: return 4;
    default: return 0;
    }
}

int componentCount(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16; // skins' inverse bind matrices (float only: no column padding)
    default: return 0;
    }
}

// What the file callbacks and the image loader share: the limits and the bytes read so far.
struct LoadState {
    const LoadLimits* limits = nullptr;
    std::size_t bufferBytes = 0;  // external buffers read
    std::size_t textureBytes = 0; // decoded RGBA of embedded images
    std::string problem;          // the first problem a callback met (reported as the error)
};

bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(std::filesystem::u8path(path), ec);
}
std::string expandFilePath(const std::string& path, void*) { return path; } // no shell expansion (wordexp)
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* state = static_cast<LoadState*>(user);
    auto bytes = readFileBytes(path, state->limits->maxFileBytes);
    if (!bytes) {
        if (err) *err += bytes.error() + "\n";
        if (state->problem.empty()) state->problem = bytes.error();
        return false;
    }
    state->bufferBytes += bytes.value().size();
    if (state->bufferBytes > state->limits->maxMemoryBytes) {
        state->problem = path + ": the model's buffers would take more than " +
                         std::to_string(state->limits->maxMemoryBytes >> 20) + " MiB";
        if (err) *err += state->problem + "\n";
        return false;
    }
    *out = std::move(bytes).value();
    return true;
}
bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "writing is not supported";
    return false;
}

// Embedded images (data URIs, GLB buffer views) decoded by our decoder (limits, hardened JPEG
// tables), as RGBA8. External images are loaded by loadGltf itself (TINYGLTF_NO_EXTERNAL_IMAGE).
bool loadImageData(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                   const unsigned char* bytes, int size, void* user) {
    auto* state = static_cast<LoadState*>(user);
    auto decoded = decodeImage(bytes, std::size_t(std::max(size, 0)), "image " + std::to_string(index));
    if (!decoded) {
        // Not fatal: the material gets the checkerboard (a warning, as for OBJ).
        image->width = image->height = 0;
        image->image.clear();
        if (err) err->clear();
        image->name = decoded.error(); // the reason, read back as the warning (loadGltfFromMemory)
        return true;
    }
    state->textureBytes += decoded.value().rgba.size();
    if (state->textureBytes > state->limits->maxTextureBytes) {
        state->problem = "textures would take more than " + std::to_string(state->limits->maxTextureBytes >> 20) + " MiB in total";
        return false;
    }
    image->width = decoded.value().width;
    image->height = decoded.value().height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = kUnsignedByte;
    image->image = std::move(decoded.value().rgba);
    return true;
}

// A validated view of an accessor's elements inside its buffer.
struct View {
    const unsigned char* base = nullptr;
    std::size_t stride = 0, count = 0;
    int componentType = 0, components = 0;
    bool normalized = false;
};

Result<View> accessorView(const tinygltf::Model& g, int index, const std::string& what) {
    using RV = Result<View>;
    if (index < 0 || std::size_t(index) >= g.accessors.size())
        return RV::failure(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = g.accessors[std::size_t(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    if (a.sparse.isSparse) return RV::failure(name + ": sparse accessors are not supported");
    View v;
    v.componentType = a.componentType;
    v.components = componentCount(a.type);
    v.normalized = a.normalized;
    v.count = a.count;
    const int csize = componentSize(a.componentType);
    if (csize == 0 || v.components == 0) return RV::failure(name + ": unknown component or element type");
    if (v.count == 0) return RV(v);
    if (a.bufferView < 0 || std::size_t(a.bufferView) >= g.bufferViews.size())
        return RV::failure(name + ": buffer view " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& bv = g.bufferViews[std::size_t(a.bufferView)];
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= g.buffers.size())
        return RV::failure(name + ": buffer " + std::to_string(bv.buffer) + " does not exist");
    const std::vector<unsigned char>& data = g.buffers[std::size_t(bv.buffer)].data;
    const std::size_t element = std::size_t(csize) * std::size_t(v.components);
    v.stride = bv.byteStride ? bv.byteStride : element;
    // Sizes are checked in a way that cannot overflow: every term is bounded first.
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        return RV::failure(name + ": buffer view " + std::to_string(a.bufferView) + " lies outside its buffer (" +
                           std::to_string(data.size()) + " bytes)");
    if (v.stride < element || v.stride > 252)
        return RV::failure(name + ": byte stride " + std::to_string(v.stride) + " is invalid for " +
                           std::to_string(element) + "-byte elements");
    const std::size_t span = bv.byteLength;
    if (a.byteOffset > span || v.count > (span - a.byteOffset) / v.stride + 1 ||
        (v.count - 1) * v.stride + element > span - a.byteOffset)
        return RV::failure(name + ": " + std::to_string(v.count) + " elements do not fit in buffer view " +
                           std::to_string(a.bufferView) + " (" + std::to_string(span) + " bytes)");
    v.base = data.data() + bv.byteOffset + a.byteOffset;
    return RV(v);
}

// Component c of element i as a float (float, or a normalised integer type).
float readFloat(const View& v, std::size_t i, int c) {
    const unsigned char* p = v.base + i * v.stride;
    switch (v.componentType) {
    case kFloat: {
        float f;
        std::memcpy(&f, p + 4 * c, 4);
        return f;
    }
    case kUnsignedByte: return float(p[c]) / 255.0f;
    case kUnsignedShort: {
        std::uint16_t s;
        std::memcpy(&s, p + 2 * c, 2);
        return float(s) / 65535.0f;
    }
    case kByte: return std::max(float(std::int8_t(p[c])) / 127.0f, -1.0f); // glTF "Animations": normalised signed
    case kShort: {
        std::int16_t s;
        std::memcpy(&s, p + 2 * c, 2);
        return std::max(float(s) / 32767.0f, -1.0f);
    }
    default: return 0.0f;
    }
}

std::uint32_t readIndex(const View& v, std::size_t i) {
    const unsigned char* p = v.base + i * v.stride;
    switch (v.componentType) {
    case kUnsignedByte: return p[0];
    case kUnsignedShort: {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        return s;
    }
    default: {
        std::uint32_t u;
        std::memcpy(&u, p, 4);
        return u;
    }
    }
}

// Component c of element i of an unsigned byte or short accessor (JOINTS_n).
std::uint32_t readIndexComponent(const View& v, std::size_t i, int c) {
    const unsigned char* p = v.base + i * v.stride;
    if (v.componentType == kUnsignedByte) return p[c];
    std::uint16_t s;
    std::memcpy(&s, p + 2 * c, 2);
    return s;
}

// The node's local transform (glTF: matrix, column-major, or T * R * S).
Mat4d localMatrix(const tinygltf::Node& n) {
    Mat4d m;
    if (n.matrix.size() == 16) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m.m[r][c] = n.matrix[std::size_t(c * 4 + r)];
        return m;
    }
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    if (n.translation.size() == 3) std::copy(n.translation.begin(), n.translation.end(), t);
    if (n.rotation.size() == 4) std::copy(n.rotation.begin(), n.rotation.end(), q);
    if (n.scale.size() == 3) std::copy(n.scale.begin(), n.scale.end(), s);
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    const double rot[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                              {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                              {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m.m[r][c] = rot[r][c] * s[c];
        m.m[r][3] = t[r];
    }
    m.m[3][3] = 1.0;
    return m;
}

bool finite(const Mat4d& m) {
    for (const auto& row : m.m)
        for (double v : row)
            if (!std::isfinite(v)) return false;
    return true;
}

// The metallic-roughness to Blinn-Phong mapping of GltfLoader.hpp.
Material materialFrom(const tinygltf::Material& gm) {
    const auto& pbr = gm.pbrMetallicRoughness;
    Material m;
    m.name = gm.name;
    m.fromFile = true;
    const double metal = std::clamp(pbr.metallicFactor, 0.0, 1.0), rough = std::clamp(pbr.roughnessFactor, 0.0, 1.0);
    double base[3] = {1, 1, 1};
    for (std::size_t c = 0; c < 3 && c < pbr.baseColorFactor.size(); ++c) base[c] = std::clamp(pbr.baseColorFactor[c], 0.0, 1.0);
    m.kd = Color{float(base[0] * (1 - metal)), float(base[1] * (1 - metal)), float(base[2] * (1 - metal)), 1.0f};
    m.ks = Color{float(0.04 * (1 - metal) + base[0] * metal), float(0.04 * (1 - metal) + base[1] * metal),
                 float(0.04 * (1 - metal) + base[2] * metal), 1.0f};
    const double alpha = rough * rough;
    const double n = alpha > 0.0 ? 2.0 / (alpha * alpha) - 2.0 : 1024.0;
    m.shininess = float(std::clamp(std::round(n), 1.0, 1024.0));
    PbrFactors f;
    f.baseColor = Color{float(base[0]), float(base[1]), float(base[2]), 1.0f};
    f.metallic = float(metal);
    f.roughness = float(rough);
    double emissive[3] = {0, 0, 0};
    for (std::size_t c = 0; c < 3 && c < gm.emissiveFactor.size(); ++c) emissive[c] = std::clamp(gm.emissiveFactor[c], 0.0, 1.0);
    double strength = 1.0;
    if (const auto ext = gm.extensions.find("KHR_materials_emissive_strength"); ext != gm.extensions.end()) {
        const tinygltf::Value& v = ext->second;
        if (v.IsObject() && v.Has("emissiveStrength") && v.Get("emissiveStrength").IsNumber())
            strength = std::max(v.Get("emissiveStrength").GetNumberAsDouble(), 0.0);
    }
    f.emissive = Vec3{float(emissive[0] * strength), float(emissive[1] * strength), float(emissive[2] * strength)};
    f.normalScale = std::isfinite(gm.normalTexture.scale) ? float(gm.normalTexture.scale) : 1.0f;
    f.occlusionStrength = float(std::clamp(gm.occlusionTexture.strength, 0.0, 1.0));
    // Alpha modes. With the factor's alpha alone (untextured, or a texture without alpha): BLEND
    // blends with it, MASK keeps the surface when it reaches alphaCutoff and drops it otherwise,
    // OPAQUE ignores it. With a base colour texture, texelAlpha holds the per-fragment rule (the
    // factor times the texel's alpha), used when the texture has alpha.
    const double a = pbr.baseColorFactor.size() > 3 ? std::clamp(pbr.baseColorFactor[3], 0.0, 1.0) : 1.0;
    m.doubleSided = gm.doubleSided;
    if (gm.alphaMode == "BLEND") {
        m.alpha = float(a);
        m.texelAlpha = {AlphaMode::Blend, float(a), 0.5f};
    } else if (gm.alphaMode == "MASK") {
        m.alpha = a >= gm.alphaCutoff ? 1.0f : 0.0f;
        m.texelAlpha = {AlphaMode::Mask, float(a), float(gm.alphaCutoff)};
    }
    f.baseColor.a = float(a);
    m.pbr = f;
    return m;
}

// A glTF sampler as SoftRaster's one wrap mode and one filter per draw. Wrap: REPEAT (the
// default), CLAMP_TO_EDGE, MIRRORED_REPEAT; when wrapS and wrapT differ, wrapS serves both (a
// note says so). Filter, from minFilter: NEAREST -> nearest, LINEAR -> bilinear, any *_MIPMAP_*
// -> trilinear; without a minFilter, a NEAREST magFilter -> nearest, else unset (the settings').
struct SamplerModes {
    WrapMode wrap = WrapMode::Repeat;
    std::optional<TextureFilter> filter;
    std::string problem, note;
};
SamplerModes samplerModes(const tinygltf::Sampler& s) {
    SamplerModes out;
    const auto wrapOf = [&](int gl, const char* axis) -> WrapMode {
        switch (gl) {
        case 10497: return WrapMode::Repeat;
        case 33071: return WrapMode::Clamp;
        case 33648: return WrapMode::Mirror;
        default: out.problem = std::string(axis) + " " + std::to_string(gl) + " is not a glTF wrap mode"; return WrapMode::Repeat;
        }
    };
    out.wrap = wrapOf(s.wrapS, "wrapS");
    const WrapMode t = wrapOf(s.wrapT, "wrapT");
    if (out.problem.empty() && t != out.wrap)
        out.note = std::string("wrapS (") + wrapName(out.wrap) + ") and wrapT (" + wrapName(t) + ") differ: " + wrapName(out.wrap) +
                   " is used for both";
    switch (s.minFilter) {
    case -1: break;
    case 9728: out.filter = TextureFilter::Nearest; break;
    case 9729: out.filter = TextureFilter::Bilinear; break;
    case 9984: case 9985: case 9986: case 9987: out.filter = TextureFilter::Trilinear; break;
    default: out.problem = "minFilter " + std::to_string(s.minFilter) + " is not a glTF filter"; break;
    }
    if (s.magFilter != -1 && s.magFilter != 9728 && s.magFilter != 9729)
        out.problem = "magFilter " + std::to_string(s.magFilter) + " is not a glTF filter";
    if (s.minFilter == -1 && s.magFilter == 9728) out.filter = TextureFilter::Nearest;
    return out;
}

// Percent-decoding of a relative URI (glTF: "URIs are relative to the .gltf file").
std::string decodeUri(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// Types of the glTF 2.0 core properties (the specification's JSON schema, by property name:
// the core schema gives each name one type, "scale" aside: a node's array or a normal
// texture's number). tinygltf skips an optional property of the wrong type as if it were
// absent; the specification calls such a file invalid, so we refuse it, naming the property.
enum class Kind { String, Uint, Number, Bool, Array, Object, NumberOrNumbers, Numbers, Uints };

const std::map<std::string, Kind>& schemaKinds() {
    static const std::map<std::string, Kind> kinds = {
        {"name", Kind::String}, {"uri", Kind::String}, {"mimeType", Kind::String}, {"type", Kind::String},
        {"alphaMode", Kind::String}, {"version", Kind::String}, {"minVersion", Kind::String},
        {"generator", Kind::String}, {"copyright", Kind::String}, {"scene", Kind::Uint}, {"mesh", Kind::Uint},
        {"camera", Kind::Uint}, {"skin", Kind::Uint}, {"buffer", Kind::Uint}, {"bufferView", Kind::Uint},
        {"byteOffset", Kind::Uint}, {"byteLength", Kind::Uint}, {"byteStride", Kind::Uint},
        {"componentType", Kind::Uint}, {"count", Kind::Uint}, {"indices", Kind::Uint}, {"material", Kind::Uint},
        {"mode", Kind::Uint}, {"sampler", Kind::Uint}, {"source", Kind::Uint}, {"index", Kind::Uint},
        {"texCoord", Kind::Uint}, {"magFilter", Kind::Uint}, {"minFilter", Kind::Uint}, {"wrapS", Kind::Uint},
        {"wrapT", Kind::Uint}, {"metallicFactor", Kind::Number}, {"roughnessFactor", Kind::Number},
        {"alphaCutoff", Kind::Number}, {"strength", Kind::Number}, {"yfov", Kind::Number}, {"znear", Kind::Number},
        {"zfar", Kind::Number}, {"aspectRatio", Kind::Number}, {"xmag", Kind::Number}, {"ymag", Kind::Number},
        {"normalized", Kind::Bool}, {"doubleSided", Kind::Bool}, {"scale", Kind::NumberOrNumbers},
        {"matrix", Kind::Numbers}, {"rotation", Kind::Numbers}, {"translation", Kind::Numbers},
        {"weights", Kind::Numbers}, {"baseColorFactor", Kind::Numbers}, {"emissiveFactor", Kind::Numbers},
        {"max", Kind::Numbers}, {"min", Kind::Numbers}, {"children", Kind::Uints}, {"joints", Kind::Uints},
        {"primitives", Kind::Array}, {"accessors", Kind::Array}, {"buffers", Kind::Array}, {"bufferViews", Kind::Array},
        {"meshes", Kind::Array}, {"materials", Kind::Array}, {"textures", Kind::Array}, {"images", Kind::Array},
        {"samplers", Kind::Array}, {"scenes", Kind::Array}, {"nodes", Kind::Array}, {"cameras", Kind::Array},
        {"skins", Kind::Array}, {"animations", Kind::Array}, {"extensionsUsed", Kind::Array},
        {"extensionsRequired", Kind::Array}, {"targets", Kind::Array}, {"attributes", Kind::Object},
        {"pbrMetallicRoughness", Kind::Object}, {"normalTexture", Kind::Object}, {"occlusionTexture", Kind::Object},
        {"emissiveTexture", Kind::Object}, {"baseColorTexture", Kind::Object}, {"metallicRoughnessTexture", Kind::Object},
        {"asset", Kind::Object}, {"perspective", Kind::Object}, {"orthographic", Kind::Object}, {"sparse", Kind::Object},
        {"extensions", Kind::Object}};
    return kinds;
}

bool isUint(const nlohmann::json& v) { return v.is_number_unsigned() || (v.is_number_integer() && v.get<long long>() >= 0); }

bool hasKind(const nlohmann::json& v, Kind k) {
    const auto all = [&](auto pred) {
        if (!v.is_array()) return false;
        for (const auto& e : v)
            if (!pred(e)) return false;
        return true;
    };
    switch (k) {
    case Kind::String: return v.is_string();
    case Kind::Uint: return isUint(v);
    case Kind::Number: return v.is_number();
    case Kind::Bool: return v.is_boolean();
    case Kind::Array: return v.is_array();
    case Kind::Object: return v.is_object();
    case Kind::NumberOrNumbers: return v.is_number() || all([](const nlohmann::json& e) { return e.is_number(); });
    case Kind::Numbers: return all([](const nlohmann::json& e) { return e.is_number(); });
    case Kind::Uints: return all([](const nlohmann::json& e) { return isUint(e); });
    }
    return false;
}

const char* kindName(Kind k) {
    switch (k) {
    case Kind::String: return "a string";
    case Kind::Uint: return "an unsigned integer";
    case Kind::Number: return "a number";
    case Kind::Bool: return "true or false";
    case Kind::Array: return "an array";
    case Kind::Object: return "an object";
    case Kind::NumberOrNumbers: return "a number or an array of numbers";
    case Kind::Numbers: return "an array of numbers";
    case Kind::Uints: return "an array of unsigned integers";
    }
    return "?";
}

// The first property of the wrong type, as "path: expected KIND", or an empty string. "extras"
// is free-form; each extension's value must be an object (its own schema is not checked); at the
// top level only the core properties are looked into (glTF 1.0 leftovers such as "programs" are
// not glTF 2.0 and are ignored, as tinygltf ignores them). ("target" is left out: an unsigned
// integer in a buffer view, an object in an animation channel.)
std::string schemaProblem(const nlohmann::json& v, const std::string& path, int depth = 0) {
    static const std::set<std::string> kTopLevel = {"asset", "scene", "scenes", "nodes", "meshes", "materials", "textures",
                                                    "images", "samplers", "buffers", "bufferViews", "accessors", "cameras",
                                                    "skins", "animations", "extensionsUsed", "extensionsRequired", "extensions"};
    if (depth > 64) return "the JSON is nested deeper than 64 levels";
    if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it) {
            const std::string& key = it.key();
            const std::string at = path.empty() ? key : path + "." + key;
            if (key == "extras" || (depth == 0 && !kTopLevel.count(key))) continue;
            const auto kind = schemaKinds().find(key);
            if (kind != schemaKinds().end() && !hasKind(it.value(), kind->second))
                return at + ": expected " + kindName(kind->second);
            if (key == "extensions") {
                for (auto e = it.value().begin(); e != it.value().end(); ++e)
                    if (!e.value().is_object()) return at + "." + e.key() + ": expected an object";
                continue;
            }
            std::string p = schemaProblem(it.value(), at, depth + 1);
            if (!p.empty()) return p;
        }
    } else if (v.is_array()) {
        for (std::size_t i = 0; i < v.size(); ++i) {
            std::string p = schemaProblem(v[i], path + "[" + std::to_string(i) + "]", depth + 1);
            if (!p.empty()) return p;
        }
    }
    return {};
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (empty when the header is malformed:
// tinygltf then reports it).
std::string jsonText(const unsigned char* data, std::size_t size, bool binary) {
    if (!binary) return std::string(reinterpret_cast<const char*>(data), size);
    if (size < 20) return {};
    std::uint32_t length = 0, type = 0;
    std::memcpy(&length, data + 12, 4);
    std::memcpy(&type, data + 16, 4);
    if (type != 0x4E4F534Au || length > size - 20) return {};
    return std::string(reinterpret_cast<const char*>(data + 20), length);
}

// Per-vertex tangents of vertices [base, end) from their triangles `tris` (numbered from base),
// appended to mesh.tangents: each triangle's dp/du (Lengyel, "Computing Tangent Space Basis
// Vectors for an Arbitrary Mesh", 2001), summed per vertex (weighted by the triangle's uv area,
// as the unnormalised sum is), made orthogonal to the normal; w = +1 when n x t points along
// dp/dv (our v, which grows up the image: glTF's bitangent), else -1. A vertex whose triangles
// give no tangent (degenerate uvs) gets any unit vector orthogonal to its normal.
void addTangents(Mesh& mesh, std::uint32_t base, const std::vector<std::uint32_t>& tris) {
    const std::size_t count = mesh.positions.size() - base;
    std::vector<Vec3d> tu(count, Vec3d{}), tv(count, Vec3d{});
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
        const std::uint32_t i[3] = {tris[t], tris[t + 1], tris[t + 2]};
        const Vec3d p0(mesh.positions[base + i[0]]), p1(mesh.positions[base + i[1]]), p2(mesh.positions[base + i[2]]);
        const Vec2 w0 = mesh.uvs[base + i[0]], w1 = mesh.uvs[base + i[1]], w2 = mesh.uvs[base + i[2]];
        const double du1 = double(w1.x) - w0.x, dv1 = double(w1.y) - w0.y, du2 = double(w2.x) - w0.x, dv2 = double(w2.y) - w0.y;
        const double det = du1 * dv2 - du2 * dv1;
        if (!(std::fabs(det) > 1e-20) || !std::isfinite(det)) continue;
        const Vec3d e1 = p1 - p0, e2 = p2 - p0;
        const Vec3d sdir = (e1 * dv2 - e2 * dv1) / det, tdir = (e2 * du1 - e1 * du2) / det;
        if (!std::isfinite(length(sdir)) || !std::isfinite(length(tdir))) continue;
        for (std::uint32_t k : i) {
            tu[k] = tu[k] + sdir;
            tv[k] = tv[k] + tdir;
        }
    }
    for (std::size_t k = 0; k < count; ++k) {
        const Vec3d n(mesh.normals[base + k]);
        Vec3d t = tu[k] - n * dot(n, tu[k]);
        double l = length(t);
        if (!(l > 1e-12) || !std::isfinite(l)) { // any vector orthogonal to n
            t = std::fabs(n.x) < 0.9 ? cross(n, Vec3d{1, 0, 0}) : cross(n, Vec3d{0, 1, 0});
            l = length(t);
        }
        t = t / l;
        const double w = dot(cross(n, t), tv[k]) < 0.0 ? -1.0 : 1.0;
        mesh.tangents.emplace_back(float(t.x), float(t.y), float(t.z), float(w));
    }
}

// KHR_texture_transform of one texture reference, as the 2x3 matrix uv' = M (u, v, 1) in glTF's
// uv space (v down the image): translation x rotation x scale, the extension's order. `found`:
// the reference carries the extension.
struct UvTransform {
    double m[2][3] = {{1, 0, 0}, {0, 1, 0}};
    bool found = false;
    bool operator==(const UvTransform& o) const {
        for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 3; ++c)
                if (m[r][c] != o.m[r][c]) return false;
        return true;
    }
};
UvTransform uvTransformOf(const tinygltf::ExtensionMap& extensions) {
    UvTransform t;
    const auto ext = extensions.find("KHR_texture_transform");
    if (ext == extensions.end() || !ext->second.IsObject()) return t;
    t.found = true;
    const tinygltf::Value& v = ext->second;
    const auto number = [&](const tinygltf::Value& x, double fallback) {
        return x.IsNumber() && std::isfinite(x.GetNumberAsDouble()) ? x.GetNumberAsDouble() : fallback;
    };
    double offset[2] = {0, 0}, scale[2] = {1, 1}, rotation = 0;
    for (int k = 0; k < 2; ++k) {
        if (v.Has("offset") && v.Get("offset").IsArray() && v.Get("offset").ArrayLen() == 2) offset[k] = number(v.Get("offset").Get(k), 0.0);
        if (v.Has("scale") && v.Get("scale").IsArray() && v.Get("scale").ArrayLen() == 2) scale[k] = number(v.Get("scale").Get(k), 1.0);
    }
    if (v.Has("rotation")) rotation = number(v.Get("rotation"), 0.0);
    const double c = std::cos(rotation), s = std::sin(rotation);
    // T R S with R = [[c, s], [-s, c]] (the extension's rotation matrix).
    t.m[0][0] = c * scale[0];
    t.m[0][1] = s * scale[1];
    t.m[0][2] = offset[0];
    t.m[1][0] = -s * scale[0];
    t.m[1][1] = c * scale[1];
    t.m[1][2] = offset[1];
    return t;
}

// The transform a material's uvs get: its base colour texture's (else that of its first other
// map that has one). One per material, baked into the vertices of its primitives (every vertex
// of a glTF primitive is its own: no other material reads it); a map with another transform is
// named in a warning.
UvTransform materialUvTransform(const tinygltf::Material& gm, std::string* problem) {
    const tinygltf::ExtensionMap* maps[] = {&gm.pbrMetallicRoughness.baseColorTexture.extensions,
                                            &gm.pbrMetallicRoughness.metallicRoughnessTexture.extensions,
                                            &gm.emissiveTexture.extensions, &gm.normalTexture.extensions,
                                            &gm.occlusionTexture.extensions};
    UvTransform chosen;
    for (const tinygltf::ExtensionMap* e : maps) {
        const UvTransform t = uvTransformOf(*e);
        if (!t.found) continue;
        if (!chosen.found) chosen = t;
        else if (!(t == chosen) && problem) *problem = "its maps have different KHR_texture_transforms: the first one is used for all";
    }
    return chosen;
}

// Everything gathered while walking the scene: vertices in world space, triangles per material.
struct Builder {
    std::string path; // the file, for warnings
    Model model;
    // A file with animations, skins or morph targets: what moves (null otherwise: nothing kept).
    std::shared_ptr<ModelAnimation> animation;
    const tinygltf::Node* node = nullptr; // the node whose primitives are being added
    int nodeIndex = -1;
    std::vector<std::vector<std::uint32_t>> trianglesOf; // [material + 1] -> indices
    std::vector<int> firstUse;                           // materials (+1) in order of first use
    std::size_t lineElements = 0, lineVertices = 0; // in model.lineSets, for the limits
    std::size_t triangles = 0; // in trianglesOf (the mesh's indices are filled at the end)
    bool anyComputedNormal = false, anyFileNormal = false;
};

// Vertex i of a POSITION accessor through the node's world transform (double, rounded to float).
Result<Vec3> worldPosition(const View& pos, std::size_t i, const Mat4d& world, const std::string& what) {
    const double x = readFloat(pos, i, 0), y = readFloat(pos, i, 1), z = readFloat(pos, i, 2);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
        return Result<Vec3>::failure(what + " POSITION: vertex " + std::to_string(i) + " is not finite");
    const double px = world.m[0][0] * x + world.m[0][1] * y + world.m[0][2] * z + world.m[0][3];
    const double py = world.m[1][0] * x + world.m[1][1] * y + world.m[1][2] * z + world.m[1][3];
    const double pz = world.m[2][0] * x + world.m[2][1] * y + world.m[2][2] * z + world.m[2][3];
    const Vec3 pf{float(px), float(py), float(pz)};
    if (!std::isfinite(pf.x) || !std::isfinite(pf.y) || !std::isfinite(pf.z))
        return Result<Vec3>::failure(what + " POSITION: vertex " + std::to_string(i) + " is not finite after the node transforms");
    return Result<Vec3>(pf);
}

// POINTS, LINES, LINE_LOOP and LINE_STRIP: a LineSet in world space (glTF "Meshes": a loop
// closes last -> first, a strip joins consecutive vertices).
Status addLines(Builder& b, const tinygltf::Model& g, const tinygltf::Primitive& prim, const View& pos,
                const std::vector<std::uint32_t>& order, const Mat4d& world, const std::string& what,
                const LoadLimits& limits) {
    LineSet set;
    set.points = prim.mode == kModePoints;
    set.material = prim.material >= 0 && std::size_t(prim.material) < g.materials.size() ? prim.material : -1;
    if (prim.material >= 0 && set.material < 0)
        return Status::failure(what + ": material " + std::to_string(prim.material) + " does not exist");
    const std::size_t n = order.size();
    if (set.points) {
        set.indices = order;
    } else if (prim.mode == kModePoints + 1) { // LINES (a whole number of pairs: checked)
        set.indices = order;
    } else {
        for (std::size_t i = 0; i + 1 < n; ++i) set.indices.insert(set.indices.end(), {order[i], order[i + 1]});
        if (prim.mode == kModePoints + 2 && n >= 2) set.indices.insert(set.indices.end(), {order[n - 1], order[0]}); // LOOP
    }
    b.lineElements += set.indices.size();
    if (b.lineElements > limits.maxTriangles * 3) return Status::failure("more line and point elements than the triangle limit allows");
    if (b.model.mesh.vertexCount() + b.lineVertices + pos.count > limits.maxVertices)
        return Status::failure("more than " + std::to_string(limits.maxVertices) + " vertices");
    b.lineVertices += pos.count;
    set.positions.reserve(pos.count);
    for (std::size_t i = 0; i < pos.count; ++i) {
        auto p = worldPosition(pos, i, world, what);
        if (!p) return Status::failure(p.error());
        set.positions.push_back(p.value());
    }
    if (!set.indices.empty()) b.model.lineSets.push_back(std::move(set));
    return success();
}

// A primitive of an animated file: its object-space vertices (in the mesh's numbering: vertex i
// reads accessor element src(i)), morph targets, and skin attributes, for ModelAnimation::pose.
template <class Source>
Status addAnimatedBlock(Builder& b, const tinygltf::Model& g, const tinygltf::Primitive& prim, const View& pos,
                        const std::optional<View>& normals, bool keepTangents, std::uint32_t first, std::size_t vertices,
                        const Source& src, bool mirrored, const std::string& what, const LoadLimits& limits) {
    AnimatedBlock block;
    block.node = b.nodeIndex;
    block.first = first;
    block.count = std::uint32_t(vertices);
    block.mirrored = mirrored;
    block.flatNormals = !normals;
    const auto vec3 = [](const View& v, std::size_t i) { return Vec3{readFloat(v, i, 0), readFloat(v, i, 1), readFloat(v, i, 2)}; };
    const auto finite3 = [](Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    block.positions.resize(vertices);
    for (std::size_t i = 0; i < vertices; ++i) block.positions[i] = vec3(pos, src(i));
    if (normals) {
        block.normals.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) block.normals[i] = vec3(*normals, src(i));
    }
    if (keepTangents) {
        const auto ti = prim.attributes.find("TANGENT");
        auto v = accessorView(g, ti->second, what + " TANGENT");
        if (!v) return Status::failure(v.error());
        block.tangents.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i)
            block.tangents[i] = Vec4{readFloat(v.value(), src(i), 0), readFloat(v.value(), src(i), 1), readFloat(v.value(), src(i), 2),
                                     readFloat(v.value(), src(i), 3)};
    }
    if (prim.targets.size() > limits.maxMorphTargets)
        return Status::failure(what + ": " + std::to_string(prim.targets.size()) + " morph targets, above the limit of " +
                               std::to_string(limits.maxMorphTargets));
    for (std::size_t k = 0; k < prim.targets.size(); ++k) {
        const std::string name = what + " target " + std::to_string(k);
        std::vector<Vec3> dp(vertices, Vec3{0, 0, 0}), dn;
        for (const char* attribute : {"POSITION", "NORMAL"}) {
            const auto it = prim.targets[k].find(attribute);
            if (it == prim.targets[k].end()) continue;
            const bool isPosition = attribute[0] == 'P';
            if (!isPosition && !normals) continue; // flat normals are made from the morphed positions
            if (it->second >= 0 && std::size_t(it->second) < g.accessors.size() && g.accessors[std::size_t(it->second)].sparse.isSparse) {
                b.model.warnings.push_back(b.path + ": " + name + " " + attribute + ": a sparse accessor (not supported): the target is ignored");
                continue;
            }
            auto v = accessorView(g, it->second, name + " " + attribute);
            if (!v) return Status::failure(v.error());
            if (v.value().components != 3 || v.value().count != pos.count)
                return Status::failure(name + " " + attribute + ": must be VEC3 with POSITION's count (" + std::to_string(pos.count) + ")");
            std::vector<Vec3>& out = isPosition ? dp : dn;
            out.resize(vertices);
            for (std::size_t i = 0; i < vertices; ++i) {
                out[i] = vec3(v.value(), src(i));
                if (!finite3(out[i])) return Status::failure(name + " " + attribute + ": vertex " + std::to_string(src(i)) + " is not finite");
            }
        }
        // TANGENT deltas, where the block keeps the file's tangents (a normal-mapped primitive).
        std::vector<Vec3> dt;
        if (const auto it = prim.targets[k].find("TANGENT"); keepTangents && it != prim.targets[k].end()) {
            auto v = accessorView(g, it->second, name + " TANGENT");
            if (!v) return Status::failure(v.error());
            if (v.value().components != 3 || v.value().count != pos.count)
                return Status::failure(name + " TANGENT: must be VEC3 with POSITION's count (" + std::to_string(pos.count) + ")");
            dt.resize(vertices);
            for (std::size_t i = 0; i < vertices; ++i) {
                dt[i] = vec3(v.value(), src(i));
                if (!finite3(dt[i])) return Status::failure(name + " TANGENT: vertex " + std::to_string(src(i)) + " is not finite");
            }
        }
        block.targetPositions.push_back(std::move(dp));
        block.targetNormals.push_back(std::move(dn));
        block.targetTangents.push_back(std::move(dt));
    }
    const int skin = b.node->skin;
    const auto joints0 = prim.attributes.find("JOINTS_0");
    const auto weights0 = prim.attributes.find("WEIGHTS_0");
    if (skin >= 0 && joints0 != prim.attributes.end() && weights0 != prim.attributes.end()) {
        if (std::size_t(skin) >= g.skins.size()) return Status::failure("node " + std::to_string(b.nodeIndex) + ": skin " + std::to_string(skin) + " does not exist");
        const std::size_t jointCount = g.skins[std::size_t(skin)].joints.size();
        if (jointCount == 0) return Status::failure("skin " + std::to_string(skin) + " has no joints");
        block.skin = skin;
        block.joints.assign(vertices, {});
        block.weights.assign(vertices, {});
        for (int set = 0; set < 2; ++set) {
            const std::string suffix = "_" + std::to_string(set);
            const auto ji = prim.attributes.find("JOINTS" + suffix), wi = prim.attributes.find("WEIGHTS" + suffix);
            if (ji == prim.attributes.end() || wi == prim.attributes.end()) break;
            auto jv = accessorView(g, ji->second, what + " JOINTS" + suffix);
            if (!jv) return Status::failure(jv.error());
            auto wv = accessorView(g, wi->second, what + " WEIGHTS" + suffix);
            if (!wv) return Status::failure(wv.error());
            const View& J = jv.value();
            const View& W = wv.value();
            if (J.components != 4 || (J.componentType != kUnsignedByte && J.componentType != kUnsignedShort) || J.count != pos.count)
                return Status::failure(what + " JOINTS" + suffix + ": must be unsigned byte or short VEC4 with POSITION's count");
            if (W.components != 4 || W.count != pos.count ||
                !(W.componentType == kFloat || (W.normalized && (W.componentType == kUnsignedByte || W.componentType == kUnsignedShort))))
                return Status::failure(what + " WEIGHTS" + suffix + ": must be float or normalised unsigned byte/short VEC4 with POSITION's count");
            for (std::size_t i = 0; i < vertices; ++i)
                for (int c = 0; c < 4; ++c) {
                    const std::uint32_t joint = readIndexComponent(J, src(i), c);
                    const float weight = readFloat(W, src(i), c);
                    if (!std::isfinite(weight) || weight < 0.0f)
                        return Status::failure(what + " WEIGHTS" + suffix + ": vertex " + std::to_string(src(i)) + " has a weight that is negative or not finite");
                    if (weight > 0.0f && joint >= jointCount)
                        return Status::failure(what + " JOINTS" + suffix + ": vertex " + std::to_string(src(i)) + " names joint " +
                                               std::to_string(joint) + ", out of range (skin " + std::to_string(skin) + " has " +
                                               std::to_string(jointCount) + ")");
                    block.joints[i][std::size_t(4 * set + c)] = std::uint16_t(weight > 0.0f ? joint : 0u);
                    block.weights[i][std::size_t(4 * set + c)] = weight;
                }
        }
        // Weights that do not sum to 1 are normalised (glTF allows it); none at all: the first joint alone.
        for (auto& w : block.weights) {
            double sum = 0.0;
            for (float x : w) sum += x;
            if (sum > 0.0) {
                for (float& x : w) x = float(x / sum);
            } else {
                w = {};
                w[0] = 1.0f;
            }
        }
    }
    b.animation->blocks.push_back(std::move(block));
    return success();
}

Status addPrimitive(Builder& b, const tinygltf::Model& g, const tinygltf::Primitive& prim, const Mat4d& world,
                    const std::string& what, const LoadLimits& limits) {
    if (prim.extensions.count("KHR_draco_mesh_compression"))
        return Status::failure(what + ": uses KHR_draco_mesh_compression (Draco-compressed meshes), which SoftRaster does not support");
    if (prim.mode < kModePoints || prim.mode > kModeFan) return Status::failure(what + ": unknown mode " + std::to_string(prim.mode));
    const auto attribute = [&](const char* name) {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const int posIndex = attribute("POSITION");
    if (posIndex < 0) return Status::failure(what + ": no POSITION attribute");
    auto pos = accessorView(g, posIndex, what + " POSITION");
    if (!pos) return Status::failure(pos.error());
    if (pos.value().componentType != kFloat || pos.value().components != 3)
        return Status::failure(what + " POSITION: must be float VEC3");
    const std::size_t count = pos.value().count;
    std::optional<View> normals, uvs, tangents;
    if (const int ti = attribute("TANGENT"); ti >= 0) {
        auto v = accessorView(g, ti, what + " TANGENT");
        if (!v) return Status::failure(v.error());
        if (v.value().componentType != kFloat || v.value().components != 4) return Status::failure(what + " TANGENT: must be float VEC4");
        if (v.value().count != count) return Status::failure(what + " TANGENT: count differs from POSITION's");
        tangents = v.value();
    }
    if (const int ni = attribute("NORMAL"); ni >= 0) {
        auto v = accessorView(g, ni, what + " NORMAL");
        if (!v) return Status::failure(v.error());
        if (v.value().componentType != kFloat || v.value().components != 3) return Status::failure(what + " NORMAL: must be float VEC3");
        if (v.value().count != count) return Status::failure(what + " NORMAL: count differs from POSITION's");
        normals = v.value();
    }
    if (const int ti = attribute("TEXCOORD_0"); ti >= 0) {
        auto v = accessorView(g, ti, what + " TEXCOORD_0");
        if (!v) return Status::failure(v.error());
        const View& t = v.value();
        const bool ok = t.components == 2 && (t.componentType == kFloat ||
                                              (t.normalized && (t.componentType == kUnsignedByte || t.componentType == kUnsignedShort)));
        if (!ok) return Status::failure(what + " TEXCOORD_0: must be float or normalised unsigned byte/short VEC2");
        if (t.count != count) return Status::failure(what + " TEXCOORD_0: count differs from POSITION's");
        uvs = t;
    }
    // The primitive's vertex order: indices, or 0..count-1.
    std::vector<std::uint32_t> order;
    if (prim.indices >= 0) {
        auto v = accessorView(g, prim.indices, what + " indices");
        if (!v) return Status::failure(v.error());
        const View& iv = v.value();
        if (iv.components != 1 || (iv.componentType != kUnsignedByte && iv.componentType != kUnsignedShort &&
                                   iv.componentType != kUnsignedInt))
            return Status::failure(what + " indices: must be unsigned byte, short or int scalars");
        if (iv.count > limits.maxTriangles * 3) return Status::failure(what + ": more indices than the triangle limit allows");
        order.resize(iv.count);
        for (std::size_t i = 0; i < iv.count; ++i) {
            order[i] = readIndex(iv, i);
            if (order[i] >= count)
                return Status::failure(what + ": index " + std::to_string(order[i]) + " (entry " + std::to_string(i) +
                                       ") is out of range (" + std::to_string(count) + " vertices)");
        }
    } else {
        order.resize(count);
        for (std::size_t i = 0; i < count; ++i) order[i] = std::uint32_t(i);
    }
    // The specification's vertex counts: whole triangles and whole segments (strips, fans and
    // loops take any count; too few draw nothing).
    if (prim.mode == kModeTriangles && order.size() % 3 != 0)
        return Status::failure(what + ": TRIANGLES with " + std::to_string(order.size()) + " vertices, not a multiple of 3");
    if (prim.mode == kModePoints + 1 && order.size() % 2 != 0)
        return Status::failure(what + ": LINES with " + std::to_string(order.size()) + " vertices, not a multiple of 2");
    if (prim.mode < kModeTriangles) return addLines(b, g, prim, pos.value(), order, world, what, limits);
    // Triangles of the mode, in the primitive's vertex numbering.
    std::vector<std::uint32_t> tris;
    const std::size_t n = order.size();
    if (prim.mode == kModeTriangles) { // a whole number of triangles: checked above
        tris = order;
    } else if (prim.mode == kModeStrip) {
        for (std::size_t i = 2; i < n; ++i) {
            const bool even = i % 2 == 0; // glTF: triangle i - 2 is (i-2, i-1, i) or (i-1, i-2, i)
            tris.insert(tris.end(), {order[even ? i - 2 : i - 1], order[even ? i - 1 : i - 2], order[i]});
        }
    } else {
        for (std::size_t i = 2; i < n; ++i) tris.insert(tris.end(), {order[i - 1], order[i], order[0]});
    }
    if (b.triangles + tris.size() / 3 > limits.maxTriangles)
        return Status::failure("more than " + std::to_string(limits.maxTriangles) + " triangles");
    // A primitive without NORMAL is drawn with flat normals (glTF "Meshes": "client
    // implementations MUST calculate flat normals"): each triangle gets vertices of its own, so
    // the area-weighted normal below is its face normal. vertex k of the primitive reads element
    // source[k] of the accessors (itself when the vertices stay shared).
    std::vector<std::uint32_t> source;
    std::size_t vertices = count;
    if (!normals) {
        source = tris;
        vertices = tris.size();
        for (std::size_t k = 0; k < tris.size(); ++k) tris[k] = std::uint32_t(k);
    }
    const auto src = [&](std::size_t k) { return source.empty() ? k : std::size_t(source[k]); };
    if (b.model.mesh.vertexCount() + vertices > limits.maxVertices)
        return Status::failure("more than " + std::to_string(limits.maxVertices) + " vertices");

    // Vertices in world space.
    Mesh& mesh = b.model.mesh;
    const auto base = std::uint32_t(mesh.positions.size());
    std::vector<Vec3d> world3(vertices);
    for (std::size_t i = 0; i < vertices; ++i) {
        auto pf = worldPosition(pos.value(), src(i), world, what);
        if (!pf) return Status::failure(pf.error());
        world3[i] = Vec3d(pf.value());
        mesh.positions.push_back(pf.value());
    }
    // Normals: the inverse transpose of the upper 3x3 (its cofactor matrix; the scale drops out
    // with the renormalisation), or area-weighted from the world-space triangles.
    const double (*a)[4] = world.m;
    const double cof[3][3] = {{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[1][2] * a[2][0] - a[1][0] * a[2][2], a[1][0] * a[2][1] - a[1][1] * a[2][0]},
                              {a[0][2] * a[2][1] - a[0][1] * a[2][2], a[0][0] * a[2][2] - a[0][2] * a[2][0], a[0][1] * a[2][0] - a[0][0] * a[2][1]},
                              {a[0][1] * a[1][2] - a[0][2] * a[1][1], a[0][2] * a[1][0] - a[0][0] * a[1][2], a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
    const double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
    std::vector<Vec3d> accum;
    if (!normals) {
        accum.assign(vertices, Vec3d{});
        for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
            const Vec3d p0 = world3[tris[t]], p1 = world3[tris[t + 1]], p2 = world3[tris[t + 2]];
            Vec3d fn = cross(p1 - p0, p2 - p0);
            if (det < 0) fn = fn * -1.0; // the winding is reversed below
            for (int k = 0; k < 3; ++k) accum[tris[t + std::size_t(k)]] = accum[tris[t + std::size_t(k)]] + fn;
        }
        b.anyComputedNormal = true;
    } else {
        b.anyFileNormal = true;
    }
    for (std::size_t i = 0; i < vertices; ++i) {
        Vec3d nv;
        if (normals) {
            const double x = readFloat(*normals, i, 0), y = readFloat(*normals, i, 1), z = readFloat(*normals, i, 2);
            // cof = det x the inverse transpose: its sign flips with a mirror, the normal must not.
            nv = Vec3d{cof[0][0] * x + cof[0][1] * y + cof[0][2] * z, cof[1][0] * x + cof[1][1] * y + cof[1][2] * z,
                       cof[2][0] * x + cof[2][1] * y + cof[2][2] * z} *
                 (det < 0 ? -1.0 : 1.0);
        } else {
            nv = accum[i];
        }
        const double l = length(nv);
        nv = l > 0.0 && std::isfinite(l) ? nv / l : Vec3d{0, 0, 1};
        mesh.normals.emplace_back(float(nv.x), float(nv.y), float(nv.z));
    }
    if (uvs) {
        if (!b.model.hasUvs) {
            mesh.uvs.assign(base, Vec2{}); // earlier vertices had none: (0, 0)
            b.model.hasUvs = true;
        }
        UvTransform transform;
        if (prim.material >= 0 && std::size_t(prim.material) < g.materials.size())
            transform = materialUvTransform(g.materials[std::size_t(prim.material)], nullptr);
        for (std::size_t i = 0; i < vertices; ++i) {
            float u = readFloat(*uvs, src(i), 0), v = readFloat(*uvs, src(i), 1);
            if (transform.found) {
                const double tu = transform.m[0][0] * u + transform.m[0][1] * v + transform.m[0][2];
                const double tv = transform.m[1][0] * u + transform.m[1][1] * v + transform.m[1][2];
                u = float(tu);
                v = float(tv);
            }
            mesh.uvs.emplace_back(std::isfinite(u) ? u : 0.0f, std::isfinite(v) ? 1.0f - v : 0.0f);
        }
    } else if (b.model.hasUvs) {
        mesh.uvs.resize(mesh.positions.size(), Vec2{});
    }
    // Tangents, for a material with a normal map: the file's TANGENT through the node's transform,
    // else generated from the uvs (addTangents). Vertices without any get (1, 0, 0, 1).
    const bool normalMapped = uvs && prim.material >= 0 && std::size_t(prim.material) < g.materials.size() &&
                              g.materials[std::size_t(prim.material)].normalTexture.index >= 0;
    if (normalMapped || !mesh.tangents.empty()) {
        mesh.tangents.resize(base, Vec4{1.0f, 0.0f, 0.0f, 1.0f});
        if (normalMapped && tangents && normals) {
            for (std::size_t i = 0; i < vertices; ++i) {
                const double x = readFloat(*tangents, i, 0), y = readFloat(*tangents, i, 1), z = readFloat(*tangents, i, 2);
                const double w = readFloat(*tangents, i, 3);
                const Vec3d t{a[0][0] * x + a[0][1] * y + a[0][2] * z, a[1][0] * x + a[1][1] * y + a[1][2] * z,
                              a[2][0] * x + a[2][1] * y + a[2][2] * z};
                // The bitangent w (n x t) in world space is the transformed one: a mirror flips w.
                const double nx = readFloat(*normals, i, 0), ny = readFloat(*normals, i, 1), nz = readFloat(*normals, i, 2);
                const Vec3d bObj = cross(Vec3d{nx, ny, nz}, Vec3d{x, y, z}) * (w < 0 ? -1.0 : 1.0);
                const Vec3d bWorld{a[0][0] * bObj.x + a[0][1] * bObj.y + a[0][2] * bObj.z, a[1][0] * bObj.x + a[1][1] * bObj.y + a[1][2] * bObj.z,
                                   a[2][0] * bObj.x + a[2][1] * bObj.y + a[2][2] * bObj.z};
                const Vec3 n = mesh.normals[base + i];
                const double l = length(t);
                const Vec3d tn = l > 0.0 && std::isfinite(l) ? t / l : Vec3d{1, 0, 0};
                const double sign = dot(cross(Vec3d(n), tn), bWorld) < 0.0 ? -1.0 : 1.0;
                mesh.tangents.emplace_back(float(tn.x), float(tn.y), float(tn.z), float(sign));
            }
        } else if (normalMapped) {
            addTangents(mesh, base, tris);
        } else {
            mesh.tangents.resize(mesh.positions.size(), Vec4{1.0f, 0.0f, 0.0f, 1.0f});
        }
    }
    if (b.animation) {
        const Status s = addAnimatedBlock(b, g, prim, pos.value(), normals, tangents && normalMapped && normals, base, vertices, src,
                                          det < 0, what, limits);
        if (!s) return s;
    }
    // Triangles into their material's list.
    const int material = prim.material >= 0 && std::size_t(prim.material) < g.materials.size() ? prim.material : -1;
    if (prim.material >= 0 && material < 0) return Status::failure(what + ": material " + std::to_string(prim.material) + " does not exist");
    auto& list = b.trianglesOf[std::size_t(material + 1)];
    b.triangles += tris.size() / 3;
    if (list.empty() && !tris.empty()) b.firstUse.push_back(material + 1);
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
        const std::uint32_t i0 = base + tris[t], i1 = base + tris[t + 1], i2 = base + tris[t + 2];
        if (det < 0) list.insert(list.end(), {i0, i2, i1});
        else list.insert(list.end(), {i0, i1, i2});
    }
    return success();
}

// A camera node: eye = the node's origin, forward = its -Z, up = its +Y (glTF "Cameras").
Status addCamera(Builder& b, const tinygltf::Camera& c, const Mat4d& world, int index) {
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
    return success();
}

// A KHR_lights_punctual light placed by a node: the light shines down its node's -Z from its
// origin. colour = color x intensity, used as it is (a directional light's lux and a point or
// spot light's candela over the squared distance land on the same scale: 1 lights a surface
// with its full diffuse colour); range 0 or absent: unlimited.
Status addLight(Builder& b, const tinygltf::Light& l, const Mat4d& world, int index) {
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
    return success();
}

// The KHR_lights_punctual light a node places (-1: none); a malformed reference is an error.
Result<int> nodeLight(const tinygltf::Node& node, std::size_t lightCount) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return Result<int>(-1);
    const tinygltf::Value& v = ext->second;
    if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsNumber())
        return Result<int>::failure("KHR_lights_punctual must name a light by its index");
    const double index = v.Get("light").GetNumberAsDouble();
    if (!(index >= 0.0 && index < double(lightCount)) || index != double(int(index))) {
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", index);
        return Result<int>::failure(std::string("KHR_lights_punctual: light ") + text + " does not exist");
    }
    return Result<int>(int(index));
}

} // namespace

namespace {

// The nodes' rest transforms and weights, the skins and the clips of an animated file, checked:
// key times finite and strictly increasing, values finite, counts as the specification says.
Status addAnimation(ModelAnimation& a, const tinygltf::Model& g, std::vector<std::string>& warnings, const std::string& path,
                    const LoadLimits& limits) {
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
        const tinygltf::Node& node = g.nodes[n];
        AnimationNode& an = a.nodes[n];
        if (node.matrix.size() == 16) {
            an.hasMatrix = true;
            an.matrix = localMatrix(node);
        }
        if (node.translation.size() == 3) std::copy(node.translation.begin(), node.translation.end(), an.translation.begin());
        if (node.rotation.size() == 4) std::copy(node.rotation.begin(), node.rotation.end(), an.rotation.begin());
        if (node.scale.size() == 3) std::copy(node.scale.begin(), node.scale.end(), an.scale.begin());
        an.weights = node.weights;
        if (an.weights.empty() && node.mesh >= 0 && std::size_t(node.mesh) < g.meshes.size()) an.weights = g.meshes[std::size_t(node.mesh)].weights;
        for (double w : an.weights)
            if (!std::isfinite(w)) return Status::failure("node " + std::to_string(n) + ": a morph weight is not finite");
    }
    for (std::size_t k = 0; k < g.skins.size(); ++k) {
        const tinygltf::Skin& gs = g.skins[k];
        const std::string what = "skin " + std::to_string(k);
        if (gs.joints.size() > limits.maxJoints)
            return Status::failure(what + ": " + std::to_string(gs.joints.size()) + " joints, above the limit of " + std::to_string(limits.maxJoints));
        AnimationSkin skin;
        for (int j : gs.joints) {
            if (j < 0 || std::size_t(j) >= g.nodes.size()) return Status::failure(what + ": joint node " + std::to_string(j) + " does not exist");
            skin.joints.push_back(j);
        }
        Mat4d identity;
        for (int i = 0; i < 4; ++i) identity.m[i][i] = 1.0;
        skin.inverseBind.assign(gs.joints.size(), identity);
        if (gs.inverseBindMatrices >= 0) {
            auto v = accessorView(g, gs.inverseBindMatrices, what + " inverseBindMatrices");
            if (!v) return Status::failure(v.error());
            if (v.value().components != 16 || v.value().componentType != kFloat || v.value().count < gs.joints.size())
                return Status::failure(what + " inverseBindMatrices: must be float MAT4, one per joint (" + std::to_string(gs.joints.size()) + ")");
            for (std::size_t j = 0; j < gs.joints.size(); ++j) {
                Mat4d m;
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) m.m[r][c] = readFloat(v.value(), j, c * 4 + r);
                const double (*e)[4] = m.m;
                const double det3 = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                                    e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
                if (!finite(m) || !(std::fabs(det3) > 0.0))
                    return Status::failure(what + " inverseBindMatrices: matrix " + std::to_string(j) + " is " +
                                           (finite(m) ? "singular (not invertible)" : "not finite"));
                skin.inverseBind[j] = m;
            }
        }
        a.skins.push_back(std::move(skin));
    }
    std::size_t totalKeys = 0;
    const auto targetsOf = [&](int node) -> std::size_t {
        const int mesh = g.nodes[std::size_t(node)].mesh;
        if (mesh < 0 || std::size_t(mesh) >= g.meshes.size() || g.meshes[std::size_t(mesh)].primitives.empty()) return 0;
        return g.meshes[std::size_t(mesh)].primitives.front().targets.size();
    };
    for (std::size_t k = 0; k < g.animations.size(); ++k) {
        const tinygltf::Animation& ga = g.animations[k];
        AnimationClip clip;
        clip.name = ga.name;
        const std::string what = "animation " + std::to_string(k);
        // What each sampler drives (the components of its values), from the channels.
        std::vector<int> components(ga.samplers.size(), 0);
        std::vector<std::uint8_t> rotation(ga.samplers.size(), 0);
        for (std::size_t c = 0; c < ga.channels.size(); ++c) {
            const tinygltf::AnimationChannel& gc = ga.channels[c];
            const std::string name = what + " channel " + std::to_string(c);
            if (gc.target_node < 0) continue; // no target: ignored (glTF: an extension may define one)
            if (std::size_t(gc.target_node) >= g.nodes.size())
                return Status::failure(name + ": node " + std::to_string(gc.target_node) + " does not exist");
            if (gc.sampler < 0 || std::size_t(gc.sampler) >= ga.samplers.size())
                return Status::failure(name + ": sampler " + std::to_string(gc.sampler) + " does not exist");
            AnimationChannel ch;
            ch.node = gc.target_node;
            ch.sampler = gc.sampler;
            int n = 0;
            if (gc.target_path == "translation") ch.path = AnimationPath::Translation, n = 3;
            else if (gc.target_path == "rotation") ch.path = AnimationPath::Rotation, n = 4;
            else if (gc.target_path == "scale") ch.path = AnimationPath::Scale, n = 3;
            else if (gc.target_path == "weights") ch.path = AnimationPath::Weights, n = int(targetsOf(gc.target_node));
            else {
                warnings.push_back(path + ": " + name + ": path '" + gc.target_path + "' is not animated");
                continue;
            }
            if (n == 0) return Status::failure(name + ": animates the weights of node " + std::to_string(gc.target_node) + ", whose mesh has no morph targets");
            int& have = components[std::size_t(gc.sampler)];
            if (have != 0 && have != n) return Status::failure(name + ": sampler " + std::to_string(gc.sampler) + " drives targets of different sizes");
            have = n;
            rotation[std::size_t(gc.sampler)] = ch.path == AnimationPath::Rotation;
            clip.channels.push_back(ch);
        }
        for (std::size_t si = 0; si < ga.samplers.size(); ++si) {
            const tinygltf::AnimationSampler& gsm = ga.samplers[si];
            const std::string name = what + " sampler " + std::to_string(si);
            AnimationSampler sm;
            sm.components = std::max(components[si], 1);
            sm.quaternion = rotation[si] != 0;
            if (gsm.interpolation == "LINEAR") sm.interpolation = AnimationSampler::Interpolation::Linear;
            else if (gsm.interpolation == "STEP") sm.interpolation = AnimationSampler::Interpolation::Step;
            else if (gsm.interpolation == "CUBICSPLINE") sm.interpolation = AnimationSampler::Interpolation::CubicSpline;
            else return Status::failure(name + ": unknown interpolation '" + gsm.interpolation + "'");
            auto in = accessorView(g, gsm.input, name + " input");
            if (!in) return Status::failure(in.error());
            if (in.value().components != 1 || in.value().componentType != kFloat || in.value().count == 0)
                return Status::failure(name + " input: must be float scalars, at least one");
            totalKeys += in.value().count;
            if (totalKeys > limits.maxAnimationKeys)
                return Status::failure("more than " + std::to_string(limits.maxAnimationKeys) + " animation keys");
            sm.times.resize(in.value().count);
            for (std::size_t i = 0; i < sm.times.size(); ++i) {
                sm.times[i] = readFloat(in.value(), i, 0);
                if (!std::isfinite(sm.times[i])) return Status::failure(name + " input: key " + std::to_string(i) + " time is not finite");
                if (i > 0 && !(sm.times[i] > sm.times[i - 1]))
                    return Status::failure(name + " input: key times are not increasing (key " + std::to_string(i) + ")");
            }
            auto out = accessorView(g, gsm.output, name + " output");
            if (!out) return Status::failure(out.error());
            const View& o = out.value();
            const std::size_t perKey = sm.interpolation == AnimationSampler::Interpolation::CubicSpline ? 3 : 1;
            const std::size_t want = sm.times.size() * perKey * std::size_t(sm.components);
            const bool scalarsOk = o.components == 1 && o.count == want;                                         // weights
            const bool vectorsOk = o.components == sm.components && o.count * std::size_t(o.components) == want; // T, R, S
            const bool typeOk = o.componentType == kFloat || (o.normalized && o.componentType != kUnsignedInt);
            if (components[si] != 0 && (!typeOk || !(scalarsOk || vectorsOk)))
                return Status::failure(name + " output: " + std::to_string(o.count) + " elements of " + std::to_string(o.components) +
                                       " components, expected " + std::to_string(want) + " values (" +
                                       std::to_string(sm.components) + " per key" + (perKey == 3 ? ", three elements per cubic key" : "") + ")");
            sm.values.resize(components[si] != 0 ? want : 0);
            for (std::size_t i = 0; i < sm.values.size(); ++i) {
                const std::size_t e = i / std::size_t(o.components);
                sm.values[i] = readFloat(o, e, int(i % std::size_t(o.components)));
                if (!std::isfinite(sm.values[i])) return Status::failure(name + " output: value " + std::to_string(i) + " is not finite");
            }
            clip.duration = std::max(clip.duration, sm.times.back());
            clip.samplers.push_back(std::move(sm));
        }
        a.clips.push_back(std::move(clip));
    }
    return success();
}

} // namespace

bool isGltfPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".gltf" || ext == ".glb";
}

Result<Model> loadModel(const std::string& utf8Path, const LoadOptions& options) {
    return isGltfPath(utf8Path) ? loadGltf(utf8Path, options) : loadObj(utf8Path, options);
}

Result<Model> loadGltf(const std::string& path, const LoadOptions& options) {
    auto bytes = readFileBytes(path, options.limits.maxFileBytes);
    if (!bytes) return R::failure(bytes.error());
    return loadGltfFromMemory(bytes.value().data(), bytes.value().size(), path, options);
}

Result<Model> loadGltfFromMemory(const unsigned char* data, std::size_t size, const std::string& path,
                                 const LoadOptions& options) {
    const LoadLimits& limits = options.limits;
    if (size > limits.maxFileBytes)
        return R::failure(path + ": " + std::to_string(size) + " bytes, above the limit of " + std::to_string(limits.maxFileBytes));
    LoadState state;
    state.limits = &limits;
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &state});
    loader.SetImageLoader(&loadImageData, &state);
    tinygltf::Model g;
    std::string err, warn;
    const std::string dir = parentDirectory(path);
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    {
        const nlohmann::json j = nlohmann::json::parse(jsonText(data, size, binary), nullptr, false);
        if (!j.is_discarded()) {
            const std::string problem = schemaProblem(j, "");
            if (!problem.empty()) return R::failure(path + ": " + problem + " (glTF 2.0 schema)");
        }
    }
    const bool loaded = binary ? loader.LoadBinaryFromMemory(&g, &err, &warn, data, unsigned(size), dir)
                               : loader.LoadASCIIFromString(&g, &err, &warn, reinterpret_cast<const char*>(data), unsigned(size), dir);
    if (!loaded) {
        std::string why = !state.problem.empty() ? state.problem : err.empty() ? std::string("not a glTF 2.0 asset") : err;
        while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
        std::replace(why.begin(), why.end(), '\n', ';');
        // tinygltf stops at a Draco primitive's accessors (they have no buffer view): say why.
        static const std::string kDraco = "KHR_draco_mesh_compression";
        if (std::search(data, data + size, kDraco.begin(), kDraco.end()) != data + size)
            why += " (the file uses KHR_draco_mesh_compression: Draco-compressed meshes are not supported)";
        return R::failure(path + ": " + why);
    }
    for (const std::string& ext : g.extensionsRequired) {
        static const std::set<std::string> kSupported = {"KHR_texture_transform", "KHR_materials_emissive_strength",
                                                         "KHR_lights_punctual"};
        if (kSupported.count(ext)) continue;
        if (ext == "KHR_draco_mesh_compression")
            return R::failure(path + ": requires KHR_draco_mesh_compression (Draco-compressed meshes), which SoftRaster does not support");
        return R::failure(path + ": requires the extension " + ext + ", which SoftRaster does not support");
    }
    if (g.scenes.empty()) return R::failure(path + ": no scene to render (the file defines no 'scenes')");
    const int sceneIndex = g.defaultScene >= 0 ? g.defaultScene : 0;
    if (std::size_t(sceneIndex) >= g.scenes.size()) return R::failure(path + ": scene " + std::to_string(sceneIndex) + " does not exist");
    if (g.nodes.size() > limits.maxNodes)
        return R::failure(path + ": " + std::to_string(g.nodes.size()) + " nodes, above the limit of " + std::to_string(limits.maxNodes));
    if (g.materials.size() > limits.maxMaterials)
        return R::failure(path + ": " + std::to_string(g.materials.size()) + " materials, above the limit of " +
                          std::to_string(limits.maxMaterials));

    Builder b;
    b.path = path;
    b.trianglesOf.resize(g.materials.size() + 2); // [material + 1]; the last slot: the override stand-in
    bool morphs = false;
    for (const tinygltf::Mesh& gm : g.meshes)
        for (const tinygltf::Primitive& prim : gm.primitives) morphs |= !prim.targets.empty();
    if (!g.animations.empty() || !g.skins.empty() || morphs) {
        b.animation = std::make_shared<ModelAnimation>();
        b.animation->nodes.resize(g.nodes.size());
    }
    // Depth-first over the scene's node trees; a node met twice makes the graph not a tree.
    std::vector<std::uint8_t> seen(g.nodes.size(), 0);
    struct Item {
        int node;
        Mat4d parent;
        std::size_t depth;
    };
    Mat4d identity;
    for (int i = 0; i < 4; ++i) identity.m[i][i] = 1.0;
    std::vector<Item> stack;
    const auto& roots = g.scenes[std::size_t(sceneIndex)].nodes;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, identity, 1});
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        if (item.node < 0 || std::size_t(item.node) >= g.nodes.size())
            return R::failure(path + ": node " + std::to_string(item.node) + " does not exist");
        if (seen[std::size_t(item.node)])
            return R::failure(path + ": node " + std::to_string(item.node) +
                              " is reached twice (the node graph must be a tree: recursive or shared nodes)");
        seen[std::size_t(item.node)] = 1;
        if (item.depth > limits.maxNodeDepth)
            return R::failure(path + ": the node hierarchy is deeper than " + std::to_string(limits.maxNodeDepth) + " levels");
        const tinygltf::Node& node = g.nodes[std::size_t(item.node)];
        const Mat4d world = item.parent * localMatrix(node);
        if (!finite(world)) return R::failure(path + ": node " + std::to_string(item.node) + " has a transform that is not finite");
        b.node = &node;
        b.nodeIndex = item.node;
        if (node.mesh >= 0) {
            if (std::size_t(node.mesh) >= g.meshes.size())
                return R::failure(path + ": node " + std::to_string(item.node) + ": mesh " + std::to_string(node.mesh) + " does not exist");
            const tinygltf::Mesh& gm = g.meshes[std::size_t(node.mesh)];
            for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
                const std::string what = "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p);
                const Status s = addPrimitive(b, g, gm.primitives[p], world, what, limits);
                if (!s) return R::failure(path + ": " + s.error());
            }
        }
        if (node.camera >= 0) {
            if (std::size_t(node.camera) >= g.cameras.size())
                return R::failure(path + ": node " + std::to_string(item.node) + ": camera " + std::to_string(node.camera) + " does not exist");
            const Status s = addCamera(b, g.cameras[std::size_t(node.camera)], world, node.camera);
            if (!s) return R::failure(path + ": " + s.error());
        }
        const Result<int> light = nodeLight(node, g.lights.size());
        if (!light) return R::failure(path + ": node " + std::to_string(item.node) + ": " + light.error());
        if (light.value() >= 0) {
            if (b.model.lights.size() >= limits.maxLights)
                return R::failure(path + ": more than " + std::to_string(limits.maxLights) + " lights in the scene");
            const Status s = addLight(b, g.lights[std::size_t(light.value())], world, light.value());
            if (!s) return R::failure(path + ": " + s.error());
        }
        for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
            stack.push_back({*it, world, item.depth + 1});
            if (b.animation && *it >= 0 && std::size_t(*it) < g.nodes.size()) b.animation->nodes[std::size_t(*it)].parent = item.node;
        }
    }
    if (b.animation) {
        const Status s = addAnimation(*b.animation, g, b.model.warnings, path, limits);
        if (!s) return R::failure(path + ": " + s.error());
        b.animation->markMovingBlocks();
    }
    Model& model = b.model;
    if (b.triangles == 0 && model.lineSets.empty()) return R::failure(path + ": the scene has nothing to draw");
    model.normalsFromFile = b.anyFileNormal && !b.anyComputedNormal;

    // Materials and their base colour textures (one slot per image).
    for (std::size_t i = 0; i < g.materials.size(); ++i) {
        model.materials.push_back(materialFrom(g.materials[i]));
        std::string problem;
        materialUvTransform(g.materials[i], &problem);
        if (!problem.empty()) model.warnings.push_back(path + ": material " + std::to_string(i) + ": " + problem);
    }
    std::map<int, int> slotOfImage;
    std::vector<int> imageOfSlot;
    const auto slotForTexture = [&](int textureIndex) {
        if (textureIndex < 0 || std::size_t(textureIndex) >= g.textures.size()) return -1;
        const int image = g.textures[std::size_t(textureIndex)].source;
        if (image < 0 || std::size_t(image) >= g.images.size()) return -1;
        const auto found = slotOfImage.find(image);
        if (found != slotOfImage.end()) return found->second;
        const int slot = int(imageOfSlot.size());
        imageOfSlot.push_back(image);
        slotOfImage.emplace(image, slot);
        return slot;
    };
    if (model.hasUvs) {
        if (!options.textureOverride.empty()) {
            model.texturePaths.push_back(options.textureOverride);
            for (Material& m : model.materials) m.texture = 0;
            if (!b.trianglesOf[0].empty()) {
                Material stand;
                stand.name = "(texture override)";
                stand.texture = 0;
                model.materials.push_back(stand);
                // Faces without a material move to the stand-in (the OBJ rule).
                b.trianglesOf.back() = std::move(b.trianglesOf[0]);
                b.trianglesOf[0].clear();
                std::replace(b.firstUse.begin(), b.firstUse.end(), 0, int(b.trianglesOf.size() - 1));
            }
        } else {
            for (std::size_t i = 0; i < g.materials.size(); ++i) {
                const int textureIndex = g.materials[i].pbrMetallicRoughness.baseColorTexture.index;
                Material& mat = model.materials[i];
                mat.metallicRoughnessTexture = slotForTexture(g.materials[i].pbrMetallicRoughness.metallicRoughnessTexture.index);
                mat.emissiveTexture = slotForTexture(g.materials[i].emissiveTexture.index);
                mat.normalTexture = slotForTexture(g.materials[i].normalTexture.index);
                mat.occlusionTexture = slotForTexture(g.materials[i].occlusionTexture.index);
                mat.texture = slotForTexture(textureIndex);
                if (mat.texture < 0) continue;
                const int sampler = g.textures[std::size_t(textureIndex)].sampler;
                if (sampler < 0) continue; // none: repeat, and the filter of the settings
                if (std::size_t(sampler) >= g.samplers.size())
                    return R::failure(path + ": texture " + std::to_string(textureIndex) + ": sampler " + std::to_string(sampler) +
                                      " does not exist");
                const SamplerModes modes = samplerModes(g.samplers[std::size_t(sampler)]);
                if (!modes.problem.empty())
                    return R::failure(path + ": sampler " + std::to_string(sampler) + ": " + modes.problem);
                if (!modes.note.empty()) model.warnings.push_back(path + ": sampler " + std::to_string(sampler) + ": " + modes.note);
                model.materials[i].wrap = modes.wrap;
                model.materials[i].filter = modes.filter;
            }
            for (int image : imageOfSlot) {
                const tinygltf::Image& img = g.images[std::size_t(image)];
                model.texturePaths.push_back(img.uri.empty() || img.uri.rfind("data:", 0) == 0
                                                 ? path + " (image " + std::to_string(image) + ")"
                                                 : dir + "/" + decodeUri(img.uri));
            }
        }
    }
    model.textures.resize(model.texturePaths.size());
    std::size_t totalBytes = 0;
    for (std::size_t slot = 0; slot < model.textures.size() && options.loadTextures; ++slot) {
        std::string problem;
        Image image;
        const tinygltf::Image* gi = options.textureOverride.empty() ? &g.images[std::size_t(imageOfSlot[slot])] : nullptr;
        if (gi && !gi->image.empty()) { // embedded, decoded by loadImageData
            image.width = gi->width;
            image.height = gi->height;
            image.rgba = gi->image;
        } else if (gi && (gi->uri.empty() || gi->uri.rfind("data:", 0) == 0)) {
            problem = gi->name.empty() ? "the embedded image could not be decoded" : gi->name;
        } else {
            auto loadedImage = loadImage(model.texturePaths[slot]);
            if (loadedImage) image = std::move(loadedImage).value();
            else problem = loadedImage.error();
        }
        if (problem.empty() && totalBytes + image.rgba.size() > limits.maxTextureBytes)
            problem = model.texturePaths[slot] + ": textures would take more than " + std::to_string(limits.maxTextureBytes >> 20) +
                      " MiB in total";
        if (!problem.empty()) {
            if (!options.textureOverride.empty()) return R::failure("texture override: " + problem);
            model.warnings.push_back(path + ": " + problem + "; using the default checkerboard texture");
            model.textures[slot] = defaultCheckerTexture();
            continue;
        }
        totalBytes += image.rgba.size();
        model.textures[slot] = std::move(image);
    }

    // One range per material in order of first use.
    for (const int key : b.firstUse) {
        std::vector<std::uint32_t>& list = b.trianglesOf[std::size_t(key)];
        DrawRange r;
        r.firstIndex = std::uint32_t(model.mesh.indices.size());
        r.indexCount = std::uint32_t(list.size());
        r.material = key - 1;
        r.texture = model.hasUvs && r.material >= 0 ? model.materials[std::size_t(r.material)].texture : -1;
        model.mesh.indices.insert(model.mesh.indices.end(), list.begin(), list.end());
        model.ranges.push_back(r);
    }
    // An animated file's rest pose: skins bound by their joints' rest transforms and the default
    // morph weights (the specification's pose without a clip); the bounds are the rest pose's.
    if (b.animation) {
        b.animation->pose(0.0, -1, model.mesh, true);
        model.animation = std::move(b.animation);
    }
    // Bounds of the drawn vertices (world space), triangles', lines' and points'.
    model.boundsMin = model.boundsMax = !model.mesh.positions.empty() ? model.mesh.positions.front() : model.lineSets.front().positions.front();
    const auto grow = [&](const std::vector<Vec3>& positions) {
        for (const Vec3& p : positions) {
            model.boundsMin = Vec3(std::min(model.boundsMin.x, p.x), std::min(model.boundsMin.y, p.y), std::min(model.boundsMin.z, p.z));
            model.boundsMax = Vec3(std::max(model.boundsMax.x, p.x), std::max(model.boundsMax.y, p.y), std::max(model.boundsMax.z, p.z));
        }
    };
    grow(model.mesh.positions);
    for (const LineSet& l : model.lineSets) grow(l.positions);
    if (!warn.empty()) {
        std::string w = warn;
        while (!w.empty() && w.back() == '\n') w.pop_back();
        model.warnings.push_back(path + ": " + w.substr(0, w.find('\n')));
    }
    return R(std::move(model));
}

} // namespace sr
