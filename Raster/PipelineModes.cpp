// Names of the pipeline modes, for the command line, the report and the bench JSON.
#include "Raster/PipelineModes.hpp"

namespace sr {

const char* perspectiveModeName(PerspectiveMode mode) {
    switch (mode) {
    case PerspectiveMode::Exact: return "exact";
    case PerspectiveMode::Span16: return "span16";
    case PerspectiveMode::Span8: return "span8";
    case PerspectiveMode::Affine: return "affine";
    }
    return "?";
}

std::optional<PerspectiveMode> parsePerspectiveMode(std::string_view text) {
    for (PerspectiveMode m : {PerspectiveMode::Exact, PerspectiveMode::Span16, PerspectiveMode::Span8,
                              PerspectiveMode::Affine})
        if (text == perspectiveModeName(m)) return m;
    return std::nullopt;
}

} // namespace sr
