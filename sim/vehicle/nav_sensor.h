#pragma once
// The navigation sensor model: what the vehicle's navigation system (INS + DVL + pressure sensor
// + altimeter) publishes, given the truth. Errors are seeded, and each is a pure function of
// (seed, time): measuring the same state twice gives the same solution, whatever was measured
// before or on which thread (noise_processes.h gives the methods).
//
// Error model (NavNoiseDesc; δ = measured - true; N_c(t) white noise of channel c, W_c(t) a
// standard Wiener process of channel c, both from noise_processes.h):
//   north, east:   δ = σ_pos·N(t) + q_pos·W(t)              per axis, independent
//   heading:       δψ = b_ψ + σ_ψ·N(t) + q_ψ·W(t)            published wrapped to [0, 2π)
//   pitch, roll:   δ = σ_att·N(t)                            each
//   velocity:      v_m = (1 + k_sf)·R(δψ)·v_true + σ_v·(N_N(t), N_E(t))   horizontal; a DVL
//                  measures in the body frame and the INS rotates it with its own heading, so
//                  the course error follows the heading error. SOG = |v_m|, COG = atan2(v_E, v_N)
//   yaw rate:      δ = σ_r·N(t)
//   depth:         δ = σ_z·N(t);  altitude: δ = σ_h·N(t) (NaN stays NaN)
// With every σ, q, b and k_sf zero the solution equals the truth exactly.
#include <cstdint>

#include "sim/core/sim_time.h"
#include "sim/vehicle/noise_processes.h"
#include "sim/vehicle/vehicle_desc.h"
#include "sim/vehicle/vehicle_state.h"

namespace sonarloop::vehicle {

// The errors of one solution, measured - true (angles wrapped to [-π, π)), for logging.
struct NavErrors {
  double north_m = 0.0;
  double east_m = 0.0;
  double horizontal_m = 0.0;  // hypot(north_m, east_m)
  double depth_m = 0.0;
  double altitude_m = 0.0;  // 0 when the altitude is unknown
  double heading = 0.0;     // rad
  double pitch = 0.0;       // rad
  double roll = 0.0;        // rad
  double speed_m_s = 0.0;   // speed over ground
  double course = 0.0;      // rad, course over ground
  double yaw_rate = 0.0;    // rad/s
};

// A published navigation solution (units SI; angles radians, frames.h conventions).
struct NavSolution {
  SimTime t = 0;
  double north_m = 0.0;  // position in W
  double east_m = 0.0;
  double depth_m = 0.0;
  double heading = 0.0;                // [0, 2π), clockwise from north
  double pitch = 0.0;                  // nose up positive
  double roll = 0.0;                   // starboard down positive
  double speed_over_ground_m_s = 0.0;  // horizontal
  double course_over_ground = 0.0;     // [0, 2π)
  double yaw_rate = 0.0;               // rad/s
  double altitude_m = 0.0;             // above the seabed; NaN when unknown
  NavErrors error;
};

class NavSensorModel {
 public:
  // Throws std::invalid_argument listing every problem of the description (validate()).
  NavSensorModel(const NavNoiseDesc& desc, std::uint64_t seed);

  // The published solution for the true state (at truth.t).
  NavSolution measure(const VehicleState& truth) const;

  // The slowly varying heading error b_ψ + q_ψ·W(t) alone (no white noise), rad; and the
  // horizontal position drift q_pos·W(t) of each axis, m.
  double heading_drift(SimTime t) const;
  Vec2 position_drift(SimTime t) const;

  const NavNoiseDesc& desc() const { return desc_; }
  std::uint64_t seed() const { return seed_; }

 private:
  double white(NavChannel channel, SimTime t) const;
  double wiener(NavChannel channel, SimTime t) const;

  NavNoiseDesc desc_;
  std::uint64_t seed_;
  SimTime noise_step_ns_;
  SimTime drift_step_ns_;
};

}  // namespace sonarloop::vehicle
