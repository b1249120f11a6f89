// The one translation unit that compiles stb_image and stb_image_write (Debian libstb-dev / vcpkg stb).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_NO_HDR // we never load HDR; keeps float decoding paths out
#include "stb_image.h"
#include "stb_image_write.h"
