// Reference line drawer: Line.hpp's rule read literally, in exact rationals on big integers, slow.
#include "ReferenceLine.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <utility>
#include <vector>

#include "TestFramework.hpp"

namespace sr::ref {

namespace {

// --- Arbitrary-precision integers: sign and magnitude, as long as needed. Deliberately not
// LineClip's fixed-width two's complement, so that the two do not share a mistake. -------------
struct Big {
    bool neg = false;
    std::vector<std::uint32_t> mag; // little-endian limbs, no high zero limb; zero is empty
};
using Mag = std::vector<std::uint32_t>;

void trim(Big& a) {
    while (!a.mag.empty() && a.mag.back() == 0) a.mag.pop_back();
    if (a.mag.empty()) a.neg = false;
}

Big big(std::int64_t v) {
    Big r;
    r.neg = v < 0;
    for (std::uint64_t m = v < 0 ? 0 - std::uint64_t(v) : std::uint64_t(v); m != 0; m >>= 32)
        r.mag.push_back(std::uint32_t(m));
    return r;
}

int cmpMag(const Mag& a, const Mag& b) {
    if (a.size() != b.size()) return a.size() < b.size() ? -1 : 1;
    for (std::size_t i = a.size(); i-- > 0;)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

Mag addMag(const Mag& a, const Mag& b) {
    Mag r(std::max(a.size(), b.size()) + 1, 0);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const std::uint64_t s = carry + (i < a.size() ? a[i] : 0u) + (i < b.size() ? b[i] : 0u);
        r[i] = std::uint32_t(s);
        carry = s >> 32;
    }
    return r;
}

Mag subMag(const Mag& a, const Mag& b) { // |a| >= |b|
    Mag r(a.size(), 0);
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        std::int64_t s = std::int64_t(a[i]) - (i < b.size() ? std::int64_t(b[i]) : 0) - borrow;
        borrow = s < 0 ? 1 : 0;
        if (s < 0) s += std::int64_t(1) << 32;
        r[i] = std::uint32_t(s);
    }
    return r;
}

Big operator+(const Big& a, const Big& b) {
    Big r;
    if (a.neg == b.neg) {
        r.mag = addMag(a.mag, b.mag);
        r.neg = a.neg;
    } else if (cmpMag(a.mag, b.mag) >= 0) {
        r.mag = subMag(a.mag, b.mag);
        r.neg = a.neg;
    } else {
        r.mag = subMag(b.mag, a.mag);
        r.neg = b.neg;
    }
    trim(r);
    return r;
}
Big operator-(Big a) {
    if (!a.mag.empty()) a.neg = !a.neg;
    return a;
}
Big operator-(const Big& a, const Big& b) { return a + (-b); }

Big operator*(const Big& a, const Big& b) {
    Big r;
    r.mag.assign(a.mag.size() + b.mag.size() + 1, 0);
    for (std::size_t i = 0; i < a.mag.size(); ++i) {
        std::uint64_t carry = 0;
        for (std::size_t j = 0; j < b.mag.size(); ++j) {
            const std::uint64_t s = std::uint64_t(a.mag[i]) * b.mag[j] + r.mag[i + j] + carry;
            r.mag[i + j] = std::uint32_t(s);
            carry = s >> 32;
        }
        r.mag[i + b.mag.size()] = std::uint32_t(carry);
    }
    r.neg = a.neg != b.neg;
    trim(r);
    return r;
}

int cmp(const Big& a, const Big& b) {
    if (a.neg != b.neg) return a.neg ? -1 : 1;
    const int m = cmpMag(a.mag, b.mag);
    return a.neg ? -m : m;
}

int bitLength(const Big& a) {
    if (a.mag.empty()) return 0;
    int n = int(32 * (a.mag.size() - 1));
    for (std::uint32_t top = a.mag.back(); top != 0; top >>= 1) ++n;
    return n;
}

Big shiftLeft(const Big& a, int bits) { // a * 2^bits
    const std::size_t whole = std::size_t(bits / 32);
    const int part = bits % 32;
    Big r;
    r.neg = a.neg;
    r.mag.assign(a.mag.size() + whole + 1, 0);
    for (std::size_t i = 0; i < a.mag.size(); ++i) {
        const std::uint64_t v = std::uint64_t(a.mag[i]) << part;
        r.mag[i + whole] |= std::uint32_t(v);
        r.mag[i + whole + 1] |= std::uint32_t(v >> 32);
    }
    trim(r);
    return r;
}

Big shiftRight(const Big& a, int bits) { // sign(a) floor(|a| / 2^bits)
    const std::size_t whole = std::size_t(bits / 32);
    const int part = bits % 32;
    Big r;
    r.neg = a.neg;
    for (std::size_t i = whole; i < a.mag.size(); ++i) {
        const std::uint64_t next = i + 1 < a.mag.size() ? a.mag[i + 1] : 0u;
        r.mag.push_back(std::uint32_t(((next << 32) | a.mag[i]) >> part));
    }
    trim(r);
    return r;
}

int trailingZeros(const Big& a) { // of a non-zero a
    std::size_t i = 0;
    while (a.mag[i] == 0) ++i;
    int n = int(32 * i);
    for (std::uint32_t l = a.mag[i]; (l & 1u) == 0; l >>= 1) ++n;
    return n;
}

// floor(n / d) for d > 0 by shift-and-subtract long division (the quotient must fit 62 bits).
std::int64_t floorDiv(const Big& n, const Big& d) {
    Big r = n;
    r.neg = false;
    std::uint64_t q = 0;
    const int top = bitLength(r) - bitLength(d);
    REQUIRE(top <= 61);
    for (int s = top; s >= 0; --s) {
        const Big ds = shiftLeft(d, s);
        if (cmpMag(ds.mag, r.mag) <= 0) {
            r = r - ds;
            q |= std::uint64_t(1) << s;
        }
    }
    if (!n.neg) return std::int64_t(q);
    return r.mag.empty() ? -std::int64_t(q) : -std::int64_t(q) - 1;
}

// --- Exact rationals n / d, d > 0, kept small by cancelling common powers of two ----------------
struct Q {
    Big n, d;
};

Q rational(Big n, Big d) {
    REQUIRE(!d.mag.empty());
    if (d.neg) {
        n = -n;
        d = -d;
    }
    if (n.mag.empty()) return {n, big(1)};
    const int z = std::min(trailingZeros(n), trailingZeros(d));
    return {shiftRight(n, z), shiftRight(d, z)};
}
Q rational(std::int64_t v) { return {big(v), big(1)}; }

Q operator+(const Q& a, const Q& b) { return rational(a.n * b.d + b.n * a.d, a.d * b.d); }
Q operator-(const Q& a, const Q& b) { return rational(a.n * b.d - b.n * a.d, a.d * b.d); }
Q operator*(const Q& a, const Q& b) { return rational(a.n * b.n, a.d * b.d); }
Q operator/(const Q& a, const Q& b) { return rational(a.n * b.d, a.d * b.n); }
int cmp(const Q& a, const Q& b) { return cmp(a.n * b.d, b.n * a.d); }
int sign(const Q& a) { return a.n.mag.empty() ? 0 : a.n.neg ? -1 : 1; }

// The exact value of a finite float: frexp's fraction times 2^24 is an integer.
Q exact(float v) {
    int e = 0;
    const float f = std::frexp(v, &e);
    const Big m = big(std::int64_t(std::ldexp(f, 24)));
    e -= 24;
    return e >= 0 ? rational(shiftLeft(m, e), big(1)) : rational(m, shiftLeft(big(1), -e));
}

// Rule 1's snap, floor(256 v + 1/2) = floor((512 n + d) / (2 d)).
std::int64_t snap(const Q& v) { return floorDiv(big(512) * v.n + v.d, big(2) * v.d); }

// --- The rule ----------------------------------------------------------------------------------

// Rules 2-3 for the snapped segment (X0, Y0)-(X1, Y1), pixels inside the scissor only (the columns
// outside it are skipped: they hold no pixel of the scissor).
PixelSet rulePixels(const Scissor& s, std::int64_t X0, std::int64_t Y0, std::int64_t X1, std::int64_t Y1) {
    const auto fdiv = [](std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
    const bool yMajor = std::llabs(Y1 - Y0) > std::llabs(X1 - X0);
    if (yMajor) {
        std::swap(X0, Y0);
        std::swap(X1, Y1);
    }
    if (X1 < X0) {
        std::swap(X0, X1);
        std::swap(Y0, Y1);
    }
    const std::int64_t first = std::max<std::int64_t>(fdiv(X0, 256), yMajor ? s.y0 : s.x0);
    const std::int64_t last = std::min<std::int64_t>(fdiv(X1, 256), (yMajor ? s.y1 : s.x1) - 1);
    PixelSet p;
    for (std::int64_t c = first; c <= last; ++c) {
        const std::int64_t m = std::clamp<std::int64_t>(c * 256 + 128, X0, X1);
        const std::int64_t row = X1 == X0 ? fdiv(Y0, 256) : fdiv(Y0 * (X1 - X0) + (m - X0) * (Y1 - Y0), 256 * (X1 - X0));
        const std::int64_t x = yMajor ? row : c, y = yMajor ? c : row;
        if (x >= s.x0 && x < s.x1 && y >= s.y0 && y < s.y1) p.insert({int(x), int(y)});
    }
    return p;
}

} // namespace

// Rule 5 then rules 1-3 in exact rationals: no canonical order (the rule is a function of the
// unordered pair), and the textbook Liang-Barsky p/q form with the clipped ends as a + t (b - a),
// where LineClip orders by sign and evaluates on the boundary.
PixelSet linePixels(const Scissor& s, float ax, float ay, float bx, float by) {
    if (!std::isfinite(ax) || !std::isfinite(ay) || !std::isfinite(bx) || !std::isfinite(by)) return {};
    const Q a[2] = {exact(ax), exact(ay)}, b[2] = {exact(bx), exact(by)};
    const float band = 16384.0f;
    if (std::fabs(ax) <= band && std::fabs(ay) <= band && std::fabs(bx) <= band && std::fabs(by) <= band)
        return rulePixels(s, snap(a[0]), snap(a[1]), snap(b[0]), snap(b[1]));
    const Q d[2] = {b[0] - a[0], b[1] - a[1]};
    const std::int64_t lo[2] = {s.x0 - 1, s.y0 - 1}, hi[2] = {s.x1 + 1, s.y1 + 1};
    Q t0 = rational(0), t1 = rational(1);
    for (int k = 0; k < 2; ++k) { // lo <= a + t d <= hi: -d t <= a - lo and d t <= hi - a
        const Q p[2] = {rational(0) - d[k], d[k]}, q[2] = {a[k] - rational(lo[k]), rational(hi[k]) - a[k]};
        for (int j = 0; j < 2; ++j) {
            if (sign(p[j]) == 0) {
                if (sign(q[j]) < 0) return {};
                continue;
            }
            const Q r = q[j] / p[j];
            if (sign(p[j]) < 0 && cmp(r, t0) > 0) t0 = r;
            if (sign(p[j]) > 0 && cmp(r, t1) < 0) t1 = r;
        }
    }
    if (cmp(t0, t1) > 0) return {};
    return rulePixels(s, snap(a[0] + t0 * d[0]), snap(a[1] + t0 * d[1]), snap(a[0] + t1 * d[0]),
                      snap(a[1] + t1 * d[1]));
}

} // namespace sr::ref
