#include "sim/acoustics/target_scattering.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "tests/sim/acoustics/tessellated_sphere.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// seawater of docs/physics.md §4: 1027 kg/m³, 1500 m/s
const double kZWater = acoustic_impedance(1027.0, 1500.0);

}  // namespace

TEST_CASE("target scattering: impedance reflectance table of docs/physics.md §4 (item 23)") {
  CHECK_THAT(kZWater, WithinRel(1.5405e6, 1e-12));
  const double z_steel = acoustic_impedance(7850.0, 5900.0);
  CHECK_THAT(z_steel, WithinRel(4.632e7, 1e-3));
  CHECK_THAT(impedance_reflectance(kZWater, z_steel), WithinAbs(0.9356, 5e-5));
  CHECK_THAT(std::pow(impedance_reflectance(kZWater, z_steel), 2.0), WithinAbs(0.8754, 5e-5));
  CHECK_THAT(impedance_reflectance(kZWater, acoustic_impedance(2700.0, 6320.0)),
             WithinAbs(0.8344, 5e-5));
  CHECK_THAT(impedance_reflectance(kZWater, acoustic_impedance(2400.0, 3700.0)),
             WithinAbs(0.7043, 5e-5));
  CHECK_THAT(impedance_reflectance(kZWater, acoustic_impedance(1800.0, 2500.0)),
             WithinAbs(0.4899, 5e-5));
  CHECK_THAT(impedance_reflectance(kZWater, acoustic_impedance(1100.0, 1600.0)),
             WithinAbs(0.0665, 5e-5));
  CHECK(impedance_reflectance(kZWater, kZWater) == 0.0);
  CHECK(impedance_reflectance(kZWater, 0.5 * kZWater) < 0.0);
}

TEST_CASE("target scattering: the documented mu = R^2/pi choice") {
  CHECK_THAT(lambert_mu_from_reflectance(1.0), WithinRel(kLambertMaxMu, 1e-15));
  CHECK_THAT(lambert_mu_from_reflectance(-1.0), WithinRel(1.0 / std::numbers::pi, 1e-15));
  const double r_steel = impedance_reflectance(kZWater, acoustic_impedance(7850.0, 5900.0));
  CHECK_THAT(lambert_mu_from_reflectance(r_steel), WithinAbs(0.8754 / std::numbers::pi, 2e-5));
}

TEST_CASE("target scattering: Lambertian facet and sphere (docs/physics.md §4, item 23)") {
  CHECK(lambert_facet_backscatter(1.0, 0.2) == 0.2);
  CHECK_THAT(lambert_facet_backscatter(0.5, 0.2), WithinRel(0.05, 1e-15));
  CHECK(lambert_facet_backscatter(-0.5, 0.2) == 0.0);
  CHECK(lambert_facet_backscatter(0.0, 0.2) == 0.0);

  const double mu = 1.0 / std::numbers::pi;
  CHECK_THAT(lambert_sphere_cross_section_m2(mu, 1.0), WithinRel(2.0 / 3.0, 1e-15));
  CHECK_THAT(target_strength_db(lambert_sphere_cross_section_m2(mu, 1.0)),
             WithinAbs(-1.761, 0.0005));
  CHECK_THAT(target_strength_db(lambert_sphere_cross_section_m2(mu, 0.5)),
             WithinAbs(-7.782, 0.0005));
  // specular sphere a²/4 for comparison
  CHECK_THAT(target_strength_db(0.25), WithinAbs(-6.021, 0.0005));

  // numeric: integrate μ cos²θ dA over a tessellated sphere and compare with (2π/3)·μ·a²
  for (double radius : {0.5, 1.0}) {
    const double numeric = sonarloop::testing::tessellated_sphere_sum(
        radius, 180, 360, 2, [&](double c) { return lambert_facet_backscatter(c, mu); });
    INFO("radius " << radius);
    CHECK_THAT(numeric, WithinRel(lambert_sphere_cross_section_m2(mu, radius), 1e-3));
    CHECK_THAT(target_strength_db(numeric),
               WithinAbs(target_strength_db(2.0 * radius * radius / 3.0), 0.005));
  }
}
