#include "sim/seabed/fft2d.h"

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

void Fft2d::rows(std::vector<std::complex<float>>& data, bool inverse) {
  const auto n = static_cast<std::size_t>(n_);
  auto& in = impl_->in;
  auto& out = impl_->out;
  for (std::size_t r = 0; r < n; ++r) {
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

void Fft2d::transpose(std::vector<std::complex<float>>& data) {
  // blocked out-of-place transpose through the scratch buffer
  const auto n = static_cast<std::size_t>(n_);
  constexpr std::size_t kBlock = 32;
  for (std::size_t r0 = 0; r0 < n; r0 += kBlock) {
    for (std::size_t c0 = 0; c0 < n; c0 += kBlock) {
      const std::size_t r1 = std::min(n, r0 + kBlock);
      const std::size_t c1 = std::min(n, c0 + kBlock);
      for (std::size_t r = r0; r < r1; ++r) {
        for (std::size_t c = c0; c < c1; ++c)
          scratch_[c * n + r] = data[r * n + c];
      }
    }
  }
  data.swap(scratch_);
}

void Fft2d::forward(std::vector<std::complex<float>>& data) {
  rows(data, false);
  transpose(data);
  rows(data, false);
}

void Fft2d::inverse(std::vector<std::complex<float>>& data) {
  rows(data, true);
  transpose(data);
  rows(data, true);
  const float scale = 1.0f / (static_cast<float>(n_) * static_cast<float>(n_));
  for (auto& v : data)
    v *= scale;
}

}  // namespace sonarloop::seabed
