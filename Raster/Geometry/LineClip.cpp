// Exact line clipping for any finite float endpoints: the visible part of a segment and its snapped ends.
#include "Raster/Geometry/LineClip.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "Raster/Setup/RasterLimits.hpp"

namespace sr {

namespace {

static_assert(std::numeric_limits<float>::is_iec559, "floats are IEEE-754 binary32");

// A signed 640-bit integer in two's complement, 20 little-endian 32-bit limbs. Plain uint64
// limb products, so it builds the same with GCC, Clang, MinGW and MSVC (no __int128). Only what
// the clipper needs; every operation asserts that its exact result fits.
class Wide {
public:
    static constexpr int kLimbs = 20;

    Wide() = default;
    explicit Wide(std::int64_t v) {
        const std::uint64_t u = std::uint64_t(v);
        limb_[0] = std::uint32_t(u);
        limb_[1] = std::uint32_t(u >> 32);
        const std::uint32_t fill = v < 0 ? 0xFFFFFFFFu : 0u;
        for (int i = 2; i < kLimbs; ++i) limb_[i] = fill;
    }

    bool negative() const { return (limb_[kLimbs - 1] >> 31) != 0; }
    int sign() const {
        if (negative()) return -1;
        for (std::uint32_t l : limb_)
            if (l != 0) return 1;
        return 0;
    }

    Wide operator-() const {
        Wide r;
        std::uint64_t carry = 1;
        for (int i = 0; i < kLimbs; ++i) {
            const std::uint64_t s = std::uint64_t(~limb_[i]) + carry;
            r.limb_[i] = std::uint32_t(s);
            carry = s >> 32;
        }
        return r;
    }

    friend Wide operator+(const Wide& a, const Wide& b) {
        Wide r;
        std::uint64_t carry = 0;
        for (int i = 0; i < kLimbs; ++i) {
            const std::uint64_t s = std::uint64_t(a.limb_[i]) + b.limb_[i] + carry;
            r.limb_[i] = std::uint32_t(s);
            carry = s >> 32;
        }
        assert(a.negative() != b.negative() || r.negative() == a.negative()); // no overflow
        return r;
    }
    friend Wide operator-(const Wide& a, const Wide& b) { return a + (-b); }

    // this * 2^bits, 0 <= bits; the result must fit.
    Wide shifted(int bits) const {
        assert(bits >= 0 && magnitudeBits() + bits < 32 * kLimbs);
        const int whole = bits / 32, part = bits % 32;
        Wide r;
        for (int i = kLimbs - 1; i >= whole; --i) {
            const std::uint64_t hi = limb_[i - whole];
            const std::uint64_t lo = i - whole - 1 >= 0 ? limb_[i - whole - 1] : 0u;
            r.limb_[i] = std::uint32_t((((hi << 32) | lo) << part) >> 32);
        }
        return r;
    }

    // Schoolbook product of the magnitudes over their non-zero limbs, then the sign.
    friend Wide operator*(const Wide& a, const Wide& b) {
        const Wide ma = a.negative() ? -a : a, mb = b.negative() ? -b : b;
        const int na = ma.usedLimbs(), nb = mb.usedLimbs();
        assert(na + nb <= kLimbs);
        Wide r;
        for (int i = 0; i < na; ++i) {
            std::uint64_t carry = 0;
            for (int j = 0; j < nb; ++j) {
                const std::uint64_t s = std::uint64_t(ma.limb_[i]) * mb.limb_[j] + r.limb_[i + j] + carry;
                r.limb_[i + j] = std::uint32_t(s);
                carry = s >> 32;
            }
            if (i + nb < kLimbs) r.limb_[i + nb] = std::uint32_t(carry);
        }
        assert(!r.negative());
        return a.negative() != b.negative() ? -r : r;
    }

    friend int compare(const Wide& a, const Wide& b) {
        if (a.negative() != b.negative()) return a.negative() ? -1 : 1;
        for (int i = kLimbs - 1; i >= 0; --i) // same sign: two's complement orders like unsigned
            if (a.limb_[i] != b.limb_[i]) return a.limb_[i] < b.limb_[i] ? -1 : 1;
        return 0;
    }

    // The value rounded to double (a few ulps; every value here is below 2^640 < DBL_MAX).
    double toDouble() const {
        if (negative()) return -(-*this).toDouble();
        double r = 0.0;
        for (int i = kLimbs - 1; i >= 0; --i) r = r * 4294967296.0 + double(limb_[i]);
        return r;
    }

private:
    // Bits of |this| (0 for zero).
    int magnitudeBits() const {
        const Wide m = negative() ? -*this : *this;
        const int n = m.usedLimbs();
        if (n == 0) return 0;
        int b = 32 * (n - 1);
        for (std::uint32_t top = m.limb_[n - 1]; top != 0; top >>= 1) ++b;
        return b;
    }

    int usedLimbs() const {
        int n = kLimbs;
        while (n > 0 && limb_[n - 1] == 0) --n;
        return n;
    }

