#pragma once
// Sample statistics for the vehicle's noise tests.
#include <cmath>
#include <vector>

namespace sonarloop::testing {

struct SampleMoments {
  double mean = 0.0;
  double variance = 0.0;  // unbiased (n - 1)
  double sd = 0.0;        // sqrt(variance)
};

inline SampleMoments sample_moments(const std::vector<double>& v) {
  double sum = 0.0, sum2 = 0.0;
  for (double x : v)
    sum += x;
  const double mean = sum / static_cast<double>(v.size());
  for (double x : v)
    sum2 += (x - mean) * (x - mean);
  const double variance = sum2 / static_cast<double>(v.size() - 1);
  return {mean, variance, std::sqrt(variance)};
}

}  // namespace sonarloop::testing
