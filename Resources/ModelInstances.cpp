// A model's instanced ranges: their vertices in the world, and written out as copies (the stored
// vertices stay, unused).
#include <cstdint>
#include <vector>

#include "Raster/Geometry/Placement.hpp"
#include "Resources/Model.hpp"

namespace sr {

void forEachWorldPosition(const Model& model, const std::function<void(Vec3)>& visit) {
    const std::vector<Vec3>& positions = model.mesh.positions;
    std::vector<std::uint8_t> local(positions.size(), 0);
    for (const DrawRange& r : model.ranges)
        if (!r.instances.empty())
            for (std::uint32_t v = r.firstVertex; v < r.firstVertex + r.vertexCount && v < positions.size(); ++v) local[v] = 1;
    for (std::size_t v = 0; v < positions.size(); ++v)
        if (!local[v]) visit(positions[v]);
    for (const DrawRange& r : model.ranges)
        for (const Mat4& m : r.instances) {
            const Placement place = Placement::of(m);
            for (std::uint32_t v = r.firstVertex; v < r.firstVertex + r.vertexCount && v < positions.size(); ++v)
                visit(place.position(positions[v]));
        }
}

void writeOutInstances(Model& model) {
    Mesh& mesh = model.mesh;
    const bool normals = mesh.hasNormals(), uvs = mesh.hasUvs(), tangents = mesh.hasTangents(), colours = mesh.hasColours(),
               uvSets = mesh.hasUvSets();
    std::vector<DrawRange> ranges;
    std::vector<std::uint32_t> indices;
    for (const DrawRange& r : model.ranges) {
        DrawRange out = r;
        out.instances.clear();
        out.firstVertex = out.vertexCount = 0;
        out.firstIndex = std::uint32_t(indices.size());
        if (r.instances.empty()) {
            indices.insert(indices.end(), mesh.indices.begin() + r.firstIndex, mesh.indices.begin() + r.firstIndex + r.indexCount);
            ranges.push_back(out);
            continue;
        }
        for (const Mat4& m : r.instances) {
            const Placement place = Placement::of(m);
            const auto base = std::uint32_t(mesh.positions.size());
            for (std::uint32_t v = r.firstVertex; v < r.firstVertex + r.vertexCount; ++v) {
                mesh.positions.push_back(place.position(mesh.positions[v]));
                if (normals) mesh.normals.push_back(place.normal(mesh.normals[v]));
                if (uvs) mesh.uvs.push_back(mesh.uvs[v]);
                if (tangents) mesh.tangents.push_back(place.tangent(mesh.tangents[v]));
                if (colours) mesh.colours.push_back(mesh.colours[v]);
                for (std::vector<Vec2>& set : mesh.uvSets)
                    if (uvSets) set.push_back(set[v]);
            }
            for (std::uint32_t k = 0; k < r.indexCount; ++k) indices.push_back(mesh.indices[r.firstIndex + k] - r.firstVertex + base);
        }
        out.indexCount = std::uint32_t(indices.size()) - out.firstIndex;
        ranges.push_back(out);
    }
    mesh.indices = std::move(indices);
    model.ranges = std::move(ranges);
}

} // namespace sr
