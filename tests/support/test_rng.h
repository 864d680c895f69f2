#pragma once
// Seeded random test inputs for the tests of layers that do not link common/ (drivers): the
// standard library's 64-bit Mersenne Twister, whose output sequence the C++ standard fixes
// ([rand.predef]), so that a seed gives the same inputs with every standard library. (No
// std::*_distribution: their output is not fixed.) The simulator's own randomness is
// common/rng.h.
#include <cstdint>
#include <random>

namespace sonarloop::testing {

class TestRng {
 public:
  explicit TestRng(std::uint64_t seed) : engine_(seed) {}
  // An integer in [0, n), n > 0 (the modulo's bias, under 2^-40 for the n used, does not matter
  // to a test input).
  std::uint64_t below(std::uint64_t n) { return engine_() % n; }
  // A real in [lo, hi): the top 53 bits of one draw.
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace sonarloop::testing
