// Per-monitor DPI awareness, loaded at run time so the exe still starts on old Windows and Wine.
#pragma once

#include "Platform/Win32/Win32Include.hpp"

namespace sr::win32 {

// Which awareness the process got (the best the system offers, tried in this order).
enum class DpiMode { PerMonitorV2, SystemAware, Unaware };

// Call before creating any window: SetProcessDpiAwarenessContext(PER_MONITOR_AWARE_V2) when
// user32 exports it (Windows 10 1703+), else SetProcessDPIAware (Vista+), else nothing.
DpiMode enableDpiAwareness();

// DPI of the monitor the window is on (GetDpiForWindow when available, else the screen DC's).
UINT dpiForWindow(HWND hwnd);

} // namespace sr::win32
