// Whole-file reads and writes with UTF-8 paths (wide-character file APIs on Windows) and limits.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "Resources/Result.hpp"

namespace sr {

// Largest file any loader reads into memory (a model or an image). Larger files are refused
// with a clear error instead of exhausting memory.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t(512) << 20; // 512 MiB

// Reads the whole file at `utf8Path`. Fails (naming the path) when it does not exist, is a
// directory, cannot be read, or is larger than maxBytes.
Result<std::vector<unsigned char>> readFileBytes(const std::string& utf8Path,
                                                 std::size_t maxBytes = kMaxInputFileBytes);

// Writes `size` bytes to `utf8Path` (created or truncated). Fails naming the path.
Status writeFileBytes(const std::string& utf8Path, const void* data, std::size_t size);

// The directory part of a path ("a/b/c.obj" -> "a/b", "c.obj" -> "."), '/' and '\\' both
// accepted as separators.
std::string parentDirectory(const std::string& path);

// Lower-cased extension including the dot ("x/Y.PNG" -> ".png"; none -> "").
std::string lowerExtension(const std::string& path);

} // namespace sr
