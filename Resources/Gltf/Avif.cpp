// EXT_texture_avif: AVIF images decoded by libavif into RGBA8 (natively, where Debian's libavif-dev is linked: SR_HAVE_AVIF), the size checked against the image limits before the pixels are decoded.
#include <cstring>

#include "Resources/Gltf/Codecs.hpp"

#if SR_HAVE_AVIF
#include <avif/avif.h>
#endif

namespace sr::gltf {

bool isAvif(const unsigned char* data, std::size_t size) {
    // An ISO-BMFF file whose 'ftyp' box names the avif (still) or avis (sequence) brand.
    return size >= 12 && std::memcmp(data + 4, "ftyp", 4) == 0 && (std::memcmp(data + 8, "avif", 4) == 0 || std::memcmp(data + 8, "avis", 4) == 0);
}

bool avifSupported() {
#if SR_HAVE_AVIF
    return true;
#else
    return false; // the Visual Studio and MinGW builds (SR_HAVE_AVIF 0 or undefined)
#endif
}

Result<sr::Image> decodeAvif(const unsigned char* data, std::size_t size, const std::string& name) {
    using R = Result<sr::Image>;
#if SR_HAVE_AVIF
    if (!isAvif(data, size)) return R::failure(name + ": not an AVIF image");
    struct Decoder {
        avifDecoder* d = avifDecoderCreate();
        ~Decoder() {
            if (d) avifDecoderDestroy(d);
        }
    } dec;
    if (!dec.d) return R::failure(name + ": the AVIF decoder could not be created");
    dec.d->imageSizeLimit = std::uint32_t(kMaxImagePixels);
    if (avifDecoderSetIOMemory(dec.d, data, size) != AVIF_RESULT_OK || avifDecoderParse(dec.d) != AVIF_RESULT_OK)
        return R::failure(name + ": the AVIF header is corrupt or unsupported");
    const std::uint32_t width = dec.d->image->width, height = dec.d->image->height;
    if (width == 0 || height == 0 || width > std::uint32_t(kMaxImageDimension) || height > std::uint32_t(kMaxImageDimension) ||
        std::int64_t(width) * height > kMaxImagePixels)
        return R::failure(name + ": a " + std::to_string(width) + "x" + std::to_string(height) + " AVIF image is larger than " +
                          std::to_string(kMaxImageDimension) + " pixels a side or " + std::to_string(kMaxImagePixels >> 20) + " Mpixels");
    const avifResult decoded = avifDecoderNextImage(dec.d);
    if (decoded != AVIF_RESULT_OK) return R::failure(name + ": the AVIF data cannot be decoded (" + avifResultToString(decoded) + ")");
    sr::Image image;
    image.width = int(width);
    image.height = int(height);
    image.rgba.resize(std::size_t(width) * height * 4);
    avifRGBImage rgb;
    avifRGBImageSetDefaults(&rgb, dec.d->image);
    rgb.format = AVIF_RGB_FORMAT_RGBA;
    rgb.depth = 8;
    rgb.pixels = image.rgba.data();
    rgb.rowBytes = width * 4;
    if (avifImageYUVToRGB(dec.d->image, &rgb) != AVIF_RESULT_OK) return R::failure(name + ": the AVIF colours cannot be converted to RGB");
    return R(std::move(image));
#else
    (void)data;
    (void)size;
    return R::failure(name + ": this build reads no AVIF (libavif is linked in the Linux build only)");
#endif
}

} // namespace sr::gltf
