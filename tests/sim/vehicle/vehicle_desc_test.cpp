#include "sim/vehicle/vehicle_desc.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

using namespace sonarloop::vehicle;

namespace {

bool any_contains(const std::vector<std::string>& messages, const std::string& part) {
  for (const std::string& m : messages) {
    if (m.find(part) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("default descriptions are valid", "[vehicle][desc]") {
  CHECK(validate(VehicleDesc{}).empty());
  TrajectoryDesc lawnmower;
  lawnmower.kind = TrajectoryKind::kLawnmower;
  CHECK(validate(lawnmower).empty());
  TrajectoryDesc altitude;
  altitude.depth.mode = DepthMode::kAltitude;
  CHECK(validate(altitude).empty());
}

TEST_CASE("validation names the key, the value and the allowed range", "[vehicle][desc]") {
  VehicleDesc desc;
  desc.trajectory.speed_m_s = -1.0;
  desc.trajectory.max_turn_rate_rad_s = 0.0;
  desc.trajectory.attitude.max_roll = 2.0;
  desc.nav.position_noise_sd_m = -0.5;
  desc.nav.noise_step_s = 0.0;
  desc.nav.heading_bias = std::numeric_limits<double>::quiet_NaN();
  const auto errors = validate(desc);
  CHECK(errors.size() == 6);
  CHECK(any_contains(errors, "trajectory.speed_m_s = -1: must be in (0, 20] m/s"));
  CHECK(any_contains(errors, "trajectory.max_turn_rate_rad_s = 0"));
  CHECK(any_contains(errors, "trajectory.attitude.max_roll = 2"));
  CHECK(any_contains(errors, "nav.position_noise_sd_m = -0.5"));
  CHECK(any_contains(errors, "nav.noise_step_s = 0"));
  CHECK(any_contains(errors, "nav.heading_bias = nan"));
}

TEST_CASE("only the selected kind's fields are checked", "[vehicle][desc]") {
  TrajectoryDesc desc;  // straight
  desc.lawnmower.legs = 0;
  desc.waypoints.clear();
  CHECK(validate(desc).empty());

  desc.kind = TrajectoryKind::kLawnmower;
  desc.lawnmower.line_spacing_m = 0.0;
  const auto lawnmower = validate(desc);
  CHECK(lawnmower.size() == 2);
  CHECK(any_contains(lawnmower, "trajectory.lawnmower.legs = 0: must be in [1, 10000]"));
  CHECK(any_contains(lawnmower, "trajectory.lawnmower.line_spacing_m = 0"));

  desc.kind = TrajectoryKind::kWaypoints;
  const auto waypoints = validate(desc);
  REQUIRE(waypoints.size() == 1);
  CHECK(any_contains(waypoints, "trajectory.waypoints: at least one waypoint is required"));
}

TEST_CASE("coincident waypoints are reported with their index", "[vehicle][desc]") {
  TrajectoryDesc desc;
  desc.kind = TrajectoryKind::kWaypoints;
  desc.start = {10.0, 20.0};
  desc.waypoints = {{10.0, 20.001}, {100.0, 0.0}, {100.0, 0.0}, {0.0, std::nan("")}};
  const auto errors = validate(desc);
  CHECK(errors.size() == 3);
  CHECK(any_contains(errors, "trajectory.waypoints[0] = (10, 20.001): is 0.001 m from the start"));
  CHECK(any_contains(errors, "trajectory.waypoints[2] = (100, 0): is 0 m from the previous"));
  CHECK(any_contains(errors, "trajectory.waypoints[3].east_m = nan"));
}

TEST_CASE("altitude mode checks its own fields", "[vehicle][desc]") {
  TrajectoryDesc desc;
  desc.depth.mode = DepthMode::kAltitude;
  desc.depth.altitude_m = 0.0;
  desc.depth.max_climb_rate_m_s = 0.0;
  desc.depth.look_ahead_m = -1.0;
  desc.depth.depth_m = -5.0;  // not used in altitude mode
  const auto errors = validate(desc);
  CHECK(errors.size() == 3);
  CHECK(any_contains(errors, "trajectory.depth.altitude_m"));
  CHECK(any_contains(errors, "trajectory.depth.max_climb_rate_m_s"));
  CHECK(any_contains(errors, "trajectory.depth.look_ahead_m"));
}

TEST_CASE("enum names round trip", "[vehicle][desc]") {
  for (auto kind :
       {TrajectoryKind::kStraight, TrajectoryKind::kWaypoints, TrajectoryKind::kLawnmower}) {
    CHECK(trajectory_kind_from_string(to_string(kind)) == kind);
  }
  for (auto side : {TurnDirection::kStarboard, TurnDirection::kPort}) {
    CHECK(turn_direction_from_string(to_string(side)) == side);
  }
  for (auto mode : {DepthMode::kConstantDepth, DepthMode::kAltitude}) {
    CHECK(depth_mode_from_string(to_string(mode)) == mode);
  }
  CHECK(to_string(TrajectoryKind::kLawnmower) == "lawnmower");
  CHECK(to_string(DepthMode::kAltitude) == "altitude");
  CHECK_FALSE(trajectory_kind_from_string("spiral").has_value());
  CHECK_FALSE(turn_direction_from_string("Starboard").has_value());
}
