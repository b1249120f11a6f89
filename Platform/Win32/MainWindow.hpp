// The demo's top-level window: owns the FrameBuffer that follows the client size, renders the
// scene with the DemoController's camera and modes, presents it, and shows the help overlay.
#pragma once

#include "Platform/App/DemoController.hpp"
#include "Platform/App/FrameStats.hpp"
#include "Platform/App/Input.hpp"
#include "Platform/App/SceneSetup.hpp"
#include "Platform/Win32/GdiPresenter.hpp"
#include "Platform/Win32/Win32Include.hpp"
#include "Raster/Frame/FrameBuffer.hpp"
#include "Raster/Frame/RenderContext.hpp"

#include <chrono>
#include <functional>
#include <string>

namespace sr::win32 {

class MainWindow {
public:
    // The scene and the controller outlive the window; an animated scene is posed each frame.
    MainWindow(app::LoadedScene& scene, app::DemoController& controller);
    ~MainWindow();
    MainWindow(const MainWindow&) = delete;
    MainWindow& operator=(const MainWindow&) = delete;

    // Registers the window class and creates the (visible) window with a client area of
    // clientWidth x clientHeight pixels (scaled from 96 DPI to the monitor's when scaleForDpi).
    // Returns false on failure.
    bool create(HINSTANCE instance, int showCommand, int clientWidth, int clientHeight, bool scaleForDpi);

    // Render threads (--threads; RenderContext::setThreads clamps, 0 or 1 = the UI thread only).
    // The picture is the same for any count.
    void setThreads(int threads) { context_.setThreads(threads); }
    // K: switches the scene to the model's next material variant (the callback reloads it and
    // says what it did, for the title's status); `current` names the variant shown, if any.
    void setVariantCycler(std::function<std::string()> cycle, std::string current) {
        cycleVariant_ = std::move(cycle);
        variant_ = std::move(current);
    }
    void setVariantName(std::string current) { variant_ = std::move(current); }

    // True while there is nothing to draw into (minimised, or a 0 x 0 client area).
    bool idle() const;

    // Advances the camera by the time since the last frame, draws one frame and presents it.
    void renderFrame();

    // Writes the last rendered frame to a UTF-8 path.
    Status saveFrame(const std::string& utf8Path) const;

    // Closes the window; the loop then receives WM_QUIT with exit code 0.
    void close();

    bool exists() const { return hwnd_ != nullptr; }

private:
    using Clock = std::chrono::steady_clock;

    static LRESULT CALLBACK windowProc(HWND hwnd, UINT msg, WPARAM wParam, LPARAM lParam);
    LRESULT handle(UINT msg, WPARAM wParam, LPARAM lParam);

    void onResize(int clientWidth, int clientHeight);
    void onKeyDown(WPARAM virtualKey, LPARAM flags);
    void draw();          // renders into the framebuffer only
    void present();       // shows the framebuffer (and the help overlay) in the client area
    void drawHelp();      // GDI text over the presented frame
    void screenshot();    // F12
    void updateTitle();
    void setStatus(std::string text);
    static app::Key translateKey(WPARAM virtualKey);

    app::LoadedScene& scene_;
    app::DemoController& controller_;

    HWND hwnd_ = nullptr;
    HDC dc_ = nullptr; // the class is CS_OWNDC: one DC for the window's lifetime
    HFONT helpFont_ = nullptr;
    int clientWidth_ = 0;
    int clientHeight_ = 0;
    bool minimised_ = false;
    FrameBuffer frame_;
    RenderContext context_{frame_};
    GdiPresenter presenter_;

    // Mouse drag (left button held): the last cursor position in client pixels.
    bool dragging_ = false;
    int lastMouseX_ = 0, lastMouseY_ = 0;

    // Title bar: statistics, a short-lived status message (e.g. where a screenshot went).
    app::FrameStats stats_;
    Clock::time_point lastFrame_{};
    bool haveLastFrame_ = false;
    std::string status_;
    std::function<std::string()> cycleVariant_;
    std::string variant_; // the material variant drawn (the title shows it); empty: the file's own materials
    Clock::time_point statusUntil_{};
    int screenshotCounter_ = 0;
    std::wstring helpText_;
};

} // namespace sr::win32
