// gltf::Document: the GLB container, the JSON's core schema types, the typed records, and the buffers' bytes.
#include "Resources/Gltf/Document.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>

#include "Resources/FileIO.hpp"

namespace sr::gltf {

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

int componentCount(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    if (type == "MAT4") return 16; // skins' inverse bind matrices (float only: no column padding)
    return 0;
}

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

Result<std::vector<unsigned char>> decodeDataUri(const std::string& uri) {
    using R = Result<std::vector<unsigned char>>;
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos) return R::failure("a data: URI without a comma before its data");
    // Without ";base64" the data is the URI's own characters, percent-decoded (RFC 2397).
    if (comma < 7 || uri.compare(comma - 7, 7, ";base64") != 0) {
        const std::string bytes = decodeUri(uri.substr(comma + 1));
        return R(std::vector<unsigned char>(bytes.begin(), bytes.end()));
    }
    std::vector<unsigned char> out;
    out.reserve((uri.size() - comma) / 4 * 3);
    std::uint32_t acc = 0;
    int bits = 0;
    for (std::size_t i = comma + 1; i < uri.size(); ++i) {
        const char c = uri[i];
        int v;
        if (c >= 'A' && c <= 'Z') v = c - 'A';
        else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
        else if (c >= '0' && c <= '9') v = c - '0' + 52;
        else if (c == '+' || c == '-') v = 62;
        else if (c == '/' || c == '_') v = 63;
        else if (c == '=') break;
        else return R::failure("a data: URI with a character that is not base64");
        acc = (acc << 6) | std::uint32_t(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back((unsigned char)(acc >> bits));
        }
    }
    return R(std::move(out));
}

namespace {

// Types of the glTF 2.0 core properties (the specification's JSON schema, by property name:
// the core schema gives each name one type, "scale" aside: a node's array or a normal
// texture's number; "indices": a primitive's accessor or a sparse accessor's object; "nodes":
// the asset's node objects or a scene's node indices). A
// property of the wrong type makes the file invalid: refused, naming the property.
enum class Kind { String, Uint, Number, Bool, Object, NumberOrNumbers, Numbers, Uints, Objects, Strings };

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
        {"primitives", Kind::Objects}, {"accessors", Kind::Objects}, {"buffers", Kind::Objects},
        {"bufferViews", Kind::Objects}, {"meshes", Kind::Objects}, {"materials", Kind::Objects},
        {"textures", Kind::Objects}, {"images", Kind::Objects}, {"samplers", Kind::Objects}, {"scenes", Kind::Objects},
        {"nodes", Kind::Objects}, {"cameras", Kind::Objects}, {"skins", Kind::Objects}, {"animations", Kind::Objects},
        {"channels", Kind::Objects}, {"targets", Kind::Objects}, {"extensionsUsed", Kind::Strings},
        {"extensionsRequired", Kind::Strings}, {"attributes", Kind::Object},
        {"pbrMetallicRoughness", Kind::Object}, {"normalTexture", Kind::Object}, {"occlusionTexture", Kind::Object},
        {"emissiveTexture", Kind::Object}, {"baseColorTexture", Kind::Object}, {"metallicRoughnessTexture", Kind::Object},
        {"asset", Kind::Object}, {"perspective", Kind::Object}, {"orthographic", Kind::Object}, {"sparse", Kind::Object},
        {"extensions", Kind::Object}};
    return kinds;
}

// An unsigned integer, also when written with a fraction of zero ("4.0": JSON has one number type).
bool isUint(const Json& v) {
    if (v.is_number_unsigned()) return true;
    if (v.is_number_integer()) return v.get<long long>() >= 0;
    if (v.is_number_float()) {
        const double d = v.get<double>();
        return d >= 0.0 && d <= 9007199254740992.0 && d == std::floor(d);
    }
    return false;
}

bool hasKind(const Json& v, Kind k) {
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
    case Kind::Object: return v.is_object();
    case Kind::NumberOrNumbers: return v.is_number() || all([](const Json& e) { return e.is_number(); });
    case Kind::Numbers: return all([](const Json& e) { return e.is_number(); });
    case Kind::Uints: return all([](const Json& e) { return isUint(e); });
    case Kind::Objects: return all([](const Json& e) { return e.is_object(); });
    case Kind::Strings: return all([](const Json& e) { return e.is_string(); });
    }
    return false;
}

