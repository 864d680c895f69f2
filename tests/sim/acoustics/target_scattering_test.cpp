#include "sim/acoustics/target_scattering.h"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

using Vec3 = std::array<double, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

Vec3 sphere_point(double radius, double polar, double azimuth) {
  return {radius * std::sin(polar) * std::cos(azimuth),
          radius * std::sin(polar) * std::sin(azimuth), radius * std::cos(polar)};
}

// Σ over flat triangles of a UV-tessellated sphere of μ·cos²θ·dA, seen from far along +z
// (the sonar direction, unit vector d = (0, 0, 1)).
double tessellated_sphere_cross_section(double mu, double radius, int n_polar, int n_azimuth) {
  const double pi = std::numbers::pi;
  double sigma = 0.0;
  auto add_triangle = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n2 = cross(sub(b, a), sub(c, a));  // |n2| = 2·area, outward by winding
    const double twice_area = norm(n2);
    if (twice_area <= 0.0) return;
    const double cos_incidence = n2[2] / twice_area;  // normal · d
    sigma += lambert_facet_backscatter(cos_incidence, mu) * 0.5 * twice_area;
  };
  for (int i = 0; i < n_polar; ++i) {
    const double p0 = pi * i / n_polar;
    const double p1 = pi * (i + 1) / n_polar;
    for (int j = 0; j < n_azimuth; ++j) {
      const double a0 = 2.0 * pi * j / n_azimuth;
      const double a1 = 2.0 * pi * (j + 1) / n_azimuth;
      const Vec3 v00 = sphere_point(radius, p0, a0);
      const Vec3 v01 = sphere_point(radius, p0, a1);
      const Vec3 v10 = sphere_point(radius, p1, a0);
      const Vec3 v11 = sphere_point(radius, p1, a1);
      add_triangle(v00, v10, v11);
      add_triangle(v00, v11, v01);
    }
  }
  return sigma;
}

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
    const double numeric = tessellated_sphere_cross_section(mu, radius, 180, 360);
    INFO("radius " << radius);
    CHECK_THAT(numeric, WithinRel(lambert_sphere_cross_section_m2(mu, radius), 1e-3));
    CHECK_THAT(target_strength_db(numeric),
               WithinAbs(target_strength_db(2.0 * radius * radius / 3.0), 0.005));
  }
}
