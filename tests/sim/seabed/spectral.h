#pragma once
// Spectral estimates for the seabed tests: 2-D periodograms, radial averages, log-log fits and
// correlation lengths. Test-only code; uses the library's Fft2d.
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "sim/seabed/fft2d.h"

namespace sonarloop::testing {

// |FFT|^2 of an n x n patch (row-major, n a power of 2) after removing the mean and applying a
// 2-D Hann window. Result in the normal layout: p[kx * n + ky], kx along rows (north).
inline std::vector<double> periodogram(const std::vector<float>& patch, int n) {
  const auto nn = static_cast<std::size_t>(n);
  double mean = 0.0;
  for (float v : patch)
    mean += v;
  mean /= static_cast<double>(patch.size());
  std::vector<std::complex<float>> buf(nn * nn);
  for (int i = 0; i < n; ++i) {
    const double wi = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / n);
    for (int j = 0; j < n; ++j) {
      const double wj = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * j / n);
      buf[static_cast<std::size_t>(i) * nn + static_cast<std::size_t>(j)] = static_cast<float>(
          (patch[static_cast<std::size_t>(i) * nn + static_cast<std::size_t>(j)] - mean) * wi * wj);
    }
  }
  seabed::Fft2d(n).forward(buf);
  std::vector<double> p(nn * nn);
  for (std::size_t m = 0; m < nn * nn; ++m)
    p[m] = std::norm(buf[m]);
  return p;
}

inline int signed_bin(int k, int n) {
  return k < n / 2 ? k : k - n;
}

// Least-squares slope of log10(P) against log10(f) over radial frequencies (cycles per sample)
// in [f_lo, f_hi], from the periodogram averaged in log-spaced rings.
inline double radial_loglog_slope(const std::vector<double>& p, int n, double f_lo, double f_hi) {
  const int nbins = 24;
  std::vector<double> sum(nbins, 0.0);
  std::vector<int> count(nbins, 0);
  const double l0 = std::log10(f_lo);
  const double l1 = std::log10(f_hi);
  for (int kx = 0; kx < n; ++kx) {
    for (int ky = 0; ky < n; ++ky) {
      const double f = std::hypot(signed_bin(kx, n), signed_bin(ky, n)) / n;
      if (f < f_lo || f > f_hi) continue;
      const int b = std::min(nbins - 1, static_cast<int>((std::log10(f) - l0) / (l1 - l0) * nbins));
      sum[b] += p[static_cast<std::size_t>(kx) * n + ky];
      ++count[b];
    }
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (int b = 0; b < nbins; ++b) {
    if (count[b] == 0) continue;
    const double x = l0 + (b + 0.5) * (l1 - l0) / nbins;
    const double y = std::log10(sum[b] / count[b]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++m;
  }
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

// Slope of log10(PSD) against log10(f) of the rows of an n x n patch (1-D periodograms with a
// Hann window, averaged over rows), fitted over f in [f_lo, f_hi] cycles per sample.
inline double profile_loglog_slope(const std::vector<float>& patch, int n, double f_lo,
                                   double f_hi) {
  const auto nn = static_cast<std::size_t>(n);
  // a direct DFT at 24 log-spaced frequencies of every fourth row: plenty for a slope
  const int nf = 24;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < nf; ++k) {
    const double f = f_lo * std::pow(f_hi / f_lo, (k + 0.5) / nf);
    double power = 0.0;
    for (std::size_t r = 0; r < nn; r += 4) {
      double mean = 0.0;
      for (std::size_t c = 0; c < nn; ++c)
        mean += patch[r * nn + c];
      mean /= n;
      double re = 0.0, im = 0.0;
      for (std::size_t c = 0; c < nn; ++c) {
        const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * c / n);
        const double v = (patch[r * nn + c] - mean) * w;
        re += v * std::cos(2.0 * std::numbers::pi * f * c);
        im -= v * std::sin(2.0 * std::numbers::pi * f * c);
      }
      power += re * re + im * im;
    }
    const double x = std::log10(f);
    const double y = std::log10(power);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (nf * sxy - sx * sy) / (nf * sxx - sx * sx);
}

// Lag (in samples, linearly interpolated) at which the normalised autocorrelation of an
// n x n patch along one axis (axis 0: rows/north, 1: columns/east) first falls below 1/e.
inline double correlation_length(const std::vector<float>& patch, int n, int axis) {
  double mean = 0.0;
  for (float v : patch)
    mean += v;
  mean /= static_cast<double>(patch.size());
  auto at = [&](int i, int j) {
    return patch[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)] - mean;
  };
  auto acf = [&](int lag) {
    double s = 0.0;
    long cnt = 0;
    for (int i = 0; i < n - (axis == 0 ? lag : 0); ++i) {
      for (int j = 0; j < n - (axis == 1 ? lag : 0); ++j) {
        s += at(i, j) * (axis == 0 ? at(i + lag, j) : at(i, j + lag));
        ++cnt;
      }
    }
    return s / static_cast<double>(cnt);
  };
  const double c0 = acf(0);
  double prev = 1.0;
  for (int lag = 1; lag < n / 2; ++lag) {
    const double c = acf(lag) / c0;
    if (c < std::exp(-1.0)) {
      return lag - 1 + (prev - std::exp(-1.0)) / (prev - c);
    }
    prev = c;
  }
  return n / 2.0;
}

}  // namespace sonarloop::testing
