// Helpers shared by the math tests: ULP distance, float unit roundoff, a portable seeded RNG.
#pragma once

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

#include "Math/Color.hpp"
#include "Math/Mat4.hpp"
#include "TestFramework.hpp"

namespace srtest {

// Unit roundoff of float: the largest relative error of one rounding to nearest (half an ULP
// of 1.0, i.e. FLT_EPSILON / 2 = 2^-24). Tolerances below are stated in multiples of it.
constexpr double kU = FLT_EPSILON / 2.0;

// Number of representable floats between a and b (0 when equal, also for +0 vs -0); huge for
// NaN. Maps the sign-magnitude bit pattern to a monotonic integer line (Bruce Dawson,
// "Comparing Floating Point Numbers, 2012 Edition").
inline std::int64_t ulpDistance(float a, float b) {
    if (std::isnan(a) || std::isnan(b)) return INT64_MAX;
    std::int32_t ia, ib;
    std::memcpy(&ia, &a, sizeof ia);
    std::memcpy(&ib, &b, sizeof ib);
    const std::int64_t la = ia < 0 ? -static_cast<std::int64_t>(ia & 0x7FFFFFFF) : ia;
    const std::int64_t lb = ib < 0 ? -static_cast<std::int64_t>(ib & 0x7FFFFFFF) : ib;
    return la > lb ? la - lb : lb - la;
}

// |got - want| / |want| (|got - want| when want == 0).
inline double relErr(double got, double want) {
    const double d = std::fabs(got - want);
    return want == 0.0 ? d : d / std::fabs(want);
}

// SplitMix64 (Steele, Lea, Flood 2014): the same sequence on every compiler and standard
// library, unlike std::uniform_real_distribution.
struct Rng {
    std::uint64_t state;
    explicit Rng(std::uint64_t seed) : state(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform float in [lo, hi).
    float uniform(float lo, float hi) {
        const double t = static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); // [0, 1)
        return static_cast<float>(lo + (hi - lo) * t);
    }
};

inline bool exactlyEqual(const sr::Mat4& a, const sr::Mat4& b) { return a == b; }

// Largest |a(r, c) - b(r, c)| over the 16 elements.
inline double maxAbsDiff(const sr::Mat4& a, const sr::Mat4& b) {
    double m = 0.0;
    for (int i = 0; i < 16; ++i) m = std::fmax(m, std::fabs(static_cast<double>(a.m[i]) - b.m[i]));
    return m;
}

} // namespace srtest

// Readable failure messages: Catch prints these types instead of "{?}".
namespace Catch {
template <>
struct StringMaker<sr::Vec3> {
    static std::string convert(sr::Vec3 v) {
        std::ostringstream o;
        o.precision(9);
        o << "(" << v.x << ", " << v.y << ", " << v.z << ")";
        return o.str();
    }
};
template <>
struct StringMaker<sr::Vec4> {
    static std::string convert(sr::Vec4 v) {
        std::ostringstream o;
        o.precision(9);
        o << "(" << v.x << ", " << v.y << ", " << v.z << ", " << v.w << ")";
        return o.str();
    }
};
template <>
struct StringMaker<sr::Color> {
    static std::string convert(sr::Color c) {
        std::ostringstream o;
        o.precision(9);
        o << "Color(" << c.r << ", " << c.g << ", " << c.b << ", " << c.a << ")";
        return o.str();
    }
};
template <>
struct StringMaker<sr::Mat4> {
    static std::string convert(const sr::Mat4& m) {
        std::ostringstream o;
        o.precision(9);
        o << "rows [";
        for (int r = 0; r < 4; ++r) {
            o << (r ? "; " : "");
            for (int c = 0; c < 4; ++c) o << (c ? " " : "") << m(r, c);
        }
        o << "]";
        return o.str();
    }
};
} // namespace Catch
