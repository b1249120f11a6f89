// Image decoding through stb_image (from memory, after our own size checks) and image writers.
#include "Resources/Image.hpp"

#include <cstring>

#include "Raster/FrameBuffer.hpp"
#include "Resources/FileIO.hpp"
#include "stb_image.h"
#include "stb_image_write.h"

namespace sr {

Result<Image> decodeImage(const unsigned char* data, std::size_t size, const std::string& name) {
    using R = Result<Image>;
    if (size == 0) return R::failure(name + ": empty file, not an image");
    if (size > std::size_t(INT32_MAX)) return R::failure(name + ": file too large to decode");
    int w = 0, h = 0, channels = 0;
    // Read the header first: a PNG claiming 100000 x 100000 must not allocate 40 GB.
    if (!stbi_info_from_memory(data, int(size), &w, &h, &channels)) {
        return R::failure(name + ": not a decodable image (" + stbi_failure_reason() + ")");
    }
    if (w <= 0 || h <= 0 || w > kMaxImageDimension || h > kMaxImageDimension ||
        std::int64_t(w) * h > kMaxImagePixels) {
        return R::failure(name + ": image is " + std::to_string(w) + "x" + std::to_string(h) +
                          ", above the limit of " + std::to_string(kMaxImageDimension) + " per side and " +
                          std::to_string(kMaxImagePixels) + " pixels");
    }
    unsigned char* pixels = stbi_load_from_memory(data, int(size), &w, &h, &channels, 4);
    if (!pixels) return R::failure(name + ": decode failed (" + stbi_failure_reason() + ")");
    Image img;
    img.width = w;
    img.height = h;
    img.rgba.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
    stbi_image_free(pixels);
    return R(std::move(img));
}

Result<Image> loadImage(const std::string& utf8Path) {
    auto bytes = readFileBytes(utf8Path);
    if (!bytes) return Result<Image>::failure(bytes.error());
    return decodeImage(bytes.value().data(), bytes.value().size(), utf8Path);
}

namespace {

void appendToVector(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

std::vector<unsigned char> rgbOf(const Image& image) {
    std::vector<unsigned char> rgb(std::size_t(image.width) * std::size_t(image.height) * 3);
    for (std::size_t i = 0, n = std::size_t(image.width) * std::size_t(image.height); i < n; ++i) {
        std::memcpy(&rgb[i * 3], &image.rgba[i * 4], 3);
    }
    return rgb;
}

} // namespace

Status writeImage(const std::string& utf8Path, const Image& image) {
    if (image.width <= 0 || image.height <= 0) return Status::failure(utf8Path + ": cannot write an empty image");
    const std::string ext = lowerExtension(utf8Path);
    const std::vector<unsigned char> rgb = rgbOf(image);
    std::vector<unsigned char> file;
    if (ext == ".ppm") {
        const std::string header = "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
        file.assign(header.begin(), header.end());
        file.insert(file.end(), rgb.begin(), rgb.end());
    } else if (ext == ".png") {
        if (!stbi_write_png_to_func(appendToVector, &file, image.width, image.height, 3, rgb.data(), image.width * 3)) {
            return Status::failure(utf8Path + ": PNG encoding failed");
        }
    } else if (ext == ".bmp") {
        if (!stbi_write_bmp_to_func(appendToVector, &file, image.width, image.height, 3, rgb.data())) {
            return Status::failure(utf8Path + ": BMP encoding failed");
        }
    } else {
        return Status::failure(utf8Path + ": unknown image extension '" + ext + "' (use .ppm, .png or .bmp)");
    }
    return writeFileBytes(utf8Path, file.data(), file.size());
}

Image toImage(const FrameBuffer& fb) {
    Image img;
    img.width = fb.width();
    img.height = fb.height();
    img.rgba.resize(std::size_t(img.width) * std::size_t(img.height) * 4);
    for (int y = 0; y < img.height; ++y) {
        const Pixel* row = fb.colorRow(y);
        for (int x = 0; x < img.width; ++x) {
            std::uint8_t* t = img.texel(x, y);
            t[0] = pixelR(row[x]);
            t[1] = pixelG(row[x]);
            t[2] = pixelB(row[x]);
            t[3] = 255;
        }
    }
    return img;
}

Status writePfm(const std::string& utf8Path, int width, int height, const float* values) {
    if (width <= 0 || height <= 0) return Status::failure(utf8Path + ": cannot write an empty depth image");
    const std::string header = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    std::vector<unsigned char> file(header.begin(), header.end());
    const std::size_t rowBytes = std::size_t(width) * sizeof(float);
    file.reserve(file.size() + rowBytes * std::size_t(height));
    for (int y = height - 1; y >= 0; --y) { // PFM: bottom row first; floats little-endian (x86)
        const auto* row = reinterpret_cast<const unsigned char*>(values + std::size_t(y) * std::size_t(width));
        file.insert(file.end(), row, row + rowBytes);
    }
    return writeFileBytes(utf8Path, file.data(), file.size());
}

} // namespace sr
