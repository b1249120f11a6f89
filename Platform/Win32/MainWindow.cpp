// The demo window: class registration, message handling (size, paint, keys, mouse, DPI),
// the per-frame render through sr_app, presenting, the help overlay and the title bar.
#include "Platform/Win32/MainWindow.hpp"

#include "Platform/App/DepthView.hpp"
#include "Platform/Win32/Console.hpp"
#include "Platform/Win32/Dpi.hpp"

#include <algorithm>
#include <ctime>

namespace sr::win32 {

namespace {

constexpr wchar_t kClassName[] = L"SoftRasterMainWindow";
constexpr DWORD kStyle = WS_OVERLAPPEDWINDOW;
constexpr DWORD kExStyle = 0;
constexpr double kStatusSeconds = 4.0; // how long a status message stays in the title

// The help overlay's text: the shared key list, one key per line.
std::wstring helpText() {
    std::string text = "SoftRaster keys (F1 hides this)\n";
    for (const app::KeyHelp& k : app::kKeyHelp)
        text += std::string(k.keys) + "\t" + k.what + "\n";
    return widen(text);
}

} // namespace

MainWindow::MainWindow(app::LoadedScene& scene, app::DemoController& controller)
    : scene_(scene), controller_(controller), helpText_(helpText()) {}

MainWindow::~MainWindow() {
    if (hwnd_)
        DestroyWindow(hwnd_);
    if (helpFont_)
        DeleteObject(helpFont_);
}

bool MainWindow::create(HINSTANCE instance, int showCommand, int clientWidth, int clientHeight, bool scaleForDpi) {
    WNDCLASSEXW wc{};
    wc.cbSize = sizeof(wc);
    // CS_OWNDC: a private DC kept for the window's lifetime (no GetDC/ReleaseDC per frame).
    // CS_HREDRAW | CS_VREDRAW: a resize repaints the whole client area.
    wc.style = CS_OWNDC | CS_HREDRAW | CS_VREDRAW;
    wc.lpfnWndProc = &MainWindow::windowProc;
    wc.hInstance = instance;
    wc.hCursor = LoadCursorW(nullptr, MAKEINTRESOURCEW(32512)); // IDC_ARROW
    wc.hIcon = LoadIconW(nullptr, MAKEINTRESOURCEW(32512));     // IDI_APPLICATION
    wc.hbrBackground = nullptr; // every pixel is ours: no background erase, no flicker
    wc.lpszClassName = kClassName;
    if (!RegisterClassExW(&wc) && GetLastError() != ERROR_CLASS_ALREADY_EXISTS)
        return false;

    // The window rectangle whose client area has the asked size (scaled to the DPI if asked).
    const UINT dpi = dpiForWindow(nullptr);
    const int w = scaleForDpi ? MulDiv(clientWidth, int(dpi), 96) : clientWidth;
    const int h = scaleForDpi ? MulDiv(clientHeight, int(dpi), 96) : clientHeight;
    RECT r{0, 0, w, h};
    AdjustWindowRectEx(&r, kStyle, FALSE, kExStyle);

    const std::wstring title = widen(app::windowTitle(stats_, context_.threads(), scene_.scene.triangleCount(), controller_.modeSummary()));
    hwnd_ = CreateWindowExW(kExStyle, kClassName, title.c_str(), kStyle, CW_USEDEFAULT, CW_USEDEFAULT,
                            r.right - r.left, r.bottom - r.top, nullptr, nullptr, instance, this);
    if (!hwnd_)
        return false;
    dc_ = GetDC(hwnd_);
    helpFont_ = CreateFontW(-MulDiv(10, int(dpiForWindow(hwnd_)), 72), 0, 0, 0, FW_NORMAL, FALSE, FALSE, FALSE,
                            DEFAULT_CHARSET, OUT_DEFAULT_PRECIS, CLIP_DEFAULT_PRECIS, CLEARTYPE_QUALITY,
                            FIXED_PITCH | FF_MODERN, L"Consolas");
    ShowWindow(hwnd_, showCommand);
    UpdateWindow(hwnd_);
    return true;
}

bool MainWindow::idle() const { return minimised_ || frame_.empty(); }

void MainWindow::renderFrame() {
    // Frame time = time since the previous frame (the controller clamps long stalls).
    const Clock::time_point now = Clock::now();
    const double dt = haveLastFrame_ ? std::chrono::duration<double>(now - lastFrame_).count() : 0.0;
    lastFrame_ = now;
    haveLastFrame_ = true;

    controller_.update(dt);
    const Clock::time_point drawStart = Clock::now();
    draw();
    controller_.frameRendered(std::chrono::duration<double, std::milli>(Clock::now() - drawStart).count()); // --quality auto
    present();
    if (stats_.addFrame(dt) || (!status_.empty() && now >= statusUntil_))
        updateTitle();
}

Status MainWindow::saveFrame(const std::string& utf8Path) const { return app::saveScreenshot(frame_, utf8Path); }

void MainWindow::close() {
    if (hwnd_)
        DestroyWindow(hwnd_);
}

void MainWindow::draw() {
    if (frame_.empty())
        return;
    context_.stats = {};
    if (controller_.animated()) {
        app::poseScene(scene_, controller_.animationTime(), controller_.animationClip());
        if (scene_.animation && scene_.animation->animatesProperties()) controller_.setLights(scene_.lights); // animated lights
    }
    app::renderFrame(context_, scene_, controller_.frameView(frame_.width(), frame_.height()), controller_.settings());
    if (controller_.depthView())
        app::depthToGrey(frame_);
}

void MainWindow::present() {
    presenter_.present(dc_, frame_, clientWidth_, clientHeight_);
    if (controller_.helpVisible())
        drawHelp();
}

// White text on black boxes over the frame (GDI, after StretchDIBits): readable on any scene.
void MainWindow::drawHelp() {
    if (!dc_ || clientWidth_ <= 0 || clientHeight_ <= 0)
        return;
    const HGDIOBJ oldFont = SelectObject(dc_, helpFont_ ? static_cast<HGDIOBJ>(helpFont_) : GetStockObject(DEFAULT_GUI_FONT));
    SetBkMode(dc_, OPAQUE);
    SetBkColor(dc_, RGB(0, 0, 0));
    SetTextColor(dc_, RGB(255, 255, 255));
    const int margin = MulDiv(12, int(dpiForWindow(hwnd_)), 96);
    RECT r{margin, margin, clientWidth_ - margin, clientHeight_ - margin};
    DrawTextW(dc_, helpText_.c_str(), int(helpText_.size()), &r, DT_LEFT | DT_TOP | DT_EXPANDTABS | DT_TABSTOP | (22 << 8));
    SelectObject(dc_, oldFont);
}

void MainWindow::screenshot() {
    const std::time_t t = std::time(nullptr);
    std::tm local{};
    localtime_s(&local, &t);
    const std::string name = app::screenshotName(local, ++screenshotCounter_);
    const Status saved = saveFrame(name);
    setStatus(saved ? "saved " + name : "screenshot failed: " + saved.error());
}

void MainWindow::setStatus(std::string text) {
    status_ = std::move(text);
    statusUntil_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kStatusSeconds));
    updateTitle();
}

