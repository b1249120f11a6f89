// gltfimport textures: which image each texture shows (EXT_texture_webp, EXT_texture_avif, or a fallback for images we cannot decode), one slot per image, decoded once (PNG, JPEG, WebP, AVIF) within the limits.
#include <algorithm>
#include <map>

#include "Resources/FileIO.hpp"
#include "Resources/Gltf/Codecs.hpp"
#include "Resources/Gltf/Import.hpp"

namespace sr::gltfimport {

namespace {

// The image a texture shows: EXT_texture_webp's source, or EXT_texture_avif's where this build
// decodes AVIF (decoded here); for an image format we cannot decode (KHR_texture_basisu,
// EXT_texture_avif without libavif, any other extension naming a source), the texture's own
// `source` as its fallback; with no fallback, an error naming the texture and the extension.
// -1: the texture names no image.
Result<int> textureImage(const gltf::Document& g, int textureIndex) {
    const gltf::Texture& t = g.textures[std::size_t(textureIndex)];
    for (const char* name : {"EXT_texture_webp", "EXT_texture_avif"}) {
        const auto ext = t.extensions.find(name);
        if (std::string(name) == "EXT_texture_avif" && !gltf::avifSupported()) continue;
        if (ext != t.extensions.end() && ext->contains("source") && (*ext)["source"].is_number_integer())
            return Result<int>((*ext)["source"].get<int>());
    }
    if (t.source >= 0) return Result<int>(t.source);
    for (auto it = t.extensions.begin(); it != t.extensions.end(); ++it)
        if (it.value().is_object() && it.value().contains("source"))
            return Result<int>::failure("texture " + std::to_string(textureIndex) + ": its image is in " + it.key() +
                                        ", which SoftRaster cannot decode, and the texture has no fallback source");
    return Result<int>(-1);
}

// PNG, JPEG (stb_image, hardened), WebP (libwebp) or AVIF (libavif), by the bytes' signature.
Result<Image> decodeAny(const unsigned char* data, std::size_t size, const std::string& name) {
    if (gltf::isWebp(data, size)) return gltf::decodeWebp(data, size, name);
    if (gltf::isAvif(data, size)) return gltf::decodeAvif(data, size, name);
    return decodeImage(data, size, name);
}

} // namespace

Status addTextures(Builder& b, const LoadOptions& options, const std::string& dir) {
    const gltf::Document& g = *b.doc;
    const std::string& path = b.path;
    const LoadLimits& limits = options.limits;
    Model& model = b.model;
    std::map<int, int> slotOfImage;
    std::vector<int> imageOfSlot;
    std::string failure;
    const auto slotForTexture = [&](int textureIndex) {
        if (textureIndex < 0 || std::size_t(textureIndex) >= g.textures.size()) return -1;
        const Result<int> chosen = textureImage(g, textureIndex);
        if (!chosen) {
            if (failure.empty()) failure = chosen.error();
            return -1;
        }
        const int image = chosen.value();
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
                const gltf::Material& gm = g.materials[i];
                const int textureIndex = gm.pbrMetallicRoughness.baseColorTexture.index;
                Material& mat = model.materials[i];
                for (const MapSlot s : kAllMapSlots) mat.maps[s] = slotForTexture(textureInfoOf(gm, s).index);
                mat.texture = slotForTexture(textureIndex);
                if (!failure.empty()) return Status::failure(path + ": " + failure);
                if (mat.texture < 0 && !mat.maps.any()) continue;
                // Every map's sampler, checked; the first map's is the draw's (materialSampler),
                // and where the maps do not share one each reads its own (materialAddressing).
                bool sampled = false;
                const auto check = [&](int texture) -> Status {
                    if (texture < 0) return success();
                    const int sampler = g.textures[std::size_t(texture)].sampler;
                    if (sampler < 0) return success(); // none: repeat, and the filter of the settings
                    if (std::size_t(sampler) >= g.samplers.size())
                        return Status::failure(path + ": texture " + std::to_string(texture) + ": sampler " + std::to_string(sampler) +
                                               " does not exist");
                    const SamplerModes modes = samplerModes(g.samplers[std::size_t(sampler)]);
                    if (!modes.problem.empty()) return Status::failure(path + ": sampler " + std::to_string(sampler) + ": " + modes.problem);
                    sampled = true;
                    return success();
                };
                if (Status s = check(textureIndex); !s) return s;
                for (const MapSlot slot : kAllMapSlots)
                    if (Status s = check(textureInfoOf(gm, slot).index); !s) return s;
                if (sampled) {
                    const SamplerModes modes = materialSampler(g, gm);
                    mat.wrap = modes.wrap;
                    mat.filter = modes.filter;
                }
                mat.addressing = materialAddressing(g, gm, nullptr, b.transformsMove(int(i)));
            }
            for (int image : imageOfSlot) {
                const gltf::Image& img = g.images[std::size_t(image)];
                model.texturePaths.push_back(img.uri.empty() || img.uri.rfind("data:", 0) == 0
                                                 ? path + " (image " + std::to_string(image) + ")"
                                                 : dir + "/" + gltf::decodeUri(img.uri));
            }
        }
    }
    model.textures.resize(model.texturePaths.size());
    std::size_t totalBytes = 0;
    for (std::size_t slot = 0; slot < model.textures.size() && options.loadTextures; ++slot) {
        std::string problem;
        Image image;
        const gltf::Image* gi = options.textureOverride.empty() ? &g.images[std::size_t(imageOfSlot[slot])] : nullptr;
        const std::string& name = model.texturePaths[slot];
        Result<Image> decoded = Result<Image>::failure("");
        if (gi && gi->bufferView >= 0) { // in a buffer (a GLB's images)
            std::size_t offset = 0, length = 0;
            auto bytes = b.accessors->bufferViewBytes(gi->bufferView, offset, length);
            decoded = bytes ? decodeAny(bytes.value()->data() + offset, length, name) : Result<Image>::failure(name + ": " + bytes.error());
        } else if (gi && gi->uri.rfind("data:", 0) == 0) {
            auto bytes = gltf::decodeDataUri(gi->uri);
            decoded = bytes ? decodeAny(bytes.value().data(), bytes.value().size(), name) : Result<Image>::failure(name + ": " + bytes.error());
        } else if (gi && gi->uri.empty()) {
            decoded = Result<Image>::failure(name + ": the image has neither a uri nor a buffer view");
        } else {
            auto bytes = readFileBytes(name, limits.maxFileBytes);
            decoded = bytes ? decodeAny(bytes.value().data(), bytes.value().size(), name) : Result<Image>::failure(bytes.error());
        }
        if (decoded) image = std::move(decoded).value();
        else problem = decoded.error();
        if (problem.empty() && totalBytes + image.rgba.size() > limits.maxTextureBytes)
            problem = name + ": textures would take more than " + std::to_string(limits.maxTextureBytes >> 20) + " MiB in total";
        if (!problem.empty()) {
            if (!options.textureOverride.empty()) return Status::failure("texture override: " + problem);
            model.warnings.push_back(path + ": " + problem + "; using the default checkerboard texture");
            model.textures[slot] = defaultCheckerTexture();
            continue;
        }
        totalBytes += image.rgba.size();
        model.textures[slot] = std::move(image);
    }
    return success();
}

} // namespace sr::gltfimport
