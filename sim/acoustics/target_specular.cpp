#include "sim/acoustics/target_specular.h"

#include <cmath>
#include <numbers>

namespace sonarloop::acoustics {

double kirchhoff_facet_backscatter(double cos_incidence, double rms_slope) {
  if (!(cos_incidence > 0.0)) return 0.0;
  const double c2 = cos_incidence * cos_incidence;
  const double tan2 = (1.0 - c2) / c2;
  const double s2 = rms_slope * rms_slope;
  // target_specular.h: |R|² exp(−tan²θ / 2s²) / (8π s² cos⁴θ)
  return std::exp(-tan2 / (2.0 * s2)) / (8.0 * std::numbers::pi * s2 * c2 * c2);
}

double specular_sphere_cross_section_m2(double radius_m) {
  // geometric optics: a sphere returns the power its tiny normal-incidence spot reflects, a²/4
  return 0.25 * radius_m * radius_m;
}

}  // namespace sonarloop::acoustics
