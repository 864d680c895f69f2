#include "sim/acoustics/beam_pattern.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "units/angles.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using sonarloop::kRadPerDeg;

namespace {

// docs/physics.md §3 worked example: f = 100 kHz, c = 1500 m/s, l = 1 m
constexpr double kLambda = 1500.0 / 100e3;
constexpr double kLength = 1.0;

// off-axis angle at which x = (π l/λ) sin θ takes the given value
double angle_for_x(double x) {
  return std::asin(x * kLambda / (std::numbers::pi * kLength));
}

}  // namespace

TEST_CASE("beam pattern: sinc is exact at 0 and continuous across the series switch") {
  CHECK(sinc(0.0) == 1.0);
  CHECK(line_array_pattern(0.0, kLength, kLambda) == 1.0);
  CHECK(line_array_pattern_db(0.0, kLength, kLambda) == 0.0);
  CHECK_THAT(sinc(0.99e-4), WithinRel(std::sin(0.99e-4) / 0.99e-4, 1e-15));
  CHECK_THAT(sinc(1.01e-4), WithinRel(1.0 - 1.01e-4 * 1.01e-4 / 6.0, 1e-15));
  CHECK(sinc(-0.3) == sinc(0.3));
}

TEST_CASE("beam pattern: half-power points and first sidelobe (docs/physics.md §4, §6 item 19)") {
  CHECK_THAT(sinc(1.391557), WithinAbs(1.0 / std::sqrt(2.0), 1e-6));
  CHECK_THAT(sinc(kSincHalfPowerX), WithinAbs(1.0 / std::sqrt(2.0), 1e-15));
  CHECK_THAT(sinc(kSincSquaredHalfPowerX) * sinc(kSincSquaredHalfPowerX),
             WithinAbs(1.0 / std::sqrt(2.0), 1e-15));
  CHECK_THAT(line_array_pattern_db(angle_for_x(4.493409), kLength, kLambda),
             WithinAbs(-13.2615, 1e-4));
  // it is a maximum of |B|: neighbours are lower
  const double peak = std::fabs(sinc(kSincFirstSidelobeX));
  CHECK(std::fabs(sinc(kSincFirstSidelobeX - 0.01)) < peak);
  CHECK(std::fabs(sinc(kSincFirstSidelobeX + 0.01)) < peak);
}

TEST_CASE("beam pattern: worked numbers of docs/physics.md §3 (l 1 m, 100 kHz)") {
  CHECK_THAT(line_array_pattern(0.2 * kRadPerDeg, kLength, kLambda), WithinAbs(0.91327, 5e-6));
  CHECK_THAT(line_array_pattern(0.5 * kRadPerDeg, kLength, kLambda), WithinAbs(0.52919, 5e-6));
  CHECK_THAT(line_array_pattern(1.0 * kRadPerDeg, kLength, kLambda), WithinAbs(-0.13442, 5e-6));
  CHECK_THAT(line_array_pattern_db(0.2 * kRadPerDeg, kLength, kLambda), WithinAbs(-0.788, 5e-4));
  CHECK_THAT(line_array_pattern_db(0.5 * kRadPerDeg, kLength, kLambda), WithinAbs(-5.528, 5e-4));
  CHECK_THAT(line_array_pattern_db(1.0 * kRadPerDeg, kLength, kLambda), WithinAbs(-17.431, 5e-4));
  CHECK_THAT(two_way_pattern_db(0.5 * kRadPerDeg, kLength, kLambda), WithinAbs(2.0 * -5.528, 1e-3));

  const double bw = beamwidth_3db_one_way_rad(kLength, kLambda);
  CHECK_THAT(bw, WithinAbs(0.013288, 5e-7));
  CHECK_THAT(bw / kRadPerDeg, WithinAbs(0.7614, 5e-5));
  CHECK_THAT(bw, WithinRel(0.885893 * kLambda / kLength, 1e-4));
  CHECK_THAT(line_array_pattern_db(bw / 2.0, kLength, kLambda), WithinAbs(-3.0103, 1e-4));
  const double bw2 = beamwidth_3db_two_way_rad(kLength, kLambda);
  CHECK_THAT(bw2, WithinRel(0.637833 * kLambda / kLength, 1e-4));
  CHECK_THAT(two_way_pattern_db(bw2 / 2.0, kLength, kLambda), WithinAbs(-3.0103, 1e-4));
  CHECK_THAT(first_null_rad(kLength, kLambda) / kRadPerDeg, WithinAbs(0.8595, 5e-5));
  CHECK(line_array_pattern_db(first_null_rad(kLength, kLambda), kLength, kLambda) < -100.0);
  CHECK_THAT(directivity_index_line_db(kLength, kLambda), WithinAbs(21.25, 0.005));
  // short aperture: no -3 dB point, reported as omnidirectional
  CHECK(beamwidth_3db_one_way_rad(0.005, kLambda) == std::numbers::pi);
  CHECK(beamwidth_3db_two_way_rad(0.004, kLambda) == std::numbers::pi);
  CHECK(first_null_rad(0.01, kLambda) == std::numbers::pi / 2.0);
}

TEST_CASE("beam pattern: dB floor and rectangular piston DI") {
  // exactly on a null: sin(π)/π is ~1e-17, well below the floor
  CHECK(line_array_pattern_db(std::numbers::pi / 2.0, 3.0 * kLambda, 3.0 * kLambda) >=
        kPatternFloorDb);
  CHECK(two_way_pattern_db(std::numbers::pi / 2.0, 3.0 * kLambda, 3.0 * kLambda) >=
        kPatternFloorDb);
  // 4π l w / λ²: l = 1 m, w = 0.05 m at 100 kHz
  CHECK_THAT(
      directivity_index_rect_db(1.0, 0.05, kLambda),
      WithinAbs(10.0 * std::log10(4.0 * std::numbers::pi * 0.05 / (kLambda * kLambda)), 1e-12));
  CHECK_THAT(directivity_index_rect_db(1.0, 0.05, kLambda), WithinAbs(34.460, 5e-4));
}

TEST_CASE("beam pattern: sidescan array two-way intensity is the product of both planes") {
  const SidescanArray array{1.0, 0.05, 15.0 * kRadPerDeg};
  CHECK(array_pattern_two_way(array, kLambda, 0.0, 0.0) == 1.0);
  for (double along : {0.0, 0.1 * kRadPerDeg, 0.37 * kRadPerDeg, 2.0 * kRadPerDeg}) {
    for (double vert : {0.0, 5.0 * kRadPerDeg, 17.0 * kRadPerDeg, 40.0 * kRadPerDeg}) {
      const double g = array_pattern_two_way(array, kLambda, along, vert);
      const double expected_db = two_way_pattern_db(along, array.length_m, kLambda) +
                                 two_way_pattern_db(vert, array.height_m, kLambda);
      INFO("along " << along / kRadPerDeg << " deg, vertical " << vert / kRadPerDeg << " deg");
      if (expected_db > -150.0) {
        CHECK_THAT(10.0 * std::log10(g), WithinAbs(expected_db, 1e-9));
      }
      CHECK(g >= 0.0);
      CHECK(g <= 1.0);
    }
  }
  // vertical -3 dB two-way half-width of a 5 cm aperture
  const double half = beamwidth_3db_two_way_rad(array.height_m, kLambda) / 2.0;
  CHECK_THAT(array_pattern_two_way(array, kLambda, 0.0, half), WithinAbs(0.5, 1e-12));
  CHECK_THAT(vertical_off_axis_rad(array, 20.0 * kRadPerDeg), WithinAbs(5.0 * kRadPerDeg, 1e-15));
}
