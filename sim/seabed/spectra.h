#pragma once
// Power spectral densities of the seabed layers, as functions of spatial frequency (fx, fy) in
// cycles per metre along north and east. Only the SHAPE matters: noise_layer.h normalises each
// layer to its configured rms. All are even in (fx, fy), as a real field's spectrum must be.
//
// Synthesis follows docs/physics.md §5: h = (white noise) ⊛ IFFT(sqrt(F)).
#include <functional>
#include <initializer_list>
#include <string>

namespace sonarloop::seabed {

// A 2-D PSD shape F(fx, fy) >= 0 (arbitrary units).
using Spectrum = std::function<double(double fx, double fy)>;

// A name for a spectrum and its parameters, exact to the last bit ("pink 2.8 40 5"), for the
// kernel cache of noise_layer.h.
std::string spectrum_key(const char* family, std::initializer_list<double> params);

// Exponent conventions (docs/physics.md §5 asks to state them). A 1-D profile through an isotropic
// surface whose 2-D PSD falls as |f|^-b has a 1-D PSD falling as f^-(b-1). Scenario files give
// the elevation and border exponents in the 1-D (profile) convention, where 1 < beta < 2 is pink
// noise with Hurst exponent H = (beta - 1)/2 and profile fractal dimension D = (5 - beta)/2; the
// code converts to the 2-D exponent beta + 1 here.
inline double profile_to_surface_exponent(double beta_1d) {
  return beta_1d + 1.0;
}

// Smoothed pink noise (the elevation layer; Pailhas et al. 2010 Sec. 2.1, docs/physics.md §5):
//   F(f) = (|f|^2 + f0^2)^(-beta/2) · exp(-(|f|·inner_scale_m)^2),   f0 = 1/outer_scale_m.
// `beta` here is the 2-D exponent: for f0 << |f| << 1/inner_scale_m the radially averaged 2-D
// PSD falls as |f|^-beta and profiles as f^-(beta-1). inner_scale_m = 0 disables smoothing.
double pink_psd(double fx, double fy, double beta, double outer_scale_m, double inner_scale_m);

// Sand ripples, Pailhas et al. (2010) eq. (1): F = 1 / (|fx' - fx0|^beta1 · |fy' - fy0|^beta),
// in the frame x' along the ripple propagation direction, so (fx0, fy0) = (1/wavelength, 0).
// Made even by folding (|fx'| - fx0), and regularised as docs/physics.md §5 advises: each |Δf| is
// floored at epsilon (one frequency bin of the synthesis grid). F(0, 0) = 0 (zero mean).
double ripple_psd(double fx, double fy, double wavelength_m, double direction_rad, double beta1,
                  double beta, double epsilon);

// Rocky seabed with anisotropic erosion. NOT Pailhas et al. eq. (2), which is unreadable in the
// paper: this is the labelled stand-in of docs/physics.md §5, an anisotropic fractal
//   F = ((a·fx')^2 + fy'^2 + f0^2)^(-beta/2),  x' along the erosion direction, a = anisotropy,
// f0 = 1/outer_scale_m. In the scaled coordinates (a·fx', fy') it is isotropic, so the field's
// correlation length along x' is exactly a times the one across (tested).
double rocky_psd(double fx, double fy, double beta, double anisotropy, double direction_rad,
                 double outer_scale_m);

}  // namespace sonarloop::seabed
