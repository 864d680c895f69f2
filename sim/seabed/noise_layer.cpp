#include "sim/seabed/noise_layer.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include "sim/core/integer_division.h"
#include "sim/seabed/fft2d.h"

namespace sonarloop::seabed {
namespace {

// One FFT (twiddles and work buffers) per size and thread.
Fft2d& thread_fft(int n) {
  thread_local std::unordered_map<int, std::unique_ptr<Fft2d>> plans;
  auto& p = plans[n];
  if (!p) p = std::make_unique<Fft2d>(n);
  return *p;
}

// The real and imaginary planes of one P x P transform, per thread.
struct Planes {
  std::vector<float> re;
  std::vector<float> im;
};
Planes& thread_planes(std::size_t n) {
  thread_local Planes planes;
  planes.re.resize(n);
  planes.im.resize(n);
  return planes;
}

// (re, im) *= (kre, kim), element by element, over n complex values
void multiply_spectra(float* re, float* im, const float* kre, const float* kim, std::size_t n) {
  for (std::size_t m = 0; m < n; ++m) {
    const float r = re[m] * kre[m] - im[m] * kim[m];
    const float i = re[m] * kim[m] + im[m] * kre[m];
    re[m] = r;
    im[m] = i;
  }
}

std::size_t wrap(std::int64_t a, int n) {
  const std::int64_t m = a % n;
  return static_cast<std::size_t>(m < 0 ? m + n : m);
}

// Tukey window with half its length tapered: 1 for |a| <= K/4, cosine roll-off to 0 at K/2.
double tukey(int a, int k) {
  const double x = std::fabs(static_cast<double>(a)) / (0.5 * k);  // 0 .. 1
  if (x <= 0.5) return 1.0;
  return 0.5 * (1.0 + std::cos(std::numbers::pi * (x - 0.5) / 0.5));
}

// sample_grid's work buffers, kept per thread: a heightmap tile's are a few hundred kB, and made
// per call they were fresh pages for the kernel to zero at every tile (with the partition's and
// make_tile's, kept the same way: 8 % of the CPU time of a survey run, docs/rendering.md).
// sample_grid is never re-entered on a thread while it uses them: gather() makes noise tiles,
// which sample no grid.
struct GridScratch {
  std::vector<float> block, col_w, tmp;
  std::vector<int> col_index;
};
GridScratch& grid_scratch() {
  thread_local GridScratch g;
  return g;
}

}  // namespace

std::uint64_t lattice_row_key(const NoiseLayerSpec& spec, std::int64_t i) {
  return hash_keys(spec.seed, spec.stream, spec.sub_key, static_cast<std::uint64_t>(i));
}

float lattice_white(std::uint64_t row_key, std::int64_t j) {
  const std::uint64_t h = mix64(row_key + static_cast<std::uint64_t>(j) * kGoldenGamma);
  const auto u = [h](int k) { return static_cast<float>((h >> (16 * k)) & 0xFFFF) + 0.5f; };
  // sum of four U(0,1): mean 2, variance 1/3
  constexpr float kScale = 1.7320508f / 65536.0f;  // sqrt(3) / 2^16
  return (u(0) + u(1) + u(2) + u(3) - 2.0f * 65536.0f) * kScale;
}

void catmull_rom_weights(double t, double w[4]) {
  const double t2 = t * t;
  const double t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
}

void catmull_rom_weights(double t, float w[4]) {
  double d[4];
  catmull_rom_weights(t, d);
  for (int k = 0; k < 4; ++k)
    w[k] = static_cast<float>(d[k]);
}

NoiseLayer::NoiseLayer(NoiseLayerSpec spec, std::size_t cache_bytes)
    : spec_(std::move(spec)),
      k_(spec_.kernel_size),
      p_(2 * spec_.kernel_size),
      cache_(std::max(kMinNoiseCachePairs, cache_bytes / pair_bytes(std::max(k_, 1)))) {
  if (k_ < 16 || k_ > 1024 || (k_ & (k_ - 1)) != 0) {
    throw std::invalid_argument("NoiseLayer: kernel_size must be a power of 2 in [16, 1024]");
  }
  if (!(spec_.spacing_m > 0.0)) throw std::invalid_argument("NoiseLayer: spacing must be > 0");
  if (spec_.kernel_key.empty()) {
    kernel_ = make_kernel(spec_);
    return;
  }
  // process-wide cache of kernels by (key, spacing, size); kernels are immutable
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const Kernel>> cache;
  char buf[96];
  std::snprintf(buf, sizeof buf, " |spacing=%.17g K=%d", spec_.spacing_m, k_);
  const std::string key = spec_.kernel_key + buf;
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) {
      kernel_ = it->second;
      return;
    }
  }
  auto k = make_kernel(spec_);
  std::lock_guard<std::mutex> lock(mutex);
  kernel_ = cache.emplace(key, std::move(k)).first->second;
}

