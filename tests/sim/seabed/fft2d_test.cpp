// The 2-D FFT the noise layers convolve with: round trip, a circular convolution against the
// direct sum, and inverse_rows() against the whole inverse.
#include "sim/seabed/fft2d.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
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

TEST_CASE("fft2d: forward then inverse gives the input back") {
  for (int n : {2, 8, 64}) {
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
  const int n = 32;
  Grid spectrum = pattern(n, 3);
  Fft2d fft(n);
  fft.forward(spectrum);
  Grid whole = spectrum;
  fft.inverse(whole);
  for (const auto& [row0, count] : std::vector<std::pair<int, int>>{{8, 16}, {0, 1}, {31, 1}}) {
    Grid part = spectrum;
    fft.inverse_rows(part, row0, count);
    for (int r = row0; r < row0 + count; ++r) {
      for (int c = 0; c < n; ++c) {
        const auto m = static_cast<std::size_t>(r * n + c);
        CHECK(part[m] == whole[m]);  // the same operations in the same order
      }
    }
  }
  Grid g = spectrum;
  CHECK_THROWS(fft.inverse_rows(g, 20, 13));
  CHECK_THROWS(fft.inverse_rows(g, -1, 2));
}
