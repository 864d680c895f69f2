#include "sim/acoustics/target_specular.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/acoustics/target_scattering.h"
#include "tests/sim/acoustics/tessellated_sphere.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double kPi = std::numbers::pi;

// ∫₀^{π/2} σ_spec(θ)·2π a² sin θ dθ by the midpoint rule (the exact sphere integral for any s).
double sphere_specular_quadrature(double radius, double rms_slope) {
  const int n = 200000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double theta = (k + 0.5) * 0.5 * kPi / n;
    sum += kirchhoff_facet_backscatter(std::cos(theta), rms_slope) * std::sin(theta);
  }
  return sum * 0.5 * kPi / n * 2 * kPi * radius * radius;
}

// The Kirchhoff integral of APL-UW TR 9407 Eqs. 35–40 in the form docs/physics.md §2.4 checks
// its closed form against, for Gaussian slopes (α = 1), per unit |R|²:
//   σ = 1/(8π sin²β cos²β)·∫₀^∞ J0(u)·exp(−q u²)·u du,  q = q_c·sin²β/cos²β,  β the grazing angle.
double apl_kirchhoff_integral(double grazing_rad, double q_c) {
  const double sb = std::sin(grazing_rad), cb = std::cos(grazing_rad);
  const double q = q_c * sb * sb / (cb * cb);
  const double u_max = std::sqrt(40.0 / q);  // exp(−40): the rest is negligible
  const int n = 400000;
  const double du = u_max / n;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double u = (k + 0.5) * du;
    sum += std::cyl_bessel_j(0.0, u) * std::exp(-q * u * u) * u;
  }
  return sum * du / (8 * kPi * sb * sb * cb * cb);
}

}  // namespace

TEST_CASE("target specular: normal incidence, facing away, and the lobe's width") {
  for (double s : {0.05, 0.15, 0.3}) {
    INFO("s " << s);
    CHECK_THAT(kirchhoff_facet_backscatter(1.0, s), WithinRel(1.0 / (8 * kPi * s * s), 1e-14));
    CHECK(kirchhoff_facet_backscatter(0.0, s) == 0.0);
    CHECK(kirchhoff_facet_backscatter(-0.7, s) == 0.0);
    // tan θ = s: exp(−1/2) / cos⁴θ of the peak
    const double c = 1.0 / std::sqrt(1.0 + s * s);
    CHECK_THAT(kirchhoff_facet_backscatter(c, s) / kirchhoff_facet_backscatter(1.0, s),
               WithinRel(std::exp(-0.5) / (c * c * c * c), 1e-12));
  }
  // a rougher surface spreads the same energy wider: dimmer at normal incidence, brighter at 30°
  const double c30 = std::cos(kPi / 6);
  CHECK(kirchhoff_facet_backscatter(1.0, 0.3) < kirchhoff_facet_backscatter(1.0, 0.1));
  CHECK(kirchhoff_facet_backscatter(c30, 0.3) > kirchhoff_facet_backscatter(c30, 0.1));
}

TEST_CASE("target specular: the Gaussian case of TR 9407's Kirchhoff integral, s^2 = 2 q_c") {
  for (double q_c : {0.005, 0.02, 0.05}) {
    const double s = std::sqrt(2 * q_c);
    for (double grazing_deg : {40.0, 60.0, 75.0, 85.0}) {
      const double b = grazing_deg * kPi / 180;
      INFO("q_c " << q_c << ", grazing " << grazing_deg << " deg");
      // incidence from the normal θ = 90° − β: cos θ = sin β
      const double closed = kirchhoff_facet_backscatter(std::sin(b), s);
      const double integral = apl_kirchhoff_integral(b, q_c);
      if (closed < 1e-12) {
        CHECK(std::abs(integral) < 1e-9);
      } else {
        CHECK_THAT(integral, WithinRel(closed, 2e-3));
      }
    }
  }
}

TEST_CASE("target specular: a sphere returns the geometric-optics a^2/4 (docs/physics.md §4)") {
  CHECK(specular_sphere_cross_section_m2(1.0) == 0.25);
  CHECK_THAT(target_strength_db(specular_sphere_cross_section_m2(1.0)), WithinAbs(-6.021, 5e-4));
  CHECK_THAT(target_strength_db(specular_sphere_cross_section_m2(0.5)), WithinAbs(-12.041, 5e-4));
  for (double radius : {0.5, 1.0}) {
    INFO("radius " << radius);
    // s → 0: the exact integral tends to a²/4 (the first correction is of order s²)
    CHECK_THAT(sphere_specular_quadrature(radius, 0.02),
               WithinRel(specular_sphere_cross_section_m2(radius), 1e-3));
    CHECK_THAT(sphere_specular_quadrature(radius, 0.05),
               WithinRel(specular_sphere_cross_section_m2(radius), 5e-3));
    // flat facets of a fine mesh (seen from +x, away from its poles, where the specular spot
    // would fall on slivers) give the same as the smooth sphere, at the default s
    CHECK_THAT(
        sonarloop::testing::tessellated_sphere_sum(
            radius, 180, 360, 0, [](double c) { return kirchhoff_facet_backscatter(c, 0.15); }),
        WithinRel(sphere_specular_quadrature(radius, 0.15), 2e-3));
  }
  // the Lambert sphere of the same reflectance is brighter: (2π/3)·(R²/π)·a² = (2/3)·R²·a²
  CHECK(lambert_sphere_cross_section_m2(lambert_mu_from_reflectance(1.0), 1.0) >
        specular_sphere_cross_section_m2(1.0));
}
