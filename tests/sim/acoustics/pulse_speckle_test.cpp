// Speckle through the pulse (sim/acoustics/pulse_speckle.h) against its oracles: exponential
// intensity with the pulse-averaged mean, and intensity correlation (1 − |k|/L)² (Goodman 2007);
// and the recorder's downsampling (sim/acoustics/recorder_downsample.h): the mean of the
// largest of m exponentials is H_m.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "common/rng.h"
#include "sim/acoustics/pulse_speckle.h"
#include "sim/acoustics/recorder_downsample.h"

using namespace sonarloop::acoustics;
using sonarloop::Rng;
using sonarloop::RngStream;

namespace {

constexpr std::size_t kRawSamples = 400000;

std::vector<double> speckled(const std::vector<double>& mean, int taps, std::uint64_t seed) {
  Rng rng(seed, RngStream::kSpeckle);
  std::vector<double> out(mean.size());
  pulse_speckle(mean, taps, rng, out);
  return out;
}

// correlation coefficient of v[j] and v[j + lag] over j >= skip
double correlation(const std::vector<double>& v, int lag, std::size_t skip) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  std::size_t n = 0;
  for (std::size_t j = skip; j + static_cast<std::size_t>(lag) < v.size(); ++j) {
    const double a = v[j];
    const double b = v[j + static_cast<std::size_t>(lag)];
    sa += a;
    sb += b;
    saa += a * a;
    sbb += b * b;
    sab += a * b;
    ++n;
  }
  const double dn = static_cast<double>(n);
  const double cov = sab / dn - (sa / dn) * (sb / dn);
  return cov / std::sqrt((saa / dn - sa * sa / dn / dn) * (sbb / dn - sb * sb / dn / dn));
}

}  // namespace

TEST_CASE("pulse speckle: exponential intensity, its mean kept, correlated over the pulse") {
  for (int taps : {1, 3, 5}) {
    const std::vector<double> mean(kRawSamples, 2.0);
    const auto out = speckled(mean, taps, 11);
    double sum = 0.0;
    std::size_t above = 0;
    for (std::size_t j = static_cast<std::size_t>(taps); j < out.size(); ++j) {
      sum += out[j];
      if (out[j] > 4.0) ++above;  // twice the mean: e^-2 of exponential samples
    }
    const double n = static_cast<double>(out.size() - static_cast<std::size_t>(taps));
    INFO("pulse of " << taps << " samples");
    CHECK(sum / n == Approx(2.0).epsilon(0.01));
    CHECK(static_cast<double>(above) / n == Approx(std::exp(-2.0)).margin(0.003));
    for (int lag = 0; lag <= taps + 1; ++lag) {
      INFO("lag " << lag);
      CHECK(correlation(out, lag, static_cast<std::size_t>(taps)) ==
            Approx(pulse_speckle_correlation(lag, taps)).margin(0.01));
    }
  }
  CHECK(pulse_speckle_correlation(2, 4) == Approx(0.25));
  CHECK(pulse_speckle_correlation(-3, 4) == Approx(1.0 / 16.0));
  CHECK(pulse_speckle_correlation(4, 4) == 0.0);
}

TEST_CASE("pulse speckle: the mean is the pulse's average of the cells' means") {
  // a periodic pattern of bright and dark runs: at each phase the mean over many periods is the
  // average of the `taps` cells ending there
  constexpr int kPeriod = 8;
  constexpr int kTaps = 3;
  std::vector<double> mean(kRawSamples);
  for (std::size_t j = 0; j < kRawSamples; ++j)
    mean[j] = (j % kPeriod) < 4 ? 9.0 : 1.0;
  const auto out = speckled(mean, kTaps, 5);
  for (int phase = 0; phase < kPeriod; ++phase) {
    double sum = 0.0;
    int n = 0;
    for (std::size_t j = kPeriod + static_cast<std::size_t>(phase); j < kRawSamples; j += kPeriod) {
      sum += out[j];
      ++n;
    }
    double expected = 0.0;
    for (int t = 0; t < kTaps; ++t)
      expected += ((phase - t + kPeriod) % kPeriod) < 4 ? 9.0 : 1.0;
    expected /= kTaps;
    INFO("phase " << phase);
    CHECK(sum / n == Approx(expected).epsilon(0.02));
  }
}

TEST_CASE("recorder downsampling: rms, max, decimate, and the mean of a maximum") {
  const std::vector<double> raw = {1.0, 4.0, 2.5};
  CHECK(downsample(raw, Downsample::kRms) == Approx(2.5));
  CHECK(downsample(raw, Downsample::kMax) == 4.0);
  CHECK(downsample(raw, Downsample::kDecimate) == 1.0);
  CHECK(xtf_downsample_method(Downsample::kMax) == 2);
  CHECK(xtf_downsample_method(Downsample::kRms) == 4);
  CHECK(xtf_downsample_method(Downsample::kDecimate) == 0);
  // independent exponential samples (a pulse of one sample), kept by threes
  const auto out = speckled(std::vector<double>(kRawSamples, 1.0), 1, 9);
  for (int m : {2, 3}) {
    double sum = 0.0;
    std::size_t bins = 0;
    for (std::size_t j = 0; j + static_cast<std::size_t>(m) <= out.size();
         j += static_cast<std::size_t>(m)) {
      sum += downsample(std::span<const double>(out.data() + j, static_cast<std::size_t>(m)),
                        Downsample::kMax);
      ++bins;
    }
    INFO("max of " << m);
    CHECK(sum / static_cast<double>(bins) == Approx(mean_of_max_exponential(m)).epsilon(0.01));
  }
  CHECK(mean_of_max_exponential(3) == Approx(11.0 / 6.0));
}
