// Tests of FrameBuffer: resize (including 0x0 and limits), clear, DIB pixel layout.
#include "TestFramework.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "Raster/Frame/FrameBuffer.hpp"

using namespace sr;

TEST_CASE("packed pixels use the 32-bpp DIB byte order B, G, R, X", "[raster][framebuffer]") {
    const Pixel p = packBgra(0x11, 0x22, 0x33);
    const auto* bytes = reinterpret_cast<const unsigned char*>(&p);
    CHECK(bytes[0] == 0x33); // blue first in memory (little-endian)
    CHECK(bytes[1] == 0x22);
    CHECK(bytes[2] == 0x11);
    CHECK(bytes[3] == 0xFF);
}

TEST_CASE("framebuffer resizes to 0x0 and rejects bad sizes", "[raster][framebuffer]") {
    FrameBuffer fb(4, 3);
    REQUIRE(fb.width() == 4);
    REQUIRE(fb.height() == 3);
    fb.clear(packBgra(1, 2, 3), 0.5f);
    CHECK(fb.pixel(3, 2) == packBgra(1, 2, 3));
    CHECK(fb.depth(0, 0) == 0.5f);

    CHECK(fb.resize(0, 0));
    CHECK(fb.empty());
    fb.clear(0); // clearing an empty buffer is a no-op, not a crash

    CHECK_FALSE(fb.resize(-1, 10));
    CHECK_FALSE(fb.resize(FrameBuffer::kMaxDimension + 1, 1));
    CHECK(fb.width() == 0); // unchanged by a rejected resize
}

TEST_CASE("resizing back to a smaller size does not reallocate", "[raster][framebuffer]") {
    FrameBuffer fb(64, 64);
    const Pixel* before = fb.colorData();
    REQUIRE(fb.resize(32, 16));
    REQUIRE(fb.resize(64, 64));
    CHECK(fb.colorData() == before);
}

TEST_CASE("fillWords writes exactly [dst, dst + count) at any alignment, as std::fill", "[raster][framebuffer]") {
    // Guard words around every slice: a vector loop that runs past either end changes them.
    std::vector<std::uint32_t> buffer(300), expected(300);
    std::uint32_t value = 0x9E3779B9u;
    for (std::size_t offset = 0; offset < 9; ++offset) {
        for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(3), std::size_t(4), std::size_t(7),
                                  std::size_t(8), std::size_t(15), std::size_t(16), std::size_t(17), std::size_t(63),
                                  std::size_t(64), std::size_t(65), std::size_t(250)}) {
            for (std::size_t i = 0; i < buffer.size(); ++i) buffer[i] = expected[i] = std::uint32_t(i * 2654435761u);
            value = value * 1664525u + 1013904223u;
            fillWords(buffer.data() + offset, count, value);
            std::fill(expected.begin() + std::ptrdiff_t(offset), expected.begin() + std::ptrdiff_t(offset + count), value);
            INFO("offset " << offset << ", count " << count);
            REQUIRE(buffer == expected);
        }
    }
}

TEST_CASE("clear fills colour and depth, with the depth value's exact bits", "[raster][framebuffer]") {
    FrameBuffer fb(37, 5); // 185 pixels: not a multiple of any vector width
    fb.clear(packBgra(1, 2, 3), -0.0f);
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x) {
            REQUIRE(fb.pixel(x, y) == packBgra(1, 2, 3));
            REQUIRE(std::signbit(fb.depth(x, y))); // -0.0f, not +0.0f
        }
    fb.clearDepth(0.25f);
    fb.clearColor(packBgra(9, 8, 7));
    CHECK(fb.depth(36, 4) == 0.25f);
    CHECK(fb.pixel(36, 4) == packBgra(9, 8, 7));
}
