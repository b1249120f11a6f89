// The stencil test and operations (OpenGL 4.5 core, section 17.3.5): an 8-bit value per pixel
// (FrameBuffer::enableStencil), compared with a reference before the depth test and updated by
// one of three operations depending on the outcome.
#pragma once

#include <cstdint>

namespace sr {

// The test passes when (ref & readMask) FUNC (stored & readMask), as glStencilFunc defines it.
enum class StencilFunc : std::uint8_t { Never, Less, LEqual, Greater, GEqual, Equal, NotEqual, Always };

// What a fragment does to the stored value (glStencilOp): Incr / Decr clamp to [0, 255],
// IncrWrap / DecrWrap wrap around, Invert flips every bit.
enum class StencilOp : std::uint8_t { Keep, Zero, Replace, Incr, IncrWrap, Decr, DecrWrap, Invert };

struct StencilState {
    bool enabled = false; // off: no test, and the stencil buffer is neither read nor written
    StencilFunc func = StencilFunc::Always;
    std::uint8_t ref = 0;
    std::uint8_t readMask = 0xFF;
    std::uint8_t writeMask = 0xFF; // only these bits of the stored value change
    StencilOp fail = StencilOp::Keep;      // the stencil test failed
    StencilOp depthFail = StencilOp::Keep; // the stencil test passed, the depth test failed
    StencilOp pass = StencilOp::Keep;      // both passed (or the depth test is off)
    bool on() const { return enabled; }
};

constexpr bool stencilPasses(StencilFunc func, std::uint8_t ref, std::uint8_t stored, std::uint8_t readMask) {
    const unsigned r = unsigned(ref & readMask), s = unsigned(stored & readMask);
    switch (func) {
    case StencilFunc::Never: return false;
    case StencilFunc::Less: return r < s;
    case StencilFunc::LEqual: return r <= s;
    case StencilFunc::Greater: return r > s;
    case StencilFunc::GEqual: return r >= s;
    case StencilFunc::Equal: return r == s;
    case StencilFunc::NotEqual: return r != s;
    case StencilFunc::Always: return true;
    }
    return false;
}

// The stored value after `op`, only the writeMask bits changed.
constexpr std::uint8_t stencilApply(StencilOp op, std::uint8_t stored, std::uint8_t ref, std::uint8_t writeMask) {
    unsigned v = stored;
    switch (op) {
    case StencilOp::Keep: return stored;
    case StencilOp::Zero: v = 0; break;
    case StencilOp::Replace: v = ref; break;
    case StencilOp::Incr: v = stored == 255 ? 255u : stored + 1u; break;
    case StencilOp::IncrWrap: v = (stored + 1u) & 0xFFu; break;
    case StencilOp::Decr: v = stored == 0 ? 0u : stored - 1u; break;
    case StencilOp::DecrWrap: v = (stored + 255u) & 0xFFu; break;
    case StencilOp::Invert: v = ~unsigned(stored) & 0xFFu; break;
    }
    return std::uint8_t((unsigned(stored) & ~unsigned(writeMask)) | (v & unsigned(writeMask)));
}

} // namespace sr
