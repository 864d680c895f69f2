#include "tests/sim/acoustics/oracles/spreading.h"

#include <catch2/catch.hpp>

#include "sim/acoustics/absorption.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;

namespace {

double alpha_db_per_m(double freq_hz) {
  return francois_garrison_db_per_km(freq_hz, 10.0, 35.0, 0.0, 8.0) / kMetresPerKilometre;
}

}  // namespace

TEST_CASE("spreading: TL examples of docs/physics.md §1c and §6 item 10") {
  CHECK_THAT(transmission_loss_db(100.0, alpha_db_per_m(100e3)), WithinAbs(43.363, 0.001));
  CHECK_THAT(transmission_loss_db(200.0, alpha_db_per_m(100e3)), WithinAbs(52.747, 0.001));
  CHECK_THAT(transmission_loss_db(50.0, alpha_db_per_m(300e3)), WithinAbs(37.636, 0.001));
  // Pailhas RL oracle of §4: TL(50 m, α 33.6303 dB/km)
  CHECK_THAT(transmission_loss_db(50.0, 33.6303e-3), WithinAbs(35.6609, 0.0001));
}

TEST_CASE("spreading: 1 m reference, 6 dB per doubling without absorption, two way") {
  CHECK_THAT(transmission_loss_db(1.0, 0.0), WithinAbs(0.0, 1e-12));
  CHECK_THAT(transmission_loss_db(20.0, 0.0) - transmission_loss_db(10.0, 0.0),
             WithinAbs(6.0206, 1e-4));
  CHECK_THAT(two_way_transmission_loss_db(120.0, 0.03),
             WithinAbs(2.0 * transmission_loss_db(120.0, 0.03), 1e-12));
}
