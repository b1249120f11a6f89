// EXT_texture_webp: WebP images decoded by libwebp into RGBA8, the header's size checked against the image limits before anything is allocated.
#include <cstring>

#include <webp/decode.h>

#include "Resources/Gltf/Codecs.hpp"

namespace sr::gltf {

bool isWebp(const unsigned char* data, std::size_t size) {
    return size >= 12 && std::memcmp(data, "RIFF", 4) == 0 && std::memcmp(data + 8, "WEBP", 4) == 0;
}

Result<sr::Image> decodeWebp(const unsigned char* data, std::size_t size, const std::string& name) {
    using R = Result<sr::Image>;
    int width = 0, height = 0;
    if (!isWebp(data, size) || !WebPGetInfo(data, size, &width, &height))
        return R::failure(name + ": not a WebP image, or its header is corrupt");
    if (width <= 0 || height <= 0 || width > kMaxImageDimension || height > kMaxImageDimension ||
        std::int64_t(width) * height > kMaxImagePixels)
        return R::failure(name + ": a " + std::to_string(width) + "x" + std::to_string(height) + " WebP image is larger than " +
                          std::to_string(kMaxImageDimension) + " pixels a side or " + std::to_string(kMaxImagePixels >> 20) + " Mpixels");
    sr::Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
    if (!WebPDecodeRGBAInto(data, size, image.rgba.data(), image.rgba.size(), width * 4))
        return R::failure(name + ": the WebP data is corrupt or truncated");
    return R(std::move(image));
}

} // namespace sr::gltf
