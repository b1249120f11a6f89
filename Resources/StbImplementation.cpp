// The one translation unit that compiles stb_image and stb_image_write (Debian libstb-dev / vcpkg stb).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
// Only the formats textures come in: GIF, PSD, PIC and HDR decoders stay out (less code that
// reads untrusted bytes; stb 2.27's GIF and PSD decoders have known out-of-bounds bugs).
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_ONLY_PNM
// Zeroed allocations: stb 2.27 does not clear its JPEG decoder state, and a Huffman table that no
// DHT segment defined would otherwise be read from stale heap bytes (see Image.cpp).
#include <cstdlib>
#define STBI_MALLOC(size) std::calloc(1, size)
#define STBI_REALLOC(pointer, size) std::realloc(pointer, size)
#define STBI_FREE(pointer) std::free(pointer)
#include "stb_image.h"
#include "stb_image_write.h"
