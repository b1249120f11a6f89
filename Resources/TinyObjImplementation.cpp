// The one translation unit that compiles tinyobjloader's implementation (Debian libtinyobjloader-dev / vcpkg tinyobjloader).
#define TINYOBJLOADER_IMPLEMENTATION
#include "tiny_obj_loader.h"
