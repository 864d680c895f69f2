#include "sim/seabed/noise_layer.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "tests/sim/seabed/spectral.h"

using namespace sonarloop;
using namespace sonarloop::seabed;

namespace {

NoiseLayerSpec pink_spec(std::uint64_t seed, double beta, int kernel) {
  NoiseLayerSpec s;
  s.seed = seed;
  s.stream = RngStream::kElevation;
  s.spacing_m = 1.0;
  s.kernel_size = kernel;
  s.rms = 1.0;
  s.spectrum = [beta](double fx, double fy) { return pink_psd(fx, fy, beta, 1e5, 0.0); };
  return s;
}

std::vector<float> patch(const NoiseLayer& layer, std::int64_t i0, std::int64_t j0, int n) {
  std::vector<float> p(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      p[static_cast<std::size_t>(i) * n + j] = layer.site(i0 + i, j0 + j);
  }
  return p;
}

}  // namespace

TEST_CASE("noise layer: pink noise periodogram recovers beta within 0.1") {
  for (double beta : {1.3, 1.8, 2.6}) {
    const NoiseLayer layer(pink_spec(11, beta, 512));
    const int n = 512;
    // average the periodogram of four independent patches to tame its variance
    std::vector<double> p(static_cast<std::size_t>(n) * n, 0.0);
    for (int k = 0; k < 4; ++k) {
      const auto q = testing::periodogram(patch(layer, 3000 * k, -1000 * k, n), n);
      for (std::size_t m = 0; m < p.size(); ++m)
        p[m] += q[m];
    }
    const double slope = testing::radial_loglog_slope(p, n, 1.0 / 64.0, 1.0 / 4.0);
    INFO("beta " << beta << " fitted " << -slope);
    CHECK(std::abs(-slope - beta) < 0.1);
  }
}

TEST_CASE("noise layer: rms matches the spec") {
  const NoiseLayer layer(pink_spec(5, 2.0, 128));
  double s2 = 0.0;
  const auto p = patch(layer, 0, 0, 512);
  for (float v : p)
    s2 += v * v;
  CHECK(std::sqrt(s2 / p.size()) == Approx(1.0).epsilon(0.1));
}

TEST_CASE("noise layer: a site does not depend on the order tiles are made in") {
  const NoiseLayer a(pink_spec(3, 1.8, 64));
  const NoiseLayer b(pink_spec(3, 1.8, 64));
  std::vector<float> va;
  std::vector<float> vb;
  for (int ti = -2; ti <= 2; ++ti) {
    for (int tj = -2; tj <= 2; ++tj)
      a.tile(ti, tj);
  }
  for (int ti = 2; ti >= -2; --ti) {
    for (int tj = 2; tj >= -2; --tj)
      b.tile(tj, ti);  // other order, transposed walk
  }
  for (int ti = -2; ti <= 2; ++ti) {
    for (int tj = -2; tj <= 2; ++tj) {
      const auto& ta = *a.tile(ti, tj);
      const auto& tb = *b.tile(ti, tj);
      REQUIRE(ta == tb);
    }
  }
}

TEST_CASE("noise layer: same seed gives identical tiles, another seed different ones") {
  const NoiseLayer a(pink_spec(3, 1.8, 64));
  const NoiseLayer b(pink_spec(3, 1.8, 64));
  const NoiseLayer c(pink_spec(4, 1.8, 64));
  CHECK(*a.tile(7, -3) == *b.tile(7, -3));
  CHECK(*a.tile(7, -3) != *c.tile(7, -3));
}

TEST_CASE("noise layer: no seam at tile borders") {
  // first differences across tile borders are distributed like those inside tiles
  const int k = 64;
  const NoiseLayer layer(pink_spec(9, 2.2, k));
  const auto p = patch(layer, -4 * k, -4 * k, 8 * k);
  const int n = 8 * k;
  double border = 0.0, interior = 0.0;
  long nb = 0, ni = 0;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double d =
          p[static_cast<std::size_t>(i + 1) * n + j] - p[static_cast<std::size_t>(i) * n + j];
      if ((i + 1) % k == 0) {
        border += d * d;
        ++nb;
      } else if ((i + 1) % k == k / 2) {
        interior += d * d;
        ++ni;
      }
    }
  }
  const double ratio = (border / nb) / (interior / ni);
  INFO("border/interior variance of first differences " << ratio);
  CHECK(ratio > 0.85);
  CHECK(ratio < 1.15);
}

