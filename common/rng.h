#pragma once
// Deterministic randomness (docs/design.md, "Rules of the house"; docs/style.md habits 11-12).
//
// Every stream of randomness is derived from (scenario seed, stream id, sub-keys) by hashing, so
// the same scenario and seed give the same numbers on any number of threads, in any order.
// No std::*_distribution is used: their output differs between standard libraries.
//
// Generator: SplitMix64 (G. Steele, D. Lea, C. Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014): state advances by the golden-ratio increment and each output is the
// state passed through a bijective 64-bit finaliser. Implemented here from the paper's
// description; it passes BigCrush, which is ample for terrain, clutter and speckle.
#include <cstdint>

namespace sonarloop {

// Stream ids: one per independent source of randomness. Never reuse or renumber an id
// (docs/style.md habit 27): goldens and recorded datasets depend on them.
enum class RngStream : std::uint64_t {
  kElevation = 1,   // large-scale pink-noise elevation layer
  kPartition = 2,   // sediment partition border warp
  kRipples = 3,     // sand ripple texture
  kRocky = 4,       // rocky (eroded) texture
  kClutter = 5,     // Poisson clutter rocks
  kSpeckle = 6,     // ping speckle
  kNoise = 7,       // ping thermal noise
  kNavNoise = 8,    // navigation sensor errors
  kDataset = 9,     // dataset sample parameters
  kRayJitter = 10,  // renderer ray jitter
  kTraining = 11,   // classifier train/test splits
  kLayout = 12,     // random target layouts of surveys (mission/layout.h)
};

// The SplitMix64 output finaliser: a bijection of 64-bit integers with good avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

inline constexpr std::uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ULL;

// Hash of a seed and up to four keys (order matters). Signed lattice indices may be cast.
constexpr std::uint64_t hash_keys(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0,
                                  std::uint64_t c = 0, std::uint64_t d = 0) {
  std::uint64_t h = mix64(seed + kGoldenGamma);
  h = mix64(h ^ (a + 1 * kGoldenGamma));
  h = mix64(h ^ (b + 2 * kGoldenGamma));
  h = mix64(h ^ (c + 3 * kGoldenGamma));
  h = mix64(h ^ (d + 4 * kGoldenGamma));
  return h;
}

constexpr std::uint64_t hash_keys(std::uint64_t seed, RngStream s, std::uint64_t b = 0,
                                  std::uint64_t c = 0, std::uint64_t d = 0) {
  return hash_keys(seed, static_cast<std::uint64_t>(s), b, c, d);
}

// Top 53 bits of a 64-bit word as a double in [0, 1).
constexpr double unit_double(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

// A standard normal value from one 64-bit hash (two 32-bit uniforms, Box–Muller).
// For lattice noise where each site needs exactly one independent N(0,1) value.
double normal_from_hash(std::uint64_t bits);

// A sequential generator for one stream. Cheap to copy; copies continue independently.
class Rng {
 public:
  explicit Rng(std::uint64_t key) : state_(key) {}
  Rng(std::uint64_t seed, RngStream stream, std::uint64_t b = 0, std::uint64_t c = 0,
      std::uint64_t d = 0)
      : state_(hash_keys(seed, stream, b, c, d)) {}

  std::uint64_t next_u64() {
    state_ += kGoldenGamma;
    return mix64(state_);
  }
  // Uniform in [0, 1).
  double uniform() { return unit_double(next_u64()); }
  // Uniform in (0, 1]: safe for log().
  double uniform_pos() { return 1.0 - uniform(); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; bias below 2^-32 for n < 2^32).
  std::uint64_t below(std::uint64_t n);
  // Standard normal N(0, 1) (Box–Muller, both values used).
  double normal();
  double normal(double mean, double sd) { return mean + sd * normal(); }
  // Exponential with the given mean (inversion).
  double exponential(double mean);
  // Poisson count with the given mean >= 0 (Knuth's product method below 30, Hörmann's PTRS
  // transformed rejection above: W. Hörmann, Insurance: Math. Econ. 12 (1993) 39-45).
  std::uint64_t poisson(double mean);
  // Gamma(shape k > 0, scale 1) (Marsaglia & Tsang, ACM TOMS 26(3) 2000).
  double gamma(double shape);

 private:
  std::uint64_t state_;
  double spare_normal_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace sonarloop