const char* kindName(Kind k) {
    switch (k) {
    case Kind::String: return "a string";
    case Kind::Uint: return "an unsigned integer";
    case Kind::Number: return "a number";
    case Kind::Bool: return "true or false";
    case Kind::Object: return "an object";
    case Kind::NumberOrNumbers: return "a number or an array of numbers";
    case Kind::Numbers: return "an array of numbers";
    case Kind::Uints: return "an array of unsigned integers";
    case Kind::Objects: return "an array of objects";
    case Kind::Strings: return "an array of strings";
    }
    return "?";
}

// The first property of the wrong type, as "path: expected KIND", or an empty string. "extras"
// is free-form; each extension's value must be an object (its own schema is not checked); at the
// top level only the core properties are looked into (glTF 1.0 leftovers such as "programs" are
// ignored). ("target" is left out: an unsigned integer in a buffer view, an object in an
// animation channel.)
std::string schemaProblem(const Json& v, const std::string& path, const std::string& parentKey, int depth) {
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
            const bool sparsePart = parentKey == "sparse" && (key == "indices" || key == "values");
            const bool sceneNodes = parentKey == "scenes" && key == "nodes";
            if (sparsePart && !it.value().is_object()) return at + ": expected an object";
            if (sceneNodes && !hasKind(it.value(), Kind::Uints)) return at + ": expected " + kindName(Kind::Uints);
            if (!sparsePart && !sceneNodes && kind != schemaKinds().end() && !hasKind(it.value(), kind->second))
                return at + ": expected " + kindName(kind->second);
            if (key == "extensions") {
                for (auto e = it.value().begin(); e != it.value().end(); ++e)
                    if (!e.value().is_object()) return at + "." + e.key() + ": expected an object";
                continue;
            }
            std::string p = schemaProblem(it.value(), at, key, depth + 1);
            if (!p.empty()) return p;
        }
    } else if (v.is_array()) {
        for (std::size_t i = 0; i < v.size(); ++i) {
            std::string p = schemaProblem(v[i], path + "[" + std::to_string(i) + "]", parentKey, depth + 1);
            if (!p.empty()) return p;
        }
    }
    return {};
}

// Readers of properties whose types the schema check has already proved.
int intOr(const Json& o, const char* key, int fallback) {
    const auto it = o.find(key);
    if (it == o.end() || !it->is_number()) return fallback;
    const double d = it->get<double>();
    return d >= 0.0 && d <= 2147483647.0 ? int(d) : fallback;
}
std::size_t sizeOr(const Json& o, const char* key, std::size_t fallback) {
    const auto it = o.find(key);
    if (it == o.end() || !it->is_number()) return fallback;
    const double d = it->get<double>();
    return d >= 0.0 && d < 1.8e19 ? std::size_t(d) : fallback;
}
double numberOr(const Json& o, const char* key, double fallback) {
    const auto it = o.find(key);
    return it != o.end() && it->is_number() ? it->get<double>() : fallback;
}
bool boolOr(const Json& o, const char* key, bool fallback) {
    const auto it = o.find(key);
    return it != o.end() && it->is_boolean() ? it->get<bool>() : fallback;
}
std::string stringOr(const Json& o, const char* key, const std::string& fallback = {}) {
    const auto it = o.find(key);
    return it != o.end() && it->is_string() ? it->get<std::string>() : fallback;
}
std::vector<double> numbers(const Json& o, const char* key, std::vector<double> fallback = {}) {
    const auto it = o.find(key);
    if (it == o.end() || !it->is_array()) return fallback;
    std::vector<double> out;
    for (const Json& e : *it) out.push_back(e.is_number() ? e.get<double>() : 0.0);
    return out;
}
std::vector<int> ints(const Json& o, const char* key) {
    std::vector<int> out;
    const auto it = o.find(key);
    if (it == o.end() || !it->is_array()) return out;
    for (const Json& e : *it) {
        const double d = e.is_number() ? e.get<double>() : -1.0;
        out.push_back(d >= 0.0 && d <= 2147483647.0 ? int(d) : -1);
    }
    return out;
}
Json objectOr(const Json& o, const char* key) {
    const auto it = o.find(key);
    return it != o.end() && it->is_object() ? *it : Json::object();
}
const Json& arrayOf(const Json& o, const char* key) {
    static const Json kEmpty = Json::array();
    const auto it = o.find(key);
    return it != o.end() && it->is_array() ? *it : kEmpty;
}
std::map<std::string, int> attributeMap(const Json& o) {
    std::map<std::string, int> out;
    if (!o.is_object()) return out;
    for (auto it = o.begin(); it != o.end(); ++it) {
        const double d = it.value().is_number() ? it.value().get<double>() : -1.0;
        out[it.key()] = d >= 0.0 && d <= 2147483647.0 ? int(d) : -1;
    }
    return out;
}

