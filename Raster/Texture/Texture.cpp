// Texture: RGBA8 storage and the box-filtered mip chain (fromRgba8), and the filter / wrap names.
// The samplers are in TextureSampling.cpp.
#include "Texture.hpp"

#include "Raster/Shade/ColorSpace.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace sr {

// --- Names ------------------------------------------------------------------------------------
const char* filterName(TextureFilter filter) {
    switch (filter) {
    case TextureFilter::Nearest: return "nearest";
    case TextureFilter::Bilinear: return "bilinear";
    case TextureFilter::Trilinear: return "trilinear";
    }
    return "?";
}

std::optional<TextureFilter> parseFilter(std::string_view name) {
    if (name == "nearest") return TextureFilter::Nearest;
    if (name == "bilinear") return TextureFilter::Bilinear;
    if (name == "trilinear") return TextureFilter::Trilinear;
    return std::nullopt;
}

const char* wrapName(WrapMode wrap) {
    switch (wrap) {
    case WrapMode::Repeat: return "repeat";
    case WrapMode::Clamp: return "clamp";
    case WrapMode::Mirror: return "mirror";
    }
    return "?";
}

std::optional<WrapMode> parseWrap(std::string_view name) {
    if (name == "repeat") return WrapMode::Repeat;
    if (name == "clamp") return WrapMode::Clamp;
    if (name == "mirror") return WrapMode::Mirror;
    return std::nullopt;
}

namespace {

constexpr std::uint32_t packRgba(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a) {
    return r | (g << 8) | (b << 16) | (a << 24);
}

bool isPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

// Integer division rounded to nearest, ties to even (n >= 0, d > 0).
std::uint32_t divRoundEven(std::uint32_t n, std::uint32_t d) {
    const std::uint32_t q = n / d, r = n % d;
    if (2 * r > d || (2 * r == d && (q & 1u))) return q + 1;
    return q;
}

} // namespace

// --- Storage and the mip chain --------------------------------------------------------------------
Texture::Level Texture::makeLevel(int width, int height) {
    Level l;
    l.width = width;
    l.height = height;
    l.maskX = isPowerOfTwo(width) ? std::uint32_t(width - 1) : 0u;
    l.maskY = isPowerOfTwo(height) ? std::uint32_t(height - 1) : 0u;
    // A size of 1 is a power of two with mask 0: the generic branch handles it (index 0 always).
    l.texels.assign(std::size_t(l.stride()) * std::size_t(height), 0u);
    return l;
}

void Texture::Level::padRows() {
    for (int y = 0; y < height; ++y) row(y)[width] = row(y)[0];
}

// One box-filter step (see the header): destination texel x takes source texels 2x, 2x + 1, and
// 2x + 2 as well when it is the last one and the source length is odd; a length of 1 maps to itself.
Texture::Level Texture::downsample(const Level& src) {
    const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
    Level dst = makeLevel(w, h);
    auto span = [](int i, int srcSize, int dstSize, int& first, int& count) {
        if (srcSize == 1) {
            first = 0;
            count = 1;
            return;
        }
        first = 2 * i;
        count = (i == dstSize - 1 && (srcSize & 1)) ? 3 : 2;
    };
    for (int y = 0; y < h; ++y) {
        int y0, ny;
        span(y, src.height, h, y0, ny);
        for (int x = 0; x < w; ++x) {
            int x0, nx;
            span(x, src.width, w, x0, nx);
            std::uint32_t sum[4] = {0, 0, 0, 0};
            for (int j = y0; j < y0 + ny; ++j)
                for (int i = x0; i < x0 + nx; ++i) {
                    const std::uint32_t t = src.row(j)[i];
                    for (int c = 0; c < 4; ++c) sum[c] += (t >> (8 * c)) & 0xFFu;
                }
            const std::uint32_t n = std::uint32_t(nx * ny);
            dst.row(y)[x] = packRgba(divRoundEven(sum[0], n), divRoundEven(sum[1], n), divRoundEven(sum[2], n),
                                     divRoundEven(sum[3], n));
        }
    }
    dst.padRows();
    return dst;
}

Texture::Texture() {
    levels_.push_back(makeLevel(1, 1));
    levels_[0].row(0)[0] = 0xFFFFFFFFu;
    levels_[0].padRows();
}

Texture Texture::fromRgba8(int width, int height, const std::uint8_t* rgbaTopRowFirst) {
    assert(width >= 1 && width <= kMaxTextureSize && height >= 1 && height <= kMaxTextureSize);
    assert(rgbaTopRowFirst != nullptr);
    Texture t;
    if (width < 1 || width > kMaxTextureSize || height < 1 || height > kMaxTextureSize || !rgbaTopRowFirst) {
        t.levels_[0].row(0)[0] = packRgba(255, 0, 255, 255); // release builds: visible "bad texture"
        t.levels_[0].padRows();
        return t;
    }
    t.levels_.clear();
    Level base = makeLevel(width, height);
    // Flip: texel row y (bottom-first) is image row height - 1 - y.
    for (int y = 0; y < height; ++y) {
        const std::uint8_t* src = rgbaTopRowFirst + std::size_t(height - 1 - y) * std::size_t(width) * 4;
        std::uint32_t* dst = base.row(y);
        for (int x = 0; x < width; ++x, src += 4) {
            dst[x] = packRgba(src[0], src[1], src[2], src[3]);
            t.hasAlpha_ = t.hasAlpha_ || src[3] != 255;
        }
    }
    base.padRows();
    t.levels_.push_back(std::move(base));
    while (t.levels_.back().width > 1 || t.levels_.back().height > 1) {
        Level next = downsample(t.levels_.back());
        t.levels_.push_back(std::move(next));
    }
    // halvingLevels: along each axis size_k == 1 or size_k * 2^k == the base size.
    auto halves = [](int size, int base, int k) { return size == 1 || (std::int64_t(size) << k) == base; };
    t.halvingLevels_ = 0;
    while (t.halvingLevels_ < t.levelCount()) {
        const Level& l = t.levels_[std::size_t(t.halvingLevels_)];
        if (!halves(l.width, width, t.halvingLevels_) || !halves(l.height, height, t.halvingLevels_)) break;
        ++t.halvingLevels_;
    }
    return t;
}

const Texture::Decoded& Texture::decoded() const {
    std::call_once(decoded_->once, [this] {
        const auto& d16 = srgbDecode16Table();
        decoded_->levels.resize(levels_.size());
        for (std::size_t k = 0; k < levels_.size(); ++k) {
            const std::vector<std::uint32_t>& src = levels_[k].texels;
            std::vector<std::uint32_t>& dst = decoded_->levels[k];
            dst.resize(2 * src.size());
            for (std::size_t i = 0; i < src.size(); ++i) {
                const std::uint32_t t = src[i];
                dst[2 * i] = std::uint32_t(d16[t & 0xFFu]) | std::uint32_t(d16[(t >> 8) & 0xFFu]) << 16;
                dst[2 * i + 1] = std::uint32_t(d16[(t >> 16) & 0xFFu]) | ((t >> 24) * 257u) << 16;
            }
        }
    });
    return *decoded_;
}

Texture::LevelView Texture::decodedLevelView(int level) const {
    LevelView v = levelView(level);
    v.decoded = decoded().levels[std::size_t(level)].data();
    return v;
}

std::uint32_t Texture::texel(int level, int x, int y) const {
    assert(level >= 0 && level < levelCount());
    const Level& l = levels_[std::size_t(level)];
    assert(x >= 0 && x < l.width && y >= 0 && y < l.height);
    return l.row(y)[x];
}

} // namespace sr
