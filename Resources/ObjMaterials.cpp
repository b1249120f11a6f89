// ObjMaterials: .mtl reading via readFileBytes, map_Kd resolution (glref's rules), texture loading with a checkerboard fallback.
#include "Resources/ObjMaterials.hpp"

#include <algorithm>
#include <cmath>
#include <istream>

#include "Resources/FileIO.hpp"
#include "Resources/ObjScan.hpp"

namespace sr {

namespace {

bool isAbsolute(const std::string& path) {
    return (!path.empty() && (path[0] == '/' || path[0] == '\\')) || (path.size() > 1 && path[1] == ':');
}

} // namespace

Image defaultCheckerTexture() {
    Image img;
    img.width = 8;
    img.height = 8;
    img.rgba.resize(8 * 8 * 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            std::uint8_t* t = img.texel(x, y);
            const bool magenta = ((x + y) & 1) == 0;
            t[0] = magenta ? 255 : 0;
            t[1] = 0;
            t[2] = magenta ? 255 : 0;
            t[3] = 255;
        }
    return img;
}

std::string objDirectory(const std::string& objPath) {
    const auto s = objPath.find_last_of("/\\");
    return s == std::string::npos ? std::string("./") : objPath.substr(0, s + 1);
}

std::string resolveTexturePath(const std::string& objDir, std::string name) {
    for (char& ch : name)
        if (ch == '\\') ch = '/';
    while (!name.empty() && (name.back() == ' ' || name.back() == '\r' || name.back() == '\t')) name.pop_back();
    if (name.empty() || isAbsolute(name)) return name;
    return objDir + name;
}

bool MtlFileReader::operator()(const std::string& matId, std::vector<tinyobj::material_t>* materials,
                               std::map<std::string, int>* matMap, std::string* warn, std::string* err) {
    (void)warn;
    std::string file = matId;
    for (char& ch : file)
        if (ch == '\\') ch = '/';
    const std::string path = isAbsolute(file) ? file : objDir_ + file;
    constexpr std::size_t kMaxMtlFiles = 64;
    if (++attempts_ > kMaxMtlFiles) {
        if (attempts_ == kMaxMtlFiles + 1)
            warnings_.push_back(path + ": more than " + std::to_string(kMaxMtlFiles) +
                                " material libraries requested; ignoring the rest");
        return false;
    }
    auto bytes = readFileBytes(path, limits_.maxMtlBytes);
    if (!bytes) {
        warnings_.push_back(bytes.error() + " (material library; its materials are untextured)");
        return false;
    }
    auto text = checkText(bytes.value().data(), bytes.value().size(), path);
    if (!text) {
        warnings_.push_back(text.error() + " (material library ignored)");
        return false;
    }
    const std::size_t count = countMtlMaterials(text.value());
    if (materials->size() + count > limits_.maxMaterials) {
        warnings_.push_back(path + ": " + std::to_string(materials->size() + count) +
                            " materials in total, above the limit of " + std::to_string(limits_.maxMaterials) +
                            " (material library ignored)");
        return false;
    }
    TextStreamBuffer buffer(text.value());
    std::istream in(&buffer);
    std::string mtlWarn;
    tinyobj::LoadMtl(matMap, materials, &in, &mtlWarn, err);
    if (!mtlWarn.empty()) warnings_.push_back(path + ": " + mtlWarn.substr(0, mtlWarn.find('\n')));
    return true;
}

Result<int> assignMaterials(Model& model, const std::vector<tinyobj::material_t>& materials,
                            const std::string& objPath, const LoadOptions& options, bool anyFaceWithoutMaterial) {
    const std::string objDir = objDirectory(objPath);
    model.materials.clear();
    for (const auto& m : materials) {
        Material q;
        q.name = m.name;
        q.fromFile = true;
        q.hasMap = !m.diffuse_texname.empty();
        q.kd = Color{float(m.diffuse[0]), float(m.diffuse[1]), float(m.diffuse[2]), 1.0f};
        q.ks = Color{float(m.specular[0]), float(m.specular[1]), float(m.specular[2]), 1.0f};
        q.shininess = float(m.shininess);
        q.alpha = std::isfinite(m.dissolve) ? std::clamp(float(m.dissolve), 0.0f, 1.0f) : 1.0f; // d, or 1 - Tr
        model.materials.push_back(q);
    }

    // Without 'vt' nothing is textured and no image is read (glref does the same).
    if (!model.hasUvs) {
        if (!options.textureOverride.empty())
            model.warnings.push_back(objPath + ": the OBJ has no texture coordinates; ignoring the texture override " +
                                     options.textureOverride);
        return Result<int>(-1);
    }

    // One slot per distinct resolved path, in material order (glref's tex_for_path).
    std::map<std::string, int> slotOfPath;
    const auto slotFor = [&](const std::string& path) {
        if (path.empty()) return -1;
        const auto it = slotOfPath.find(path);
        if (it != slotOfPath.end()) return it->second;
        model.texturePaths.push_back(path);
        model.textures.emplace_back();
        const int slot = int(model.texturePaths.size()) - 1;
        slotOfPath.emplace(path, slot);
        return slot;
    };

    int overrideMaterial = -1;
    if (!options.textureOverride.empty()) {
        const int slot = slotFor(options.textureOverride);
        for (auto& m : model.materials) m.texture = slot;
        if (anyFaceWithoutMaterial) {
            Material stand;
            stand.name = "(texture override)";
            stand.texture = slot;
            model.materials.push_back(stand);
            overrideMaterial = int(model.materials.size()) - 1;
        }
    } else {
        for (std::size_t i = 0; i < materials.size(); ++i)
            model.materials[i].texture = slotFor(resolveTexturePath(objDir, materials[i].diffuse_texname));
    }
    if (!options.loadTextures) return Result<int>(overrideMaterial);

    // Decode each slot; failures get the checkerboard (or fail the load, for an override).
    std::size_t totalBytes = 0;
    for (std::size_t slot = 0; slot < model.textures.size(); ++slot) {
        const std::string& path = model.texturePaths[slot];
        auto image = loadImage(path);
        std::string problem;
        if (!image) {
            problem = image.error();
        } else if (totalBytes + image.value().rgba.size() > options.limits.maxTextureBytes) {
            problem = path + ": textures would take more than " + std::to_string(options.limits.maxTextureBytes >> 20) +
                      " MiB in total";
        }
        if (!problem.empty()) {
            if (!options.textureOverride.empty()) return Result<int>::failure("texture override: " + problem);
            std::string users;
            for (const auto& m : model.materials)
                if (m.texture == int(slot)) users += (users.empty() ? "'" : ", '") + m.name + "'";
            model.warnings.push_back(objPath + ": material " + users + ": " + problem +
                                     "; using the default checkerboard texture");
            model.textures[slot] = defaultCheckerTexture();
            continue;
        }
        totalBytes += image.value().rgba.size();
        model.textures[slot] = std::move(image).value();
    }
    return Result<int>(overrideMaterial);
}

} // namespace sr