    std::uint32_t limb_[kLimbs] = {};
};

// Every coordinate is held as an integer count of 2^-149, the smallest float step, so the
// binary value of any finite float is exact: |v| < 2^128 is below 2^277 units, a difference of
// two below 2^278, and the products formed below (at most two such factors, then small
// factors and shifts) stay under 2^560, well inside the 639 bits of Wide.
constexpr int kUnitShift = 149;

Wide exactFloat(float v) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    const int e = int((bits >> 23) & 0xFFu);
    assert(e != 0xFF); // finite
    // Normal: (2^23 + f) 2^(e - 150) = (2^23 + f) 2^(e - 1) units; subnormal: f 2^-149 = f units.
    const std::int64_t m = e == 0 ? std::int64_t(bits & 0x7FFFFFu) : std::int64_t((bits & 0x7FFFFFu) | 0x800000u);
    const Wide w = Wide(m).shifted(e == 0 ? 0 : e - 1);
    return (bits >> 31) != 0 ? -w : w;
}

// A parameter t = num / den along the segment, den > 0.
struct Ratio {
    Wide num, den;
};

bool less(const Ratio& p, const Ratio& q) { return compare(p.num * q.den, q.num * p.den) < 0; }

// floor(n / d) for d > 0, given that the exact quotient lies in [lo, hi]: a double estimate,
// clamped to the range before the conversion to an integer, then corrected exactly (the
// estimate's relative error is a few 2^-53 and |quotient| < 2^41, so each loop runs at most once).
std::int64_t floorDivIn(const Wide& n, const Wide& d, std::int64_t lo, std::int64_t hi) {
    assert(d.sign() > 0 && lo <= hi);
    const double q = std::clamp(std::floor(n.toDouble() / d.toDouble()), double(lo), double(hi));
    std::int64_t k = std::int64_t(q);
    while (k > lo && compare(Wide(k) * d, n) > 0) --k;
    while (k < hi && compare(Wide(k + 1) * d, n) <= 0) ++k;
    return k;
}

// snapToFixed's floor(256 c + 1/2) for the coordinate c = p + t dp (p, dp in units, so c in
// pixels is (p den + num dp) / (den 2^149)), known to lie in [lo, hi] pixels:
//   256 c + 1/2 = (2 (p den + num dp) + den 2^141) / (den 2^142).
std::int64_t snapAt(const Wide& p, const Wide& dp, const Ratio& t, std::int64_t lo, std::int64_t hi) {
    constexpr int kShift = kUnitShift - kSubPixelBits; // 2^141
    const Wide n = (p * t.den + t.num * dp).shifted(1) + t.den.shifted(kShift);
    const Wide d = t.den.shifted(kShift + 1);
    return floorDivIn(n, d, lo * kSubPixelScale, hi * kSubPixelScale);
}

} // namespace

std::optional<ExactClip> clipSegmentExact(float ax, float ay, float bx, float by, const ClipBox& box) {
    assert(box.x0 <= box.x1 && box.y0 <= box.y1);
    const Wide p[2] = {exactFloat(ax), exactFloat(ay)};
    const Wide d[2] = {exactFloat(bx) - p[0], exactFloat(by) - p[1]};
    const std::int64_t lo[2] = {box.x0, box.y0}, hi[2] = {box.x1, box.y1};

    // Liang-Barsky: on each axis lo <= p + t d <= hi, i.e. (lo - p) <= t d <= (hi - p), gives
    // one lower and one upper bound on t (or, with d = 0, all or nothing); keep the tightest.
    Ratio t0{Wide(0), Wide(1)}, t1{Wide(1), Wide(1)};
    for (int axis = 0; axis < 2; ++axis) {
        const Wide l = Wide(lo[axis]).shifted(kUnitShift) - p[axis];
        const Wide h = Wide(hi[axis]).shifted(kUnitShift) - p[axis];
        const int s = d[axis].sign();
        if (s == 0) {
            if (l.sign() > 0 || h.sign() < 0) return std::nullopt; // parallel and outside
            continue;
        }
        const Ratio enter = s > 0 ? Ratio{l, d[axis]} : Ratio{-h, -d[axis]};
        const Ratio leave = s > 0 ? Ratio{h, d[axis]} : Ratio{-l, -d[axis]};
        if (less(t0, enter)) t0 = enter;
        if (less(leave, t1)) t1 = leave;
    }
    if (less(t1, t0)) return std::nullopt;

    // p(t0) and p(t1) lie in the box, so each snapped coordinate lies in 256 [lo, hi].
    ExactClip c;
    c.x0 = snapAt(p[0], d[0], t0, box.x0, box.x1);
    c.y0 = snapAt(p[1], d[1], t0, box.y0, box.y1);
    c.x1 = snapAt(p[0], d[0], t1, box.x0, box.x1);
    c.y1 = snapAt(p[1], d[1], t1, box.y0, box.y1);
    c.t0 = t0.num.toDouble() / t0.den.toDouble();
    c.t1 = t1.num.toDouble() / t1.den.toDouble();
    return c;
}

} // namespace sr
