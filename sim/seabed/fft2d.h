#pragma once
// Square 2-D complex FFTs of power-of-two size on row-major buffers, built on Eigen's FFT module
// (kissfft backend, BSD-licensed, shipped with Eigen; no FFTW).
//
// The 2-D transform is done as rows, transpose, rows: the result of forward() is left
// TRANSPOSED (element [kx][ky] at ky * n + kx) and inverse() expects that layout and returns
// the normal layout. Pointwise products between two forward() results are unaffected, which is
// all the convolution code needs, and it saves two transposes per convolution.
#include <complex>
#include <memory>
#include <vector>

namespace sonarloop::seabed {

class Fft2d {
 public:
  explicit Fft2d(int n);
  int size() const { return n_; }
  // In place on n*n values. forward: unnormalised; inverse: divides by n*n.
  void forward(std::vector<std::complex<float>>& data);
  void inverse(std::vector<std::complex<float>>& data);
  // inverse() computing only rows [row0, row0 + count) of the result (the others are left
  // undefined): an overlap-save convolution keeps only its valid rows, and the last pass of
  // FFTs and the transpose before it shrink with them.
  void inverse_rows(std::vector<std::complex<float>>& data, int row0, int count);

 private:
  // 1-D FFTs of rows [r0, r1)
  void rows(std::vector<std::complex<float>>& data, bool inverse, std::size_t r0, std::size_t r1);
  // rows [r0, r1) of the transpose (the whole transpose for 0, n)
  void transpose(std::vector<std::complex<float>>& data, std::size_t r0, std::size_t r1);

  int n_;
  std::vector<std::complex<float>> scratch_;
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace sonarloop::seabed
