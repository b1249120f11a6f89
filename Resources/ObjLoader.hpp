// ObjLoader: loads a Wavefront OBJ (+ MTL + textures) into a Model exactly as the llvmpipe reference (glref) does.
#pragma once

#include <cstddef>
#include <string>

#include "Resources/Model.hpp"
#include "Resources/Result.hpp"

namespace sr {

// Loads the OBJ at a UTF-8 path. Mirrors shared/tools/llvmpipe-ref/glref.cpp's load_mesh:
//  - tinyobjloader (2.0.0rc10) with triangulate = true; triangles read in file order (shape by
//    shape, face by face, vertices in OBJ order); vertices de-duplicated by their (v, vn, vt) triple;
//  - a face-vertex's 'vn' is normalised in double; without one (or with a zero 'vn') the normal is
//    the area-weighted vertex normal (sum of (p1-p0)x(p2-p0) over the triangles using that
//    position, normalised in double; zero -> (0,0,1));
//  - uvs only if the file has any 'vt'; a face-vertex without one gets (0,0);
//  - map_Kd per material (resolved as glref), and each material's Kd, Ks and Ns (Model.hpp).
// Draw order: ONE draw range per material (faces without one share the material -1 range).
// Ranges come in the order of each material's first face in the file; inside a range the faces
// keep their file order. Vertices are numbered in file order of first use.
// The load and the draws are linear in the faces whatever the material order (a checkerboard of
// two materials is two ranges, not one per quad). The image can differ from file order (and from
// glref, which draws runs of faces sharing a texture and material in file order) only where two
// faces of different materials give the SAME depth at a pixel centre: the depth test
// (reversed-Z, GREATER) keeps the first drawn, i.e. the face whose material appears first in the
// file (faces of one material tie in file order). A model whose faces of each material already
// form one run of the file draws exactly in file order (the bunny); the spider's runs are one
// range per material, so it draws in file order too (its images are among scripts/perf-identity.sh's).
// Deliberate differences from glref: a texture that cannot be loaded gets defaultCheckerTexture()
// (glref draws those faces grey), a UTF-8 BOM is skipped (glref would lose the first line), what
// glref would read out of bounds or silently misread (bad indices, "nan" coordinates) is an
// error, and the draw order above. Every failure is one line naming the file (and "path:LINE:"
// where a line is known).
Result<Model> loadObj(const std::string& utf8Path, const LoadOptions& options = {});

// The same from OBJ text already in memory (`size` bytes at `data`; the size limit of `options`
// applies). `utf8Path` names the text in messages and locates "mtllib" files and textures, which
// are still read from disk relative to its directory. For fuzzing and for callers that hold the
// file already.
Result<Model> loadObjFromMemory(const unsigned char* data, std::size_t size, const std::string& utf8Path,
                                const LoadOptions& options = {});

} // namespace sr
