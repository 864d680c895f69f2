#include "sim/acoustics/apl_sediment.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/seabed/sediment.h"
#include "tests/sim/acoustics/apl_sediment_by_key.h"
#include "units/angles.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using sonarloop::kRadPerDeg;
using sonarloop::seabed::find_sediment;
using sonarloop::seabed::sediment_table;
using sonarloop::testing::apl_sediment_by_key;

TEST_CASE("apl sediment: grain-size relations, sandy gravel and very fine sand (items 11, 12)") {
  const AplSediment g = apl_from_grain_size(-1.0);
  CHECK_THAT(g.rho, WithinRel(2.4923, 1e-4));
  CHECK_THAT(g.nu, WithinRel(1.3370, 1e-4));
  CHECK_THAT(g.delta, WithinRel(0.01705, 1e-4 + 0.5e-5 / 0.01705));
  CHECK_THAT(g.w2_cm4, WithinRel(0.012937, 1e-4));
  CHECK(g.sigma2 == 0.002);
  CHECK(g.gamma == 3.25);

  const AplSediment v = apl_from_grain_size(3.5);
  CHECK_THAT(v.rho, WithinRel(1.2677, 1e-4));
  CHECK_THAT(v.nu, WithinRel(1.0568, 1e-4));
  CHECK_THAT(v.delta, WithinRel(0.01875, 1e-4 + 0.5e-5 / 0.01875));
  CHECK_THAT(v.w2_cm4, WithinRel(0.001544, 1e-4 + 0.5e-6 / 0.001544));
  CHECK(v.sigma2 == 0.002);
}

TEST_CASE("apl sediment: every row of TR 9407 Table 2 as printed in docs/physics.md §2.2") {
  struct Row {
    const char* key;
    double rho, nu, delta, sigma2, w2;
  };
  const Row rows[] = {
      {"rough_rock", 2.5, 2.5, 0.01374, 0.002, 0.20693},
      {"rock", 2.5, 2.5, 0.01374, 0.002, 0.01862},
      {"cobble", 2.5, 1.8, 0.01374, 0.002, 0.016},
      {"sandy_gravel", 2.492, 1.3370, 0.01705, 0.002, 0.012937},
      {"very_coarse_sand", 2.401, 1.3067, 0.01667, 0.002, 0.010573},
      {"muddy_sandy_gravel", 2.314, 1.2778, 0.01630, 0.002, 0.008602},
      {"coarse_sand", 2.231, 1.2503, 0.01638, 0.002, 0.006957},
      {"gravelly_muddy_sand", 2.151, 1.2241, 0.01645, 0.002, 0.005587},
      {"medium_sand", 1.845, 1.1782, 0.01624, 0.002, 0.004446},
      {"muddy_gravel", 1.615, 1.1396, 0.01610, 0.002, 0.003498},
      {"fine_sand", 1.451, 1.1073, 0.01602, 0.002, 0.002715},
      {"muddy_sand", 1.339, 1.0800, 0.01728, 0.002, 0.002070},
      {"very_fine_sand", 1.268, 1.0568, 0.01875, 0.002, 0.001544},
      {"clayey_sand", 1.224, 1.0364, 0.02019, 0.002, 0.001119},
      {"coarse_silt", 1.195, 1.0179, 0.02158, 0.002, 0.000781},
      {"sandy_silt", 1.169, 0.9999, 0.01261, 0.002, 0.000517},
      {"medium_silt", 1.149, 0.9885, 0.00676, 0.001, 0.000517},
      {"sandy_mud", 1.149, 0.9873, 0.00386, 0.001, 0.000517},
      {"fine_silt", 1.148, 0.9861, 0.00306, 0.001, 0.000517},
      {"sandy_clay", 1.147, 0.9849, 0.00242, 0.001, 0.000517},
      {"very_fine_silt", 1.147, 0.9837, 0.00194, 0.001, 0.000517},
      {"silty_clay", 1.146, 0.9824, 0.00163, 0.001, 0.000517},
      {"clay", 1.145, 0.9800, 0.00148, 0.001, 0.000517},
  };
  REQUIRE(sediment_table().size() == std::size(rows));
  for (const Row& r : rows) {
    INFO(r.key);
    const AplSediment s = apl_sediment_by_key(r.key);
    // tolerances: half a unit of the printed last digit
    CHECK_THAT(s.rho, WithinAbs(r.rho, 0.0005 + 1e-9));
    CHECK_THAT(s.nu, WithinAbs(r.nu, 0.00005 + 1e-9));
    CHECK_THAT(s.delta, WithinAbs(r.delta, 0.000005 + 1e-9));
    CHECK(s.sigma2 == r.sigma2);
    CHECK(s.gamma == 3.25);
    CHECK_THAT(s.w2_cm4, WithinAbs(r.w2, 0.0000005 + 1e-9));
  }
}

