#include "sim/acoustics/bottom_backscatter_apl.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>

#include "units/angles.h"

namespace sonarloop::acoustics {
namespace {

using std::numbers::pi;
constexpr double kCmPerMetre = 100.0;

// Eq. 57 clamp of the blend argument (IV.C.4).
constexpr double kBlendClamp = 40.0;
// Eqs. 57-64: width of the Kirchhoff / composite blend in cos θ.
constexpr double kKirchhoffBlendWidthCos = 0.0125;
// Eqs. 57-64: slope angle (deg) around which large roughness takes over, and blend width (deg).
constexpr double kLargeRoughnessSlopeDeg = 7.0;
constexpr double kLargeRoughnessBlendDeg = 0.5;
// Eq. 54: critical angle assigned when ν < 1.001 (slow or nearly matched sediment), degrees.
constexpr double kSlowBottomCriticalDeg = 2.5613;
constexpr double kSlowBottomSpeedRatio = 1.001;
// Eqs. 46-48: 3-point Gauss-Hermite abscissae and weights as printed (weights sum to √π).
constexpr double kGaussHermiteNodes[3] = {1.224745, 0.0, -1.224745};
constexpr double kGaussHermiteWeights[3] = {0.295410, 1.181636, 0.295410};

double clamp_grazing_deg(double grazing_rad) {
  return std::clamp(grazing_rad * kDegPerRad, kAplMinGrazingDeg, 90.0);
}

// Eqs. 46-48: (1/√π)·Σ w_i·σ(θ − x_i·θ_s), tilted angle clipped to [0°, 90°] (p. IV-30).
template <typename CrossSection>
double slope_average(double grazing_deg, double slope_rms_deg, CrossSection sigma) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double tilted_deg =
        std::clamp(grazing_deg - kGaussHermiteNodes[i] * slope_rms_deg, 0.0, 90.0);
    sum += kGaussHermiteWeights[i] * sigma(tilted_deg * kRadPerDeg);
  }
  return sum / std::sqrt(pi);
}

// Eqs. 50-52, Y(θ) = [(ρ−1)²cos²θ + ρ² − κ²] / (ρ·sinθ + P)²
std::complex<double> bragg_y(double grazing_rad, const AplSediment& sed) {
  const std::complex<double> kappa = std::complex<double>(1.0, sed.delta) / sed.nu;
  const std::complex<double> p = apl_vertical_wavenumber(grazing_rad, sed);
  const double c = std::cos(grazing_rad);
  const double rm1 = sed.rho - 1.0;
  const std::complex<double> den = sed.rho * std::sin(grazing_rad) + p;
  return (rm1 * rm1 * c * c + sed.rho * sed.rho - kappa * kappa) / (den * den);
}

}  // namespace

KirchhoffConstants kirchhoff_constants(double gamma) {
  const double al = gamma / 2.0 - 1.0;
  const double a =
      std::pow(8.0 * al * al * std::tgamma(1.0 / (2.0 * al) + 0.5) /
                   (std::tgamma(0.5) * std::tgamma(1.0 / al) * std::tgamma(1.0 / (2.0 * al))),
               2.0 * al);
  // plus exponent: makes σ_kr at 90° equal the exact Kirchhoff integral (docs/physics.md §2.4 ★)
  const double b = std::pow(a, 0.5 + 1.0 / (2.0 * al)) * std::tgamma(1.0 / al) / (2.0 * al);
  return {a, b};
}

