#include "sim/acoustics/noise.h"

#include <catch2/catch.hpp>

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;

TEST_CASE("noise: Mellen thermal noise (docs/physics.md §4 table, §6 item 20)") {
  CHECK_THAT(thermal_noise_spectrum_db(100e3), WithinAbs(25.000, 0.0005));
  CHECK_THAT(thermal_noise_spectrum_db(300e3), WithinAbs(34.542, 0.0005));
  CHECK_THAT(thermal_noise_spectrum_db(80e3), WithinAbs(23.062, 0.0005));
  CHECK_THAT(thermal_noise_spectrum_db(150e3), WithinAbs(28.522, 0.0005));
  CHECK_THAT(thermal_noise_spectrum_db(1e3), WithinAbs(-15.0, 1e-12));
}

TEST_CASE("noise: band level adds 10 log10 B") {
  CHECK_THAT(noise_band_level_db(100e3, 20e3), WithinAbs(25.0 + 43.0103, 1e-4));
  CHECK_THAT(noise_band_level_db(100e3, 1.0), WithinAbs(thermal_noise_spectrum_db(100e3), 1e-12));
}
