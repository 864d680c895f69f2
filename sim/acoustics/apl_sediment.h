#pragma once
// Seabed inputs of the APL-UW high-frequency bottom model and its forward reflection.
//
// Source: APL-UW, "High-Frequency Ocean Environmental Acoustic Models Handbook", TR 9407 /
// AEAS 9501 (1994), Section IV: Table 1 (the six inputs), Table 2 (sediment classes), Eqs. 2-10
// (inputs from mean grain size), Eqs. 29-33 (lossy Rayleigh reflection). Transcribed in
// docs/physics.md §2.1-§2.3.
#include <complex>

#include "sim/seabed/sediment.h"

namespace sonarloop::acoustics {

// The six TR 9407 Table 1 inputs. All ratios are sediment over water.
struct AplSediment {
  double rho;     // ρ, density ratio (TR 9407 limits: 1..3)
  double nu;      // ν, sound-speed ratio (0.8..3)
  double delta;   // δ, loss parameter Im(k)/Re(k) of the sediment wavenumber (0..0.1)
  double sigma2;  // σ2, volume scattering parameter (0..1)
  double gamma;   // γ, relief spectral exponent (2 < γ < 4 required; table value 3.25)
  double w2_cm4;  // w2, relief spectral strength at K = 1 cm^-1, cm⁴ (0..1)
};

// Water sound speed TR 9407 used for its Table 2 loss parameters and Table 3 strengths (m/s).
inline constexpr double kAplTableSoundSpeed_m_s = 1528.0;
// Reference length h0 of the relief spectrum W(K) = w2/(h0·K)^γ (TR 9407 Eq. 7), cm.
inline constexpr double kAplReliefReferenceLength_cm = 1.0;
// Grain-size range over which Eqs. 2-10 are fitted (φ units).
inline constexpr double kAplMinGrainSizePhi = -1.0;
inline constexpr double kAplMaxGrainSizePhi = 9.0;

// TR 9407 Eqs. 2-10: the six inputs from the mean grain size Mz (φ units).
// c1_m_s is the water sound speed used to turn Hamilton's attenuation into δ (Eq. 4); the table
// used 1528 m/s. Mz outside [-1, 9] is clamped to that range (the fits are not defined beyond).
// γ = 3.25 (Eq. 8) and w2 follows Eq. 10, which is valid for that γ only.
AplSediment apl_from_grain_size(double mz_phi, double c1_m_s = kAplTableSoundSpeed_m_s);

// TR 9407 Table 2 row for a sediment of sim/seabed/sediment.h. Rock, rough rock and cobble are
// the table's constants (docs/physics.md §2.2; cobble w2 = 0.016 cm⁴ as the CASS port, ±0.003
// uncertain); every other row is its Mz through apl_from_grain_size (c1 = 1528 m/s).
// Throws std::invalid_argument for an id outside seabed::sediment_table().
AplSediment apl_sediment(seabed::SedimentId id);

// P(θ) = sqrt(κ² − cos²θ), κ = (1 + iδ)/ν (TR 9407 Eqs. 29-33): the sediment's normalised
// vertical wavenumber, principal root (phase half the argument's). θ is grazing, rad.
std::complex<double> apl_vertical_wavenumber(double grazing_rad, const AplSediment& sediment);

// Lossy fluid-fluid Rayleigh reflection coefficient (TR 9407 Eqs. 29-33):
// y = ρ·sinθ/P(θ), R = (y − 1)/(y + 1). θ grazing in [0, π/2] rad. Frequency independent.
std::complex<double> rayleigh_reflection(double grazing_rad, const AplSediment& sediment);

// Bottom (forward reflection) loss, BL = −20·log10|R(θ)| dB (TR 9407 Eq. 29).
double bottom_loss_db(double grazing_rad, const AplSediment& sediment);

}  // namespace sonarloop::acoustics
