// Whole-file reads/writes through std::filesystem paths built from UTF-8, so Windows gets the
// wide-character file APIs (libstdc++ and MSVC open a filesystem::path with _wfopen there).
#include "Resources/FileIO.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace sr {
namespace fs = std::filesystem;

namespace {
fs::path toPath(const std::string& utf8) {
    // u8path is deprecated in C++20 but is exactly the C++17 way to say "these bytes are UTF-8".
    return fs::u8path(utf8);
}
} // namespace

Result<std::vector<unsigned char>> readFileBytes(const std::string& utf8Path, std::size_t maxBytes) {
    using R = Result<std::vector<unsigned char>>;
    std::error_code ec;
    const fs::path path = toPath(utf8Path);
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) return R::failure(utf8Path + ": no such file");
    if (fs::is_directory(st)) return R::failure(utf8Path + ": is a directory, not a file");
    const auto size = fs::file_size(path, ec);
    if (ec) return R::failure(utf8Path + ": cannot read the file size (" + ec.message() + ")");
    if (size > maxBytes) {
        return R::failure(utf8Path + ": file is " + std::to_string(size) + " bytes, above the limit of " +
                          std::to_string(maxBytes) + " bytes");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) return R::failure(utf8Path + ": cannot open for reading");
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size))) {
        return R::failure(utf8Path + ": read error");
    }
    return R(std::move(bytes));
}

Status writeFileBytes(const std::string& utf8Path, const void* data, std::size_t size) {
    std::ofstream out(toPath(utf8Path), std::ios::binary | std::ios::trunc);
    if (!out) return Status::failure(utf8Path + ": cannot open for writing");
    out.write(static_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) return Status::failure(utf8Path + ": write error");
    return success();
}

std::string parentDirectory(const std::string& path) {
    const auto pos = path.find_last_of("/\\");
    if (pos == std::string::npos) return ".";
    if (pos == 0) return path.substr(0, 1);
    return path.substr(0, pos);
}

std::string lowerExtension(const std::string& path) {
    const auto slash = path.find_last_of("/\\");
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

} // namespace sr
