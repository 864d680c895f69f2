#include "sim/acoustics/backscatter_table.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "sim/acoustics/bottom_backscatter_apl.h"
#include "sim/seabed/sediment.h"
#include "units/angles.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using sonarloop::kRadPerDeg;
using sonarloop::seabed::find_sediment;

TEST_CASE("backscatter table: APL interpolation error < 0.05 dB over 1-90 deg") {
  for (const char* key : {"rough_rock", "rock", "cobble", "sandy_gravel", "very_coarse_sand",
                          "medium_sand", "very_fine_sand", "silty_clay", "clay"}) {
    const auto id = find_sediment(key);
    REQUIRE(id.has_value());
    for (double freq : {30e3, 100e3, 300e3}) {
      const BackscatterTable table = make_backscatter_table(*id, freq, BottomModel::kApl);
      const AplBackscatterSetup setup = make_apl_backscatter_setup(freq, apl_sediment(*id));
      double worst_db = 0.0;
      double worst_deg = 0.0;
      // 0.0037° steps land between grid nodes at every phase
      for (double deg = 1.0; deg <= 90.0; deg += 0.0037) {
        const double err = std::fabs(table.sigma_db(deg * kRadPerDeg) -
                                     apl_backscatter_db(deg * kRadPerDeg, setup));
        if (err > worst_db) {
          worst_db = err;
          worst_deg = deg;
        }
      }
      INFO(key << " " << freq << " Hz: worst " << worst_db << " dB at " << worst_deg << " deg");
      CHECK(worst_db < 0.05);
    }
  }
}

TEST_CASE("backscatter table: exact at nodes and ends, clamped outside, NaN-safe") {
  const auto id = find_sediment("medium_sand");
  REQUIRE(id.has_value());
  const AplBackscatterSetup setup = make_apl_backscatter_setup(100e3, apl_sediment(*id));
  const BackscatterTable table = make_backscatter_table(*id, 100e3, BottomModel::kApl);
  CHECK(table.size() == 1801);  // 0..90° in 0.05° steps
  CHECK_THAT(table.step_rad(), WithinRel(0.05 * kRadPerDeg, 1e-12));
  for (int i : {0, 1, 200, 1000, 1799}) {
    const double th = i * table.step_rad();
    CHECK_THAT(table.sigma(th), WithinRel(apl_backscatter_linear(th, setup), 1e-12));
  }
  const double top = apl_backscatter_linear(std::numbers::pi / 2.0, setup);
  CHECK_THAT(table.sigma(std::numbers::pi / 2.0), WithinRel(top, 1e-12));
  CHECK_THAT(table.sigma(2.0), WithinRel(top, 1e-12));
  CHECK(table.sigma(-0.3) == table.sigma(0.0));
  CHECK(table.sigma(std::numeric_limits<double>::quiet_NaN()) == table.sigma(0.0));
  CHECK(table.sigma(std::numeric_limits<double>::infinity()) == table.sigma(2.0));
}

TEST_CASE("backscatter table: Lambert model and arbitrary functions") {
  const BackscatterTable lambert = make_backscatter_table(0, 100e3, BottomModel::kLambert);
  CHECK_THAT(lambert.sigma_db(30.0 * kRadPerDeg), WithinAbs(-33.021, 0.001));
  CHECK_THAT(lambert.sigma_db(90.0 * kRadPerDeg), WithinAbs(-27.0, 1e-9));
  for (double deg = 1.0; deg <= 90.0; deg += 0.013) {
    CHECK_THAT(lambert.sigma_db(deg * kRadPerDeg),
               WithinAbs(lambert_backscatter_db(deg * kRadPerDeg), 0.05));
  }
  // a linear function is interpolated exactly; a step that does not divide 90° is adjusted
  const BackscatterTable lin([](double th) { return 2.0 * th; }, 0.07 * kRadPerDeg);
  CHECK_THAT(lin.step_rad() * static_cast<double>(lin.size() - 1),
             WithinRel(std::numbers::pi / 2.0, 1e-12));
  CHECK(lin.step_rad() <= 0.07 * kRadPerDeg);
  CHECK_THAT(lin.sigma(0.123456), WithinRel(0.246912, 1e-12));
  CHECK_THROWS_AS(BackscatterTable([](double) { return -1.0; }), std::invalid_argument);
  CHECK_THROWS_AS(BackscatterTable([](double) { return 1.0; }, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(make_backscatter_table(999, 100e3, BottomModel::kApl), std::invalid_argument);
}
