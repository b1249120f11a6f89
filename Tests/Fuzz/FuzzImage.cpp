// libFuzzer target: decodeImage on arbitrary bytes must return an image or a one-line error, never crash or over-allocate.
#include <cassert>
#include <cstddef>
#include <cstdint>

#include "Resources/Image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // 1 Mpixel instead of 64: the size checks are the same code, and runs stay fast.
    const sr::Result<sr::Image> r = sr::decodeImage(data, size, "fuzz-input", std::int64_t(1) << 20);
    if (r.ok()) {
        const sr::Image& img = r.value();
        assert(img.width > 0 && img.height > 0 && img.width <= sr::kMaxImageDimension &&
               img.height <= sr::kMaxImageDimension);
        assert(img.rgba.size() == std::size_t(img.width) * std::size_t(img.height) * 4);
        // Touch the last texel: a short buffer would be caught by ASan here.
        volatile std::uint8_t last = *img.texel(img.width - 1, img.height - 1);
        (void)last;
    } else {
        assert(!r.error().empty() && r.error().find('\n') == std::string::npos);
        assert(r.error().rfind("fuzz-input", 0) == 0);
    }
    return 0;
}