std::shared_ptr<const NoiseLayer::Kernel> NoiseLayer::make_kernel(const NoiseLayerSpec& spec) {
  const int k = spec.kernel_size;
  const int p = 2 * k;
  // sqrt(F) on a 2K x 2K frequency grid, then its inverse FFT is the (periodic) kernel
  const int m = 2 * k;
  const auto mm = static_cast<std::size_t>(m);
  const double df = 1.0 / (m * spec.spacing_m);
  std::vector<std::complex<float>> grid(mm * mm);
  for (int kx = 0; kx < m; ++kx) {
    const double fx = (kx < m / 2 ? kx : kx - m) * df;
    for (int ky = 0; ky < m; ++ky) {
      const double fy = (ky < m / 2 ? ky : ky - m) * df;
      const double f = spec.spectrum(fx, fy);
      grid[static_cast<std::size_t>(kx) * mm + static_cast<std::size_t>(ky)] =
          static_cast<float>(std::sqrt(std::max(f, 0.0)));
    }
  }
  Fft2d(m).inverse(grid);
  // crop the central K x K, taper, normalise to unit sum of squares (unit output variance)
  auto kernel = std::make_shared<Kernel>();
  auto& taps = kernel->taps;
  const auto kk = static_cast<std::size_t>(k);
  taps.assign(kk * kk, 0.0f);
  double sum2 = 0.0;
  for (int a = -k / 2; a < k / 2; ++a) {
    for (int b = -k / 2; b < k / 2; ++b) {
      const double v = grid[wrap(a, m) * mm + wrap(b, m)].real() * tukey(a, k) * tukey(b, k);
      taps[static_cast<std::size_t>(a + k / 2) * kk + static_cast<std::size_t>(b + k / 2)] =
          static_cast<float>(v);
      sum2 += v * v;
    }
  }
  if (!(sum2 > 0.0)) throw std::invalid_argument("NoiseLayer: spectrum is zero everywhere");
  const auto norm = static_cast<float>(1.0 / std::sqrt(sum2));
  for (auto& v : taps)
    v *= norm;
  // the kernel's spectrum on the P x P convolution grid
  const auto pp = static_cast<std::size_t>(p);
  auto& re = kernel->spectrum_re;
  auto& im = kernel->spectrum_im;
  re.assign(pp * pp, 0.0f);
  im.assign(pp * pp, 0.0f);
  for (int a = -k / 2; a < k / 2; ++a) {
    for (int b = -k / 2; b < k / 2; ++b) {
      re[wrap(a, p) * pp + wrap(b, p)] =
          taps[static_cast<std::size_t>(a + k / 2) * kk + static_cast<std::size_t>(b + k / 2)];
    }
  }
  Fft2d(p).forward(re.data(), im.data());
  return kernel;
}