void MainWindow::updateTitle() {
    if (!status_.empty() && Clock::now() >= statusUntil_)
        status_.clear();
    if (!hwnd_)
        return;
    std::string modes = controller_.modeSummary();
    if (!variant_.empty()) modes += " | variant " + variant_;
    const std::string title = app::windowTitle(stats_, context_.threads(), scene_.scene.triangleCount(), modes, status_);
    SetWindowTextW(hwnd_, widen(title).c_str());
}

// The framebuffer follows the client area 1:1 (so the picture is always sharp and the aspect
// ratio always right). Sizes above FrameBuffer::kMaxDimension are clamped and the presenter
// stretches; 0 x 0 (minimised) is a valid, empty framebuffer and the loop then waits.
void MainWindow::onResize(int clientWidth, int clientHeight) {
    clientWidth_ = std::max(clientWidth, 0);
    clientHeight_ = std::max(clientHeight, 0);
    const int w = std::min(clientWidth_, FrameBuffer::kMaxDimension);
    const int h = std::min(clientHeight_, FrameBuffer::kMaxDimension);
    [[maybe_unused]] const bool ok = frame_.resize(w, h); // in range by construction
    // Redraw now so the modal sizing loop (which starves our PeekMessage loop) shows the new size.
    draw();
}

void MainWindow::onKeyDown(WPARAM virtualKey, LPARAM flags) {
    const bool repeat = (flags & (LPARAM(1) << 30)) != 0; // previous key state: already down
    switch (controller_.keyDown(translateKey(virtualKey), repeat)) {
    case app::Action::Quit: close(); return;
    case app::Action::Screenshot: screenshot(); return;
    case app::Action::CycleVariant:
        if (cycleVariant_) setStatus(cycleVariant_());
        return;
    case app::Action::None: return;
    default: updateTitle(); return; // a mode changed: show it now, not at the next average
    }
}

