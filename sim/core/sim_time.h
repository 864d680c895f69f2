#pragma once
// Simulation time: an explicit argument everywhere in sim/ (docs/design.md, "Rules of the house").
// Only the emulator's pacer reads a wall clock; everything else receives a SimTime.
#include <cstdint>

namespace sonarloop {

// Nanoseconds since the scenario epoch (int64: ±292 years).
using SimTime = std::int64_t;

inline constexpr SimTime kNanosecondsPerSecond = 1'000'000'000;

constexpr double to_seconds(SimTime t_ns) {
  return static_cast<double>(t_ns) * 1e-9;
}
constexpr SimTime from_seconds(double t_s) {
  return static_cast<SimTime>(t_s * 1e9 + (t_s >= 0 ? 0.5 : -0.5));
}

}  // namespace sonarloop
