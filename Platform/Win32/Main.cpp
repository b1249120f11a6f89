// SoftRaster.exe entry point: command line, DPI awareness, and the never-blocking message loop.
#include "Platform/Demo/CommandLine.hpp"
#include "Platform/Win32/Console.hpp"
#include "Platform/Win32/Dpi.hpp"
#include "Platform/Win32/MainWindow.hpp"
#include "Platform/Win32/Win32Include.hpp"

namespace {

// Pumps every pending message. Returns false once WM_QUIT arrives (exitCode is then its value).
bool pumpMessages(int& exitCode) {
    MSG msg;
    while (PeekMessageW(&msg, nullptr, 0, 0, PM_REMOVE)) {
        if (msg.message == WM_QUIT) {
            exitCode = int(msg.wParam);
            return false;
        }
        TranslateMessage(&msg);
        DispatchMessageW(&msg);
    }
    return true;
}

// Renders as fast as messages allow; sleeps in WaitMessage while there is nothing to draw
// (minimised / 0 x 0), so a hidden demo costs no CPU. Stops after maxFrames rendered frames
// when given (then exits with 0 like a user close).
int runMessageLoop(sr::win32::MainWindow& window, long long maxFrames) {
    int exitCode = sr::demo::kExitOk;
    long long frames = 0;
    for (;;) {
        if (window.exists() && window.idle())
            WaitMessage();
        if (!pumpMessages(exitCode))
            return exitCode;
        if (!window.exists() || window.idle())
            continue;
        window.renderFrame();
        if (maxFrames > 0 && ++frames >= maxFrames)
            window.close(); // WM_DESTROY posts WM_QUIT(0)
    }
}

} // namespace

int WINAPI wWinMain(HINSTANCE instance, HINSTANCE, PWSTR, int showCommand) {
    using namespace sr;
    const demo::ParseResult parsed = demo::parseCommandLine(win32::commandLineArguments());
    if (!parsed.ok) {
        // A bad flag: say so on stderr (for scripts) and in a message box (for Explorer users).
        const std::string message = "SoftRaster: " + parsed.error + "\n" + demo::usageText("SoftRaster.exe");
        win32::writeStderr(message);
        win32::showMessageBox(message, /*isError=*/true);
        return demo::kExitUsage;
    }
    if (parsed.options.help) {
        const std::string text = demo::usageText("SoftRaster.exe");
        if (!win32::writeStdout(text))
            win32::showMessageBox(text, /*isError=*/false);
        return demo::kExitOk;
    }

    win32::enableDpiAwareness(); // before any window exists
    win32::MainWindow window;
    if (!window.create(instance, showCommand)) {
        const std::string message = "SoftRaster: could not create the window (error " +
                                    std::to_string(GetLastError()) + ")\n";
        win32::writeStderr(message);
        win32::showMessageBox(message, /*isError=*/true);
        return 1;
    }
    return runMessageLoop(window, parsed.options.frames.value_or(0));
}