TEST_CASE("noise layer: ripple periodogram peaks at the wavelength and direction") {
  const double wavelength = 0.6;
  const double dir = 30.0 * std::numbers::pi / 180.0;
  NoiseLayerSpec s;
  s.seed = 21;
  s.stream = RngStream::kRipples;
  s.spacing_m = 0.05;
  s.kernel_size = 256;
  const double eps = 1.0 / (2 * 256 * 0.05);
  s.spectrum = [=](double fx, double fy) {
    return ripple_psd(fx, fy, wavelength, dir, 2.0, 2.5, eps);
  };
  const NoiseLayer layer(s);
  const int n = 512;
  const auto p = testing::periodogram(patch(layer, 100, 200, n), n);
  int best_kx = 0, best_ky = 0;
  double best = -1.0;
  for (int kx = 0; kx < n; ++kx) {
    for (int ky = 0; ky < n; ++ky) {
      if (testing::signed_bin(kx, n) < 0) continue;  // the spectrum is even: one half-plane
      const double v = p[static_cast<std::size_t>(kx) * n + ky];
      if (v > best) {
        best = v;
        best_kx = kx;
        best_ky = ky;
      }
    }
  }
  const double df = 1.0 / (n * s.spacing_m);
  const double want_kx = std::cos(dir) / wavelength / df;
  const double want_ky = std::sin(dir) / wavelength / df;
  INFO("peak bin (" << testing::signed_bin(best_kx, n) << ", " << testing::signed_bin(best_ky, n)
                    << ") expected (" << want_kx << ", " << want_ky << ")");
  CHECK(std::abs(testing::signed_bin(best_kx, n) - want_kx) <= 1.0);
  CHECK(std::abs(testing::signed_bin(best_ky, n) - want_ky) <= 1.0);
}

TEST_CASE("noise layer: rocky stand-in correlation-length ratio matches its anisotropy") {
  for (double aniso : {2.0, 4.0}) {
    NoiseLayerSpec s;
    s.seed = 33;
    s.stream = RngStream::kRocky;
    s.spacing_m = 0.05;
    s.kernel_size = 512;
    s.spectrum = [=](double fx, double fy) { return rocky_psd(fx, fy, 3.2, aniso, 0.0, 0.6); };
    const NoiseLayer layer(s);
    const int n = 512;
    double along = 0.0, across = 0.0;
    for (int k = 0; k < 3; ++k) {
      const auto p = patch(layer, 1000 * k, 0, n);
      along += testing::correlation_length(p, n, 0);  // x' = north
      across += testing::correlation_length(p, n, 1);
    }
    INFO("anisotropy " << aniso << " measured " << along / across);
    CHECK(along / across == Approx(aniso).epsilon(0.1));
  }
}

TEST_CASE("noise layer: Catmull-Rom sampling reproduces sites and is smooth between them") {
  const NoiseLayer layer(pink_spec(2, 3.0, 64));
  // at lattice sites the interpolant equals the site values
  for (int i = -3; i < 3; ++i) {
    CHECK(layer.sample(i * 1.0, 5.0) == Approx(layer.site(i, 5)).margin(1e-5));
  }
  // a fine grid across a site boundary has no jumps larger than the local slope allows
  std::vector<float> g(1 * 200);
  layer.sample_grid(10.0, 3.0, 0.01, 1, 200, g.data(), 200);
  double max_step = 0.0;
  for (int c = 1; c < 200; ++c)
    max_step = std::max(max_step, std::abs(double(g[c] - g[c - 1])));
  double max_site_step = 0.0;
  for (int j = 3; j < 5; ++j)
    max_site_step =
        std::max(max_site_step, std::abs(double(layer.site(10, j + 1) - layer.site(10, j))));
  CHECK(max_step < 0.1 * max_site_step + 1e-4);
}
