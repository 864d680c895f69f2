#include "tests/sim/acoustics/oracles/sonar_equation.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/acoustics/beam_pattern.h"
#include "tests/sim/acoustics/oracles/reverberation.h"
#include "tests/sim/acoustics/oracles/spreading.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;

TEST_CASE(
    "sonar equation: echo level of a seabed cell equals RL on axis (docs/physics.md §0, §3)") {
  const double tl = transmission_loss_db(50.0, 33.6303e-3);
  const double area = reverberation_cell_area_m2(50.0, 100e-6, 1500.0, 0.013288);
  const double strength = -30.0 + 10.0 * std::log10(area);
  CHECK_THAT(echo_level_db(210.0, tl, strength, 0.0), WithinAbs(95.6532, 0.001));
  CHECK_THAT(echo_level_db(210.0, tl, strength, 0.0),
             WithinAbs(boundary_reverberation_level_db(210.0, tl, -30.0, area), 1e-12));
  // off axis at the one-way −3 dB point the two-way pattern takes 6.02 dB
  const double lambda = 0.015;
  const double off = beamwidth_3db_one_way_rad(1.0, lambda) / 2.0;
  CHECK_THAT(echo_level_db(210.0, tl, strength, two_way_pattern_db(off, 1.0, lambda)),
             WithinAbs(95.6532 - 6.0206, 0.001));
}

TEST_CASE("sonar equation: signal excess as printed, and power sums") {
  // XS = SL − 2TL + TS + DI − NL − RL
  CHECK_THAT(signal_excess_db(210.0, 40.0, -10.0, 21.25, 25.0, 60.0),
             WithinAbs(210.0 - 80.0 - 10.0 + 21.25 - 25.0 - 60.0, 1e-12));
  CHECK_THAT(power_sum_db(60.0, 60.0), WithinAbs(63.0103, 1e-4));
  CHECK_THAT(power_sum_db(60.0, 40.0), WithinAbs(60.0432, 1e-4));
  CHECK_THAT(power_sum_db(40.0, 60.0), WithinAbs(60.0432, 1e-4));
  CHECK(std::isfinite(power_sum_db(2000.0, 1990.0)));
}
