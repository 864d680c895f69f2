#pragma once
// Plane geometry of the autonomy agent: points in the mission's local frame (north_m, east_m:
// the scenario's frame, that of the contacts' north_m / east_m, atr/contact.h) and headings in
// radians clockwise from north (sim/frames.h's yaw, without depending on sim).
#include <cmath>
#include <numbers>

#include "units/angles.h"

namespace sonarloop::autonomy {

struct Point2 {
  double north_m = 0.0;
  double east_m = 0.0;
  friend bool operator==(const Point2&, const Point2&) = default;
};

inline Point2 operator+(Point2 a, Point2 b) {
  return {a.north_m + b.north_m, a.east_m + b.east_m};
}
inline Point2 operator-(Point2 a, Point2 b) {
  return {a.north_m - b.north_m, a.east_m - b.east_m};
}
inline Point2 operator*(double s, Point2 a) {
  return {s * a.north_m, s * a.east_m};
}

inline double norm(Point2 a) {
  return std::hypot(a.north_m, a.east_m);
}
inline double distance_m(Point2 a, Point2 b) {
  return norm(b - a);
}

// The unit vector of a heading (clockwise from north).
inline Point2 direction(double heading_rad) {
  return {std::cos(heading_rad), std::sin(heading_rad)};
}

// The heading from a to b (clockwise from north), in (-pi, pi].
inline double bearing_rad(Point2 a, Point2 b) {
  return std::atan2(b.east_m - a.east_m, b.north_m - a.north_m);
}

// The unsigned angle between two headings, 0..pi.
inline double heading_difference_rad(double a_rad, double b_rad) {
  return std::fabs(wrap_to_pi(a_rad - b_rad));
}

inline double degrees(double rad) {
  return rad * kDegPerRad;
}
inline double radians(double deg) {
  return deg * kRadPerDeg;
}

}  // namespace sonarloop::autonomy
