// ObjScan: a validating pre-pass over OBJ/MTL text before tinyobjloader sees it (encoding, indices, numbers, limits).
#pragma once

#include <cstddef>
#include <streambuf>
#include <string>

#include "Resources/Model.hpp"
#include "Resources/Result.hpp"

namespace sr {

// A text in memory, [begin, end).
struct TextSpan {
    const char* begin = nullptr;
    const char* end = nullptr;
};

// A read-only std::streambuf over a TextSpan (no copy), for tinyobjloader's std::istream input.
class TextStreamBuffer : public std::streambuf {
public:
    explicit TextStreamBuffer(TextSpan t) {
        char* p = const_cast<char*>(t.begin); // get area only: never written through
        setg(p, p, p + (t.end - t.begin));
    }
};

// Refuses what is not 8-bit text: UTF-16/32 (BOM or NUL bytes: "UTF-16 text is not supported, save
// as UTF-8"), images renamed .obj, and binary data (a control byte other than tab, CR, LF, VT, FF,
// Ctrl-Z). On success returns the text with a UTF-8 BOM, if any, removed. Errors name `name`.
Result<TextSpan> checkText(const unsigned char* data, std::size_t size, const std::string& name);

// What the scan counted, for the memory estimate and the loader's cross-checks.
struct ObjScanStats {
    std::size_t positions = 0, normals = 0, texcoords = 0; // v, vn, vt entries
    std::size_t faces = 0;                                  // 'f' lines with >= 3 vertices
    std::size_t triangles = 0;                              // upper bound after triangulation
    std::size_t estimatedBytes = 0;                         // peak memory while loading
};

// Checks every line of an OBJ exactly as tinyobjloader 2.0.0rc10 will tokenise it, so that the
// library never sees an index it would read out of bounds:
//  - v / vn / vt: each coordinate read must be a number tinyobjloader parses ("nan", "inf", "1e",
//    and the misparsed "1.#INF" and "0,5" are errors naming the vertex number);
//  - f: every v/vt/vn index must be nonzero and refer to an entry defined BEFORE the line
//    (positive: <= count so far; negative: count + index >= 0);
//  - counts against `limits` (vertices, triangles, polygon size, estimated memory).
// Errors are one line: "name:LINE: message".
Result<ObjScanStats> scanObj(TextSpan text, const std::string& name, const LoadLimits& limits);

// Kinds of numbered OBJ entries, for messages about the n-th one.
enum class ObjEntry { Position, Normal, TexCoord };

// The 1-based line number of the n-th (0-based) entry of `kind`, or 0 if there is none.
std::size_t lineOfEntry(TextSpan text, ObjEntry kind, std::size_t n);

// Number of "newmtl" lines in an MTL text (tinyobjloader allocates one material_t, ~1 KB, each).
std::size_t countMtlMaterials(TextSpan text);

} // namespace sr
