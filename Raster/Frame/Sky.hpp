// The sky: what a frame shows where no geometry was drawn - a cube map or a procedural gradient.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "Math/Color.hpp"
#include "Math/Vec.hpp"
#include "Raster/Frame/FrameBuffer.hpp"

namespace sr {

class MsaaBuffer;

// Cube faces in OpenGL's order: +X, -X, +Y, -Y, +Z, -Z (file names px, nx, py, ny, pz, nz).
enum class CubeFace { PosX, NegX, PosY, NegY, PosZ, NegZ };
inline constexpr int kCubeFaces = 6;

// A cube map sampled as OpenGL samples one (OpenGL 4.5 core, section 8.13, table 8.19): the
// direction r's largest component picks the face (ties: x, then y, then z) and
//   +X: sc = -rz, tc = -ry     -X: sc = +rz, tc = -ry
//   +Y: sc = +rx, tc = +rz     -Y: sc = +rx, tc = -rz
//   +Z: sc = +rx, tc = -ry     -Z: sc = -rx, tc = -ry
// s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2, ma the major component. Texel column s x N,
// row t x N, row 0 the face image's FIRST (top) row, as the images are given to
// glTexImage2D without flipping. Bilinear (texel centres at +0.5) and seamless, as
// GL_TEXTURE_CUBE_MAP_SEAMLESS: where the 2 x 2 footprint crosses a face edge it takes the
// neighbouring face's texels (each face is stored with a one-texel border copied from its
// neighbours when the map is made; a border corner takes one of its two neighbours' texels).
class CubeMap {
public:
    // Six square faces of one size n >= 1, RGBA8 top row first, in CubeFace order.
    // Preconditions (asserted; release builds get a 1 x 1 magenta map): n in [1, 16384], six
    // non-null pointers.
    static CubeMap fromRgba8(int size, const std::array<const std::uint8_t*, kCubeFaces>& faces);

    int size() const { return size_; }
    // The colour seen along direction r (any length > 0; NaN or zero: face +X's centre).
    // The reference: double arithmetic throughout.
    Color sample(Vec3 r) const;
    // The same texel footprint in float arithmetic, packed as packBgra8 packs (the sky pass's
    // per-pixel path): within one unit per channel of packBgra8(sample(r)) (Tests: SkyTests).
    std::uint32_t samplePacked(float rx, float ry, float rz) const;

private:
    int size_ = 0;
    int stride_ = 0;                        // size + 2
    std::vector<std::uint32_t> texels_;     // per face (size + 2)^2, packed RGBA8 (Texture's packing)
    std::uint32_t texel(int face, int x, int y) const; // x, y in [-1, size]
};

// A vertical gradient by the direction's elevation e = ry / |r|: from `horizon` at e = 0 to
// `zenith` at e = 1 (linear in e), and `ground` below the horizon (e < 0).
struct SkyGradient {
    Color zenith{0.18f, 0.36f, 0.70f, 1.0f};
    Color horizon{0.70f, 0.80f, 0.92f, 1.0f};
    Color ground{0.22f, 0.21f, 0.20f, 1.0f};
    Color sample(Vec3 r) const;
    // The colour at elevation t in [0, 1] (sample's formula above the horizon).
    Color above(float t) const;
};

// What a scene shows behind its geometry: nothing (the clear colour), a gradient or a cube map.
struct Sky {
    enum class Kind { None, Gradient, Cube };
    Kind kind = Kind::None;
    SkyGradient gradient;
    std::shared_ptr<const CubeMap> cube; // Kind::Cube
    bool on() const { return kind != Kind::None; }
    Color sample(Vec3 r) const;
};

// The eye ray through a point of the image: forward + ndcX x right + ndcY x up (ndc in [-1, 1],
// y up; not normalised: the samplers divide by the major axis or the length themselves).
struct ViewRays {
    Vec3 forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};
    Vec3 at(double ndcX, double ndcY) const;
};

// Draws the sky into rows [y0, y1) of fb where the depth is still FrameBuffer::kFarDepth
// (nothing drawn there: no overdraw), one sample per pixel at its centre. Returns the number of
// pixels drawn.
std::uint64_t drawSkyRows(FrameBuffer& fb, const ViewRays& rays, const Sky& sky, int y0, int y1);
// The same for a multisampled target: the colour at each pixel's centre goes to every sample
// of that pixel whose depth is still far (so edges resolve against the sky, not the clear colour).
std::uint64_t drawSkyMsaaRows(MsaaBuffer& target, const ViewRays& rays, const Sky& sky, int y0, int y1);

} // namespace sr
