#pragma once
// A stationary Gaussian random field with a given power spectrum, defined on an infinite
// lattice and generated lazily in tiles (docs/physics.md §5 spectral synthesis, made tileable).
//
// Method: the field is white noise on the lattice convolved with a finite kernel
// k = IFFT(sqrt(F)) (cropped to K×K cells and tapered). Each lattice site's white value is a
// hash of (seed, stream, sub-key, i, j), so the field at any site is a pure function of the
// seed and its position: tiles are seamless by construction and identical whatever order they
// are made in. Each tile of K×K sites is one overlap-save FFT convolution of size 2K.
// The kernel's finite size is the field's largest correlated scale; the layer's factory picks
// K from the spectrum's outer scale (see seabed_model.cpp).
//
// Values between lattice sites come from Catmull–Rom interpolation (C1: slopes and normals are
// continuous), so a layer synthesised at its own native spacing can be sampled on any grid:
// changing the heightmap spacing resamples the same surface instead of drawing a new one.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/rng.h"
#include "sim/seabed/spectra.h"
#include "sim/seabed/tile_cache.h"

namespace sonarloop::seabed {

struct NoiseLayerSpec {
  std::uint64_t seed = 0;
  RngStream stream = RngStream::kElevation;
  std::uint64_t sub_key = 0;  // distinguishes layers of one stream (region index, warp axis)
  double spacing_m = 1.0;     // native lattice spacing
  int kernel_size = 256;      // K: power of two, 16 .. 1024; also the tile size
  double rms = 1.0;           // rms of the output field
  Spectrum spectrum;          // PSD shape; F(0, 0) should be 0
  // Names the spectrum and all its parameters (e.g. "pink beta=2.8 outer=40 inner=5"). When
  // set, the kernel (which depends only on the spectrum, spacing and kernel size) is shared
  // through a process-wide cache, so scenes built repeatedly (datasets, benches) synthesise it
  // once. Leave empty for a spectrum that cannot be named.
  std::string kernel_key;
};

inline constexpr std::size_t kDefaultNoiseCacheBytes = 64u << 20;
inline constexpr std::size_t kMinNoiseCachePairs = 4;

class NoiseLayer {
 public:
  using Tile = std::vector<float>;  // (K x K), row-major, row = lattice i (north)

  // Its tiles are cached up to cache_bytes (at least kMinNoiseCachePairs pairs of tiles).
  explicit NoiseLayer(NoiseLayerSpec spec, std::size_t cache_bytes = kDefaultNoiseCacheBytes);

  int tile_size() const { return k_; }
  double spacing_m() const { return spec_.spacing_m; }
  double rms() const { return spec_.rms; }
  // Its tile cache's counters (tile_cache.h; a tile pair is one entry) and one entry's bytes.
  TileCacheCounters cache_counters() const { return cache_.counters(); }
  std::size_t cache_entry_bytes() const { return pair_bytes(k_); }
  // The bytes of one cache entry (two K x K float tiles) for kernel size K.
  static std::size_t pair_bytes(int k) {
    return 2 * sizeof(float) * static_cast<std::size_t>(k) * k;
  }

  // The tile whose sites are i in [ti*K, ti*K + K), j in [tj*K, tj*K + K).
  std::shared_ptr<const Tile> tile(std::int64_t ti, std::int64_t tj) const;
  // The value at lattice site (i, j): position (i * spacing, j * spacing).
  float site(std::int64_t i, std::int64_t j) const;

  // Samples the field at the nx × ny points (x0 + r·d, y0 + c·d), r < nx, c < ny, by
  // Catmull–Rom interpolation, writing out[r * stride + c] (+= weight·value if accumulate).
  void sample_grid(double x0, double y0, double d, int nx, int ny, float* out, std::size_t stride,
                   bool accumulate = false, float weight = 1.0f) const;
  // One point (slow path: use sample_grid for many).
  double sample(double x, double y) const;

  // The kernel (K×K, centred at [K/2][K/2]), normalised to unit sum of squares; for tests.
  const std::vector<float>& kernel() const { return kernel_->taps; }

 private:
  // Tiles are made in pairs along j: one complex FFT convolves two real noise windows at once
  // (the real part carries tile (ti, 2m), the imaginary part tile (ti, 2m + 1)), because the
  // kernel is real. Each tile is still a pure function of its own lattice sites.
  struct TilePair {
    Tile even;
    Tile odd;
  };
  std::shared_ptr<const TilePair> make_pair(std::int64_t ti, std::int64_t pair_j) const;
  // copies sites [i0, i0+ni) × [j0, j0+nj) into dst (row-major, ni × nj)
  void gather(std::int64_t i0, std::int64_t j0, int ni, int nj, float* dst) const;

  NoiseLayerSpec spec_;
  int k_;
  int p_;
  struct Kernel {
    std::vector<float> taps;         // K×K
    std::vector<float> spectrum_re;  // its P×P spectrum (Fft2d::forward), real part
    std::vector<float> spectrum_im;  // and imaginary part
  };
  static std::shared_ptr<const Kernel> make_kernel(const NoiseLayerSpec& spec);

  std::shared_ptr<const Kernel> kernel_;
  mutable TileCache<TilePair> cache_;
};

// Unit-variance white noise value for one lattice site (Irwin–Hall sum of four 16-bit
// uniforms: cheap, and the convolution makes the output Gaussian by the central limit theorem).
float lattice_white(std::uint64_t row_key, std::int64_t j);
std::uint64_t lattice_row_key(const NoiseLayerSpec& spec, std::int64_t i);

// Catmull–Rom weights for fractional offset t in [0, 1): taps at -1, 0, 1, 2.
void catmull_rom_weights(double t, double w[4]);
void catmull_rom_weights(double t, float w[4]);  // the same, rounded to float

}  // namespace sonarloop::seabed
