// Vertex records passed between pipeline stages (clip space -> screen space -> triangle setup).
#pragma once

#include <array>

#include "Math/Vec.hpp"

namespace sr {

// Most float varyings a vertex carries (e.g. world position 3 + normal 3 + uv 2 + colour 4,
// or Gouraud's ambient+diffuse and specular terms). Only the first `varyingCount` of a draw
// are read by any stage: nothing interpolates what no stage reads.
inline constexpr int kMaxVaryings = 16;

using Varyings = std::array<float, kMaxVaryings>;

// After the vertex transform: homogeneous clip-space position (Math/Conventions.hpp: inside
// when -w <= x, y <= w and 0 <= z <= w) and the raw varyings.
struct ClipVertex {
    Vec4 position;
    Varyings varyings{};
};

// After the perspective divide and viewport transform: screen position in pixels (y down,
// pixel centres at +0.5), z = reversed-Z depth z_clip / w_clip in [0, 1], invW = 1 / w_clip,
// and the varyings as they were in clip space (NOT divided by w; setup does that).
struct ScreenVertex {
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
    float invW = 1.0f;
    Varyings varyings{};
};

} // namespace sr
