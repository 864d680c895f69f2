#include "sim/acoustics/apl_sediment.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sonarloop::acoustics {
namespace {

// TR 9407 Eq. 8: default relief spectral exponent.
constexpr double kDefaultGamma = 3.25;
// TR 9407 Eq. 6: volume parameter for sand/silt (Mz < 5.5) and finer sediments.
constexpr double kSigma2Coarse = 0.002;
constexpr double kSigma2Fine = 0.001;
constexpr double kSigma2FineFromPhi = 5.5;

// TR 9407 Eq. 2: density ratio from grain size.
double density_ratio(double mz) {
  if (mz < 1.0) return 0.007797 * mz * mz - 0.17057 * mz + 2.3139;
  if (mz < 5.3) return -0.0165406 * mz * mz * mz + 0.2290201 * mz * mz - 1.1069031 * mz + 3.0455;
  return -0.0012973 * mz + 1.1565;
}

// TR 9407 Eq. 3: sound-speed ratio from grain size.
double speed_ratio(double mz) {
  if (mz < 1.0) return 0.002709 * mz * mz - 0.056452 * mz + 1.2778;
  if (mz < 5.3) return -0.0014881 * mz * mz * mz + 0.0213937 * mz * mz - 0.1382798 * mz + 1.3425;
  return -0.0024324 * mz + 1.0019;
}

// TR 9407 Eq. 5 (Hamilton 1972): sediment attenuation over frequency k_p, dB m^-1 kHz^-1.
double hamilton_kp(double mz) {
  if (mz < 0.0) return 0.4556;
  if (mz < 2.6) return 0.4556 + 0.0245 * mz;
  if (mz < 4.5) return 0.1978 + 0.1245 * mz;
  if (mz < 6.0) return 8.0399 - 2.5228 * mz + 0.20098 * mz * mz;
  if (mz < 9.5) return 0.9431 - 0.2041 * mz + 0.0117 * mz * mz;
  return 0.0601;
}

// TR 9407 Eq. 4: δ = k_p·ν·c1·ln10/(40π) with c1 in m/ms. It is Im(k)/Re(k): the attenuation
// k_p·f dB/m in Np/m (× ln10/20) over the sediment wavenumber 2π·f/(ν·c1).
double loss_parameter(double kp, double nu, double c1_m_s) {
  constexpr double kMetresPerSecondPerMetrePerMs = 1000.0;
  return kp * nu * (c1_m_s / kMetresPerSecondPerMetrePerMs) * std::numbers::ln10 /
         (40.0 * std::numbers::pi);
}

// TR 9407 Eqs. 9-10: rms relief h (cm, 100-cm track) and w2 = 0.00207·h²·h0² cm⁴ (γ = 3.25).
double spectral_strength_cm4(double mz) {
  const double h_cm = mz < 5.0 ? (2.03846 - 0.26923 * mz) / (1.0 + 0.076923 * mz) : 0.5;
  return 0.00207 * h_cm * h_cm * kAplReliefReferenceLength_cm * kAplReliefReferenceLength_cm;
}

// TR 9407 Table 2 constant rows (docs/physics.md §2.2).
struct ConstantRow {
  std::string_view key;
  AplSediment params;
};
constexpr ConstantRow kConstantRows[] = {
    {"rough_rock", {2.5, 2.5, 0.01374, 0.002, 3.25, 0.20693}},
    {"rock", {2.5, 2.5, 0.01374, 0.002, 3.25, 0.01862}},
    // cobble w2: CASS port value 0.016; the scan of Table 2 is ambiguous (docs/physics.md §2.2)
    {"cobble", {2.5, 1.8, 0.01374, 0.002, 3.25, 0.016}},
};

}  // namespace

AplSediment apl_from_grain_size(double mz_phi, double c1_m_s) {
  const double mz = std::clamp(mz_phi, kAplMinGrainSizePhi, kAplMaxGrainSizePhi);
  AplSediment s{};
  s.rho = density_ratio(mz);
  s.nu = speed_ratio(mz);
  s.delta = loss_parameter(hamilton_kp(mz), s.nu, c1_m_s);
  s.sigma2 = mz < kSigma2FineFromPhi ? kSigma2Coarse : kSigma2Fine;
  s.gamma = kDefaultGamma;
  s.w2_cm4 = spectral_strength_cm4(mz);
  return s;
}

AplSediment apl_sediment(seabed::SedimentId id) {
  const auto table = seabed::sediment_table();
  if (id < 0 || static_cast<std::size_t>(id) >= table.size()) {
    throw std::invalid_argument("apl_sediment: sediment id " + std::to_string(id) +
                                " is outside 0.." + std::to_string(table.size() - 1) +
                                " (sim/seabed/sediment.h)");
  }
  const seabed::SedimentInfo& info = table[static_cast<std::size_t>(id)];
  if (info.mz_phi) return apl_from_grain_size(*info.mz_phi, kAplTableSoundSpeed_m_s);
  for (const ConstantRow& row : kConstantRows) {
    if (row.key == info.key) return row.params;
  }
  throw std::invalid_argument("apl_sediment: sediment '" + std::string(info.key) +
                              "' has neither a grain size nor TR 9407 table constants");
}

std::complex<double> apl_vertical_wavenumber(double grazing_rad, const AplSediment& sediment) {
  const std::complex<double> kappa = std::complex<double>(1.0, sediment.delta) / sediment.nu;
  const double c = std::cos(grazing_rad);
  return std::sqrt(kappa * kappa - c * c);  // std::sqrt is the principal root
}

std::complex<double> rayleigh_reflection(double grazing_rad, const AplSediment& sediment) {
  const std::complex<double> p = apl_vertical_wavenumber(grazing_rad, sediment);
  const std::complex<double> y = sediment.rho * std::sin(grazing_rad) / p;
  return (y - 1.0) / (y + 1.0);
}

double bottom_loss_db(double grazing_rad, const AplSediment& sediment) {
  return -20.0 * std::log10(std::abs(rayleigh_reflection(grazing_rad, sediment)));
}

}  // namespace sonarloop::acoustics
