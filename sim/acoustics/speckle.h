#pragma once
// Speckle: the fluctuation of the echo intensity of a cell about its mean (docs/physics.md §3).
//
// Fully developed speckle (many random scatterers per cell): the complex field is circular
// Gaussian, so the amplitude is Rayleigh and the intensity exponential with the cell's mean
// (Goodman, "Speckle Phenomena in Optics", Roberts & Co. 2007, ch. 3; Abraham & Lyons, IEEE JOE
// 27(4) 800-813, 2002).
// Few scatterers per cell (clutter, patchy seabed): the K distribution, generated as a
// Gamma(ν)-distributed local mean times exponential speckle (Jakeman & Pusey, IEEE Trans.
// Antennas Propag. 24(6) 806-814, 1976; Abraham & Lyons 2002), scintillation index 1 + 2/ν.
//
// Noise is an argument (docs/style.md habit 12): the exponential form takes the uniform variate u,
// so a caller can draw u from any deterministic stream; the K form takes an Rng.
#include <span>

#include "common/rng.h"

namespace sonarloop::acoustics {

// Exponential (fully developed speckle) intensity with the given mean, by inversion of the CDF:
// I = −mean·ln u, u uniform in (0, 1] (Rng::uniform_pos()). u = 1 gives 0.
double apply_speckle(double mean_intensity, double u);

// In place over a line: intensity[i] = apply_speckle(intensity[i], u[i]) for i below the
// shorter length (the rest untouched). Each u[i] must be in (0, 1].
void apply_speckle(std::span<double> intensity, std::span<const double> u);

// Rayleigh amplitude whose square has mean mean_intensity: A = sqrt(−mean·ln u).
double rayleigh_amplitude(double mean_intensity, double u);

// K-distributed intensity with mean mean_intensity and shape ν > 0:
// I = Gamma(ν, 1)·Exp(λ_K) with λ_K = mean/ν (so E[I] = ν·λ_K = mean).
double k_distributed(double mean_intensity, double shape_nu, Rng& rng);

// Analytic helpers for tests and calibration:
// P(I > threshold) for exponential intensity with the given mean: e^(−t/mean).
double speckle_exceedance_probability(double threshold, double mean_intensity);
// Scintillation index Var(I)/E[I]² of the K distribution with shape ν: 1 + 2/ν.
double k_scintillation_index(double shape_nu);
// Scintillation index of a sample (population variance over squared mean); 0 for < 2 samples.
double scintillation_index(std::span<const double> intensities);

}  // namespace sonarloop::acoustics
