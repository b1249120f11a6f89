// softraster: the headless command (render / bench / report) as a console program.
#include <iostream>
#include <string>
#include <vector>

#include "Platform/Headless/Commands.hpp"

namespace {
int run(const std::vector<std::string>& args) {
    sr::headless::Streams io{std::cout, std::cerr, true};
    const int rc = sr::headless::runHeadless(args, io);
    std::cout.flush();
    return rc;
}
} // namespace

#ifdef _WIN32
// Windows: main()'s argv is in the ANSI code page, which cannot hold most non-ASCII paths, so the
// entry point is wmain (MinGW links it with -municode; MSVC picks it by itself) and each UTF-16
// argument is converted to the UTF-8 every other part of SoftRaster expects. No windows.h needed.
namespace {
std::string utf8FromUtf16(const wchar_t* w) {
    std::string out;
    for (; *w; ++w) {
        unsigned long c = static_cast<unsigned long>(*w) & 0xFFFFu;
        if (c >= 0xD800 && c <= 0xDBFF && (static_cast<unsigned long>(w[1]) & 0xFC00u) == 0xDC00) {
            c = 0x10000 + ((c - 0xD800) << 10) + ((static_cast<unsigned long>(w[1]) & 0xFFFFu) - 0xDC00);
            ++w; // a surrogate pair
        } else if (c >= 0xD800 && c <= 0xDFFF) {
            c = 0xFFFD; // a lone surrogate: the replacement character
        }
        if (c < 0x80) {
            out += char(c);
        } else if (c < 0x800) {
            out += char(0xC0 | (c >> 6));
            out += char(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            out += char(0xE0 | (c >> 12));
            out += char(0x80 | ((c >> 6) & 0x3F));
            out += char(0x80 | (c & 0x3F));
        } else {
            out += char(0xF0 | (c >> 18));
            out += char(0x80 | ((c >> 12) & 0x3F));
            out += char(0x80 | ((c >> 6) & 0x3F));
            out += char(0x80 | (c & 0x3F));
        }
    }
    return out;
}
} // namespace

int wmain(int argc, wchar_t** argv) {
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) args.push_back(utf8FromUtf16(argv[i]));
    return run(args);
}
#else
int main(int argc, char** argv) {
    // Arguments are taken as UTF-8 bytes (the Linux convention).
    return run(std::vector<std::string>(argv + 1, argv + argc));
}
#endif