app::Key MainWindow::translateKey(WPARAM vk) {
    using app::Key;
    switch (vk) {
    case VK_ESCAPE: return Key::Escape;
    case 'W': return Key::W;
    case 'A': return Key::A;
    case 'S': return Key::S;
    case 'D': return Key::D;
    case 'Q': return Key::Q;
    case 'E': return Key::E;
    case VK_UP: return Key::Up;
    case VK_DOWN: return Key::Down;
    case VK_LEFT: return Key::Left;
    case VK_RIGHT: return Key::Right;
    case VK_SHIFT: return Key::Shift;
    case 'C': return Key::C;
    case 'K': return Key::K;
    case 'I': return Key::I;
    case 'M': return Key::M;
    case 'T': return Key::T;
    case 'P': return Key::P;
    case 'N': return Key::N;
    case 'L': return Key::L;
    case 'O': return Key::O;
    case 'H': return Key::H;
    case 'G': return Key::G;
    case 'Z': return Key::Z;
    case 'R': return Key::R;
    case 'V': return Key::V;
    case VK_SPACE: return Key::Space;
    case VK_OEM_COMMA: return Key::Comma;
    case VK_OEM_PERIOD: return Key::Period;
    case VK_F1: return Key::F1;
    case VK_F12: return Key::F12;
    default: return Key::Unknown;
    }
}

LRESULT CALLBACK MainWindow::windowProc(HWND hwnd, UINT msg, WPARAM wParam, LPARAM lParam) {
    // The MainWindow* arrives with WM_NCCREATE (CreateWindowExW's last argument); messages sent
    // before it (WM_GETMINMAXINFO) take the default path.
    if (msg == WM_NCCREATE) {
        const auto* cs = reinterpret_cast<const CREATESTRUCTW*>(lParam);
        auto* self = static_cast<MainWindow*>(cs->lpCreateParams);
        self->hwnd_ = hwnd;
        SetWindowLongPtrW(hwnd, GWLP_USERDATA, reinterpret_cast<LONG_PTR>(self));
    }
    auto* self = reinterpret_cast<MainWindow*>(GetWindowLongPtrW(hwnd, GWLP_USERDATA));
    if (!self)
        return DefWindowProcW(hwnd, msg, wParam, lParam);
    return self->handle(msg, wParam, lParam);
}

LRESULT MainWindow::handle(UINT msg, WPARAM wParam, LPARAM lParam) {
    switch (msg) {
    case WM_SIZE:
        minimised_ = (wParam == SIZE_MINIMIZED);
        onResize(LOWORD(lParam), HIWORD(lParam));
        return 0;

    case WM_PAINT:
        // Show the last frame, then mark the whole client area valid (the DC is our own, so
        // BeginPaint/EndPaint are not needed).
        present();
        ValidateRect(hwnd_, nullptr);
        return 0;

    case WM_ERASEBKGND:
        return 1; // WM_PAINT covers every pixel

    case WM_KEYDOWN:
        onKeyDown(wParam, lParam);
        return 0;

    case WM_KEYUP:
        controller_.keyUp(translateKey(wParam));
        return 0;

    case WM_KILLFOCUS: // key-ups will go elsewhere: stop flying
        controller_.releaseAllKeys();
        dragging_ = false;
        return 0;

    // Mouse drag with the left button turns the camera.
    case WM_LBUTTONDOWN:
        SetCapture(hwnd_);
        dragging_ = true;
        lastMouseX_ = short(LOWORD(lParam));
        lastMouseY_ = short(HIWORD(lParam));
        return 0;
    case WM_MOUSEMOVE:
        if (dragging_) {
            const int x = short(LOWORD(lParam)), y = short(HIWORD(lParam));
            controller_.mouseDrag(x - lastMouseX_, y - lastMouseY_);
            lastMouseX_ = x;
            lastMouseY_ = y;
        }
        return 0;
    case WM_LBUTTONUP:
        if (dragging_)
            ReleaseCapture(); // WM_CAPTURECHANGED ends the drag
        return 0;
    case WM_CAPTURECHANGED:
        dragging_ = false;
        return 0;

    case WM_DPICHANGED: {
        // Per-monitor DPI: take the size Windows suggests for the new monitor (WM_SIZE follows).
        const auto* suggested = reinterpret_cast<const RECT*>(lParam);
        SetWindowPos(hwnd_, nullptr, suggested->left, suggested->top, suggested->right - suggested->left,
                     suggested->bottom - suggested->top, SWP_NOZORDER | SWP_NOACTIVATE);
        return 0;
    }

    case WM_DESTROY:
        dc_ = nullptr; // released with the window (CS_OWNDC)
        SetWindowLongPtrW(hwnd_, GWLP_USERDATA, 0);
        hwnd_ = nullptr;
        PostQuitMessage(0);
        return 0;

    default:
        break;
    }
    return DefWindowProcW(hwnd_, msg, wParam, lParam);
}

} // namespace sr::win32
