#pragma once
// Square 2-D complex FFTs of power-of-two size, written for the noise layers' convolutions
// (docs/rendering.md, "Seabed tiles"): our own code, no FFT library.
//
// The data are two planes of n*n floats (real and imaginary parts, row-major). Each pass is a
// radix-2 Stockham FFT along the row index done on strips of 16 columns at once: a butterfly
// combines two rows of the strip with one twiddle, so the inner loop runs over 16 contiguous
// floats and the compiler vectorises it. A strip is copied into a small buffer that stays in
// the first-level cache for all log2(n) stages, and it is written back transposed, so two
// passes make the 2-D transform without a separate transpose. Results are in the normal layout
// (frequency [kx][ky] at kx * n + ky, kx along rows).

#include <complex>
#include <vector>

namespace sonarloop::seabed {

class Fft2d {
 public:
  explicit Fft2d(int n);
  int size() const { return n_; }

  // In place on the planes re and im (n*n floats each). forward: unnormalised; inverse:
  // divides by n*n.
  void forward(float* re, float* im);
  void inverse(float* re, float* im);
  // inverse() writing only rows [row0, row0 + count) of the result (the others are left
  // undefined): an overlap-save convolution keeps only its valid rows.
  void inverse_rows(float* re, float* im, int row0, int count);

  // The same on interleaved complex values (n*n of them), through the planes.
  void forward(std::vector<std::complex<float>>& data);
  void inverse(std::vector<std::complex<float>>& data);

 private:
  // One pass: the 1-D FFT along the row index of the columns [col0, col1) of (src_re, src_im),
  // column c written, times scale, to row c of (dst_re, dst_im). Other rows of dst may be
  // written too (the strips are 16 columns wide).
  void pass(const float* src_re, const float* src_im, float* dst_re, float* dst_im, bool inverse,
            int col0, int col1, float scale);
  void split(const std::vector<std::complex<float>>& data);
  void join(std::vector<std::complex<float>>& data) const;

  int n_;
  std::vector<float> twiddle_re_;  // cos(2 pi k / n), k < n/2
  std::vector<float> twiddle_im_;  // -sin(2 pi k / n): the forward transform's
  std::vector<float> strip_;       // two strip buffers, each n rows x kStrip (re, then im)
  std::vector<float> mid_re_;      // the transform between its two passes
  std::vector<float> mid_im_;
  std::vector<float> plane_re_;  // the interleaved overloads' planes
  std::vector<float> plane_im_;
};

}  // namespace sonarloop::seabed