AplBackscatterSetup make_apl_backscatter_setup(double freq_hz, const AplSediment& sediment,
                                               double c1_m_s) {
  if (!(freq_hz > 0.0) || !(c1_m_s > 0.0)) {
    throw std::invalid_argument("APL-UW backscatter: frequency (" + std::to_string(freq_hz) +
                                " Hz) and water sound speed (" + std::to_string(c1_m_s) +
                                " m/s) must be positive");
  }
  if (!(sediment.gamma > 2.0 && sediment.gamma < 4.0)) {
    throw std::invalid_argument(
        "APL-UW backscatter: spectral exponent gamma = " + std::to_string(sediment.gamma) +
        " must lie strictly between 2 and 4 (TR 9407 p. IV-27)");
  }
  AplBackscatterSetup s{};
  s.sediment = sediment;
  const double g = sediment.gamma;
  const double al = g / 2.0 - 1.0;
  const double h0 = kAplReliefReferenceLength_cm;
  const double k = 2.0 * pi * freq_hz / (c1_m_s * kCmPerMetre);
  s.k_per_cm = k;
  s.alpha = al;
  s.kirchhoff = kirchhoff_constants(g);

  // Eqs. 35-40: structure-function constant C_h² (cm^(2-2α)) and the Kirchhoff parameter q_c
  const double ch2 = 2.0 * pi * sediment.w2_cm4 * std::tgamma(2.0 - al) * std::pow(2.0, -2.0 * al) /
                     (std::pow(h0, g) * al * (1.0 - al) * std::tgamma(1.0 + al));
  s.q_c = ch2 * std::pow(2.0, 1.0 - 2.0 * al) * std::pow(k, 2.0 * (1.0 - al));

  // Eqs. 41-52 (and 49): mean-square large-scale slope s² (closed form of the report) and the rms
  // slope angle θ_s in degrees
  const double s2 = std::pow(2.0 * pi * sediment.w2_cm4 * std::pow(h0, -g), 1.0 / al) /
                    (2.0 * (1.0 - al)) * std::pow(k * k / al, (1.0 - al) / al);
  s.slope_rms = std::sqrt(s2);
  s.slope_rms_deg = s.slope_rms * kDegPerRad;

  s.r90_sq = std::norm(rayleigh_reflection(pi / 2.0, sediment));

  // Eq. 54: critical angle
  s.critical_deg = sediment.nu >= kSlowBottomSpeedRatio ? std::acos(1.0 / sediment.nu) * kDegPerRad
                                                        : kSlowBottomCriticalDeg;

  // Eqs. 57-64: angle θ_kdb where Kirchhoff hands over to composite roughness
  const double c4 =
      std::pow(1000.0, 1.0 / (1.0 + al)) * std::pow(s.kirchhoff.a * s.q_c * s.q_c, 1.0 / al);
  s.cos_kirchhoff_db = std::pow(1.0 / c4 + 4.0, -0.25);

  // Eqs. 57-64: large-roughness blend on the slope angle atan(s)
  s.rough_weight = apl_blend((std::atan(s.slope_rms) * kDegPerRad - kLargeRoughnessSlopeDeg) /
                             kLargeRoughnessBlendDeg);
  return s;
}

double apl_blend(double x) {
  return 1.0 / (1.0 + std::exp(std::clamp(x, -kBlendClamp, kBlendClamp)));
}

double kirchhoff_sigma(double grazing_rad, const AplBackscatterSetup& setup) {
  if (grazing_rad * kDegPerRad < kAplKirchhoffMinDeg) return 0.0;
  const double al = setup.alpha;
  const double sn = std::sin(grazing_rad);
  const double cs = std::fabs(std::cos(grazing_rad));
  const double qc = setup.q_c;
  const double den_base = std::pow(cs, 4.0 * al) + setup.kirchhoff.a * qc * qc * sn * sn * sn * sn;
  return setup.kirchhoff.b * setup.r90_sq * qc /
         (8.0 * pi * std::pow(den_base, (1.0 + al) / (2.0 * al)));
}

double bragg_sigma(double grazing_rad, const AplBackscatterSetup& setup) {
  const AplSediment& sed = setup.sediment;
  const double k = setup.k_per_cm;
  const double sn = std::sin(grazing_rad);
  const double cs = std::cos(grazing_rad);
  // Eqs. 50-52: Bragg wavenumber 2k·cosθ, regularised by k/10 so the spectrum stays finite at 90°
  const double bragg_k = std::sqrt(4.0 * k * k * cs * cs + (k / 10.0) * (k / 10.0));
  // Eq. 7: relief spectrum W(K) = w2·(h0·K)^(−γ), cm⁴
  const double w = sed.w2_cm4 * std::pow(kAplReliefReferenceLength_cm * bragg_k, -sed.gamma);
  const double sn2 = sn * sn;
  return 4.0 * k * k * k * k * sn2 * sn2 * std::norm(bragg_y(grazing_rad, sed)) * w;
}

double shadowing_factor(double grazing_rad, double slope_rms) {
  const double t = std::tan(grazing_rad) / slope_rms;
  if (!(t <= 2.0)) return 1.0;  // t > 2 (and t = ∞ at 90°): unshadowed (IV.C.4)
  if (t <= 0.0) return 0.0;
  const double q = (std::exp(-t * t) / std::sqrt(pi) - t * std::erfc(t)) / (4.0 * t);
  if (q <= 0.0) return 1.0;
  return -std::expm1(-2.0 * q) / (2.0 * q);
}

