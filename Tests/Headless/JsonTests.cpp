// Tests of jsonNumber, the one number writer of bench's and the flight's JSON lines.
#include "TestFramework.hpp"

#include <cfloat>
#include <limits>
#include <string>

#include "Platform/Headless/Json.hpp"

using sr::headless::jsonNumber;

TEST_CASE("jsonNumber writes integers with four decimals", "[headless][json]") {
    CHECK(jsonNumber(0.0) == "0.0000");
    CHECK(jsonNumber(42.0) == "42.0000");
    CHECK(jsonNumber(-7.0) == "-7.0000");
    CHECK(jsonNumber(1e6) == "1000000.0000");
}

TEST_CASE("jsonNumber rounds fractions to four decimals", "[headless][json]") {
    CHECK(jsonNumber(0.5) == "0.5000");
    CHECK(jsonNumber(-2.25) == "-2.2500");
    CHECK(jsonNumber(1.0 / 3.0) == "0.3333");
    CHECK(jsonNumber(2.0 / 3.0) == "0.6667");
    CHECK(jsonNumber(123456.789) == "123456.7890");
    CHECK(jsonNumber(0.00004) == "0.0000");
}

TEST_CASE("jsonNumber writes a non-finite value as null, the largest finite one whole", "[headless][json]") {
    CHECK(jsonNumber(std::numeric_limits<double>::quiet_NaN()) == "null");
    CHECK(jsonNumber(-std::numeric_limits<double>::quiet_NaN()) == "null");
    CHECK(jsonNumber(std::numeric_limits<double>::infinity()) == "null");
    CHECK(jsonNumber(-std::numeric_limits<double>::infinity()) == "null");
    // Not cut short: a sign, 309 digits, the point and four decimals.
    const std::string most = jsonNumber(-DBL_MAX);
    CHECK(most.size() == 315);
    CHECK(most.substr(most.size() - 5) == ".0000");
}
