// Tests of FrameBuffer: resize (including 0x0 and limits), clear, DIB pixel layout.
#include "TestFramework.hpp"

#include "Raster/FrameBuffer.hpp"

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
