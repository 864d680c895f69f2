#pragma once
// A UV-tessellated sphere (flat triangles between circles of latitude and longitude about +z)
// for the target-scattering oracles: Σ over its triangles of σ(cos θ)·dA, θ between a
// triangle's outward normal and the sonar direction `toward` (a unit axis: 0 = +x, 2 = +z).
#include <array>
#include <cmath>
#include <numbers>

namespace sonarloop::testing {

template <class Sigma>
double tessellated_sphere_sum(double radius, int n_polar, int n_azimuth, int toward,
                              const Sigma& sigma_of_cos) {
  using V = std::array<double, 3>;
  constexpr double kPi = std::numbers::pi;
  const auto point = [&](double polar, double azimuth) {
    return V{radius * std::sin(polar) * std::cos(azimuth),
             radius * std::sin(polar) * std::sin(azimuth), radius * std::cos(polar)};
  };
  double sum = 0.0;
  const auto add_triangle = [&](const V& a, const V& b, const V& c) {
    const V u{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const V v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    // |n| = 2·area, outward by winding
    const V n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double twice_area = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (twice_area <= 0.0) return;
    sum += sigma_of_cos(n[static_cast<std::size_t>(toward)] / twice_area) * 0.5 * twice_area;
  };
  for (int i = 0; i < n_polar; ++i) {
    const double p0 = kPi * i / n_polar, p1 = kPi * (i + 1) / n_polar;
    for (int j = 0; j < n_azimuth; ++j) {
      const double a0 = 2 * kPi * j / n_azimuth, a1 = 2 * kPi * (j + 1) / n_azimuth;
      add_triangle(point(p0, a0), point(p1, a0), point(p1, a1));
      add_triangle(point(p0, a0), point(p1, a1), point(p0, a1));
    }
  }
  return sum;
}

}  // namespace sonarloop::testing
