// Image: 8-bit RGBA pixels in memory; decoding (stb_image) and writing (PPM, PNG, BMP, PFM depth).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "Resources/Result.hpp"

namespace sr {

class FrameBuffer;

// Limits for decoded images: a header that claims more is refused before any allocation.
inline constexpr int kMaxImageDimension = 16384;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(64) << 20; // 64 Mpixel = 256 MiB RGBA

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // width * height * 4 bytes, top row first

    const std::uint8_t* texel(int x, int y) const { return &rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4]; }
    std::uint8_t* texel(int x, int y) { return &rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4]; }
};

// Decodes PNG, JPEG, BMP, TGA, PNM (the stb_image decoders we compile in) into RGBA8, top row
// first. `name` is used in error messages (usually the file path). Header sizes are checked
// against the limits above, and JPEG Huffman tables with more than 256 codes (which make stb
// 2.27 write out of bounds) are refused, before stb_image allocates or decodes anything.
// `maxPixels` lowers the pixel limit (the fuzz target uses it to stay fast).
Result<Image> decodeImage(const unsigned char* data, std::size_t size, const std::string& name,
                          std::int64_t maxPixels = kMaxImagePixels);

// Reads and decodes the file at a UTF-8 path; errors name the file and the reason.
Result<Image> loadImage(const std::string& utf8Path);

// Writes by extension: .ppm (binary P6), .png, .bmp. Alpha is dropped (written opaque).
Status writeImage(const std::string& utf8Path, const Image& image);

// The colour buffer of a framebuffer as an opaque RGBA image.
Image toImage(const FrameBuffer& fb);

// Writes a 1-channel PFM ("Pf", little-endian, scale -1.0) of `values` given top row first;
// the file stores rows bottom-to-top as the PFM format requires.
Status writePfm(const std::string& utf8Path, int width, int height, const float* values);

} // namespace sr
