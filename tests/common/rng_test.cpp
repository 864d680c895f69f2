#include "common/rng.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

using sonarloop::Rng;
using sonarloop::RngStream;

TEST_CASE("rng: same key gives the same sequence, other keys differ") {
  Rng a(42, RngStream::kElevation, 3);
  Rng b(42, RngStream::kElevation, 3);
  Rng c(42, RngStream::kElevation, 4);
  Rng d(43, RngStream::kElevation, 3);
  int same_c = 0;
  int same_d = 0;
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next_u64();
    REQUIRE(x == b.next_u64());
    same_c += x == c.next_u64();
    same_d += x == d.next_u64();
  }
  CHECK(same_c == 0);
  CHECK(same_d == 0);
}

TEST_CASE("rng: normal, exponential, gamma and Poisson moments") {
  Rng rng(7, RngStream::kSpeckle);
  const int n = 200000;
  double s1 = 0, s2 = 0, e1 = 0, g1 = 0, g2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.normal();
    s1 += x;
    s2 += x * x;
    e1 += rng.exponential(2.0);
    const double g = rng.gamma(2.5);
    g1 += g;
    g2 += g * g;
  }
  CHECK(std::abs(s1 / n) < 0.01);
  CHECK(std::abs(s2 / n - 1.0) < 0.02);
  CHECK(std::abs(e1 / n - 2.0) < 0.03);
  CHECK(std::abs(g1 / n - 2.5) < 0.03);                        // mean k
  CHECK(std::abs(g2 / n - (g1 / n) * (g1 / n) - 2.5) < 0.08);  // variance k
  for (double mean : {0.5, 4.0, 29.0, 31.0, 250.0}) {
    double p1 = 0, p2 = 0;
    const int m = 50000;
    for (int i = 0; i < m; ++i) {
      const double k = static_cast<double>(rng.poisson(mean));
      p1 += k;
      p2 += k * k;
    }
    const double mu = p1 / m;
    const double var = p2 / m - mu * mu;
    INFO("mean " << mean);
    // 5 sigma bounds on the sample mean and (roughly) the sample variance
    CHECK(std::abs(mu - mean) < 5.0 * std::sqrt(mean / m));
    CHECK(std::abs(var - mean) < 5.0 * mean * std::sqrt(2.0 / m) + 5.0 * std::sqrt(mean / m));
  }
}

TEST_CASE("rng: normal_from_hash is standard normal over hashed lattice sites") {
  const int n = 100000;
  double s1 = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = sonarloop::normal_from_hash(sonarloop::hash_keys(1, RngStream::kRocky, i));
    s1 += x;
    s2 += x * x;
  }
  CHECK(std::abs(s1 / n) < 0.015);
  CHECK(std::abs(s2 / n - 1.0) < 0.02);
}
