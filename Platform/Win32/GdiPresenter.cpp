// StretchDIBits presenter: the FrameBuffer's memory is already a top-down BI_RGB 32-bpp DIB.
#include "Platform/Win32/GdiPresenter.hpp"

namespace sr::win32 {

GdiPresenter::GdiPresenter() {
    BITMAPINFOHEADER& h = info_.bmiHeader;
    h.biSize = sizeof(BITMAPINFOHEADER);
    h.biPlanes = 1;
    h.biBitCount = 32;         // one sr::Pixel (bytes B, G, R, X) per pixel
    h.biCompression = BI_RGB;  // rows are DWORD-aligned automatically at 32 bpp
}

void GdiPresenter::present(HDC dc, const FrameBuffer& fb, int destWidth, int destHeight) {
    if (!dc || fb.empty() || destWidth <= 0 || destHeight <= 0)
        return;
    BITMAPINFOHEADER& h = info_.bmiHeader;
    h.biWidth = fb.width();
    h.biHeight = -fb.height(); // negative height: top-down rows, as FrameBuffer stores them
    h.biSizeImage = 0;         // allowed for BI_RGB
    SetStretchBltMode(dc, COLORONCOLOR);
    StretchDIBits(dc, 0, 0, destWidth, destHeight, 0, 0, fb.width(), fb.height(), fb.colorData(),
                  &info_, DIB_RGB_COLORS, SRCCOPY);
}

} // namespace sr::win32
