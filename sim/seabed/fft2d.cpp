#include "sim/seabed/fft2d.h"

#include <algorithm>
#include <stdexcept>
#include <unsupported/Eigen/FFT>

namespace sonarloop::seabed {

struct Fft2d::Impl {
  Eigen::FFT<float> fft;
  std::vector<std::complex<float>> in;
  std::vector<std::complex<float>> out;
};

Fft2d::Fft2d(int n) : n_(n), impl_(std::make_shared<Impl>()) {
  if (n < 2 || (n & (n - 1)) != 0) throw std::invalid_argument("Fft2d: size must be a power of 2");
  impl_->fft.SetFlag(Eigen::FFT<float>::Unscaled);
  impl_->in.resize(static_cast<std::size_t>(n));
  impl_->out.resize(static_cast<std::size_t>(n));
  scratch_.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
}

void Fft2d::rows(std::vector<std::complex<float>>& data, bool inverse, std::size_t r0,
                 std::size_t r1) {
  const auto n = static_cast<std::size_t>(n_);
  auto& in = impl_->in;
  auto& out = impl_->out;
  for (std::size_t r = r0; r < r1; ++r) {
    std::complex<float>* row = data.data() + r * n;
    std::copy(row, row + n, in.begin());
    if (inverse) {
      impl_->fft.inv(out.data(), in.data(), static_cast<Eigen::Index>(n));
    } else {
      impl_->fft.fwd(out.data(), in.data(), static_cast<Eigen::Index>(n));
    }
    std::copy(out.begin(), out.end(), row);
  }
}

void Fft2d::transpose(std::vector<std::complex<float>>& data, std::size_t r0, std::size_t r1) {
  // blocked out-of-place transpose through the scratch buffer: result row r is data's column r
  const auto n = static_cast<std::size_t>(n_);
  constexpr std::size_t kBlock = 32;
  for (std::size_t rb = r0; rb < r1; rb += kBlock) {
    for (std::size_t cb = 0; cb < n; cb += kBlock) {
      const std::size_t re = std::min(r1, rb + kBlock);
      const std::size_t ce = std::min(n, cb + kBlock);
      for (std::size_t c = cb; c < ce; ++c) {
        for (std::size_t r = rb; r < re; ++r)
          scratch_[r * n + c] = data[c * n + r];
      }
    }
  }
  data.swap(scratch_);
}

void Fft2d::forward(std::vector<std::complex<float>>& data) {
  const auto n = static_cast<std::size_t>(n_);
  rows(data, false, 0, n);
  transpose(data, 0, n);
  rows(data, false, 0, n);
}

void Fft2d::inverse(std::vector<std::complex<float>>& data) {
  inverse_rows(data, 0, n_);
}

void Fft2d::inverse_rows(std::vector<std::complex<float>>& data, int row0, int count) {
  if (row0 < 0 || count < 0 || row0 + count > n_) {
    throw std::invalid_argument("Fft2d::inverse_rows: rows outside the transform");
  }
  const auto n = static_cast<std::size_t>(n_);
  const auto r0 = static_cast<std::size_t>(row0);
  const auto r1 = r0 + static_cast<std::size_t>(count);
  rows(data, true, 0, n);
  transpose(data, r0, r1);
  rows(data, true, r0, r1);
  const float scale = 1.0f / (static_cast<float>(n_) * static_cast<float>(n_));
  for (std::size_t m = r0 * n; m < r1 * n; ++m)
    data[m] *= scale;
}

}  // namespace sonarloop::seabed
