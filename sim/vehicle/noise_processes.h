#pragma once
// Noise processes that are pure functions of (seed, channel, time): the same arguments give the
// same value on any thread, in any order, with no state and no cache (docs/design.md, randomness).
// Every normal value is normal_from_hash(hash_keys(seed, RngStream::kNavNoise, key, i, j)) with
// keys that never repeat between channels, kinds or time indices (common/rng.h).
//
// White noise: N(0, 1) held constant within each time step [k·step, (k+1)·step), independent
// between steps (k = floor(t / step), negative t included).
//
// Wiener process (standard Brownian motion, unit diffusion): W(t) = 0 for t <= 0; exact in law
// at the knots t_k = k·step (W(t_k) ~ N(0, t_k) in seconds, independent increments), linear
// between knots (where the variance is t_k + f²·step instead of t_k + f·step, f the fraction of
// the step: at most step/4 low). Construction by Brownian-bridge midpoint refinement (Lévy's
// construction; P. Glasserman, "Monte Carlo Methods in Financial Engineering", Springer 2004,
// Sec. 3.1, Brownian bridge construction): knots are grouped in blocks of 2^16; the value at
// block ends is a sum of independent N(0, 2^16·step) block increments; inside a block the value
// at the midpoint of [a, b] given W(a), W(b) is (W(a) + W(b))/2 + sqrt((b - a)/4)·N(0, 1), each
// midpoint with its own hash key, refined until the knot is reached (at most 16 steps). Every
// knot value is therefore a fixed function of the hashed normals, whatever is asked first: cost
// O(16 + t / (2^16·step)) hashes per value, no storage.
#include <cstdint>

#include "sim/core/sim_time.h"

namespace sonarloop::vehicle {

// Channel ids of the navigation errors (part of the hash key). Never reuse or renumber
// (docs/style.md habit 27): recorded datasets depend on them.
enum class NavChannel : std::uint64_t {
  kNorth = 1,
  kEast = 2,
  kHeading = 3,
  kPitch = 4,
  kRoll = 5,
  kVelocityNorth = 6,
  kVelocityEast = 7,
  kDepth = 8,
  kAltitude = 9,
  kYawRate = 10,
};

// N(0, 1) white noise of a channel at time t, held over steps of step_ns (> 0).
double hashed_white_noise(std::uint64_t seed, NavChannel channel, SimTime t, SimTime step_ns);

// Standard Wiener process W(t) of a channel (variance t in seconds at the knots), knots every
// step_ns (> 0), W = 0 for t <= 0.
double hashed_wiener(std::uint64_t seed, NavChannel channel, SimTime t, SimTime step_ns);

}  // namespace sonarloop::vehicle
