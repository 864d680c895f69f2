#pragma once
// Target scattering, the specular (facet-normal) part: Kirchhoff / geometric-optics backscatter
// from a surface whose micro-slopes are Gaussian (docs/physics.md §4).
//
// A target's surface is smooth at the sonar's wavelength over patches larger than it (painted or
// corroded metal, glass-fibre shells): each patch reflects like a mirror, and only the patches
// whose local normal points back at the sonar return energy. With slopes (γx, γy) normally
// distributed, each component of variance s² (s: the rms slope per component), the stationary-
// phase (Kirchhoff) limit gives the monostatic cross section per unit mean area per steradian
//
//   σ_spec(θ) = |R|² · exp(−tan²θ / (2 s²)) / (8π · s² · cos⁴θ)
//
// θ the incidence angle from the mean facet normal, R the normal-incidence reflectance. This is
// the Gaussian-slope case (γ = 4, α = 1) of the Kirchhoff integral that APL-UW TR 9407 Eqs.
// 35–40 use for the seabed near vertical (bottom_backscatter_apl.h):
//   σ = |R|²/(8π sin²β cos²β)·∫₀^∞ J0(u)·exp(−q u²)·u du,   q = q_c·tan²β,   β = 90° − θ
// (the grazing angle); the integral is exp(−1/(4q))/(2q), which is the line above with
// s² = 2·q_c, since sin β = cos θ and cot β = tan θ (the geometric-optics
// facet model; Jackson & Richardson, "High-Frequency Seafloor Acoustics", Springer 2007, ch. 13).
// Integrated over a sphere of radius a ≫ λ it gives the geometric-optics cross section
// a²·|R|²/4 as s → 0 (docs/physics.md §4: "the specular sphere a²/4").
//
// DESIGN CHOICE: a target facet splits the energy it reflects, R², between a diffuse Lambert
// part μ = (1 − f)·R²/π (target_scattering.h) and this specular part with weight f·R²
// (f = sonar key target_specular_fraction; 0, the default, is the paper's Lambert-only model).
// Validity: s of the order of 0.05–0.3 (the exponential is the large-roughness, high-frequency
// limit); no edge diffraction, no elastic resonances, no multiple scattering.
namespace sonarloop::acoustics {

// σ_spec(θ) above per unit |R|² (so the weight f·R² multiplies it), for cos θ = cos_incidence
// and rms slope s per component (> 0). Facets facing away (cos_incidence <= 0) return 0.
double kirchhoff_facet_backscatter(double cos_incidence, double rms_slope);

// The s → 0 limit of ∫ σ_spec dA over a sphere of radius a, per unit |R|²: a²/4 (m²).
double specular_sphere_cross_section_m2(double radius_m);

}  // namespace sonarloop::acoustics
