#pragma once
// A simple kinematic AUV model for the autonomy agent (ours): constant speed through the water, a
// bounded turn rate towards the commanded heading, and depth changed at a bounded vertical rate
// towards the commanded depth (altitude keeping is a depth command, depth_for_altitude()). No
// current, no sideslip: the vehicle moves along its heading. Pitch follows the climb angle, roll
// is zero (the sonar is level in turns too, a simplification).
//
// Deterministic: step() is a pure function of (state, command, dt); the same inputs give the same
// track on any machine. Explicit Euler on the heading, exact on the straight parts.
#include "autonomy/geometry.h"

namespace sonarloop::autonomy {

struct VehicleParams {
  double speed_m_s = 2.0;              // through the water, > 0
  double max_turn_rate_rad_s = 0.105;  // |d heading / dt|, > 0 (6 deg/s: 19 m turn radius)
  double max_vertical_rate_m_s = 0.5;  // |d depth / dt|, > 0
  // Throws std::invalid_argument naming the field that is not > 0 and finite.
  void validate() const;
  // The radius of a turn at the full turn rate.
  double turn_radius_m() const { return speed_m_s / max_turn_rate_rad_s; }
};

struct VehicleState {
  double t_s = 0.0;  // the agent's mission time
  Point2 position;
  double depth_m = 0.0;      // below the surface, + down
  double heading_rad = 0.0;  // clockwise from north, (-pi, pi]
  double pitch_rad = 0.0;    // + nose up
  double turn_rate_rad_s = 0.0;
};

struct VehicleCommand {
  double heading_rad = 0.0;
  double depth_m = 0.0;
};

// step_vehicle: the state dt_s later (dt_s >= 0) under the command: heading turned towards the
// command by at most max_turn_rate x dt (the shorter way), depth moved towards the command by at
// most max_vertical_rate x dt, position advanced along the mean heading of the step.
VehicleState step_vehicle(const VehicleState& s, const VehicleCommand& c, const VehicleParams& p,
                          double dt_s);

// Altitude keeping: the depth that puts the vehicle `target_altitude_m` above the seabed, from its
// depth and measured altitude now (the seabed's depth is depth + altitude).
inline double depth_for_altitude(double depth_m, double altitude_m, double target_altitude_m) {
  return depth_m + altitude_m - target_altitude_m;
}

}  // namespace sonarloop::autonomy
