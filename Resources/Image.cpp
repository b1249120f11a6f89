// Image decoding through stb_image (from memory, after our own size checks) and image writers.
#include "Resources/Image.hpp"

#include <algorithm>
#include <cstring>

#include "Raster/Frame/FrameBuffer.hpp"
#include "Resources/FileIO.hpp"
#include "stb_image.h"
#include "stb_image_write.h"

namespace sr {

namespace {

// stb_image 2.27 (Debian 12's libstb-dev) trusts the 16 code counts of a JPEG DHT segment: more
// than 256 codes in one table write past stbi__huffman's 257-byte size[] and 256-byte values[]
// (fixed upstream in 2.28 with "if (n > 256) bad DHT header"). stb finds markers wherever an
// 0xFF byte leads to one (it resynchronises byte by byte), so every FF C4 in the file is parsed
// here as stb would parse a DHT segment, with stb's rule that bytes past the end read as 0.
// Returns the offending code count, or 0 when every table is within 256.
int oversizedJpegHuffmanTable(const unsigned char* data, std::size_t size) {
    std::size_t soi = 0; // stb's SOI test: 0xFF, any number of 0xFF fill bytes, 0xD8
    while (soi < size && data[soi] == 0xFF) ++soi;
    if (soi < 1 || soi >= size || data[soi] != 0xD8) return 0; // not a JPEG
    const auto at = [&](std::size_t i) -> int { return i < size ? data[i] : 0; };
    for (std::size_t m = 2; m + 1 < size; ++m) {
        if (data[m] != 0xFF || data[m + 1] != 0xC4) continue;
        std::size_t p = m + 2;
        long length = (at(p) << 8 | at(p + 1)) - 2;
        p += 2;
        while (length > 0 && p < size) {
            const int q = at(p++);
            if ((q >> 4) > 1 || (q & 15) > 3) break; // stb stops at a bad table header
            int n = 0;
            for (int i = 0; i < 16; ++i) n += at(p++);
            if (n > 256) return n;
            p += std::size_t(n);
            length -= 17 + n;
        }
    }
    return 0;
}

// stb 2.27 mallocs its JPEG decoder state without clearing it, so a Huffman table that no DHT
// segment defined is whatever the heap held: a scan that selects one reads symbol ids from
// garbage (an out-of-bounds read found by fuzzing; 2.28 bounds the id instead). StbImplementation.cpp
// makes stb's allocations zeroed (a zero table decodes without reading out of bounds); this walk
// turns the case into a clear error first. It follows the marker structure as stb reads it:
// segments by their length, each scan's entropy-coded data up to the next marker that is not a
// stuffed byte or a restart, DHT segments recorded as they come. A scan needs the DC tables of
// its components when it codes DC coefficients for the first time (baseline, or progressive
// with Ss = 0 and Ah = 0), and their AC tables when it codes AC coefficients (baseline, or Ss > 0).
// Returns the problem, or "" when every table a scan uses was defined before it.
std::string jpegHuffmanSelectionProblem(const unsigned char* data, std::size_t size) {
    std::size_t p = 0;
    while (p < size && data[p] == 0xFF) ++p;
    if (p < 1 || p >= size || data[p] != 0xD8) return ""; // not a JPEG
    ++p;
    const auto at = [&](std::size_t i) -> unsigned { return i < size ? data[i] : 0u; };
    bool defined[2][4] = {};
    bool progressive = false;
    while (p < size) {
        while (p < size && data[p] != 0xFF) ++p; // stb resynchronises on the next 0xFF
        while (p < size && data[p] == 0xFF) ++p;
        if (p >= size) break;
        const unsigned marker = data[p++];
        if (marker == 0xD9) break;                                               // EOI
        if (marker == 0x00 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue; // no length
        const std::size_t length = at(p) << 8 | at(p + 1);
        if (length < 2) break; // stb refuses the segment
        const std::size_t end = p + length;
        if (marker == 0xC2) progressive = true;
        if (marker == 0xC4) { // DHT: one or more tables
            std::size_t q = p + 2;
            while (q < end && q < size) {
                const unsigned tc = at(q) >> 4, th = at(q) & 15;
                if (tc > 1 || th > 3) return ""; // stb refuses the table itself
                std::size_t codes = 0;
                for (std::size_t i = 1; i <= 16; ++i) codes += at(q + i);
                defined[tc][th] = true;
                q += 17 + codes;
            }
        } else if (marker == 0xDA) { // SOS: check the selectors, then skip the entropy-coded data
            const unsigned components = at(p + 2);
            const std::size_t tail = p + 3 + 2 * std::size_t(components);
            const unsigned ss = at(tail), se = at(tail + 1), ah = at(tail + 2) >> 4;
            const bool needDc = !progressive || (ss == 0 && ah == 0);
            const bool needAc = !progressive || ss > 0 || se > 0;
            for (unsigned c = 0; c < components; ++c) {
                const unsigned dc = at(p + 4 + 2 * c) >> 4, ac = at(p + 4 + 2 * c) & 15;
                if (dc > 3 || ac > 3) return ""; // stb refuses the scan header itself
                if ((needDc && !defined[0][dc]) || (needAc && !defined[1][ac])) {
                    const bool dcMissing = needDc && !defined[0][dc];
                    return std::string("corrupt JPEG (a scan uses Huffman table ") + (dcMissing ? "DC " : "AC ") +
                           std::to_string(dcMissing ? dc : ac) + ", which no DHT segment before it defines)";
                }
            }
            std::size_t q = end;
            while (q + 1 < size && !(data[q] == 0xFF && data[q + 1] != 0x00 && data[q + 1] != 0xFF &&
                                     (data[q + 1] < 0xD0 || data[q + 1] > 0xD7)))
                ++q;
            p = q;
            continue;
        }
        p = end;
    }
    return "";
}

// Two stb 2.27 PNM bugs (both fixed upstream in 2.28) are refused before stb reads the header:
//  - the numbers (width, height, max value) are read into an int with no overflow check;
//  - a 16-bit file (max value > 255) is converted to RGBA with the 8-bit converter, and the
//    16 -> 8 bit step then reads twice the buffer's size (a heap overflow, for every such file).
// Tokenises a binary P5/P6 header as stb does (whitespace, '#' comments to the end of the line).
// Returns the problem, or "" when stb may read the file.
std::string pnmHeaderProblem(const unsigned char* data, std::size_t size) {
    if (size < 2 || data[0] != 'P' || (data[1] != '5' && data[1] != '6')) return "";
    const auto space = [](unsigned char c) { return c == ' ' || (c >= '\t' && c <= '\r'); };
    std::size_t p = 2;
    std::int64_t value = 0;
    for (int number = 0; number < 3; ++number) {
        for (;;) { // whitespace, then a comment to the end of its line, repeatedly
            while (p < size && space(data[p])) ++p;
            if (p >= size || data[p] != '#') break;
            while (p < size && data[p] != '\n' && data[p] != '\r') ++p;
        }
        value = 0;
        for (; p < size && data[p] >= '0' && data[p] <= '9'; ++p) {
            value = value * 10 + (data[p] - '0');
            if (value > INT32_MAX) return "corrupt PNM header (a number above " + std::to_string(INT32_MAX) + ")";
        }
    }
    if (value > 255) return "16-bit PNM (max value " + std::to_string(value) + ") is not supported, use 8 bits";
    return "";
}

// stb 2.27 grows its IDAT buffer to a chunk's claimed length before reading the chunk, so a
// 100-byte PNG claiming a 2 GiB chunk allocates 2 GiB. Walks the chunks as stb does (length,
// type, data, CRC; up to IEND) and returns the problem when a chunk claims more bytes than the
// file has left, or "" when the layout is consistent.
std::string pngChunkProblem(const unsigned char* data, std::size_t size) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (size < 8 || std::memcmp(data, kSignature, 8) != 0) return "";
    std::size_t p = 8;
    while (p + 8 <= size) {
        const std::uint32_t length = std::uint32_t(data[p]) << 24 | std::uint32_t(data[p + 1]) << 16 |
                                     std::uint32_t(data[p + 2]) << 8 | data[p + 3];
        std::string type(reinterpret_cast<const char*>(data + p + 4), 4);
        const std::size_t left = size - (p + 8);
        if (length > left) {
            for (char& c : type)
                if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = '?';
            return "corrupt PNG (chunk '" + type + "' claims " + std::to_string(length) + " bytes, the file has " +
                   std::to_string(left) + " left)";
        }
        if (type == "IEND") break;
        p += 8 + std::size_t(length) + 4; // header, data, CRC
    }
    return "";
}

// stb's failure reason, safe for a one-line message: stb 2.27 copies a PNG chunk's four type
// bytes from the file into "XXXX PNG chunk not known", so they may be newlines or any byte.
std::string stbReason() {
    std::string reason = stbi_failure_reason() ? stbi_failure_reason() : "unknown error";
    for (char& c : reason)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = '?';
    return reason;
}

} // namespace

Result<Image> decodeImage(const unsigned char* data, std::size_t size, const std::string& name, std::int64_t maxPixels) {
    using R = Result<Image>;
    if (size == 0) return R::failure(name + ": empty file, not an image");
    if (size > std::size_t(INT32_MAX)) return R::failure(name + ": file too large to decode");
    if (const int codes = oversizedJpegHuffmanTable(data, size)) {
        return R::failure(name + ": corrupt JPEG (a Huffman table defines " + std::to_string(codes) +
                          " codes, at most 256 are possible)");
    }
    for (const std::string& problem :
         {jpegHuffmanSelectionProblem(data, size), pnmHeaderProblem(data, size), pngChunkProblem(data, size)})
        if (!problem.empty()) return R::failure(name + ": " + problem);
    int w = 0, h = 0, channels = 0;
    // Read the header first: a PNG claiming 100000 x 100000 must not allocate 40 GB.
    if (!stbi_info_from_memory(data, int(size), &w, &h, &channels)) {
        return R::failure(name + ": not a decodable image (" + stbReason() + ")");
    }
    if (w <= 0 || h <= 0 || w > kMaxImageDimension || h > kMaxImageDimension ||
        std::int64_t(w) * h > std::min(maxPixels, kMaxImagePixels)) {
        return R::failure(name + ": image is " + std::to_string(w) + "x" + std::to_string(h) +
                          ", above the limit of " + std::to_string(kMaxImageDimension) + " per side and " +
                          std::to_string(std::min(maxPixels, kMaxImagePixels)) + " pixels");
    }
    unsigned char* pixels = stbi_load_from_memory(data, int(size), &w, &h, &channels, 4);
    if (!pixels) return R::failure(name + ": decode failed (" + stbReason() + ")");
    Image img;
    img.width = w;
    img.height = h;
    img.rgba.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
    stbi_image_free(pixels);
    return R(std::move(img));
}

Result<Image> loadImage(const std::string& utf8Path) {
    auto bytes = readFileBytes(utf8Path);
    if (!bytes) return Result<Image>::failure(bytes.error());
    return decodeImage(bytes.value().data(), bytes.value().size(), utf8Path);
}

namespace {

void appendToVector(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

std::vector<unsigned char> rgbOf(const Image& image) {
    std::vector<unsigned char> rgb(std::size_t(image.width) * std::size_t(image.height) * 3);
    for (std::size_t i = 0, n = std::size_t(image.width) * std::size_t(image.height); i < n; ++i) {
        std::memcpy(&rgb[i * 3], &image.rgba[i * 4], 3);
    }
    return rgb;
}

} // namespace

Status writeImage(const std::string& utf8Path, const Image& image) {
    if (image.width <= 0 || image.height <= 0) return Status::failure(utf8Path + ": cannot write an empty image");
    const std::string ext = lowerExtension(utf8Path);
    const std::vector<unsigned char> rgb = rgbOf(image);
    std::vector<unsigned char> file;
    if (ext == ".ppm") {
        const std::string header = "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
        file.assign(header.begin(), header.end());
        file.insert(file.end(), rgb.begin(), rgb.end());
    } else if (ext == ".png") {
        if (!stbi_write_png_to_func(appendToVector, &file, image.width, image.height, 3, rgb.data(), image.width * 3)) {
            return Status::failure(utf8Path + ": PNG encoding failed");
        }
    } else if (ext == ".bmp") {
        if (!stbi_write_bmp_to_func(appendToVector, &file, image.width, image.height, 3, rgb.data())) {
            return Status::failure(utf8Path + ": BMP encoding failed");
        }
    } else {
        return Status::failure(utf8Path + ": unknown image extension '" + ext + "' (use .ppm, .png or .bmp)");
    }
    return writeFileBytes(utf8Path, file.data(), file.size());
}

Image toImage(const FrameBuffer& fb) {
    Image img;
    img.width = fb.width();
    img.height = fb.height();
    img.rgba.resize(std::size_t(img.width) * std::size_t(img.height) * 4);
    for (int y = 0; y < img.height; ++y) {
        const Pixel* row = fb.colorRow(y);
        for (int x = 0; x < img.width; ++x) {
            std::uint8_t* t = img.texel(x, y);
            t[0] = pixelR(row[x]);
            t[1] = pixelG(row[x]);
            t[2] = pixelB(row[x]);
            t[3] = 255;
        }
    }
    return img;
}

Status writePfm(const std::string& utf8Path, int width, int height, const float* values) {
    if (width <= 0 || height <= 0) return Status::failure(utf8Path + ": cannot write an empty depth image");
    const std::string header = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    std::vector<unsigned char> file(header.begin(), header.end());
    const std::size_t rowBytes = std::size_t(width) * sizeof(float);
    file.reserve(file.size() + rowBytes * std::size_t(height));
    for (int y = height - 1; y >= 0; --y) { // PFM: bottom row first; floats little-endian (x86)
        const auto* row = reinterpret_cast<const unsigned char*>(values + std::size_t(y) * std::size_t(width));
        file.insert(file.end(), row, row + rowBytes);
    }
    return writeFileBytes(utf8Path, file.data(), file.size());
}

} // namespace sr
