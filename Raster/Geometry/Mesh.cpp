// Mesh validation.
#include "Raster/Geometry/Mesh.hpp"

namespace sr {

bool indicesValid(const Mesh& mesh) {
    if (mesh.indices.size() % 3 != 0) return false;
    for (std::uint32_t i : mesh.indices)
        if (i >= mesh.positions.size()) return false;
    return true;
}

} // namespace sr
