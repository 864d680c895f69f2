#pragma once
// Angle wrapping for the vehicle model (radians; headings clockwise from north, frames.h).
#include <cmath>
#include <numbers>

namespace sonarloop::vehicle {

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

}  // namespace sonarloop::vehicle
