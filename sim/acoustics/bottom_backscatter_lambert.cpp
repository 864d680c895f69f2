#include "sim/acoustics/bottom_backscatter_lambert.h"

#include <cmath>

namespace sonarloop::acoustics {

double lambert_backscatter_db(double grazing_rad, double mu_db) {
  return mu_db + 20.0 * std::log10(std::sin(grazing_rad));
}

double lambert_backscatter_linear(double grazing_rad, double mu) {
  if (!(grazing_rad > 0.0)) return 0.0;
  const double s = std::sin(grazing_rad);
  return mu * s * s;
}

}  // namespace sonarloop::acoustics