std::shared_ptr<const NoiseLayer::Tile> NoiseLayer::tile(std::int64_t ti, std::int64_t tj) const {
  const std::int64_t pair_j = floor_div(tj, 2);
  auto pair = cache_.get({ti, pair_j}, [&] { return make_pair(ti, pair_j); });
  // aliasing shared_ptr: the tile lives as long as its pair
  const Tile* t = (tj - 2 * pair_j) == 0 ? &pair->even : &pair->odd;
  return std::shared_ptr<const Tile>(pair, t);
}

std::shared_ptr<const NoiseLayer::TilePair> NoiseLayer::make_pair(std::int64_t ti,
                                                                  std::int64_t pair_j) const {
  // overlap-save: the white noise of a tile plus a K/2 apron on each side fills the P x P grid
  // exactly (P = 2K); the circular convolution is exact on the tile's K x K sites
  const int k = k_;
  const int p = p_;
  const auto pp = static_cast<std::size_t>(p);
  auto& [re, im] = thread_planes(pp * pp);
  const std::int64_t i_base = ti * k - k / 2;
  const std::int64_t j_even = 2 * pair_j * k - k / 2;
  const std::int64_t j_odd = j_even + k;
  for (int q = 0; q < p; ++q) {
    const std::uint64_t row_key = lattice_row_key(spec_, i_base + q);
    float* row_re = re.data() + static_cast<std::size_t>(q) * pp;
    float* row_im = im.data() + static_cast<std::size_t>(q) * pp;
    for (int r = 0; r < p; ++r) {
      row_re[r] = lattice_white(row_key, j_even + r);
      row_im[r] = lattice_white(row_key, j_odd + r);
    }
  }
  Fft2d& fft = thread_fft(p);
  fft.forward(re.data(), im.data());
  multiply_spectra(re.data(), im.data(), kernel_->spectrum_re.data(), kernel_->spectrum_im.data(),
                   re.size());
  fft.inverse_rows(re.data(), im.data(), k / 2, k);  // the valid rows: the tile's K rows
  auto out = std::make_shared<TilePair>();
  const auto kk = static_cast<std::size_t>(k);
  out->even.resize(kk * kk);
  out->odd.resize(kk * kk);
  const auto rms = static_cast<float>(spec_.rms);
  for (int t = 0; t < k; ++t) {
    const std::size_t from = static_cast<std::size_t>(t + k / 2) * pp + kk / 2;
    float* even = out->even.data() + static_cast<std::size_t>(t) * kk;
    float* odd = out->odd.data() + static_cast<std::size_t>(t) * kk;
    for (std::size_t u = 0; u < kk; ++u) {
      even[u] = rms * re[from + u];
      odd[u] = rms * im[from + u];
    }
  }
  return out;
}

float NoiseLayer::site(std::int64_t i, std::int64_t j) const {
  const std::int64_t ti = floor_div(i, k_);
  const std::int64_t tj = floor_div(j, k_);
  const auto t = tile(ti, tj);
  return (*t)[static_cast<std::size_t>(i - ti * k_) * static_cast<std::size_t>(k_) +
              static_cast<std::size_t>(j - tj * k_)];
}

void NoiseLayer::gather(std::int64_t i0, std::int64_t j0, int ni, int nj, float* dst) const {
  const std::int64_t ti0 = floor_div(i0, k_);
  const std::int64_t ti1 = floor_div(i0 + ni - 1, k_);
  const std::int64_t tj0 = floor_div(j0, k_);
  const std::int64_t tj1 = floor_div(j0 + nj - 1, k_);
  const auto kk = static_cast<std::size_t>(k_);
  for (std::int64_t ti = ti0; ti <= ti1; ++ti) {
    for (std::int64_t tj = tj0; tj <= tj1; ++tj) {
      const auto t = tile(ti, tj);
      const std::int64_t ia = std::max(i0, ti * k_);
      const std::int64_t ib = std::min(i0 + ni, ti * k_ + k_);
      const std::int64_t ja = std::max(j0, tj * k_);
      const std::int64_t jb = std::min(j0 + nj, tj * k_ + k_);
      for (std::int64_t i = ia; i < ib; ++i) {
        const float* src = t->data() + static_cast<std::size_t>(i - ti * k_) * kk +
                           static_cast<std::size_t>(ja - tj * k_);
        float* d = dst + static_cast<std::size_t>(i - i0) * static_cast<std::size_t>(nj) +
                   static_cast<std::size_t>(ja - j0);
        std::copy(src, src + (jb - ja), d);
      }
    }
  }
}

