#pragma once
// How each seabed layer is synthesised: native lattice spacing and kernel size, chosen from the
// layer's own spectrum so that the synthesis is "enough for the layer and no more", and
// independent of the heightmap's grid spacing (so a coarser or finer heightmap samples the same
// surface).
#include <algorithm>
#include <cmath>

namespace sonarloop::seabed {

// Kernel size K (power of two in [64, 512]) covering `extent_m` at `spacing_m`. The kernel's
// extent is the largest correlated scale the layer can have; 4 outer scales keep the kernel's
// truncation below a few per cent of its energy for the spectra used here.
inline int kernel_size_for(double extent_m, double spacing_m) {
  const double cells = std::ceil(extent_m / spacing_m);
  int k = 64;
  while (k < cells && k < 512)
    k *= 2;
  return k;
}

// Pink layers (elevation, border warp): the kernel of (f² + f0²)^(-b/4) decays as
// exp(-2π·f0·r) beyond the outer scale, so 3 outer scales (±1.5 L: e^(-9.4) = 8e-5 of the
// centre) lose nothing measurable.
inline double pink_kernel_extent_m(double outer_scale_m) {
  return 3.0 * outer_scale_m;
}

// Sand ripples: 12 samples per ripple wavelength (Catmull–Rom interpolation then reproduces a
// sinusoid to < 0.5 % of its amplitude), kernel over 16 wavelengths (crest coherence length).
inline double ripple_spacing_m(double wavelength_m) {
  return wavelength_m / 12.0;
}
inline double ripple_kernel_extent_m(double wavelength_m) {
  return 16.0 * wavelength_m;
}

// Rocky texture: 64 samples per outer scale, at least 1 cm, at most 25 cm.
inline double rocky_spacing_m(double outer_scale_m) {
  return std::clamp(outer_scale_m / 64.0, 0.01, 0.25);
}
inline double rocky_kernel_extent_m(double outer_scale_m, double anisotropy) {
  return 4.0 * outer_scale_m * anisotropy;
}

// Partition warp: 32 samples per border outer scale, within [0.1, 2] m.
inline double warp_spacing_m(double border_scale_m) {
  return std::clamp(border_scale_m / 32.0, 0.1, 2.0);
}

}  // namespace sonarloop::seabed