double composite_sigma(double grazing_rad, const AplBackscatterSetup& setup) {
  const double avg = slope_average(grazing_rad * kDegPerRad, setup.slope_rms_deg,
                                   [&setup](double th) { return bragg_sigma(th, setup); });
  return shadowing_factor(grazing_rad, setup.slope_rms) * avg;
}

double large_roughness_sigma(double grazing_rad, const AplBackscatterSetup& setup) {
  const AplSediment& sed = setup.sediment;
  const double s = setup.slope_rms;
  const double th_deg = grazing_rad * kDegPerRad;
  const double th_s = setup.slope_rms_deg;
  const double th_c = setup.critical_deg;
  // Eqs. 53-56: exponent and level of the diffuse part
  const double m = 0.7263 * std::pow(s, -1.0 / 3.0);
  const double contrast = (1.0 - 2.0 / sed.rho) / (sed.nu * sed.nu) + 1.0;
  const double sigma1 = 0.04682 * std::pow(s, 1.25) * std::pow(sed.nu, 3.25) * contrast * contrast /
                        (1.0 + 3.54 * th_s / th_c);
  // Eqs. 53-56: diffuse lobe plus a near-specular facet term
  const double crit = 1.0 + 0.81 * th_c * th_c / (th_deg * th_deg);
  const double diffuse = sigma1 * std::pow(std::sin(pi / crit), m);  // sin(180°/crit)
  const double d90 = th_deg - 90.0;
  const double facet =
      0.0260 * setup.r90_sq / (s * s * std::pow(1.0 + d90 * d90 / (2.6 * th_s * th_s), 1.9) * crit);
  return diffuse + facet;
}

double flat_volume_sigma(double grazing_rad, const AplBackscatterSetup& setup) {
  const AplSediment& sed = setup.sediment;
  const std::complex<double> r = rayleigh_reflection(grazing_rad, sed);
  const std::complex<double> p = apl_vertical_wavenumber(grazing_rad, sed);
  const double im_p = p.imag();
  if (!(im_p > 0.0)) return 0.0;  // lossless sediment: no volume term
  const double sn = std::sin(grazing_rad);
  const double out = 5.0 * sed.delta * sed.sigma2 * std::norm(1.0 - r * r) * sn * sn /
                     (sed.nu * std::numbers::ln10 * std::norm(p) * im_p);
  return std::isfinite(out) ? out : 0.0;
}

double volume_sigma(double grazing_rad, const AplBackscatterSetup& setup) {
  const double avg = slope_average(grazing_rad * kDegPerRad, setup.slope_rms_deg,
                                   [&setup](double th) { return flat_volume_sigma(th, setup); });
  return shadowing_factor(grazing_rad, setup.slope_rms) * avg;
}

double roughness_sigma(double grazing_rad, const AplBackscatterSetup& setup) {
  // Eqs. 57-64: Kirchhoff near vertical, composite roughness below θ_kdb
  const double fx =
      apl_blend((std::cos(grazing_rad) - setup.cos_kirchhoff_db) / kKirchhoffBlendWidthCos);
  const double sigma_mr =
      fx * kirchhoff_sigma(grazing_rad, setup) + (1.0 - fx) * composite_sigma(grazing_rad, setup);
  // Eqs. 57-64: large roughness when the slope angle exceeds ~7°
  const double fy = setup.rough_weight;
  if (fy == 1.0) return sigma_mr;  // skip σ_lr when its weight underflows
  return fy * sigma_mr + (1.0 - fy) * large_roughness_sigma(grazing_rad, setup);
}

double apl_backscatter_linear(double grazing_rad, const AplBackscatterSetup& setup) {
  const double th = clamp_grazing_deg(grazing_rad) * kRadPerDeg;
  return roughness_sigma(th, setup) + volume_sigma(th, setup);
}

double apl_backscatter_db(double grazing_rad, const AplBackscatterSetup& setup) {
  return 10.0 * std::log10(apl_backscatter_linear(grazing_rad, setup));
}

double apl_backscatter_db(double grazing_rad, double freq_hz, const AplSediment& sediment,
                          double c1_m_s) {
  return apl_backscatter_db(grazing_rad, make_apl_backscatter_setup(freq_hz, sediment, c1_m_s));
}

}  // namespace sonarloop::acoustics
