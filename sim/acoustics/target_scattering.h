#pragma once
// Target scattering: impedance reflectance and Lambertian facets (docs/physics.md §0, §4).
//
// Pailhas, Petillot & Capus (2010) (docs/physics.md §0) model targets as diffuse (Lambertian)
// scatterers:
//   dσ = μ·cosθ_i·cosθ_s·dA,   monostatic: dσ = μ·cos²θ·dA       θ from the facet normal
// with μ set from the material's normal-incidence reflectance R = (Z2 − Z1)/(Z2 + Z1), Z = ρ·c
// (normal-incidence plane-wave reflection, Kinsler et al., "Fundamentals of Acoustics", 4th ed.
// 2000, ch. 6).
//
// DESIGN CHOICE (docs/physics.md §4 leaves it open): μ = R²/π. R² is the fraction of incident
// ENERGY reflected at normal incidence, and 1/π is the largest μ a Lambertian surface can have
// without scattering more energy than it receives (∫ cosθ_s dΩ over a hemisphere = π). So a
// perfect reflector (|R| = 1) is the brightest allowed Lambert surface, and steel gives
// μ = 0.8754/π. Using R (amplitude) instead would brighten weak reflectors (rubber: +11.8 dB).
// Validity: facets large against the wavelength and rough at its scale (diffuse); no specular
// glints, no elastic resonances, no multiple scattering.
#include <numbers>

namespace sonarloop::acoustics {

// Lambert energy bound: the largest physical μ (per steradian).
inline constexpr double kLambertMaxMu = std::numbers::inv_pi;

// Acoustic impedance Z = ρ·c, Rayl (kg m⁻² s⁻¹).
double acoustic_impedance(double density_kg_m3, double sound_speed_m_s);

// Normal-incidence pressure reflection coefficient (Z2 − Z1)/(Z2 + Z1) from medium 1 (water)
// onto medium 2 (target). Signed: negative for a softer target.
double impedance_reflectance(double z1_rayl, double z2_rayl);

// The documented choice above: μ = R²/π, in [0, 1/π].
double lambert_mu_from_reflectance(double reflectance);

// Monostatic backscattering cross section per unit facet area, μ·cos²θ (m²/m² per sr), where
// cos_incidence = cosine between the facet normal and the direction back to the sonar.
// Facets facing away (cos_incidence <= 0) return 0.
inline double lambert_facet_backscatter(double cos_incidence, double mu) {
  return cos_incidence > 0.0 ? mu * cos_incidence * cos_incidence : 0.0;
}

// Analytic backscattering cross section of a Lambertian sphere of radius a (m²):
// ∫ over the lit hemisphere of μ·cos²θ dA = (2π/3)·μ·a².
double lambert_sphere_cross_section_m2(double mu, double radius_m);

// Target strength TS = 10·log10 σ_bs (σ_bs in m², re 1 m²).
double target_strength_db(double cross_section_m2);

}  // namespace sonarloop::acoustics
