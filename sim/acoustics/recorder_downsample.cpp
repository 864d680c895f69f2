#include "sim/acoustics/recorder_downsample.h"

#include <algorithm>

namespace sonarloop::acoustics {

double downsample(std::span<const double> raw_intensity, Downsample how) {
  switch (how) {
    case Downsample::kMax:
      return *std::max_element(raw_intensity.begin(), raw_intensity.end());
    case Downsample::kDecimate:
      return raw_intensity.front();
    case Downsample::kRms:
      break;
  }
  double sum = 0.0;
  for (double v : raw_intensity)
    sum += v;
  return sum / static_cast<double>(raw_intensity.size());
}

std::uint16_t xtf_downsample_method(Downsample how) {
  switch (how) {
    case Downsample::kMax:
      return 2;
    case Downsample::kRms:
      return 4;
    case Downsample::kDecimate:
      break;
  }
  return 0;
}

double mean_of_max_exponential(int m) {
  double h = 0.0;
  for (int k = 1; k <= m; ++k)
    h += 1.0 / k;
  return h;
}

}  // namespace sonarloop::acoustics
