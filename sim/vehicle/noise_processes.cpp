#include "sim/vehicle/noise_processes.h"

#include <cmath>

#include "common/rng.h"

namespace sonarloop::vehicle {

namespace {

// kinds of hashed value within a channel (part of the key; never renumber)
enum Kind : std::uint64_t {
  kWhite = 1,      // keys (k, 0): step index k
  kBlockStep = 2,  // keys (m, 0): increment over block m
  kMidpoint = 3,   // keys (m, i): midpoint knot i (within block m)
};

constexpr int kBlockLevels = 16;
constexpr std::int64_t kBlockKnots = std::int64_t{1} << kBlockLevels;

std::uint64_t key(NavChannel channel, Kind kind) {
  return static_cast<std::uint64_t>(channel) * 16 + kind;
}

double normal(std::uint64_t seed, NavChannel channel, Kind kind, std::uint64_t i, std::uint64_t j) {
  return normal_from_hash(hash_keys(seed, RngStream::kNavNoise, key(channel, kind), i, j));
}

// W at knot k >= 0 in units of sqrt(step): a sum of k independent N(0, 1) in law.
double wiener_at_knot(std::uint64_t seed, NavChannel channel, std::int64_t k) {
  const std::int64_t block = k / kBlockKnots;
  std::int64_t offset = k % kBlockKnots;
  // value at the start of the block: the sum of the whole-block increments before it
  const double block_sd = std::sqrt(static_cast<double>(kBlockKnots));
  double lo_value = 0.0;
  for (std::int64_t m = 0; m < block; ++m) {
    lo_value += block_sd * normal(seed, channel, kBlockStep, static_cast<std::uint64_t>(m), 0);
  }
  if (offset == 0) return lo_value;
  double hi_value =
      lo_value + block_sd * normal(seed, channel, kBlockStep, static_cast<std::uint64_t>(block), 0);
  // bisect [lo, hi] (knot offsets within the block) down to the knot
  std::int64_t lo = 0;
  std::int64_t hi = kBlockKnots;
  for (;;) {
    const std::int64_t mid = (lo + hi) / 2;
    const double sd = std::sqrt(static_cast<double>(hi - lo) / 4.0);
    const double mid_value =
        0.5 * (lo_value + hi_value) + sd * normal(seed, channel, kMidpoint,
                                                  static_cast<std::uint64_t>(block),
                                                  static_cast<std::uint64_t>(mid));
    if (offset == mid) return mid_value;
    if (offset < mid) {
      hi = mid;
      hi_value = mid_value;
    } else {
      lo = mid;
      lo_value = mid_value;
    }
  }
}

}  // namespace

double hashed_white_noise(std::uint64_t seed, NavChannel channel, SimTime t, SimTime step_ns) {
  // floor division (t may be negative)
  std::int64_t k = t / step_ns;
  if (t % step_ns != 0 && t < 0) --k;
  return normal(seed, channel, kWhite, static_cast<std::uint64_t>(k), 0);
}

double hashed_wiener(std::uint64_t seed, NavChannel channel, SimTime t, SimTime step_ns) {
  if (t <= 0) return 0.0;
  const std::int64_t k = t / step_ns;
  const SimTime rest = t - k * step_ns;
  const double scale = std::sqrt(to_seconds(step_ns));
  const double w0 = wiener_at_knot(seed, channel, k);
  if (rest == 0) return scale * w0;
  const double w1 = wiener_at_knot(seed, channel, k + 1);
  const double f = static_cast<double>(rest) / static_cast<double>(step_ns);
  return scale * (w0 + f * (w1 - w0));
}

}  // namespace sonarloop::vehicle
