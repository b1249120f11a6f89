// How the headless command writes a number into its JSON lines (bench, and bench's flight).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace sr::headless {

// v with four decimals, the precision of every time and ratio the JSON lines carry ("%.4f": 42 ->
// "42.0000", 2/3 -> "0.6667"). JSON has no NaN or infinity: a non-finite value is written as null.
inline std::string jsonNumber(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[328]; // the longest finite "%.4f": a sign, DBL_MAX's 309 digits, a point, 4 decimals
    std::snprintf(buf, sizeof buf, "%.4f", v);
    return buf;
}

} // namespace sr::headless
