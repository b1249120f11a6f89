// Helpers for the OBJ loader tests: a fresh temporary directory per test and small file writers.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "Resources/Image.hpp"

namespace sr::objtest {

// An empty directory <temp>/softraster-obj-tests/<name>, as a UTF-8 string with '/' separators.
inline std::string freshDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / "softraster-obj-tests" / std::filesystem::u8path(name);
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    std::filesystem::create_directories(dir);
    std::string s = dir.u8string();
    for (char& c : s)
        if (c == '\\') c = '/';
    return s;
}

inline std::string writeText(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream out(std::filesystem::u8path(path), std::ios::binary);
    out << text;
    return path;
}

// A w x h RGBA image whose texel (x, y) is (x*40, y*40, 7, 255): rows distinguishable.
inline Image rampImage(int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.rgba.resize(std::size_t(w) * std::size_t(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* t = img.texel(x, y);
            t[0] = std::uint8_t(x * 40);
            t[1] = std::uint8_t(y * 40);
            t[2] = 7;
            t[3] = 255;
        }
    return img;
}

inline bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

} // namespace sr::objtest