void NoiseLayer::sample_grid(double x0, double y0, double d, int nx, int ny, float* out,
                             std::size_t stride, bool accumulate, float weight) const {
  if (nx <= 0 || ny <= 0) return;
  const double s = spec_.spacing_m;
  const auto lattice_floor = [](double u) { return static_cast<std::int64_t>(std::floor(u)); };
  const std::int64_t ia = lattice_floor(x0 / s) - 1;
  const std::int64_t ib = lattice_floor((x0 + (nx - 1) * d) / s) + 2;
  const std::int64_t ja = lattice_floor(y0 / s) - 1;
  const std::int64_t jb = lattice_floor((y0 + (ny - 1) * d) / s) + 2;
  const int ni = static_cast<int>(ib - ia + 1);
  const int nj = static_cast<int>(jb - ja + 1);
  GridScratch& g = grid_scratch();
  std::vector<float>& block = g.block;  // every value written below
  block.resize(static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj));
  gather(ia, ja, ni, nj, block.data());
  // interpolate along j (east) for every lattice row, then along i (north)
  std::vector<int>& col_index = g.col_index;
  col_index.resize(static_cast<std::size_t>(ny));
  std::vector<float>& col_w = g.col_w;
  col_w.resize(static_cast<std::size_t>(ny) * 4);
  for (int c = 0; c < ny; ++c) {
    const double v = (y0 + c * d) / s;
    const std::int64_t jj = lattice_floor(v);
    col_index[static_cast<std::size_t>(c)] = static_cast<int>(jj - 1 - ja);
    catmull_rom_weights(v - static_cast<double>(jj), &col_w[static_cast<std::size_t>(c) * 4]);
  }
  std::vector<float>& tmp = g.tmp;
  tmp.resize(static_cast<std::size_t>(ni) * static_cast<std::size_t>(ny));
  for (int a = 0; a < ni; ++a) {
    const float* row = block.data() + static_cast<std::size_t>(a) * static_cast<std::size_t>(nj);
    float* t = tmp.data() + static_cast<std::size_t>(a) * static_cast<std::size_t>(ny);
    for (int c = 0; c < ny; ++c) {
      const float* w = &col_w[static_cast<std::size_t>(c) * 4];
      const float* r = row + col_index[static_cast<std::size_t>(c)];
      t[c] = w[0] * r[0] + w[1] * r[1] + w[2] * r[2] + w[3] * r[3];
    }
  }
  for (int r = 0; r < nx; ++r) {
    const double u = (x0 + r * d) / s;
    const std::int64_t ii = lattice_floor(u);
    float w[4];
    catmull_rom_weights(u - static_cast<double>(ii), w);
    const auto a0 = static_cast<std::size_t>(ii - 1 - ia);
    const auto nyy = static_cast<std::size_t>(ny);
    const float* t0 = tmp.data() + a0 * nyy;
    float* o = out + static_cast<std::size_t>(r) * stride;
    for (int c = 0; c < ny; ++c) {
      const float v =
          w[0] * t0[c] + w[1] * t0[c + ny] + w[2] * t0[c + 2 * ny] + w[3] * t0[c + 3 * ny];
      o[c] = accumulate ? o[c] + weight * v : weight * v;
    }
  }
}

double NoiseLayer::sample(double x, double y) const {
  float v = 0.0f;
  sample_grid(x, y, 1.0, 1, 1, &v, 1);
  return v;
}

}  // namespace sonarloop::seabed
