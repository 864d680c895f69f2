#pragma once
// Shared by the vehicle loader's tests (vehicle_loader_test.cpp, vehicle_loader_errors_test.cpp,
// vehicle_loader_random_test.cpp): the field-by-field comparison of two vehicles, a flat seabed to
// plan over, parsing a standalone vehicle document that must pass or fail, and the documented
// keys of each map.
#include <catch2/catch.hpp>

#include <numbers>
#include <string>
#include <vector>

#include "config/loader/vehicle_loader.h"
#include "sim/vehicle/vehicle_desc.h"
#include "tests/config/config_error_checks.h"

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

// The loader's conversion: one multiplication by the double nearest π/180.
inline double rad(double deg) {
  return deg * (std::numbers::pi / 180.0);
}

// Parses `yaml` as a standalone vehicle "vehicle.yaml", which must fail.
inline config::ConfigIssue expect_vehicle_error(const std::string& yaml, const std::string& path,
                                                const std::vector<std::string>& parts = {}) {
  return expect_config_error(config::parse_vehicle, "vehicle.yaml", yaml, path, parts);
}

// Parses `yaml` as a standalone vehicle "vehicle.yaml", which must pass.
inline vehicle::VehicleDesc parse_ok(const std::string& yaml) {
  INFO("yaml:\n" << yaml);
  try {
    return config::parse_vehicle(yaml, "vehicle.yaml");
  } catch (const config::ConfigError& e) {
    FAIL("rejected: " << e.what());
  }
  return {};
}

// The keys of each map, in the documented order.
inline const std::vector<std::string> kTrajectoryKeys = {
    "kind",        "start_m",   "heading_deg", "length_m",
    "waypoints_m", "lawnmower", "speed_m_s",   "max_turn_rate_deg_s",
    "depth",       "sway",      "attitude"};
inline const std::vector<std::string> kLawnmowerKeys = {
    "origin_m", "first_leg_heading_deg", "leg_length_m", "line_spacing_m", "legs", "first_turn"};
inline const std::vector<std::string> kDepthKeys = {
    "mode",         "depth_m",     "altitude_m",           "max_climb_rate_m_s",
    "look_ahead_m", "min_depth_m", "vertical_smoothing_m", "profile_step_m"};
inline const std::vector<std::string> kSwayKeys = {"amplitude_m", "period_s", "phase_deg",
                                                   "yaw_coupling"};
inline const std::vector<std::string> kAttitudeKeys = {
    "roll_gain",     "max_roll_deg",       "roll_time_constant_s", "pitch_gain",
    "max_pitch_deg", "roll_amplitude_deg", "pitch_amplitude_deg",  "wave_period_s"};
inline const std::vector<std::string> kNavKeys = {"position_noise_m",
                                                  "position_drift_m_per_sqrt_s",
                                                  "heading_bias_deg",
                                                  "heading_noise_deg",
                                                  "heading_drift_deg_per_sqrt_s",
                                                  "attitude_noise_deg",
                                                  "speed_noise_m_s",
                                                  "speed_scale_error",
                                                  "yaw_rate_noise_deg_s",
                                                  "depth_noise_m",
                                                  "altitude_noise_m",
                                                  "noise_step_s",
                                                  "drift_step_s"};

// a flat seabed 30 m down, for planning in altitude mode
inline double flat_seabed(double, double) {
  return 30.0;
}

}  // namespace sonarloop::testing
