#pragma once
// Lambert's law for bottom backscatter, the simple fallback to the APL-UW model
// (docs/physics.md §2.6).
//
// Source: Mackenzie, "Bottom reverberation for 530- and 1030-cps sound in deep water",
// JASA 33(11) 1498-1504 (1961); Urick (1983) §8.12. Bistatic σ = μ·sinθ_i·sinθ_s, monostatic
//   S_b(θ) = 10·log10 μ + 20·log10 sin θ       dB, θ grazing
// Validity: diffuse (rough-at-wavelength-scale) bottoms away from normal incidence; it has no
// specular peak. Energy conservation bounds μ ≤ 1/π (−4.97 dB).
namespace sonarloop::acoustics {

// Mackenzie's (1961) deep-sea value of the Lambert parameter, dB.
inline constexpr double kMackenzieLambertMuDb = -27.0;

// Monostatic Lambert backscattering strength, dB. grazing_rad in (0, π/2]; 0 gives −inf.
double lambert_backscatter_db(double grazing_rad, double mu_db = kMackenzieLambertMuDb);

// Linear form μ·sin²θ (mu linear, not dB); 0 at grazing ≤ 0.
double lambert_backscatter_linear(double grazing_rad, double mu);

}  // namespace sonarloop::acoustics
