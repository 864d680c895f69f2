#pragma once
// Speckle through the pulse (docs/physics.md §3, "Receive chain"): the echo drawn as a complex
// field on the receiver's raw samples and smoothed by the pulse, so that its intensity is
// correlated over the pulse's range resolution as a real sidescan's is, instead of one
// independent exponential draw per bin after the smoothing (speckle.h).
//
// Each raw sample's cell returns a circular complex Gaussian field of power its mean intensity
// (many scatterers; Goodman, "Speckle Phenomena in Optics", Roberts & Co. 2007, ch. 3); the
// received sample is the sum of the cells the pulse covers, weighted by its envelope
// (rectangular, L raw samples long, unit energy: h = 1/sqrt(L)). The intensity is then
// exponential with the mean of those L cells, and its correlation coefficient between samples k
// apart is |μ(k)|², μ the envelope's normalised autocorrelation: (1 − |k|/L)² for |k| < L, 0
// beyond (Goodman 2007, §4.3 and §5.5: the intensity correlation of a filtered circular
// Gaussian field).
//
// Noise is an argument (docs/style.md habit 12): the field's values are drawn from `rng` in
// sample order.
#include <span>

#include "common/rng.h"

namespace sonarloop::acoustics {

// out[j] = |Σ_{t < L} sqrt(mean[j−t] / L) · z_{j−t}|², z circular complex Gaussian of unit
// power (cells before the first count as silent). mean and out have the same length; L >= 1.
void pulse_speckle(std::span<const double> mean_intensity, int pulse_samples, Rng& rng,
                   std::span<double> out);

// The oracle: intensity correlation coefficient at `lag` raw samples for a pulse of L samples.
double pulse_speckle_correlation(int lag, int pulse_samples);

}  // namespace sonarloop::acoustics
