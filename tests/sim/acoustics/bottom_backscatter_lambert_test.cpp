#include "sim/acoustics/bottom_backscatter_lambert.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "units/angles.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using sonarloop::kRadPerDeg;

TEST_CASE("lambert: Mackenzie -27 dB (docs/physics.md §2.6, §6 item 17)") {
  CHECK_THAT(lambert_backscatter_db(30.0 * kRadPerDeg), WithinAbs(-33.021, 0.001));
  CHECK_THAT(lambert_backscatter_db(10.0 * kRadPerDeg), WithinAbs(-42.207, 0.001));
  CHECK_THAT(lambert_backscatter_db(90.0 * kRadPerDeg), WithinAbs(-27.0, 1e-12));
  CHECK_THAT(lambert_backscatter_db(30.0 * kRadPerDeg, -20.0), WithinAbs(-26.021, 0.001));
}

TEST_CASE("lambert: linear form matches the dB form; energy bound is -4.97 dB") {
  const double mu = std::pow(10.0, kMackenzieLambertMuDb / 10.0);
  for (double deg : {1.0, 10.0, 45.0, 80.0}) {
    CHECK_THAT(10.0 * std::log10(lambert_backscatter_linear(deg * kRadPerDeg, mu)),
               WithinAbs(lambert_backscatter_db(deg * kRadPerDeg), 1e-12));
  }
  CHECK(lambert_backscatter_linear(0.0, mu) == 0.0);
  CHECK(lambert_backscatter_linear(-0.1, mu) == 0.0);
  CHECK_THAT(10.0 * std::log10(1.0 / std::numbers::pi), WithinAbs(-4.97, 0.005));
}