TextureInfo textureInfo(const Json& o, const char* key) {
    TextureInfo t;
    const Json j = objectOr(o, key);
    if (j.empty()) return t;
    t.index = intOr(j, "index", -1);
    t.texCoord = intOr(j, "texCoord", 0);
    t.scale = numberOr(j, "scale", 1.0);
    t.strength = numberOr(j, "strength", 1.0);
    t.extensions = objectOr(j, "extensions");
    return t;
}

// The GLB container (glTF 2.0 "Binary glTF Layout"): the JSON chunk's text and the BIN chunk.
Status splitGlb(const unsigned char* data, std::size_t size, std::string& json, const unsigned char*& bin, std::size_t& binSize) {
    const auto u32 = [&](std::size_t at) {
        std::uint32_t v;
        std::memcpy(&v, data + at, 4);
        return v;
    };
    if (size < 20) return Status::failure("a GLB shorter than its header");
    if (u32(4) != 2) return Status::failure("GLB version " + std::to_string(u32(4)) + " (only 2 is glTF 2.0)");
    // The header's length, never past the bytes there are (nor short of the header itself).
    const std::size_t total = std::min<std::size_t>(u32(8), size);
    if (total < 20) return Status::failure("a GLB whose header gives a length of " + std::to_string(u32(8)) + " bytes");
    const std::size_t jsonLength = u32(12);
    if (u32(16) != 0x4E4F534Au || jsonLength > total - 20) return Status::failure("the GLB's first chunk is not a whole JSON chunk");
    json.assign(reinterpret_cast<const char*>(data + 20), jsonLength);
    const std::size_t next = 20 + ((jsonLength + 3) & ~std::size_t(3));
    bin = nullptr;
    binSize = 0;
    if (next + 8 <= total && u32(next + 4) == 0x004E4942u) {
        const std::size_t length = u32(next);
        if (length > total - next - 8) return Status::failure("the GLB's BIN chunk runs past the end of the file");
        bin = data + next + 8;
        binSize = length;
    }
    return success();
}

} // namespace

