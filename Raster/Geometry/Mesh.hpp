// Mesh: an indexed triangle list in object space, the unit a draw call submits.
#pragma once

#include <cstdint>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"

namespace sr {

// Vertex attributes are parallel arrays (structure of arrays): positions always; normals and
// uvs either empty or one per position. Triangles are index triples into them, counter-
// clockwise for front faces (Math/Conventions.hpp). A stage reads only the arrays it needs.
struct Mesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<Vec2> uvs;
    // Tangent space of a normal map: xyz the unit tangent (along +u), w = +-1 the handedness of
    // the bitangent (B = w N x T, glTF TANGENT's convention). Empty, or one per position.
    std::vector<Vec4> tangents;
    // Vertex colours in linear light (glTF COLOR_0, RGBA; alpha 1 where the file gives RGB): a
    // factor of the base colour. Empty, or one per position.
    std::vector<Color> colours;
    // The file's TEXCOORD_0 and TEXCOORD_1 as stored (u, 1 - v), without any texture transform:
    // for the draws of a material whose maps have addresses of their own (MapAddressing). Both
    // empty, or both one per position.
    std::vector<Vec2> uvSets[2];
    std::vector<std::uint32_t> indices; // 3 per triangle

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return indices.size() / 3; }
    bool hasNormals() const { return !normals.empty() && normals.size() == positions.size(); }
    bool hasUvs() const { return !uvs.empty() && uvs.size() == positions.size(); }
    bool hasTangents() const { return !tangents.empty() && tangents.size() == positions.size(); }
    bool hasColours() const { return !colours.empty() && colours.size() == positions.size(); }
    bool hasUvSets() const {
        return !uvSets[0].empty() && uvSets[0].size() == positions.size() && uvSets[1].size() == positions.size();
    }
};

// Every index refers to an existing vertex and the index count is a multiple of 3. Loaders
// check this for outside input; draws assert it.
bool indicesValid(const Mesh& mesh);

} // namespace sr
