// gltf codecs: the encodings a glTF file may use, each one small unit around its maintained library (meshoptimizer, Draco, libwebp, libavif).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "Resources/Gltf/Accessors.hpp"
#include "Resources/Gltf/Document.hpp"
#include "Resources/Image.hpp"
#include "Resources/Result.hpp"

namespace sr::gltf {

// Meshopt.cpp: a buffer view compressed by EXT_meshopt_compression or KHR_meshopt_compression
// (`ext`: the extension's object: buffer, byteOffset, byteLength, byteStride, count, mode
// ATTRIBUTES / TRIANGLES / INDICES, filter NONE / OCTAHEDRAL / QUATERNION / EXPONENTIAL),
// decoded with libmeshoptimizer into count x byteStride bytes. Errors start with `what`.
Result<std::vector<unsigned char>> decodeMeshoptView(const Document& doc, const Json& ext, const std::string& what);

// Draco.cpp: a primitive's KHR_draco_mesh_compression (`ext`: bufferView, attributes: name ->
// Draco attribute id) decoded with Draco; each of the primitive's attributes that Draco holds,
// and its indices, handed to `accessors` in the accessors' own types. Counts are checked against
// the accessors (a file whose accessors disagree with its Draco stream is refused).
Status decodeDracoPrimitive(const Document& doc, const Primitive& prim, const Json& ext, Accessors& accessors,
                            const std::string& what);

// Webp.cpp: true when the bytes are a WebP file (RIFF....WEBP).
bool isWebp(const unsigned char* data, std::size_t size);
// A WebP image (lossy or lossless, with or without alpha) as RGBA8, top row first, within the
// image limits of Image.hpp. Errors name `name`.
Result<sr::Image> decodeWebp(const unsigned char* data, std::size_t size, const std::string& name);

// Avif.cpp: true when the bytes are an AVIF file (ISO-BMFF, brand avif or avis); whether this
// build decodes AVIF (the Linux build, with Debian's libavif: SR_HAVE_AVIF); an AVIF image as
// RGBA8, top row first, within the image limits (a build without libavif: an error saying so).
bool isAvif(const unsigned char* data, std::size_t size);
bool avifSupported();
Result<sr::Image> decodeAvif(const unsigned char* data, std::size_t size, const std::string& name);

} // namespace sr::gltf
