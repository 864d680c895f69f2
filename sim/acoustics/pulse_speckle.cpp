#include "sim/acoustics/pulse_speckle.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <vector>

namespace sonarloop::acoustics {

void pulse_speckle(std::span<const double> mean_intensity, int pulse_samples, Rng& rng,
                   std::span<double> out) {
  const std::size_t n = std::min(mean_intensity.size(), out.size());
  const auto taps = static_cast<std::size_t>(std::max(1, pulse_samples));
  const double weight = 1.0 / static_cast<double>(taps);
  // the pulse's running sum over the last `taps` cells, whose fields (unit-power circular
  // Gaussian, variance 1/2 per part, times the cell's amplitude) are kept in a ring of `taps`
  std::vector<std::complex<double>> ring(taps);
  std::complex<double> sum = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double re = rng.normal();
    const double im = rng.normal();
    std::complex<double>& slot = ring[j % taps];
    const std::complex<double> field =
        std::sqrt(0.5 * weight * mean_intensity[j]) * std::complex<double>(re, im);
    sum += field;
    if (j >= taps) sum -= slot;  // the cell taps back leaves the pulse
    slot = field;
    out[j] = std::norm(sum);
  }
}

double pulse_speckle_correlation(int lag, int pulse_samples) {
  const int l = std::max(1, pulse_samples);
  const int k = std::abs(lag);
  if (k >= l) return 0.0;
  const double mu = 1.0 - static_cast<double>(k) / l;
  return mu * mu;
}

}  // namespace sonarloop::acoustics
