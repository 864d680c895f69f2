#pragma once
// What the trajectory's tests share (trajectory_test.cpp: the path and the depth;
// trajectory_attitude_test.cpp: pitch, roll, waves and sway): times, sampling, a lawnmower, a
// sinusoidal seabed and a terrain-following line.
#include <vector>

#include "sim/vehicle/trajectory.h"
#include "units/angles.h"

namespace sonarloop::vehicle::trajectory_test {

inline SimTime at_s(double t_s) {
  return from_seconds(t_s);
}

// States every dt_s from 0 to the end of the trajectory.
inline std::vector<VehicleState> sample(const Trajectory& tr, double dt_s) {
  std::vector<VehicleState> out;
  const auto n = static_cast<long>(std::floor(tr.duration_s() / dt_s));
  out.reserve(static_cast<std::size_t>(n + 1));
  for (long i = 0; i <= n; ++i)
    out.push_back(tr.state_at(at_s(static_cast<double>(i) * dt_s)));
  return out;
}

inline TrajectoryDesc lawnmower_desc(double spacing_m) {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kLawnmower;
  desc.speed_m_s = 2.0;
  desc.max_turn_rate_rad_s = 0.1;  // R = 20 m
  desc.lawnmower.origin = {0.0, 0.0};
  desc.lawnmower.first_leg_heading = 20.0 * kRadPerDeg;
  desc.lawnmower.leg_length_m = 200.0;
  desc.lawnmower.line_spacing_m = spacing_m;
  desc.lawnmower.legs = 4;
  desc.depth.depth_m = 25.0;
  return desc;
}

// A synthetic sinusoidal seabed along north: depth 30 + a·sin(2π·north / wavelength).
inline SeabedDepthFn sinusoid(double amplitude_m, double wavelength_m) {
  return [=](double north_m, double) {
    return 30.0 + amplitude_m * std::sin(2.0 * std::numbers::pi * north_m / wavelength_m);
  };
}

inline TrajectoryDesc altitude_line(double altitude_m, double look_ahead_m) {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kStraight;
  desc.start = {0.0, 0.0};
  desc.start_heading = 0.0;
  desc.straight_length_m = 1000.0;
  desc.speed_m_s = 2.0;
  desc.depth.mode = DepthMode::kAltitude;
  desc.depth.altitude_m = altitude_m;
  desc.depth.max_climb_rate_m_s = 0.5;
  desc.depth.look_ahead_m = look_ahead_m;
  return desc;
}

}  // namespace sonarloop::vehicle::trajectory_test
