#include "sim/acoustics/speckle.h"

#include <algorithm>
#include <cmath>

namespace sonarloop::acoustics {

double apply_speckle(double mean_intensity, double u) {
  // inverse CDF of the exponential distribution: P(I > x) = e^(−x/mean) = u
  return -mean_intensity * std::log(u);
}

void apply_speckle(std::span<double> intensity, std::span<const double> u) {
  const std::size_t n = std::min(intensity.size(), u.size());
  for (std::size_t i = 0; i < n; ++i)
    intensity[i] = apply_speckle(intensity[i], u[i]);
}

double rayleigh_amplitude(double mean_intensity, double u) {
  return std::sqrt(apply_speckle(mean_intensity, u));
}

double k_distributed(double mean_intensity, double shape_nu, Rng& rng) {
  const double scale = mean_intensity / shape_nu;  // λ_K
  // local mean Gamma(ν)·λ_K, then exponential speckle about it
  return rng.gamma(shape_nu) * rng.exponential(scale);
}

double speckle_exceedance_probability(double threshold, double mean_intensity) {
  return std::exp(-threshold / mean_intensity);
}

double k_scintillation_index(double shape_nu) {
  return 1.0 + 2.0 / shape_nu;
}

double scintillation_index(std::span<const double> intensities) {
  const std::size_t n = intensities.size();
  if (n < 2) return 0.0;
  double sum = 0.0;
  for (double v : intensities)
    sum += v;
  const double mean = sum / static_cast<double>(n);
  double ss = 0.0;
  for (double v : intensities)
    ss += (v - mean) * (v - mean);
  return ss / static_cast<double>(n) / (mean * mean);
}

}  // namespace sonarloop::acoustics
