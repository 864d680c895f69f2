#include "sim/vehicle/vehicle_desc.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

using namespace sonarloop::vehicle;

namespace {

using sonarloop::Limit;
using sonarloop::Problem;

bool any_contains(const std::vector<Problem>& problems, const std::string& part) {
  for (const Problem& p : problems) {
    if (p.message().find(part) != std::string::npos) return true;
  }
  return false;
}

// The problem of `field`; fails the test when there is none.
const Problem& problem_of(const std::vector<Problem>& problems, const std::string& field) {
  for (const Problem& p : problems) {
    if (p.field == field) return p;
  }
  FAIL("no problem at " << field);
  throw std::logic_error("unreachable");
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
  CHECK(any_contains(errors, "trajectory.waypoints[0]: (10, 20.001) is 0.001 m from the start"));
  CHECK(any_contains(errors, "trajectory.waypoints[2]: (100, 0) is 0 m from the previous"));
  // the rule's limit is the distance, not a value of the field
  const Problem& gap = problem_of(errors, "trajectory.waypoints[0]");
  CHECK_FALSE(gap.value.has_value());
  REQUIRE(gap.allowed.has_value());
  CHECK(gap.allowed->lo == 0.01);
  CHECK_FALSE(gap.allowed->lo_open);
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

TEST_CASE("problems carry the field path, the value and the allowed range in SI",
          "[vehicle][desc]") {
  VehicleDesc desc;
  desc.trajectory.attitude.max_roll = 2.0;
  desc.trajectory.max_turn_rate_rad_s = 2.5;
  desc.trajectory.kind = TrajectoryKind::kLawnmower;
  desc.trajectory.lawnmower.legs = 0;
  desc.nav.speed_scale_factor_error = -0.5;
  const auto problems = validate(desc);
  REQUIRE(problems.size() == 4);

  // (0, π/2) rad, open at both ends
  const Problem& roll = problem_of(problems, "trajectory.attitude.max_roll");
  CHECK(roll.value == 2.0);
  REQUIRE(roll.allowed.has_value());
  CHECK(roll.allowed->lo == 0.0);
  CHECK(roll.allowed->hi == std::numbers::pi / 2);
  CHECK(roll.allowed->lo_open);
  CHECK(roll.allowed->hi_open);
  CHECK(roll.allowed->unit == "rad");
  CHECK(roll.text == "must be in (0, 1.5708) rad");

  // (0, 2] rad/s
  const Problem& turn = problem_of(problems, "trajectory.max_turn_rate_rad_s");
  CHECK(turn.value == 2.5);
  REQUIRE(turn.allowed.has_value());
  CHECK(turn.allowed->hi == 2.0);
  CHECK_FALSE(turn.allowed->hi_open);
  CHECK(turn.allowed->lo_open);

  // whole numbers 1 .. 10000
  const Problem& legs = problem_of(problems, "trajectory.lawnmower.legs");
  CHECK(legs.value == 0.0);
  REQUIRE(legs.allowed.has_value());
  CHECK(legs.allowed->integer);
  CHECK(legs.allowed->lo == 1.0);
  CHECK(legs.allowed->hi == 10000.0);

  // the prefix is the caller's
  const auto nav = validate(desc.nav, "vehicle.nav");
  REQUIRE(nav.size() == 1);
  CHECK(nav[0].field == "vehicle.nav.speed_scale_factor_error");
  CHECK(nav[0].message() == "vehicle.nav.speed_scale_factor_error = -0.5: must be in (-0.5, 0.5)");
}

TEST_CASE("limit_of gives the limit validate() applies", "[vehicle][desc]") {
  for (const char* field : {"trajectory.attitude.max_roll", "trajectory.speed_m_s",
                            "trajectory.depth.profile_step_m", "nav.noise_step_s"}) {
    INFO(field);
    REQUIRE(limit_of(field).has_value());
  }
  CHECK(limit_of("trajectory.attitude.max_pitch")->hi == std::numbers::pi / 2);
  CHECK(limit_of("nav.noise_step_s")->lo == 1e-9);
  CHECK(limit_of("trajectory.lawnmower.legs")->integer);
  CHECK_FALSE(limit_of("trajectory.waypoints").has_value());
  CHECK_FALSE(limit_of("trajectory.attitude.max_roll_deg").has_value());  // a YAML name
  CHECK_FALSE(limit_of("speed_m_s").has_value());                         // no prefix

  // a value just outside every reported limit is a problem of that field
  VehicleDesc desc;
  desc.trajectory.sway.period_s = 0.0;  // checked even without sway
  const auto problems = validate(desc);
  REQUIRE(problems.size() == 1);
  CHECK(problems[0].field == "trajectory.sway.period_s");
  CHECK(problems[0].allowed->lo == limit_of("trajectory.sway.period_s")->lo);
}
