// UTF-8 <-> UTF-16 at the Win32 boundary, writing to std handles or the parent console, message boxes.
#include "Platform/Win32/Console.hpp"

#include "Platform/Win32/Win32Include.hpp"

#include <shellapi.h>

namespace sr::win32 {

namespace {

std::string toUtf8(const wchar_t* text) {
    const int bytes = WideCharToMultiByte(CP_UTF8, 0, text, -1, nullptr, 0, nullptr, nullptr);
    if (bytes <= 1)
        return {};
    std::string out(std::size_t(bytes), '\0');
    WideCharToMultiByte(CP_UTF8, 0, text, -1, out.data(), bytes, nullptr, nullptr);
    out.resize(std::size_t(bytes - 1)); // drop the terminating NUL
    return out;
}

std::wstring toUtf16(const std::string& text) {
    if (text.empty())
        return {};
    const int chars = MultiByteToWideChar(CP_UTF8, 0, text.data(), int(text.size()), nullptr, 0);
    std::wstring out(std::size_t(chars > 0 ? chars : 0), L'\0');
    if (chars > 0)
        MultiByteToWideChar(CP_UTF8, 0, text.data(), int(text.size()), out.data(), chars);
    return out;
}

bool usable(HANDLE h) { return h != nullptr && h != INVALID_HANDLE_VALUE; }

// Writes to a console with WriteConsoleW (correct for any code page), to anything else as UTF-8.
bool writeTo(HANDLE h, const std::string& utf8) {
    DWORD mode = 0;
    if (GetConsoleMode(h, &mode)) {
        const std::wstring wide = toUtf16(utf8);
        DWORD written = 0;
        return WriteConsoleW(h, wide.data(), DWORD(wide.size()), &written, nullptr) != 0;
    }
    DWORD written = 0;
    return WriteFile(h, utf8.data(), DWORD(utf8.size()), &written, nullptr) != 0;
}

// A GUI-subsystem process gets std handles only when its parent redirected them. Otherwise
// borrow the parent's console (cmd.exe, PowerShell) if there is one.
bool writeStd(DWORD which, const std::string& utf8) {
    HANDLE h = GetStdHandle(which);
    if (usable(h) && writeTo(h, utf8))
        return true;
    static const bool attached = AttachConsole(ATTACH_PARENT_PROCESS) != 0;
    if (!attached)
        return false;
    HANDLE console = CreateFileW(L"CONOUT$", GENERIC_READ | GENERIC_WRITE, FILE_SHARE_READ | FILE_SHARE_WRITE,
                                 nullptr, OPEN_EXISTING, 0, nullptr);
    if (!usable(console))
        return false;
    const bool ok = writeTo(console, utf8);
    CloseHandle(console);
    return ok;
}

} // namespace

std::vector<std::string> commandLineArguments() {
    std::vector<std::string> args;
    int argc = 0;
    wchar_t** argv = CommandLineToArgvW(GetCommandLineW(), &argc);
    if (!argv)
        return args;
    for (int i = 1; i < argc; ++i)
        args.push_back(toUtf8(argv[i]));
    LocalFree(argv);
    return args;
}

bool writeStdout(const std::string& utf8) { return writeStd(STD_OUTPUT_HANDLE, utf8); }
bool writeStderr(const std::string& utf8) { return writeStd(STD_ERROR_HANDLE, utf8); }

std::wstring widen(const std::string& utf8) { return toUtf16(utf8); }

void showMessageBox(const std::string& utf8, bool isError) {
    const std::wstring text = toUtf16(utf8);
    MessageBoxW(nullptr, text.c_str(), L"SoftRaster",
                MB_OK | MB_SETFOREGROUND | (isError ? MB_ICONERROR : MB_ICONINFORMATION));
}

} // namespace sr::win32
