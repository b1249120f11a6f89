// Placement: the normal matrix and handedness of a mesh-to-world transform.
#include "Raster/Geometry/Placement.hpp"

namespace sr {

Placement Placement::of(const Mat4& toWorld) {
    Placement p;
    p.toWorld = toWorld;
    // a[r][c] of the upper 3x3 (Mat4 is column-major: m[c * 4 + r]).
    const auto a = [&](int r, int c) { return double(toWorld.m[c * 4 + r]); };
    // Cofactor matrix, in double: the rows of det x the inverse transpose.
    double cof[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[r][c] = a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1);
        }
    const double det = a(0, 0) * cof[0][0] + a(0, 1) * cof[0][1] + a(0, 2) * cof[0][2];
    const double sign = det < 0.0 ? -1.0 : 1.0;
    p.handedness = float(sign);
    for (int r = 0; r < 3; ++r) p.normalRows[r] = Vec3(float(cof[r][0] * sign), float(cof[r][1] * sign), float(cof[r][2] * sign));
    return p;
}

} // namespace sr
