#include "sim/acoustics/speckle.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "common/rng.h"

using namespace sonarloop::acoustics;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using sonarloop::Rng;
using sonarloop::RngStream;

namespace {

constexpr int kSamples = 200000;

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v)
    s += x;
  return s / static_cast<double>(v.size());
}

double median_of(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

TEST_CASE("speckle: inversion is the exponential quantile function") {
  CHECK(apply_speckle(3.0, 1.0) == 0.0);
  CHECK_THAT(apply_speckle(3.0, 0.5), WithinRel(3.0 * std::log(2.0), 1e-15));
  CHECK_THAT(apply_speckle(2.0, std::exp(-2.0)), WithinRel(4.0, 1e-15));
  CHECK_THAT(rayleigh_amplitude(2.0, std::exp(-2.0)), WithinRel(2.0, 1e-15));
  CHECK_THAT(speckle_exceedance_probability(2.0, 1.0), WithinAbs(0.135335, 5e-7));
  CHECK_THAT(k_scintillation_index(2.0), WithinRel(2.0, 1e-15));

  std::vector<double> line{1.0, 2.0, 4.0};
  const std::vector<double> u{0.5, 1.0};
  apply_speckle(line, u);
  CHECK_THAT(line[0], WithinRel(std::log(2.0), 1e-15));
  CHECK(line[1] == 0.0);
  CHECK(line[2] == 4.0);  // beyond the shorter span: untouched
}

TEST_CASE("speckle: exponential intensity and Rayleigh amplitude statistics (item 24)") {
  Rng rng(2024, RngStream::kSpeckle);
  const double mu = 5.0;
  std::vector<double> intensity(kSamples);
  std::vector<double> amplitude(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double u = rng.uniform_pos();
    intensity[i] = apply_speckle(mu, u);
    amplitude[i] = rayleigh_amplitude(mu, u);
  }
  const double over = static_cast<double>(
      std::count_if(intensity.begin(), intensity.end(), [&](double v) { return v > 2.0 * mu; }));
  CHECK_THAT(over / kSamples, WithinAbs(0.1353, 0.005));
  CHECK_THAT(median_of(intensity) / mean_of(intensity), WithinAbs(0.6931, 0.01));
  CHECK_THAT(mean_of(intensity), WithinRel(mu, 0.01));
  CHECK_THAT(scintillation_index(intensity), WithinAbs(1.0, 0.03));

  const double a_mean = mean_of(amplitude);
  double ss = 0.0;
  for (double a : amplitude)
    ss += (a - a_mean) * (a - a_mean);
  const double a_std = std::sqrt(ss / kSamples);
  CHECK_THAT(a_std / a_mean, WithinAbs(0.5227, 0.01));
  CHECK_THAT(a_mean, WithinRel(0.886227 * std::sqrt(mu), 0.01));
}

TEST_CASE("speckle: K-distribution mean and scintillation index (item 24)") {
  for (double nu : {2.0, 5.0, 0.7}) {
    Rng rng(77, RngStream::kSpeckle, static_cast<std::uint64_t>(nu * 10));
    const double mean = 3.0;
    std::vector<double> v(kSamples);
    for (double& x : v)
      x = k_distributed(mean, nu, rng);
    INFO("nu " << nu);
    CHECK_THAT(mean_of(v), WithinRel(mean, 0.03));
    const double tol = nu == 2.0 ? 0.1 : 0.1 * k_scintillation_index(nu) / 2.0;
    CHECK_THAT(scintillation_index(v), WithinAbs(k_scintillation_index(nu), tol));
  }
  // deterministic: the same stream gives the same values
  Rng a(5, RngStream::kSpeckle);
  Rng b(5, RngStream::kSpeckle);
  for (int i = 0; i < 100; ++i)
    CHECK(k_distributed(1.0, 2.0, a) == k_distributed(1.0, 2.0, b));
}
