#include "sim/seabed/fft2d.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace sonarloop::seabed {
namespace {

// Columns per strip: 16 floats are one 64-byte cache line of each row; a strip of 512 rows
// (both parts) is 64 KiB, two of them 128 KiB.
constexpr int kStrip = 16;

// n radix-2 butterflies with one twiddle w, on real and imaginary parts apart: s = a + b,
// d = (a - b) w. The runs never overlap: restrict-qualified parameters tell the compiler so
// (GCC does not take it from restrict-qualified locals), so that it vectorises the loop without
// a run-time overlap check.
void radix2(const float* __restrict ar, const float* __restrict ai, const float* __restrict br,
            const float* __restrict bi, float* __restrict sr, float* __restrict si,
            float* __restrict dr, float* __restrict di, std::size_t n, float wr, float wi) {
  for (std::size_t l = 0; l < n; ++l) {
    sr[l] = ar[l] + br[l];
    si[l] = ai[l] + bi[l];
    const float xr = ar[l] - br[l];
    const float xi = ai[l] - bi[l];
    dr[l] = xr * wr - xi * wi;
    di[l] = xr * wi + xi * wr;
  }
}

// The 1-D FFTs of w columns at once, held as n rows of w floats (real block, then imaginary
// block, each n * w) in x; y is scratch of the same size. Radix-2 Stockham autosort, decimation
// in frequency (Van Loan, "Computational Frameworks for the FFT", SIAM 1992, §1.7): at a stage
// of sub-length len = 2m and stride s, the butterfly of p < m takes the rows s*p + q and
// s*(p + m) + q (q < s) and writes the rows s*2p + q and s*(2p + 1) + q, the second times
// exp(-+2 pi i p / len). Each row group is a contiguous run of s * w floats with one twiddle,
// so the inner loop is long and vectorised. tw holds exp(-2 pi i k / n), k < n/2. Returns the
// buffer holding the result (x or y).
//
// (Radix-4 stages, with half as many passes over the strip, measured 10-20 % slower here; the
// strip stays in the first- or second-level cache either way.)
float* strip_fft(float* x, float* y, int n, int w, const float* tw_re, const float* tw_im,
                 float sign) {
  const auto plane = static_cast<std::size_t>(n) * static_cast<std::size_t>(w);
  std::size_t s = 1;
  for (int len = n; len > 1; len /= 2) {
    const auto m = static_cast<std::size_t>(len / 2);
    const auto step = static_cast<std::size_t>(n / len);
    const std::size_t run = s * static_cast<std::size_t>(w);
    for (std::size_t p = 0; p < m; ++p) {
      const std::size_t a = p * run;
      const std::size_t b = (p + m) * run;
      const std::size_t sum = 2 * p * run;
      const std::size_t diff = sum + run;
      radix2(x + a, x + plane + a, x + b, x + plane + b, y + sum, y + plane + sum, y + diff,
             y + plane + diff, run, tw_re[p * step], sign * tw_im[p * step]);
    }
    std::swap(x, y);
    s *= 2;
  }
  return x;
}

}  // namespace

Fft2d::Fft2d(int n) : n_(n) {
  if (n < 2 || (n & (n - 1)) != 0) throw std::invalid_argument("Fft2d: size must be a power of 2");
  const auto nn = static_cast<std::size_t>(n);
  twiddle_re_.resize(nn / 2);
  twiddle_im_.resize(nn / 2);
  for (std::size_t k = 0; k < nn / 2; ++k) {
    const double angle = 2.0 * std::numbers::pi * static_cast<double>(k) / n;
    twiddle_re_[k] = static_cast<float>(std::cos(angle));
    twiddle_im_[k] = static_cast<float>(-std::sin(angle));
  }
  strip_.resize(4 * nn * static_cast<std::size_t>(std::min(n, kStrip)));
  mid_re_.resize(nn * nn);
  mid_im_.resize(nn * nn);
}

void Fft2d::pass(const float* src_re, const float* src_im, float* dst_re, float* dst_im,
                 bool inverse, int col0, int col1, float scale) {
  const int n = n_;
  const int w = std::min(n, kStrip);
  const auto nn = static_cast<std::size_t>(n);
  const auto ww = static_cast<std::size_t>(w);
  const std::size_t plane = nn * ww;
  float* x = strip_.data();
  float* y = x + 2 * plane;
  const int first = col0 / w * w;
  for (int c0 = first; c0 < col1; c0 += w) {
    // gather the strip: row r of columns [c0, c0 + w)
    for (std::size_t r = 0; r < nn; ++r) {
      const std::size_t from = r * nn + static_cast<std::size_t>(c0);
      std::copy(src_re + from, src_re + from + ww, x + r * ww);
      std::copy(src_im + from, src_im + from + ww, x + plane + r * ww);
    }
    const float* out =
        strip_fft(x, y, n, w, twiddle_re_.data(), twiddle_im_.data(), inverse ? -1.0f : 1.0f);
    // scatter transposed, by blocks of w x w: column c0 + l becomes row c0 + l
    for (std::size_t r0 = 0; r0 < nn; r0 += ww) {
      for (std::size_t l = 0; l < ww; ++l) {
        float* dr = dst_re + (static_cast<std::size_t>(c0) + l) * nn + r0;
        float* di = dst_im + (static_cast<std::size_t>(c0) + l) * nn + r0;
        const float* sr = out + r0 * ww + l;
        const float* si = sr + plane;
        for (std::size_t r = 0; r < ww; ++r) {
          dr[r] = scale * sr[r * ww];
          di[r] = scale * si[r * ww];
        }
      }
    }
  }
}

void Fft2d::forward(float* re, float* im) {
  pass(re, im, mid_re_.data(), mid_im_.data(), false, 0, n_, 1.0f);
  pass(mid_re_.data(), mid_im_.data(), re, im, false, 0, n_, 1.0f);
}

void Fft2d::inverse(float* re, float* im) {
  inverse_rows(re, im, 0, n_);
}

void Fft2d::inverse_rows(float* re, float* im, int row0, int count) {
  if (row0 < 0 || count < 0 || row0 + count > n_) {
    throw std::invalid_argument("Fft2d::inverse_rows: rows outside the transform");
  }
  if (count == 0) return;
  const float scale = 1.0f / (static_cast<float>(n_) * static_cast<float>(n_));
  pass(re, im, mid_re_.data(), mid_im_.data(), true, 0, n_, 1.0f);
  // the second pass's column c is the result's row c
  pass(mid_re_.data(), mid_im_.data(), re, im, true, row0, row0 + count, scale);
}

void Fft2d::split(const std::vector<std::complex<float>>& data) {
  const auto nn = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_);
  if (data.size() != nn) throw std::invalid_argument("Fft2d: data must hold n*n values");
  plane_re_.resize(nn);
  plane_im_.resize(nn);
  for (std::size_t m = 0; m < nn; ++m) {
    plane_re_[m] = data[m].real();
    plane_im_[m] = data[m].imag();
  }
}

void Fft2d::join(std::vector<std::complex<float>>& data) const {
  for (std::size_t m = 0; m < data.size(); ++m)
    data[m] = {plane_re_[m], plane_im_[m]};
}

void Fft2d::forward(std::vector<std::complex<float>>& data) {
  split(data);
  forward(plane_re_.data(), plane_im_.data());
  join(data);
}

void Fft2d::inverse(std::vector<std::complex<float>>& data) {
  split(data);
  inverse(plane_re_.data(), plane_im_.data());
  join(data);
}

}  // namespace sonarloop::seabed
