#include "sim/acoustics/target_scattering.h"

#include <cmath>
#include <numbers>

namespace sonarloop::acoustics {

double acoustic_impedance(double density_kg_m3, double sound_speed_m_s) {
  return density_kg_m3 * sound_speed_m_s;
}

double impedance_reflectance(double z1_rayl, double z2_rayl) {
  return (z2_rayl - z1_rayl) / (z2_rayl + z1_rayl);
}

double lambert_mu_from_reflectance(double reflectance) {
  // energy reflectance R² scaled by the Lambert energy bound 1/π (see header)
  return reflectance * reflectance / std::numbers::pi;
}

double lambert_sphere_cross_section_m2(double mu, double radius_m) {
  // ∫_0^{π/2} μ cos²θ · 2π a² sinθ dθ = 2π a² μ / 3
  return 2.0 * std::numbers::pi / 3.0 * mu * radius_m * radius_m;
}

double target_strength_db(double cross_section_m2) {
  return 10.0 * std::log10(cross_section_m2);
}

}  // namespace sonarloop::acoustics
