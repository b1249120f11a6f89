// The one translation unit that compiles tinygltf's implementation (Debian libtinygltf-dev with
// nlohmann-json3-dev / vcpkg tinygltf). On Windows tinygltf's implementation includes windows.h
// for its own UTF-8 path helpers (unused: TINYGLTF_NO_FS); no SoftRaster source includes it.
// Its writer code uses std::ofstream even under TINYGLTF_NO_FS, which leaves <fstream> out.
#include <fstream>
#define TINYGLTF_IMPLEMENTATION
#include "Resources/TinyGltf.hpp"
