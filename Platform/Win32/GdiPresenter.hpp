// Shows a FrameBuffer in a window with StretchDIBits (a top-down 32-bpp BI_RGB DIB, no copy).
#pragma once

#include "Platform/Win32/Win32Include.hpp"
#include "Raster/Frame/FrameBuffer.hpp"

namespace sr::win32 {

class GdiPresenter {
public:
    GdiPresenter();

    // Blits the framebuffer to (0, 0, destWidth, destHeight) of dc, stretching if the sizes
    // differ (they do only when the client area exceeds FrameBuffer::kMaxDimension). Nothing is
    // drawn for an empty framebuffer or an empty destination. Never allocates.
    void present(HDC dc, const FrameBuffer& fb, int destWidth, int destHeight);

private:
    // Reused every frame: only biWidth / biHeight change.
    BITMAPINFO info_{};
};

} // namespace sr::win32
