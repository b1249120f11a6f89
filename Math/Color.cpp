// Color <-> 8-bit conversions: unpacking (toUnorm8 and packBgra8 are inline in Color.hpp).
#include "Color.hpp"

namespace sr {

Color unpackBgra8(std::uint32_t v) {
    return fromRgba8(static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
                     static_cast<std::uint8_t>(v), 255);
}

Color fromRgba8(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
    return {static_cast<float>(r) / 255.0f, static_cast<float>(g) / 255.0f, static_cast<float>(b) / 255.0f,
            static_cast<float>(a) / 255.0f};
}

} // namespace sr
