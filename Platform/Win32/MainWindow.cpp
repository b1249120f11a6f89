// The demo window: class registration, message handling (size, paint, keys, DPI) and presenting.
#include "Platform/Win32/MainWindow.hpp"

#include "Platform/Demo/Gradient.hpp"
#include "Platform/Win32/Dpi.hpp"

#include <algorithm>

namespace sr::win32 {

namespace {

constexpr wchar_t kClassName[] = L"SoftRasterMainWindow";
constexpr wchar_t kTitle[] = L"SoftRaster - first light";
constexpr int kInitialClientWidth = 960; // at 96 DPI; scaled by the monitor's DPI
constexpr int kInitialClientHeight = 540;
constexpr DWORD kStyle = WS_OVERLAPPEDWINDOW;
constexpr DWORD kExStyle = 0;

} // namespace

MainWindow::~MainWindow() {
    if (hwnd_)
        DestroyWindow(hwnd_);
}

bool MainWindow::create(HINSTANCE instance, int showCommand) {
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

    // Size the window so its client area is 960 x 540 at 96 DPI, scaled to the screen's DPI.
    const UINT dpi = dpiForWindow(nullptr);
    RECT r{0, 0, MulDiv(kInitialClientWidth, int(dpi), 96), MulDiv(kInitialClientHeight, int(dpi), 96)};
    AdjustWindowRectEx(&r, kStyle, FALSE, kExStyle);

    hwnd_ = CreateWindowExW(kExStyle, kClassName, kTitle, kStyle, CW_USEDEFAULT, CW_USEDEFAULT,
                            r.right - r.left, r.bottom - r.top, nullptr, nullptr, instance, this);
    if (!hwnd_)
        return false;
    dc_ = GetDC(hwnd_);
    ShowWindow(hwnd_, showCommand);
    UpdateWindow(hwnd_);
    return true;
}

bool MainWindow::idle() const { return minimised_ || frame_.empty(); }

void MainWindow::renderFrame() {
    draw();
    present();
}

void MainWindow::close() {
    if (hwnd_)
        DestroyWindow(hwnd_);
}

void MainWindow::draw() {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    demo::renderGradient(frame_, seconds);
}

void MainWindow::present() { presenter_.present(dc_, frame_, clientWidth_, clientHeight_); }

// The framebuffer follows the client area. Sizes above FrameBuffer::kMaxDimension are clamped
// and the presenter stretches; 0 x 0 (minimised) is a valid, empty framebuffer.
void MainWindow::onResize(int clientWidth, int clientHeight) {
    clientWidth_ = std::max(clientWidth, 0);
    clientHeight_ = std::max(clientHeight, 0);
    const int w = std::min(clientWidth_, FrameBuffer::kMaxDimension);
    const int h = std::min(clientHeight_, FrameBuffer::kMaxDimension);
    [[maybe_unused]] const bool ok = frame_.resize(w, h); // in range by construction
    // Redraw now so the modal sizing loop (which starves our PeekMessage loop) shows the new size.
    if (!frame_.empty())
        draw();
}

demo::Key MainWindow::translateKey(WPARAM virtualKey) {
    switch (virtualKey) {
    case VK_ESCAPE: return demo::Key::Escape;
    default: return demo::Key::Unknown;
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
        if (demo::actionForKey(translateKey(wParam)) == demo::Action::Quit) {
            close();
            return 0;
        }
        break;

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
