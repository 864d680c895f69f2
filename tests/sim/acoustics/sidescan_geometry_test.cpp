#include "tests/sim/acoustics/oracles/sidescan_geometry.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/acoustics/beam_pattern.h"
#include "units/angles.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using sonarloop::kRadPerDeg;

TEST_CASE("geometry: ranges, grazing angle and resolutions (docs/physics.md §3, item 21)") {
  CHECK_THAT(ground_range_m(50.0, 10.0), WithinAbs(48.9898, 5e-5));
  const double grazing = grazing_angle_rad(50.0, 10.0);
  CHECK_THAT(grazing / kRadPerDeg, WithinAbs(11.537, 5e-4));
  const double dr = range_resolution_cw_m(100e-6, 1500.0);
  CHECK_THAT(dr, WithinAbs(0.0750, 1e-12));
  CHECK_THAT(ground_range_resolution_m(dr, grazing), WithinAbs(0.07655, 5e-6));
  CHECK_THAT(range_resolution_chirp_m(20e3, 1500.0), WithinAbs(0.0375, 1e-12));
  CHECK_THAT(slant_range_m(2.0 * 50.0 / 1500.0, 1500.0), WithinRel(50.0, 1e-12));
  // inside the water column
  CHECK(ground_range_m(8.0, 10.0) == 0.0);
  CHECK(grazing_angle_rad(8.0, 10.0) == std::numbers::pi / 2.0);
}

TEST_CASE("geometry: along-track resolution, far field, ping rate, tow speed (items 19, 22)") {
  const double lambda = 1500.0 / 100e3;
  const double beta = beamwidth_3db_one_way_rad(1.0, lambda);
  CHECK_THAT(along_track_resolution_m(50.0, beta), WithinAbs(0.664, 5e-4));
  CHECK_THAT(far_field_range_m(1.0, lambda), WithinAbs(66.7, 0.05));
  CHECK_THAT(min_ping_interval_s(150.0, 1500.0), WithinRel(0.2, 1e-12));
  const double v = max_tow_speed_m_s(1.0, 1500.0, 100.0, 3.0);
  CHECK_THAT(v, WithinAbs(2.500, 1e-12));
  CHECK_THAT(v * 3600.0 / 1852.0, WithinAbs(4.86, 0.005));  // knots
}
