#include "common/rng.h"

#include <cmath>
#include <numbers>

namespace sonarloop {

double normal_from_hash(std::uint64_t bits) {
  // two 32-bit uniforms: u1 in (0, 1], u2 in [0, 1)
  const double u1 = (static_cast<double>(bits >> 32) + 1.0) * 0x1.0p-32;
  const double u2 = static_cast<double>(bits & 0xFFFFFFFFULL) * 0x1.0p-32;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::uint64_t Rng::below(std::uint64_t n) {
  if (n <= 0xFFFFFFFFULL) return ((next_u64() >> 32) * n) >> 32;
  return next_u64() % n;
}

double Rng::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_normal_;
  }
  const double u1 = uniform_pos();
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double phi = 2.0 * std::numbers::pi * u2;
  spare_normal_ = r * std::sin(phi);
  has_spare_ = true;
  return r * std::cos(phi);
}

double Rng::exponential(double mean) {
  return -mean * std::log(uniform_pos());
}

std::uint64_t Rng::poisson(double mean) {
  if (!(mean > 0.0)) return 0;
  if (mean < 30.0) {
    // Knuth: multiply uniforms until the product drops below exp(-mean).
    const double limit = std::exp(-mean);
    std::uint64_t k = 0;
    double p = uniform_pos();
    while (p > limit) {
      ++k;
      p *= uniform_pos();
    }
    return k;
  }
  // Hörmann (1993) PTRS: transformed rejection with squeeze.
  const double slam = std::sqrt(mean);
  const double loglam = std::log(mean);
  const double b = 0.931 + 2.53 * slam;
  const double a = -0.059 + 0.02483 * b;
  const double inv_alpha = 1.1239 + 1.1328 / (b - 3.4);
  const double vr = 0.9277 - 3.6224 / (b - 2.0);
  for (;;) {
    const double u = uniform() - 0.5;
    const double v = uniform();
    const double us = 0.5 - std::fabs(u);
    const double k = std::floor((2.0 * a / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= vr) return static_cast<std::uint64_t>(k);
    if (k < 0.0 || (us < 0.013 && v > us)) continue;
    if (std::log(v) + std::log(inv_alpha) - std::log(a / (us * us) + b) <=
        -mean + k * loglam - std::lgamma(k + 1.0)) {
      return static_cast<std::uint64_t>(k);
    }
  }
}

double Rng::gamma(double shape) {
  if (shape < 1.0) {
    // boost to shape + 1, then scale by U^(1/shape) (Marsaglia & Tsang, section 5)
    const double g = gamma(shape + 1.0);
    return g * std::pow(uniform_pos(), 1.0 / shape);
  }
  const double d = shape - 1.0 / 3.0;
  const double c = 1.0 / std::sqrt(9.0 * d);
  for (;;) {
    double x = 0.0;
    double v = 0.0;
    do {
      x = normal();
      v = 1.0 + c * x;
    } while (v <= 0.0);
    v = v * v * v;
    const double u = uniform_pos();
    if (u < 1.0 - 0.0331 * x * x * x * x) return d * v;
    if (std::log(u) < 0.5 * x * x + d * (1.0 - v + std::log(v))) return d * v;
  }
}

}  // namespace sonarloop
