// Loads a skybox: six cube-map face images from one folder (--skybox DIR).
#pragma once

#include <string>

#include "Raster/Frame/Sky.hpp"
#include "Resources/Result.hpp"

namespace sr {

// The faces px, nx, py, ny, pz, nz of folder `dir` (OpenGL's +X, -X, +Y, -Y, +Z, -Z, used as
// OpenGL samples a cube map: CubeMap in Raster/Frame/Sky.hpp), each a file of that name with one of
// the image extensions loadImage decodes (.png .jpg .jpeg .bmp .tga .ppm .pgm .pnm; the first
// found in that order). Errors, each one line naming the file or the folder: a missing face, a
// face that does not decode, a face that is not square or larger than kMaxSkyboxFace, faces of
// different sizes.
inline constexpr int kMaxSkyboxFace = 4096; // six 4098^2 RGBA8 faces with borders: 403 MB
Result<CubeMap> loadSkybox(const std::string& dir);

} // namespace sr
