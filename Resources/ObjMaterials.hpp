// ObjMaterials: reading .mtl files through our FileIO, resolving map_Kd paths as glref does, and loading textures.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "Resources/Model.hpp"
#include "Resources/Result.hpp"
#include "tiny_obj_loader.h"

namespace sr {

// The directory of an OBJ with a trailing '/' ("a/b.obj" -> "a/", "b.obj" -> "./"), as glref's
// dir_of; '\\' is accepted as a separator too (Windows paths).
std::string objDirectory(const std::string& objPath);

// glref's resolve_tex_path: backslashes -> '/', trailing blanks/CR dropped, relative paths joined
// to objDir ("" stays "" = no map). A leading '/' or a drive letter ("C:") is absolute.
std::string resolveTexturePath(const std::string& objDir, std::string name);

// tinyobjloader's MaterialReader, reading each "mtllib" file with readFileBytes (UTF-8 paths,
// size limit) and checking its text like the OBJ's. A missing or unreadable .mtl is a warning
// (the materials it would define stay unknown: faces using them are untextured), never an error.
class MtlFileReader : public tinyobj::MaterialReader {
public:
    MtlFileReader(std::string objDir, const LoadLimits& limits, std::vector<std::string>& warnings)
        : objDir_(std::move(objDir)), limits_(limits), warnings_(warnings) {}
    bool operator()(const std::string& matId, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* matMap, std::string* warn, std::string* err) override;

private:
    std::string objDir_;
    const LoadLimits& limits_;
    std::vector<std::string>& warnings_;
    std::size_t attempts_ = 0; // .mtl files tried; a file naming thousands is not read thousands of times
};

// Fills model.materials, model.textures and model.texturePaths, mirroring glref: textures only
// when the OBJ has uvs; one texture per distinct resolved path; --texture overrides every
// material (and faces without one: returns the material index they must use, else -1).
// A map that cannot be loaded becomes defaultCheckerTexture() plus a warning; an override that
// cannot be loaded is an error.
Result<int> assignMaterials(Model& model, const std::vector<tinyobj::material_t>& materials,
                            const std::string& objPath, const LoadOptions& options, bool anyFaceWithoutMaterial);

} // namespace sr
