// Catch2 v2's main, compiled once in its own translation unit (v3 links Catch2WithMain instead).
#if !defined(SR_CATCH2_V3)
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
#endif
