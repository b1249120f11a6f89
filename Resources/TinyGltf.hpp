// tinygltf (Debian libtinygltf-dev / vcpkg tinygltf) as SoftRaster uses it: the same options in every translation unit.
#pragma once

// No file system or image decoding of its own: GltfLoader.cpp gives it our file callbacks (UTF-8
// paths, size limits, no shell expansion) and our image decoder (limits, hardened JPEG tables);
// external images are read by GltfLoader itself. Nothing is ever written.
#define TINYGLTF_NO_FS
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
