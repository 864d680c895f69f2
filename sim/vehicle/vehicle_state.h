#pragma once
// The true kinematic state of the vehicle at one instant (trajectory.h computes it; nav_sensor.h
// measures it). Frames and angles as in sim/frames.h.
#include <limits>

#include "sim/core/sim_time.h"
#include "sim/frames.h"

namespace sonarloop::vehicle {

struct VehicleState {
  SimTime t = 0;                   // time of the state, ns
  Pose pose;                       // true pose in W; yaw wrapped to [-π, π)
  Vec3 velocity_W = Vec3::Zero();  // true velocity over ground in W (north, east, down), m/s
  double yaw_rate = 0.0;           // dψ/dt, rad/s; > 0 turning to starboard
  double speed_m_s = 0.0;          // horizontal speed over ground |(v_N, v_E)|, m/s
  // Height of the vehicle origin above the seabed directly below, m; NaN when unknown (no seabed
  // given, or outside the planned path).
  double altitude_m = std::numeric_limits<double>::quiet_NaN();
  double path_s_m = 0.0;  // arc length along the planned path (speed·t), m
  int leg = -1;           // lawnmower survey leg being flown (0-based), -1 otherwise
};

}  // namespace sonarloop::vehicle
