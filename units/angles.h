#pragma once
// Angles, once for the whole project: degrees <-> radians and wrapping. A header of its own,
// below every layer (scripts/check_layers.sh: any folder may include units/), since the
// simulator, the drivers, the onboard side and the agent all convert and wrap angles.
#include <cmath>
#include <numbers>

namespace sonarloop {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

// a wrapped to [-π, π).
inline double wrap_to_pi(double a) {
  double w = std::fmod(a + std::numbers::pi, kTwoPi);
  if (w < 0.0) w += kTwoPi;
  w -= std::numbers::pi;
  // fmod can return exactly 2π - ulp + ... rounding to π: keep the half-open interval
  return w >= std::numbers::pi ? w - kTwoPi : w;
}

// a wrapped to [0, 2π) (a heading as NMEA 2000 publishes it).
inline double wrap_to_two_pi(double a) {
  double w = std::fmod(a, kTwoPi);
  if (w < 0.0) w += kTwoPi;
  return w >= kTwoPi ? 0.0 : w;
}

// a in degrees wrapped to [0, 360).
inline double wrap_to_360_deg(double a) {
  a = std::fmod(a, 360.0);
  if (a < 0.0) a += 360.0;
  return a >= 360.0 ? 0.0 : a;
}

}  // namespace sonarloop
