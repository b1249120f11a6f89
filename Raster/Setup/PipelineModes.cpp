// Names of the pipeline modes, for the command line, the report and the bench JSON.
#include "Raster/Setup/PipelineModes.hpp"

namespace sr {

const char* perspectiveModeName(PerspectiveMode mode) {
    switch (mode) {
    case PerspectiveMode::Exact: return "exact";
    case PerspectiveMode::Affine: return "affine";
    }
    return "?";
}

std::optional<PerspectiveMode> parsePerspectiveMode(std::string_view text) {
    for (PerspectiveMode m : {PerspectiveMode::Exact, PerspectiveMode::Affine})
        if (text == perspectiveModeName(m)) return m;
    return std::nullopt;
}

bool isRetiredPerspectiveMode(std::string_view text) { return text == "span16" || text == "span8"; }

} // namespace sr
