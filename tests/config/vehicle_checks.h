#pragma once
// Shared by the vehicle loader's tests (vehicle_loader_test.cpp, vehicle_loader_random_test.cpp):
// the field-by-field comparison of two vehicles and a flat seabed to plan over.
#include <catch2/catch.hpp>

#include "sim/vehicle/vehicle_desc.h"

namespace sonarloop::testing {

// exact comparison, field by field
inline void check_same_vehicle(const vehicle::VehicleDesc& a, const vehicle::VehicleDesc& b) {
  const auto& ta = a.trajectory;
  const auto& tb = b.trajectory;
  CHECK(ta.kind == tb.kind);
  CHECK(ta.start.north_m == tb.start.north_m);
  CHECK(ta.start.east_m == tb.start.east_m);
  CHECK(ta.start_heading == tb.start_heading);
  CHECK(ta.straight_length_m == tb.straight_length_m);
  REQUIRE(ta.waypoints.size() == tb.waypoints.size());
  for (std::size_t i = 0; i < ta.waypoints.size(); ++i) {
    CHECK(ta.waypoints[i].north_m == tb.waypoints[i].north_m);
    CHECK(ta.waypoints[i].east_m == tb.waypoints[i].east_m);
  }
  CHECK(ta.lawnmower.origin.north_m == tb.lawnmower.origin.north_m);
  CHECK(ta.lawnmower.origin.east_m == tb.lawnmower.origin.east_m);
  CHECK(ta.lawnmower.first_leg_heading == tb.lawnmower.first_leg_heading);
  CHECK(ta.lawnmower.leg_length_m == tb.lawnmower.leg_length_m);
  CHECK(ta.lawnmower.line_spacing_m == tb.lawnmower.line_spacing_m);
  CHECK(ta.lawnmower.legs == tb.lawnmower.legs);
  CHECK(ta.lawnmower.first_turn == tb.lawnmower.first_turn);
  CHECK(ta.speed_m_s == tb.speed_m_s);
  CHECK(ta.max_turn_rate_rad_s == tb.max_turn_rate_rad_s);
  CHECK(ta.depth.mode == tb.depth.mode);
  CHECK(ta.depth.depth_m == tb.depth.depth_m);
  CHECK(ta.depth.altitude_m == tb.depth.altitude_m);
  CHECK(ta.depth.max_climb_rate_m_s == tb.depth.max_climb_rate_m_s);
  CHECK(ta.depth.look_ahead_m == tb.depth.look_ahead_m);
  CHECK(ta.depth.min_depth_m == tb.depth.min_depth_m);
  CHECK(ta.depth.profile_step_m == tb.depth.profile_step_m);
  CHECK(ta.depth.vertical_smoothing_m == tb.depth.vertical_smoothing_m);
  CHECK(ta.sway.amplitude_m == tb.sway.amplitude_m);
  CHECK(ta.sway.period_s == tb.sway.period_s);
  CHECK(ta.sway.phase == tb.sway.phase);
  CHECK(ta.sway.yaw_coupling == tb.sway.yaw_coupling);
  CHECK(ta.attitude.roll_gain == tb.attitude.roll_gain);
  CHECK(ta.attitude.max_roll == tb.attitude.max_roll);
  CHECK(ta.attitude.roll_time_constant_s == tb.attitude.roll_time_constant_s);
  CHECK(ta.attitude.pitch_gain == tb.attitude.pitch_gain);
  CHECK(ta.attitude.max_pitch == tb.attitude.max_pitch);
  CHECK(ta.attitude.roll_amplitude == tb.attitude.roll_amplitude);
  CHECK(ta.attitude.pitch_amplitude == tb.attitude.pitch_amplitude);
  CHECK(ta.attitude.wave_period_s == tb.attitude.wave_period_s);
  const auto& na = a.nav;
  const auto& nb = b.nav;
  CHECK(na.position_noise_sd_m == nb.position_noise_sd_m);
  CHECK(na.position_drift_m_per_sqrt_s == nb.position_drift_m_per_sqrt_s);
  CHECK(na.heading_bias == nb.heading_bias);
  CHECK(na.heading_noise_sd == nb.heading_noise_sd);
  CHECK(na.heading_drift_rad_per_sqrt_s == nb.heading_drift_rad_per_sqrt_s);
  CHECK(na.attitude_noise_sd == nb.attitude_noise_sd);
  CHECK(na.speed_noise_sd_m_s == nb.speed_noise_sd_m_s);
  CHECK(na.speed_scale_factor_error == nb.speed_scale_factor_error);
  CHECK(na.yaw_rate_noise_sd_rad_s == nb.yaw_rate_noise_sd_rad_s);
  CHECK(na.depth_noise_sd_m == nb.depth_noise_sd_m);
  CHECK(na.altitude_noise_sd_m == nb.altitude_noise_sd_m);
  CHECK(na.noise_step_s == nb.noise_step_s);
  CHECK(na.drift_step_s == nb.drift_step_s);
}

// a flat seabed 30 m down, for planning in altitude mode
inline double flat_seabed(double, double) {
  return 30.0;
}

}  // namespace sonarloop::testing
