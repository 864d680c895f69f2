#include "sim/vehicle/noise_processes.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/sim/vehicle/sample_moments.h"

using namespace sonarloop;
using namespace sonarloop::vehicle;
using sonarloop::testing::sample_moments;
using sonarloop::testing::SampleMoments;

namespace {

constexpr SimTime kSecond = kNanosecondsPerSecond;

}  // namespace

TEST_CASE("white noise is standard normal and held within a step", "[vehicle][noise]") {
  const SimTime step = 10'000'000;  // 10 ms
  std::vector<double> v;
  for (SimTime k = -5000; k < 45000; ++k)
    v.push_back(hashed_white_noise(7, NavChannel::kNorth, k * step, step));
  const SampleMoments m = sample_moments(v);
  std::printf("white noise: mean %.4f sd %.4f over %zu steps\n", m.mean, std::sqrt(m.variance),
              v.size());
  CHECK(std::abs(m.mean) < 0.02);
  CHECK(std::sqrt(m.variance) == Approx(1.0).epsilon(0.02));

  // held within a step, negative times included
  CHECK(hashed_white_noise(7, NavChannel::kNorth, 3 * step + 1, step) ==
        hashed_white_noise(7, NavChannel::kNorth, 4 * step - 1, step));
  CHECK(hashed_white_noise(7, NavChannel::kNorth, -1, step) ==
        hashed_white_noise(7, NavChannel::kNorth, -step, step));
  CHECK(hashed_white_noise(7, NavChannel::kNorth, -1, step) !=
        hashed_white_noise(7, NavChannel::kNorth, 0, step));
  // channels and seeds are independent streams
  CHECK(hashed_white_noise(7, NavChannel::kNorth, 0, step) !=
        hashed_white_noise(7, NavChannel::kEast, 0, step));
  CHECK(hashed_white_noise(7, NavChannel::kNorth, 0, step) !=
        hashed_white_noise(8, NavChannel::kNorth, 0, step));
  // consecutive steps uncorrelated
  double lag1 = 0.0;
  for (std::size_t i = 1; i < v.size(); ++i)
    lag1 += v[i] * v[i - 1];
  CHECK(std::abs(lag1 / static_cast<double>(v.size())) < 0.02);
}

TEST_CASE("the Wiener process starts at zero and its variance grows linearly with time",
          "[vehicle][noise]") {
  const SimTime step = kSecond;
  CHECK(hashed_wiener(1, NavChannel::kHeading, 0, step) == 0.0);
  CHECK(hashed_wiener(1, NavChannel::kHeading, -5 * kSecond, step) == 0.0);

  // across 4000 seeds: Var W(t) = t at knots (also beyond one block of 2^16 knots), and
  // increments over disjoint intervals are independent with variance = the interval
  const int seeds = 4000;
  const std::vector<double> times_s = {1.0, 10.0, 100.0, 1000.0, 70000.0};
  for (double t_s : times_s) {
    std::vector<double> v;
    for (int seed = 0; seed < seeds; ++seed) {
      v.push_back(hashed_wiener(static_cast<std::uint64_t>(seed), NavChannel::kNorth,
                                static_cast<SimTime>(t_s) * kSecond, step));
    }
    const SampleMoments m = sample_moments(v);
    std::printf("wiener: t = %7.0f s  mean %+.3f·sqrt(t)  var/t %.4f\n", t_s,
                m.mean / std::sqrt(t_s), m.variance / t_s);
    CHECK(std::abs(m.mean) < 4.0 * std::sqrt(t_s / seeds));
    CHECK(m.variance / t_s == Approx(1.0).epsilon(0.1));
  }

  std::vector<double> d1, d2;
  for (int seed = 0; seed < seeds; ++seed) {
    const auto s = static_cast<std::uint64_t>(seed);
    const double w100 = hashed_wiener(s, NavChannel::kEast, 100 * kSecond, step);
    const double w400 = hashed_wiener(s, NavChannel::kEast, 400 * kSecond, step);
    const double w500 = hashed_wiener(s, NavChannel::kEast, 500 * kSecond, step);
    d1.push_back(w400 - w100);
    d2.push_back(w500 - w400);
  }
  CHECK(sample_moments(d1).variance / 300.0 == Approx(1.0).epsilon(0.1));
  CHECK(sample_moments(d2).variance / 100.0 == Approx(1.0).epsilon(0.1));
  double cov = 0.0;
  for (int i = 0; i < seeds; ++i)
    cov += d1[static_cast<std::size_t>(i)] * d2[static_cast<std::size_t>(i)];
  cov /= seeds;
  CHECK(std::abs(cov) / std::sqrt(300.0 * 100.0) < 0.06);  // correlation ~ 0 (sd 0.016)
}

TEST_CASE("the Wiener process is continuous and order-independent", "[vehicle][noise]") {
  const SimTime step = kSecond / 2;
  // linear between knots: no jumps
  double max_jump = 0.0;
  double previous = hashed_wiener(3, NavChannel::kHeading, 0, step);
  for (SimTime t = 1'000'000; t < 200 * kSecond; t += 1'000'000) {
    const double w = hashed_wiener(3, NavChannel::kHeading, t, step);
    max_jump = std::max(max_jump, std::abs(w - previous));
    previous = w;
  }
  CHECK(max_jump < 0.02);  // 1 ms of a unit-rate walk on 0.5 s knots: |ΔW| ~ 1e-3·|N|/0.7

  // the value at a time does not depend on what was asked before
  const SimTime t = 12345 * kSecond + 678;
  const double first = hashed_wiener(9, NavChannel::kRoll, t, step);
  for (SimTime u = 0; u < 1000; ++u)
    (void)hashed_wiener(9, NavChannel::kRoll, u * 77 * kSecond, step);
  CHECK(hashed_wiener(9, NavChannel::kRoll, t, step) == first);
}
