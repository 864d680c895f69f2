#pragma once
// APL-UW TR 9407 (1994) bottom backscattering strength, Section IV.C, Eqs. 34-66
// (docs/physics.md §2.4). Monostatic, 10-100 kHz fit band; values above 100 kHz extrapolate.
//
//   S_b(θ) = 10·log10( σ_r(θ) + σ_v(θ) )                                        Eq. 34
//   σ_r: interface roughness — Kirchhoff near vertical (Eqs. 35-40), composite roughness with
//        shadowing and slope averaging (Eqs. 41-52), empirical large roughness for gravel and
//        rock (Eqs. 53-56), joined by logistic interpolations (Eqs. 57-64);
//   σ_v: sediment volume scattering (Eqs. 65-66).
//
// Units: θ grazing in rad at the API; the report's empirical angle formulas work in degrees
// and are converted inside. Wavenumbers are in cm^-1 (k = 2πf/c1 with c1 in cm/s), because the
// relief spectrum W(K) = w2/(h0·K)^γ has h0 = 1 cm and w2 in cm⁴.
// Deviation from the printed report: the Kirchhoff constant b uses exponent +(1/2 + 1/(2α)),
// not the printed (1/2 − 1/(2α)); the plus form equals the exact Kirchhoff integral at normal
// incidence and reproduces Table 3 (docs/physics.md §2.4 ★).
// Validity (TR 9407 IV.A.8): 10-100 kHz, 0-90° grazing, c1 1400-1600 m/s, 2 < γ < 4. Stated
// model uncertainty: ~3 dB for sand/silt above 5°, ~10 dB for rock and gravel above 15°.
#include "sim/acoustics/apl_sediment.h"

namespace sonarloop::acoustics {

// Below this grazing angle the strength at it is used (TR 9407 IV.C.4): S_b → −∞ at 0°.
inline constexpr double kAplMinGrazingDeg = 0.001;
// The Kirchhoff cross section is used at and above this grazing angle (TR 9407 Eq. 37).
inline constexpr double kAplKirchhoffMinDeg = 40.0;

// Kirchhoff power-law constants a and b of TR 9407 Eqs. 35-40, α = γ/2 − 1:
//   a = [8α²·Γ(1/(2α) + 1/2) / (Γ(1/2)·Γ(1/α)·Γ(1/(2α)))]^(2α)
//   b = a^(1/2 + 1/(2α))·Γ(1/α)/(2α)            (plus exponent, see header note)
// γ = 3.25: a = 1.689248, b = 1.413167.
struct KirchhoffConstants {
  double a;
  double b;
};
KirchhoffConstants kirchhoff_constants(double gamma);

// Everything of the model that depends on (frequency, sediment, c1) but not on the angle.
// Build once per frequency and sediment; the component functions below are then cheap.
struct AplBackscatterSetup {
  AplSediment sediment;
  double k_per_cm;               // water wavenumber 2πf/c1, cm^-1
  double alpha;                  // α = γ/2 − 1, in (0, 1)
  KirchhoffConstants kirchhoff;  // Eqs. 35-40
  double q_c;                    // Eqs. 35-40: C_h²·2^(1−2α)·k^(2(1−α)), dimensionless
  double slope_rms;              // s, rms large-scale slope (Eqs. 41-52), dimensionless
  double slope_rms_deg;          // θ_s = s·180/π (Eq. 49), degrees
  double r90_sq;                 // |R(90°)|²
  double critical_deg;           // θ_c (Eq. 54), degrees
  double cos_kirchhoff_db;       // cos θ_kdb (Eqs. 57-64)
  double rough_weight;           // f(y) of Eqs. 57-64: weight of σ_mr against σ_lr
};

// Precomputes the angle-independent terms. Throws std::invalid_argument if freq_hz or c1_m_s
// is not positive or γ is outside (2, 4) (α must lie in (0, 1), TR 9407 p. IV-27).
AplBackscatterSetup make_apl_backscatter_setup(double freq_hz, const AplSediment& sediment,
                                               double c1_m_s = kAplTableSoundSpeed_m_s);

// Eq. 57: the logistic blend f(x) = 1/(1 + e^x), x clamped to [−40, 40] (IV.C.4).
double apl_blend(double x);

// Eqs. 35-40: Kirchhoff cross section σ_kr (linear, per unit area per steradian); 0 below 40°.
//   σ_kr = b·|R(90°)|²·q_c / (8π·[cos^(4α)θ + a·q_c²·sin⁴θ]^((1+α)/(2α)))
// The closed form interpolates the exact power-law Kirchhoff integral; their ratio depends only on
// q = q_c·sin²θ/cos^(2α)θ: equal at 90° (q → ∞), within 0.16 dB for q >= 0.8, −0.34 dB near
// q = 0.4, up to +0.9 dB at q = 0.01 (γ = 3.25; measured in the tests). Exact for γ = 3.
double kirchhoff_sigma(double grazing_rad, const AplBackscatterSetup& setup);

// Eqs. 50-52: first-order perturbation (Bragg) cross section σ_pr, before shadowing and slope
// averaging: 4k⁴·sin⁴θ·|Y(θ)|²·W(K), K = sqrt(4k²cos²θ + (k/10)²).
double bragg_sigma(double grazing_rad, const AplBackscatterSetup& setup);

// Eqs. 43-45: shadowing factor S(θ) ∈ (0, 1] for rms slope s; S = 1 for tanθ/s > 2.
double shadowing_factor(double grazing_rad, double slope_rms);

// Eqs. 41-52: composite roughness σ_cr = S(θ)·⟨σ_pr⟩(θ), the slope average being a 3-point
// Gauss-Hermite sum over tilts ±1.224745·θ_s (Eqs. 46-48), tilted angles clipped to [0°, 90°].
double composite_sigma(double grazing_rad, const AplBackscatterSetup& setup);

// Eqs. 53-56: empirical large-roughness cross section σ_lr for gravel and rock.
double large_roughness_sigma(double grazing_rad, const AplBackscatterSetup& setup);

// Eq. 65: sediment volume cross section σ_pv of a flat interface:
//   5·δ·σ2·|1 − R²|²·sin²θ / (ν·ln10·|P|²·Im P)
double flat_volume_sigma(double grazing_rad, const AplBackscatterSetup& setup);

// Eq. 66: σ_v = S(θ)·⟨σ_pv⟩(θ) (same shadowing and slope average as composite_sigma).
double volume_sigma(double grazing_rad, const AplBackscatterSetup& setup);

// Eqs. 57-64: roughness cross section σ_r: Kirchhoff blended into composite roughness at θ_kdb
// (σ_mr), then σ_mr blended with large roughness by the slope angle atan(s) around 7°.
double roughness_sigma(double grazing_rad, const AplBackscatterSetup& setup);

// Eq. 34 in linear form: σ_r + σ_v (grazing clamped to [0.001°, 90°]).
double apl_backscatter_linear(double grazing_rad, const AplBackscatterSetup& setup);

// Eq. 34: backscattering strength S_b = 10·log10(σ_r + σ_v), dB re 1 m² per m² per sr.
double apl_backscatter_db(double grazing_rad, const AplBackscatterSetup& setup);

// Convenience: builds the setup and evaluates Eq. 34. Use the setup form in loops.
double apl_backscatter_db(double grazing_rad, double freq_hz, const AplSediment& sediment,
                          double c1_m_s = kAplTableSoundSpeed_m_s);

}  // namespace sonarloop::acoustics
