// softraster: the headless command (render / bench / report) as a console program.
#include <iostream>
#include <string>
#include <vector>

#include "Platform/Headless/Commands.hpp"

int main(int argc, char** argv) {
    // Arguments are taken as UTF-8 bytes (Linux; on Windows the MinGW runtime passes the ANSI
    // code page: non-ASCII paths need SoftRaster.exe's wide-character entry point).
    std::vector<std::string> args(argv + 1, argv + argc);
    sr::headless::Streams io{std::cout, std::cerr, true};
    const int rc = sr::headless::runHeadless(args, io);
    std::cout.flush();
    return rc;
}
