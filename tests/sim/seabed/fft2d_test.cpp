// The 2-D FFT the noise layers convolve with: the direct sum's values and layout, round trip, a
// circular convolution against the direct sum, and inverse_rows() against the whole inverse.
#include "sim/seabed/fft2d.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

using namespace sonarloop::seabed;
using Grid = std::vector<std::complex<float>>;

namespace {

// deterministic, non-symmetric test values
Grid pattern(int n, int salt) {
  Grid g(static_cast<std::size_t>(n * n));
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const double a = std::sin(0.37 * r + 1.3 * c + salt) + 0.25 * std::cos(2.1 * r * c + salt);
      g[static_cast<std::size_t>(r * n + c)] = {static_cast<float>(a), static_cast<float>(0.5 * a)};
    }
  }
  return g;
}

}  // namespace

TEST_CASE("fft2d: forward is the direct sum, in the normal layout") {
  // X[kx][ky] = sum over (r, c) of x[r][c] exp(-2 pi i (kx r + ky c) / n), every size from the
  // one-stage transform up to one wider than a strip of columns
  for (int n : {2, 4, 8, 16, 32}) {
    const Grid x = pattern(n, 7);
    Grid y = x;
    Fft2d(n).forward(y);
    double worst = 0.0;
    for (int kx = 0; kx < n; ++kx) {
      for (int ky = 0; ky < n; ++ky) {
        std::complex<double> sum = 0.0;
        for (int r = 0; r < n; ++r) {
          for (int c = 0; c < n; ++c) {
            const double phase = -2.0 * std::numbers::pi * ((kx * r + ky * c) % n) / n;
            sum += std::complex<double>(x[static_cast<std::size_t>(r * n + c)]) *
                   std::polar(1.0, phase);
          }
        }
        worst = std::max(
            worst, std::abs(std::complex<double>(y[static_cast<std::size_t>(kx * n + ky)]) - sum));
      }
    }
    INFO("n = " << n);
    CHECK(worst < 2e-6 * n * n);
  }
}

TEST_CASE("fft2d: forward then inverse gives the input back") {
  for (int n : {2, 8, 64, 256}) {
    const Grid x = pattern(n, n);
    Grid y = x;
    Fft2d fft(n);
    fft.forward(y);
    fft.inverse(y);
    for (std::size_t m = 0; m < x.size(); ++m)
      CHECK(std::abs(y[m] - x[m]) < 1e-5);
  }
  CHECK_THROWS(Fft2d(12));
}

TEST_CASE("fft2d: the product of two forward transforms is the circular convolution") {
  const int n = 16;
  const Grid a = pattern(n, 1);
  const Grid b = pattern(n, 2);
  Grid fa = a;
  Grid fb = b;
  Fft2d fft(n);
  fft.forward(fa);
  fft.forward(fb);
  for (std::size_t m = 0; m < fa.size(); ++m)
    fa[m] *= fb[m];
  fft.inverse(fa);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      std::complex<double> sum = 0.0;
      for (int u = 0; u < n; ++u) {
        for (int v = 0; v < n; ++v) {
          const auto av = a[static_cast<std::size_t>(u * n + v)];
          const auto bv = b[static_cast<std::size_t>(((r - u + n) % n) * n + (c - v + n) % n)];
          sum += std::complex<double>(av) * std::complex<double>(bv);
        }
      }
      CHECK(std::abs(std::complex<double>(fa[static_cast<std::size_t>(r * n + c)]) - sum) < 1e-3);
    }
  }
}

TEST_CASE("fft2d: inverse_rows gives the inverse's rows it was asked for") {
  const int n = 64;
  const Grid spectrum = pattern(n, 3);
  std::vector<float> re(spectrum.size());
  std::vector<float> im(spectrum.size());
  const auto load = [&] {
    for (std::size_t m = 0; m < spectrum.size(); ++m) {
      re[m] = spectrum[m].real();
      im[m] = spectrum[m].imag();
    }
  };
  Fft2d fft(n);
  Grid whole = spectrum;
  fft.inverse(whole);
  // within one strip of 16 columns, across strips, and the edges
  for (const auto& [row0, count] :
       std::vector<std::pair<int, int>>{{16, 32}, {5, 3}, {10, 30}, {0, 1}, {63, 1}}) {
    load();
    fft.inverse_rows(re.data(), im.data(), row0, count);
    for (int r = row0; r < row0 + count; ++r) {
      for (int c = 0; c < n; ++c) {
        const auto m = static_cast<std::size_t>(r * n + c);
        CHECK(re[m] == whole[m].real());  // the same operations in the same order
        CHECK(im[m] == whole[m].imag());
      }
    }
  }
  CHECK_THROWS(fft.inverse_rows(re.data(), im.data(), 60, 5));
  CHECK_THROWS(fft.inverse_rows(re.data(), im.data(), -1, 2));
}
