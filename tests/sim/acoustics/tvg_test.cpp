#include "sim/acoustics/tvg.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "tests/sim/acoustics/oracles/reverberation.h"
#include "tests/sim/acoustics/oracles/spreading.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;

TEST_CASE("tvg: the three laws of docs/physics.md §3") {
  const double alpha = 0.0336;  // dB/m, 100 kHz
  CHECK_THAT(tvg_db(100.0, alpha, TvgLaw::kArea), WithinAbs(60.0 + 6.72, 1e-9));
  CHECK_THAT(tvg_db(100.0, alpha, TvgLaw::kPoint), WithinAbs(80.0 + 6.72, 1e-9));
  CHECK_THAT(tvg_db(100.0, alpha, TvgLaw::kSpherical), WithinAbs(40.0 + 6.72, 1e-9));
  CHECK(tvg_spreading_coeff(TvgLaw::kArea) == 30.0);
  CHECK(tvg_spreading_coeff(TvgLaw::kPoint) == 40.0);
  CHECK(tvg_spreading_coeff(TvgLaw::kSpherical) == 20.0);
  CHECK_THAT(tvg_db(1.0, 0.0, 30.0), WithinAbs(0.0, 1e-15));
}

TEST_CASE("tvg: the area law flattens seabed echoes, the point law point echoes") {
  // echo of a constant-S_b seabed cell: SL − 2TL + S_b + 10 log A(r), A ∝ r
  const double alpha = 0.05;
  auto seabed_echo = [&](double r) {
    return 210.0 - two_way_transmission_loss_db(r, alpha) - 30.0 +
           10.0 * std::log10(reverberation_cell_area_m2(r, 100e-6, 1500.0, 0.0133));
  };
  auto point_echo = [&](double r) { return 210.0 - two_way_transmission_loss_db(r, alpha) - 10.0; };
  const double seabed_ref = seabed_echo(10.0) + tvg_db(10.0, alpha, TvgLaw::kArea);
  const double point_ref = point_echo(10.0) + tvg_db(10.0, alpha, TvgLaw::kPoint);
  for (double r : {20.0, 55.0, 150.0}) {
    CHECK_THAT(seabed_echo(r) + tvg_db(r, alpha, TvgLaw::kArea), WithinAbs(seabed_ref, 1e-9));
    CHECK_THAT(point_echo(r) + tvg_db(r, alpha, TvgLaw::kPoint), WithinAbs(point_ref, 1e-9));
  }
}
