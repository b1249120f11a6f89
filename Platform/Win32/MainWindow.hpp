// The demo's top-level window: owns the FrameBuffer that follows the client size and presents it.
#pragma once

#include "Platform/Demo/Input.hpp"
#include "Platform/Win32/GdiPresenter.hpp"
#include "Platform/Win32/Win32Include.hpp"
#include "Raster/FrameBuffer.hpp"

#include <chrono>

namespace sr::win32 {

class MainWindow {
public:
    MainWindow() = default;
    ~MainWindow();
    MainWindow(const MainWindow&) = delete;
    MainWindow& operator=(const MainWindow&) = delete;

    // Registers the window class and creates the (visible) window. Returns false on failure.
    bool create(HINSTANCE instance, int showCommand);

    // True while there is nothing to draw into (minimised, or a 0 x 0 client area).
    bool idle() const;

    // Draws one frame for the current time and presents it.
    void renderFrame();

    // Closes the window; the loop then receives WM_QUIT with exit code 0.
    void close();

    bool exists() const { return hwnd_ != nullptr; }

private:
    static LRESULT CALLBACK windowProc(HWND hwnd, UINT msg, WPARAM wParam, LPARAM lParam);
    LRESULT handle(UINT msg, WPARAM wParam, LPARAM lParam);

    void onResize(int clientWidth, int clientHeight);
    void draw();    // renders into the framebuffer only
    void present(); // shows the framebuffer in the client area
    static demo::Key translateKey(WPARAM virtualKey);

    HWND hwnd_ = nullptr;
    HDC dc_ = nullptr; // the class is CS_OWNDC: one DC for the window's lifetime
    int clientWidth_ = 0;
    int clientHeight_ = 0;
    bool minimised_ = false;
    FrameBuffer frame_;
    GdiPresenter presenter_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

} // namespace sr::win32