Result<Document> parseDocument(const unsigned char* data, std::size_t size, const std::string& dir, const LoadLimits& limits) {
    using R = Result<Document>;
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    std::string text;
    const unsigned char* bin = nullptr;
    std::size_t binSize = 0;
    if (binary) {
        const Status s = splitGlb(data, size, text, bin, binSize);
        if (!s) return R::failure(s.error());
    } else {
        text.assign(reinterpret_cast<const char*>(data), size);
    }
    const Json j = Json::parse(text, nullptr, false);
    if (j.is_discarded()) return R::failure(std::string("not a glTF 2.0 asset: the ") + (binary ? "GLB's JSON chunk" : "file") + " is not JSON");
    if (!j.is_object()) return R::failure("not a glTF 2.0 asset: the JSON is not an object");
    const std::string problem = schemaProblem(j, "", "", 0);
    if (!problem.empty()) return R::failure(problem + " (glTF 2.0 schema)");
    const Json asset = objectOr(j, "asset");
    const std::string version = stringOr(asset, "version");
    if (version.empty()) return R::failure("not a glTF 2.0 asset: no asset.version");
    if (version.rfind("2.", 0) != 0) return R::failure("glTF version " + version + " (only 2.x is read)");

    Document d;
    d.defaultScene = intOr(j, "scene", -1);
    for (const Json& e : arrayOf(j, "extensionsUsed"))
        if (e.is_string()) d.extensionsUsed.push_back(e.get<std::string>());
    for (const Json& e : arrayOf(j, "extensionsRequired"))
        if (e.is_string()) d.extensionsRequired.push_back(e.get<std::string>());
    const Json rootExtensions = objectOr(j, "extensions");

    for (const Json& o : arrayOf(j, "accessors")) {
        Accessor a;
        a.bufferView = intOr(o, "bufferView", -1);
        a.byteOffset = sizeOr(o, "byteOffset", 0);
        a.componentType = intOr(o, "componentType", 0);
        a.normalized = boolOr(o, "normalized", false);
        a.count = sizeOr(o, "count", 0);
        a.type = stringOr(o, "type");
        const Json sparse = objectOr(o, "sparse");
        if (!sparse.empty()) {
            const Json indices = objectOr(sparse, "indices"), values = objectOr(sparse, "values");
            a.sparse.count = sizeOr(sparse, "count", 0);
            a.sparse.indicesBufferView = intOr(indices, "bufferView", -1);
            a.sparse.indicesByteOffset = sizeOr(indices, "byteOffset", 0);
            a.sparse.indicesComponentType = intOr(indices, "componentType", 0);
            a.sparse.valuesBufferView = intOr(values, "bufferView", -1);
            a.sparse.valuesByteOffset = sizeOr(values, "byteOffset", 0);
            if (a.sparse.count == 0) return R::failure("accessor " + std::to_string(d.accessors.size()) + ": sparse.count must be at least 1");
        }
        d.accessors.push_back(a);
    }
    for (const Json& o : arrayOf(j, "bufferViews")) {
        BufferView v;
        v.buffer = intOr(o, "buffer", -1);
        v.byteOffset = sizeOr(o, "byteOffset", 0);
        v.byteLength = sizeOr(o, "byteLength", 0);
        v.byteStride = sizeOr(o, "byteStride", 0);
        v.extensions = objectOr(o, "extensions");
        d.bufferViews.push_back(v);
    }
    std::size_t bufferBytes = 0;
    for (const Json& o : arrayOf(j, "buffers")) {
        Buffer b;
        const std::size_t index = d.buffers.size();
        const std::string name = "buffer " + std::to_string(index);
        b.byteLength = sizeOr(o, "byteLength", 0);
        const std::string uri = stringOr(o, "uri");
        if (uri.rfind("data:", 0) == 0) {
            auto bytes = decodeDataUri(uri);
            if (!bytes) return R::failure(name + ": " + bytes.error());
            b.data = std::move(bytes).value();
            b.source = name + " (a data: URI)";
        } else if (!uri.empty()) {
            // A file that cannot be read (missing, or a URI we do not fetch, http: say) is an
            // error only when something reads the buffer: it is named then.
            const std::string file = dir + "/" + decodeUri(uri);
            auto bytes = readFileBytes(file, limits.maxFileBytes);
            if (bytes) {
                b.data = std::move(bytes).value();
                b.source = file;
            } else {
                b.source = bytes.error();
            }
        } else if (binary && index == 0 && bin) {
            if (b.byteLength > binSize) return R::failure(name + ": byteLength " + std::to_string(b.byteLength) +
                                                          " is more than the GLB's BIN chunk (" + std::to_string(binSize) + " bytes)");
            b.data.assign(bin, bin + binSize);
            b.source = "the GLB's BIN chunk";
        } else {
            b.source = name + " (no uri: its bytes are not in the file)";
        }
        if (!b.data.empty() && b.data.size() < b.byteLength)
            return R::failure(name + ": byteLength " + std::to_string(b.byteLength) + " but " + std::to_string(b.data.size()) + " bytes");
        bufferBytes += b.data.size();
        if (bufferBytes > limits.maxMemoryBytes)
            return R::failure("the model's buffers would take more than " + std::to_string(limits.maxMemoryBytes >> 20) + " MiB");
        d.buffers.push_back(std::move(b));
    }
    for (const Json& o : arrayOf(j, "images")) {
        Image im;
        im.name = stringOr(o, "name");
        im.uri = stringOr(o, "uri");
        im.mimeType = stringOr(o, "mimeType");
        im.bufferView = intOr(o, "bufferView", -1);
        d.images.push_back(im);
    }
    for (const Json& o : arrayOf(j, "samplers")) {
        Sampler s;
        s.minFilter = intOr(o, "minFilter", -1);
        s.magFilter = intOr(o, "magFilter", -1);
        s.wrapS = intOr(o, "wrapS", 10497);
        s.wrapT = intOr(o, "wrapT", 10497);
        d.samplers.push_back(s);
    }
    for (const Json& o : arrayOf(j, "textures")) {
        Texture t;
        t.source = intOr(o, "source", -1);
        t.sampler = intOr(o, "sampler", -1);
        t.extensions = objectOr(o, "extensions");
        d.textures.push_back(t);
    }
    for (const Json& o : arrayOf(j, "materials")) {
        Material m;
        m.name = stringOr(o, "name");
        const Json pbr = objectOr(o, "pbrMetallicRoughness");
        m.pbrMetallicRoughness.baseColorFactor = numbers(pbr, "baseColorFactor", {1, 1, 1, 1});
        m.pbrMetallicRoughness.metallicFactor = numberOr(pbr, "metallicFactor", 1.0);
        m.pbrMetallicRoughness.roughnessFactor = numberOr(pbr, "roughnessFactor", 1.0);
        m.pbrMetallicRoughness.baseColorTexture = textureInfo(pbr, "baseColorTexture");
        m.pbrMetallicRoughness.metallicRoughnessTexture = textureInfo(pbr, "metallicRoughnessTexture");
        m.normalTexture = textureInfo(o, "normalTexture");
        m.occlusionTexture = textureInfo(o, "occlusionTexture");
        m.emissiveTexture = textureInfo(o, "emissiveTexture");
        m.emissiveFactor = numbers(o, "emissiveFactor", {0, 0, 0});
        m.alphaMode = stringOr(o, "alphaMode", "OPAQUE");
        m.alphaCutoff = numberOr(o, "alphaCutoff", 0.5);
        m.doubleSided = boolOr(o, "doubleSided", false);
        m.extensions = objectOr(o, "extensions");
        const Json specular = objectOr(m.extensions, "KHR_materials_specular");
        m.specularTexture = textureInfo(specular, "specularTexture");
        m.specularColorTexture = textureInfo(specular, "specularColorTexture");
        const Json clearcoat = objectOr(m.extensions, "KHR_materials_clearcoat");
        m.clearcoatTexture = textureInfo(clearcoat, "clearcoatTexture");
        m.clearcoatRoughnessTexture = textureInfo(clearcoat, "clearcoatRoughnessTexture");
        m.clearcoatNormalTexture = textureInfo(clearcoat, "clearcoatNormalTexture");
        const Json sheen = objectOr(m.extensions, "KHR_materials_sheen");
        m.sheenColorTexture = textureInfo(sheen, "sheenColorTexture");
        m.sheenRoughnessTexture = textureInfo(sheen, "sheenRoughnessTexture");
        if (const auto sg = m.extensions.find("KHR_materials_pbrSpecularGlossiness"); sg != m.extensions.end() && sg->is_object()) {
            m.specularGlossiness.present = true;
            m.pbrMetallicRoughness.baseColorFactor = numbers(*sg, "diffuseFactor", {1, 1, 1, 1});
            m.pbrMetallicRoughness.baseColorTexture = textureInfo(*sg, "diffuseTexture");
            m.pbrMetallicRoughness.metallicRoughnessTexture = TextureInfo{};
            m.specularGlossiness.specularFactor = numbers(*sg, "specularFactor", {1, 1, 1});
            m.specularGlossiness.glossinessFactor = numberOr(*sg, "glossinessFactor", 1.0);
            m.specularColorTexture = m.glossinessTexture = textureInfo(*sg, "specularGlossinessTexture");
        }
        d.materials.push_back(std::move(m));
    }
    for (const Json& o : arrayOf(j, "meshes")) {
        Mesh m;
        m.name = stringOr(o, "name");
        m.weights = numbers(o, "weights");
        for (const Json& p : arrayOf(o, "primitives")) {
            Primitive prim;
            prim.attributes = attributeMap(objectOr(p, "attributes"));
            prim.indices = intOr(p, "indices", -1);
            prim.material = intOr(p, "material", -1);
            prim.mode = intOr(p, "mode", kModeTriangles);
            for (const Json& t : arrayOf(p, "targets")) prim.targets.push_back(attributeMap(t));
            prim.extensions = objectOr(p, "extensions");
            m.primitives.push_back(std::move(prim));
        }
        d.meshes.push_back(std::move(m));
    }
    for (const Json& o : arrayOf(j, "nodes")) {
        Node n;
        n.name = stringOr(o, "name");
        n.camera = intOr(o, "camera", -1);
        n.skin = intOr(o, "skin", -1);
        n.mesh = intOr(o, "mesh", -1);
        n.children = ints(o, "children");
        n.rotation = numbers(o, "rotation");
        n.scale = numbers(o, "scale");
        n.translation = numbers(o, "translation");
        n.matrix = numbers(o, "matrix");
        n.weights = numbers(o, "weights");
        n.extensions = objectOr(o, "extensions");
        d.nodes.push_back(std::move(n));
    }
    for (const Json& o : arrayOf(j, "skins")) {
        Skin s;
        s.inverseBindMatrices = intOr(o, "inverseBindMatrices", -1);
        s.joints = ints(o, "joints");
        d.skins.push_back(std::move(s));
    }
    for (const Json& o : arrayOf(j, "animations")) {
        Animation a;
        a.name = stringOr(o, "name");
        for (const Json& c : arrayOf(o, "channels")) {
            AnimationChannel ch;
            ch.sampler = intOr(c, "sampler", -1);
            const Json target = objectOr(c, "target");
            ch.target_node = intOr(target, "node", -1);
            ch.target_path = stringOr(target, "path");
            const Json targetExtensions = objectOr(target, "extensions");
            ch.pointer = stringOr(objectOr(targetExtensions, "KHR_animation_pointer"), "pointer");
            a.channels.push_back(ch);
        }
        for (const Json& s : arrayOf(o, "samplers")) {
            AnimationSampler sm;
            sm.input = intOr(s, "input", -1);
            sm.output = intOr(s, "output", -1);
            sm.interpolation = stringOr(s, "interpolation", "LINEAR");
            a.samplers.push_back(sm);
        }
        d.animations.push_back(std::move(a));
    }
    for (const Json& o : arrayOf(j, "cameras")) {
        Camera c;
        c.name = stringOr(o, "name");
        c.type = stringOr(o, "type");
        const Json p = objectOr(o, "perspective");
        c.perspective.yfov = numberOr(p, "yfov", 0.0);
        c.perspective.znear = numberOr(p, "znear", 0.0);
        c.perspective.zfar = numberOr(p, "zfar", 0.0);
        c.perspective.aspectRatio = numberOr(p, "aspectRatio", 0.0);
        d.cameras.push_back(c);
    }
    const Json lightsExtension = objectOr(rootExtensions, "KHR_lights_punctual");
    for (const Json& o : arrayOf(lightsExtension, "lights")) {
        Light l;
        if (!o.is_object()) return R::failure("KHR_lights_punctual: each light must be an object");
        l.name = stringOr(o, "name");
        l.type = stringOr(o, "type");
        l.color = numbers(o, "color");
        l.intensity = numberOr(o, "intensity", 1.0);
        l.range = numberOr(o, "range", 0.0);
        const Json spot = objectOr(o, "spot");
        l.spot.innerConeAngle = numberOr(spot, "innerConeAngle", 0.0);
        l.spot.outerConeAngle = numberOr(spot, "outerConeAngle", 0.7853981633974483);
        d.lights.push_back(l);
    }
    const Json variantsExtension = objectOr(rootExtensions, "KHR_materials_variants");
    for (const Json& o : arrayOf(variantsExtension, "variants"))
        d.variants.push_back(o.is_object() ? stringOr(o, "name") : std::string());
    for (const Json& o : arrayOf(j, "scenes")) {
        Scene s;
        s.name = stringOr(o, "name");
        s.nodes = ints(o, "nodes");
        d.scenes.push_back(std::move(s));
    }
    return R(std::move(d));
}

} // namespace sr::gltf
