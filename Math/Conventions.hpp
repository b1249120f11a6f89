// Conventions of SoftRaster's math and pipeline: read this first; everything else keeps it true.
#pragma once

#include <cfloat>

// Floating point: IEEE binary32/binary64, every operation rounded on its own (to nearest, ties to
// even). No x87 excess precision (asserted below) and no FMA contraction (the build passes
// -ffp-contract=off, MSVC /fp:precise): the SIMD kernels are bit-identical to the scalar
// reference only because both round each multiply and add the same way.
static_assert(FLT_EVAL_METHOD == 0, "SoftRaster needs float/double evaluated at their own precision (SSE, not x87)");

// World and view space
//  - Right-handed, +Y up. In view space the camera sits at the origin and looks down -Z.
//  - Angles are radians inside the code; degrees only at the user interface (flags, UI text).
//
// Vectors and matrices
//  - Column vectors: p' = M * p. A chain M = P * V * W applies W first.
//  - Mat4 stores its 16 floats in COLUMN-MAJOR order (as OpenGL): element (row r, column c)
//    is m[c * 4 + r]; the translation of an affine matrix lives in m[12], m[13], m[14].
//
// Clip space and depth
//  - Clip space: a point is inside when -w <= x <= w, -w <= y <= w and 0 <= z <= w
//    (Direct3D-style z range, not OpenGL's [-w, w]).
//  - Depth is REVERSED-Z: the near plane maps to z_ndc = 1, the far plane to z_ndc = 0, and an
//    infinite far plane is allowed (z_ndc -> 0 as distance -> infinity). The depth buffer is
//    float32, cleared to 0 (= infinitely far), and the depth test is GREATER (strictly nearer
//    wins; on an exact tie the fragment drawn first stays). Reversed-Z puts the dense part of
//    float's exponent range where 1/z is small, which is the most precise combination known
//    for perspective depth (Reed, "Depth Precision Visualized", NVIDIA 2015).
//
// Screen space
//  - Pixel (0,0) is the top-left pixel of the image; x grows right, y grows DOWN.
//  - Pixel centres are at (x + 0.5, y + 0.5).
//  - Viewport: x_s = (x_ndc + 1) * W / 2, y_s = (1 - y_ndc) * H / 2 (NDC +Y up -> screen down).
//  - Framebuffer rows are stored top row first (a top-down 32-bpp DIB).
//
// Rasterization (Direct3D 10+ rules)
//  - Vertex positions are snapped to fixed point with 8 sub-pixel bits (1/256 pixel).
//  - Coverage is sampled at pixel centres with the top-left fill rule in this y-down space:
//    a centre exactly on an edge is inside only for a left edge or a horizontal top edge.
//  - Front faces are counter-clockwise as the viewer sees the image (on screen, y down, a CCW
//    triangle has a negative (x1-x0)(y2-y0) - (x2-x0)(y1-y0)). Cull modes: none, cull CW,
//    cull CCW.
//
// Non-finite values
//  - Math functions propagate NaN/Inf (IEEE semantics) unless their comment says otherwise;
//    the pipeline drops any primitive with a non-finite vertex before rasterization.
//  - The exceptions, each tested in Tests/Math and documented at its declaration:
//    * normalize (Vec.hpp): zero -> zero; a vector with infinite components -> the unit vector
//      along their signs; any NaN -> all NaN. length() never overflows or underflows.
//    * inverse / affineInverse / normalMatrix (Mat4.hpp): an EMPTY optional for any non-finite
//      input element, for a matrix singular within the rounding of its float elements, and when
//      the inverse would overflow float. A returned inverse is always finite.
//    * determinant (Mat4.hpp): computed in double; +-Inf only when the value exceeds FLT_MAX.
//    * lookAt (Transform.hpp): any non-finite argument -> every element NaN. Degenerate finite
//      input (eye == target, up zero or parallel to the view) gets a deterministic fallback.
//    * perspective / perspectiveInfinite / orthographic: non-finite or out-of-range arguments are
//      programming errors (assert); release builds substitute documented values, so these
//      matrices are ALWAYS finite. far = +Inf is valid (the infinite-far projection).
//    * aspectRatio / viewport: sizes <= 0 (a minimised 0x0 window) give aspect 1 and a finite
//      zero-size viewport, never a division by zero.
//    * packBgra8 / toUnorm8 (Color.hpp): NaN -> 0, +Inf -> 255, -Inf -> 0.
//    * clamp (Vec.hpp, Color.hpp) keeps NaN as NaN; transformPoint divides by a w of 0 (IEEE).

namespace sr {

// Pi, written out once: kPiD in double, kPi its float rounding.
inline constexpr double kPiD = 3.14159265358979323846;
inline constexpr float kPi = float(kPiD);

constexpr float radians(float degrees) { return degrees * (kPi / 180.0f); }
constexpr float degrees(float radians) { return radians * (180.0f / kPi); }

} // namespace sr
