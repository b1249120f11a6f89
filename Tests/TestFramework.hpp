// The one header tests include: hides the Catch2 v2 (Debian) / v3 (vcpkg) difference.
#pragma once

#if defined(SR_CATCH2_V3)
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>
#include <catch2/matchers/catch_matchers_floating_point.hpp>
using Catch::Approx; // v2 has Approx in the global namespace already
#else
#include <catch2/catch.hpp>
#endif

