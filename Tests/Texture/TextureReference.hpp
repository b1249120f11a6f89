// The straightforward reference sampler the fast paths of Raster/Texture/TextureSampling.cpp are tested against.
#pragma once

#include "Math/Color.hpp"
#include "Math/Vec.hpp"
#include "Raster/Texture/Texture.hpp"

namespace sr::test {

// The straightforward reference of Texture::sample(): the coordinate policies of Texture.hpp
// restated on their own, then OpenGL 4.5's generic per-texel wrap (table 8.20) and a fetch of
// each texel through Texture's public API (texel(), levelWidth() ...), no specialisation. The fast
// paths (sample / sampleNearest / sampleBilinear / sampleTrilinear) are tested to be
// bit-identical to it (TextureFastPathTests.cpp, TextureSamplingTests.cpp, TextureMipTests.cpp).
Color sampleReference(const Texture& texture, Vec2 uv, float lod, TextureFilter filter, WrapMode wrap);
// The same with a wrap mode per axis (a glTF sampler's wrapS and wrapT): each axis wrapped by its own.
Color sampleReference(const Texture& texture, Vec2 uv, float lod, TextureFilter filter, WrapModes wrap);

} // namespace sr::test
