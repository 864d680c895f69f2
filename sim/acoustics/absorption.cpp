#include "sim/acoustics/absorption.h"

#include <cmath>

namespace sonarloop::acoustics {
namespace {

constexpr double kHzPerKilohertz = 1000.0;
constexpr double kCelsiusToKelvin = 273.0;  // F&G use θ = 273 + T (not 273.15)
// F&G reference salinity (ppt) of the relaxation-frequency scalings.
constexpr double kReferenceSalinityPpt = 35.0;
// F&G switch between the cold and warm pure-water fits (°C); AttenMod.f90 takes T >= 20 as warm.
constexpr double kWarmWaterFitFromC = 20.0;

// relaxation term A·P·f_r·f²/(f_r² + f²), all frequencies in kHz
double relaxation(double amplitude, double pressure_factor, double f_relax_khz, double f_khz) {
  const double f2 = f_khz * f_khz;
  return amplitude * pressure_factor * f_relax_khz * f2 / (f_relax_khz * f_relax_khz + f2);
}

}  // namespace

double sound_speed_fg_m_s(double temperature_c, double salinity_ppt, double depth_m) {
  return 1412.0 + 3.21 * temperature_c + 1.19 * salinity_ppt + 0.0167 * depth_m;
}

FrancoisGarrisonTerms francois_garrison_terms(double freq_hz, double temperature_c,
                                              double salinity_ppt, double depth_m, double ph) {
  const double t = temperature_c;
  const double s = salinity_ppt;
  const double d = depth_m;
  const double f_khz = freq_hz / kHzPerKilohertz;
  const double c = sound_speed_fg_m_s(t, s, d);
  const double theta_k = kCelsiusToKelvin + t;

  // boric acid (F&G 1982b, docs/physics.md §1): A1 in dB km^-1 kHz^-1, P1 = 1, f1 in kHz
  const double a1 = 8.86 / c * std::pow(10.0, 0.78 * ph - 5.0);
  const double f1 =
      2.8 * std::sqrt(s / kReferenceSalinityPpt) * std::pow(10.0, 4.0 - 1245.0 / theta_k);

  // magnesium sulphate
  const double a2 = 21.44 * s / c * (1.0 + 0.025 * t);
  const double p2 = 1.0 - 1.37e-4 * d + 6.2e-9 * d * d;
  const double f2 =
      8.17 * std::pow(10.0, 8.0 - 1990.0 / theta_k) / (1.0 + 0.0018 * (s - kReferenceSalinityPpt));

  // pure water viscosity: two cubic fits in T
  const double a3 = t < kWarmWaterFitFromC
                        ? 4.937e-4 - 2.59e-5 * t + 9.11e-7 * t * t - 1.50e-8 * t * t * t
                        : 3.964e-4 - 1.146e-5 * t + 1.45e-7 * t * t - 6.5e-10 * t * t * t;
  const double p3 = 1.0 - 3.83e-5 * d + 4.9e-10 * d * d;

  FrancoisGarrisonTerms out{};
  out.boric_acid_db_per_km = relaxation(a1, 1.0, f1, f_khz);
  out.magnesium_sulphate_db_per_km = relaxation(a2, p2, f2, f_khz);
  out.pure_water_db_per_km = a3 * p3 * f_khz * f_khz;
  return out;
}

double francois_garrison_db_per_km(double freq_hz, double temperature_c, double salinity_ppt,
                                   double depth_m, double ph) {
  return francois_garrison_terms(freq_hz, temperature_c, salinity_ppt, depth_m, ph).total();
}

double ainslie_mccolm_db_per_km(double freq_hz, double temperature_c, double salinity_ppt,
                                double depth_m, double ph) {
  const double t = temperature_c;
  const double s_ratio = salinity_ppt / kReferenceSalinityPpt;
  const double z_km = depth_m / kMetresPerKilometre;
  const double f_khz = freq_hz / kHzPerKilohertz;
  const double f2 = f_khz * f_khz;

  // relaxation frequencies (kHz)
  const double f1 = 0.78 * std::sqrt(s_ratio) * std::exp(t / 26.0);
  const double f2r = 42.0 * std::exp(t / 17.0);

  const double boric = 0.106 * f1 * f2 / (f1 * f1 + f2) * std::exp((ph - 8.0) / 0.56);
  const double mgso4 =
      0.52 * (1.0 + t / 43.0) * s_ratio * f2r * f2 / (f2r * f2r + f2) * std::exp(-z_km / 6.0);
  const double water = 0.00049 * f2 * std::exp(-(t / 27.0 + z_km / 17.0));
  return boric + mgso4 + water;
}

}  // namespace sonarloop::acoustics
