// The vertex stage of a draw: the program's vertex(), the clip code and the divide per vertex, and
// the key under which a draw's transformed vertices are reused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "Raster/Frame/RenderContext.hpp"
#include "Raster/Geometry/Clipper.hpp"
#include "Raster/Geometry/Viewport.hpp"

namespace sr {
namespace detail {

// The vertex stage is split across lanes only when each lane gets at least this many vertices.
inline constexpr std::size_t kMinVerticesPerLane = 4096;

// The vertex stage for vertices [begin, end): program.vertex, the clip code, and the divide
// wherever it is defined (w > 0); with `snap`, also the snapped position (snapVertex) of each
// usable vertex, for binning.
template <int kVaryings, class Program>
void vertexRange(RenderContext& ctx, const Clipper& clipper, std::size_t begin, std::size_t end, Program& program,
                 bool snap) {
    const int width = ctx.target().width(), height = ctx.target().height();
    for (std::size_t i = begin; i < end; ++i) {
        ClipVertex& cv = ctx.clipVertices[i];
        program.vertex(i, cv);
        const unsigned code = clipper.vertexCode(cv.position);
        ctx.clipCodes[i] = code;
        // Finite with w > 0 (the MinW bit is w - 1e-12 < 0 in double; test w itself).
        const bool usable = !(code & kCodeNonFinite) && cv.position.w > 0.0f;
        ctx.usable[i] = usable;
        if (!usable) continue;
        ScreenVertex& screen = ctx.screenVertices[i];
        writeScreenVertex(cv, width, height, kVaryings, screen);
        if (snap) ctx.snappedVertices[i] = snapVertex(screen);
    }
}

// A distinct address per Program type: the vertex-cache key's program identity.
template <class Program>
inline constexpr char kVertexProgramTag = 0;

// A program whose vertex() also reads per-draw constants (Gouraud: the specular exponent)
// returns them packed in vertexVariant(); the vertex-cache key includes it (0 otherwise).
template <class Program, class = void>
struct HasVertexVariant : std::false_type {};
template <class Program>
struct HasVertexVariant<Program, std::void_t<decltype(std::declval<const Program&>().vertexVariant())>>
    : std::true_type {};
template <class Program>
std::uint64_t vertexVariantOf(const Program& program) {
    if constexpr (HasVertexVariant<Program>::value) return program.vertexVariant();
    else return 0;
}

} // namespace detail
} // namespace sr