TEST_CASE("apl sediment: id validation, Mz clamping and c1 in Eq. 4") {
  CHECK_THROWS_AS(apl_sediment(-1), std::invalid_argument);
  CHECK_THROWS_AS(apl_sediment(static_cast<int>(sediment_table().size())), std::invalid_argument);
  try {
    apl_sediment(99);
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("99") != std::string::npos);
  }
  const AplSediment lo = apl_from_grain_size(-3.0);
  const AplSediment at = apl_from_grain_size(-1.0);
  CHECK(lo.rho == at.rho);
  CHECK(lo.w2_cm4 == at.w2_cm4);
  CHECK(apl_from_grain_size(12.0).nu == apl_from_grain_size(9.0).nu);
  // δ scales linearly with c1 (Eq. 4)
  CHECK_THAT(apl_from_grain_size(2.0, 1500.0).delta,
             WithinRel(apl_from_grain_size(2.0, 1528.0).delta * 1500.0 / 1528.0, 1e-12));
}

TEST_CASE("apl sediment: Rayleigh reflection and bottom loss (§2.3, item 13)") {
  const AplSediment vfs = apl_sediment_by_key("very_fine_sand");
  const AplSediment gravel = apl_sediment_by_key("sandy_gravel");
  const AplSediment rough = apl_sediment_by_key("rough_rock");
  CHECK_THAT(std::abs(rayleigh_reflection(90.0 * kRadPerDeg, vfs)), WithinAbs(0.1454, 0.0005));
  CHECK_THAT(std::abs(rayleigh_reflection(90.0 * kRadPerDeg, rough)), WithinAbs(0.7241, 0.0005));
  CHECK_THAT(std::abs(rayleigh_reflection(90.0 * kRadPerDeg, gravel)), WithinAbs(0.5383, 0.0005));
  CHECK_THAT(bottom_loss_db(10.0 * kRadPerDeg, vfs), WithinAbs(1.783, 0.0005));
  CHECK_THAT(bottom_loss_db(30.0 * kRadPerDeg, vfs), WithinAbs(12.053, 0.0005));
  CHECK_THAT(bottom_loss_db(90.0 * kRadPerDeg, vfs), WithinAbs(16.749, 0.0005));
  CHECK_THAT(bottom_loss_db(30.0 * kRadPerDeg, gravel), WithinAbs(0.271, 0.0005));
  CHECK_THAT(bottom_loss_db(90.0 * kRadPerDeg, gravel), WithinAbs(5.379, 0.0005));
  CHECK_THAT(bottom_loss_db(90.0 * kRadPerDeg, rough), WithinAbs(2.804, 0.0005));
  // grazing incidence is total reflection with a phase flip, R(0) = −1
  CHECK_THAT(rayleigh_reflection(0.0, vfs).real(), WithinAbs(-1.0, 1e-12));
  // below the critical angle a lossless fast bottom reflects totally
  AplSediment lossless = gravel;
  lossless.delta = 0.0;
  const double critical = std::acos(1.0 / lossless.nu);
  CHECK_THAT(std::abs(rayleigh_reflection(0.5 * critical, lossless)), WithinAbs(1.0, 1e-12));
  // P is the principal root: non-negative real part, and Im P > 0 with loss
  const auto p = apl_vertical_wavenumber(20.0 * kRadPerDeg, vfs);
  CHECK(p.real() >= 0.0);
  CHECK(p.imag() > 0.0);
}
