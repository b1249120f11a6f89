// Per-monitor DPI awareness through GetProcAddress: degrades to system awareness, then nothing.
#include "Platform/Win32/Dpi.hpp"

namespace sr::win32 {

namespace {

// Looks up a user32 export as a typed function pointer (nullptr when this Windows lacks it).
// The detour through void(*)() is the documented way to convert FARPROC without a
// -Wcast-function-type warning.
template <typename Fn>
Fn user32Function(const char* name) {
    const HMODULE user32 = GetModuleHandleW(L"user32.dll");
    if (!user32)
        return nullptr;
    const FARPROC proc = GetProcAddress(user32, name);
    return reinterpret_cast<Fn>(reinterpret_cast<void (*)()>(proc));
}

} // namespace

DpiMode enableDpiAwareness() {
    using SetContextFn = BOOL(WINAPI*)(DPI_AWARENESS_CONTEXT);
    if (const auto setContext = user32Function<SetContextFn>("SetProcessDpiAwarenessContext")) {
        if (setContext(DPI_AWARENESS_CONTEXT_PER_MONITOR_AWARE_V2))
            return DpiMode::PerMonitorV2;
    }
    using SetAwareFn = BOOL(WINAPI*)();
    if (const auto setAware = user32Function<SetAwareFn>("SetProcessDPIAware")) {
        if (setAware())
            return DpiMode::SystemAware;
    }
    return DpiMode::Unaware;
}

UINT dpiForWindow(HWND hwnd) {
    using GetDpiFn = UINT(WINAPI*)(HWND);
    static const auto getDpiForWindow = user32Function<GetDpiFn>("GetDpiForWindow");
    if (getDpiForWindow && hwnd) {
        const UINT dpi = getDpiForWindow(hwnd);
        if (dpi != 0)
            return dpi;
    }
    UINT dpi = USER_DEFAULT_SCREEN_DPI;
    if (HDC screen = GetDC(nullptr)) {
        const int logPixels = GetDeviceCaps(screen, LOGPIXELSX);
        if (logPixels > 0)
            dpi = UINT(logPixels);
        ReleaseDC(nullptr, screen);
    }
    return dpi;
}

} // namespace sr::win32
