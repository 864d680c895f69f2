// Tests of the vehicle loader (config/loader/vehicle_loader.h): every key and its unit
// conversion, the defaults (VehicleDesc{}), each trajectory kind and depth mode, keys of other
// kinds and modes, every validation rule (per-key ranges, validate()'s cross-field rules, the
// path limits, the seabed extent in altitude mode), the shipped scenarios' vehicles,
// config/reference.yaml, reading files and writing YAML. The seeded randomized test is in
// vehicle_loader_random_test.cpp.
#include "config/loader/vehicle_loader.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/config_test_text.h"
#include "tests/config/scenario_checks.h"
#include "tests/config/vehicle_checks.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/rng.h"
#include "config/loader/scenario_loader.h"
#include "sim/scene/scene.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/path.h"
#include "sim/vehicle/trajectory.h"
#include "tests/support/temp_dir.h"

using sonarloop::Rng;
using sonarloop::RngStream;
using sonarloop::Vec2;
using namespace sonarloop::config;
namespace vehicle = sonarloop::vehicle;
namespace scene = sonarloop::scene;
using vehicle::DepthMode;
using vehicle::TrajectoryKind;
using vehicle::TurnDirection;
using vehicle::VehicleDesc;

using sonarloop::testing::check_same_vehicle;
using sonarloop::testing::contains;
using sonarloop::testing::expect_scenario_error;
using sonarloop::testing::flat_seabed;
using sonarloop::testing::real_text;
using sonarloop::testing::slurp;

namespace {

// The loader's conversion: one multiplication by the double nearest π/180.
double rad(double deg) {
  return deg * (std::numbers::pi / 180.0);
}

// Parses `yaml` as a standalone vehicle "vehicle.yaml", which must fail.
ConfigIssue expect_vehicle_error(const std::string& yaml, const std::string& path,
                                 const std::vector<std::string>& parts = {}) {
  return sonarloop::testing::expect_config_error(parse_vehicle, "vehicle.yaml", yaml, path, parts);
}

VehicleDesc parse_ok(const std::string& yaml) {
  INFO("yaml:\n" << yaml);
  try {
    return parse_vehicle(yaml, "vehicle.yaml");
  } catch (const ConfigError& e) {
    FAIL("rejected: " << e.what());
  }
  return {};
}

// The keys of each map, in the documented order.
const std::vector<std::string> kTrajectoryKeys = {
    "kind",        "start_m",   "heading_deg", "length_m",
    "waypoints_m", "lawnmower", "speed_m_s",   "max_turn_rate_deg_s",
    "depth",       "sway",      "attitude"};
const std::vector<std::string> kLawnmowerKeys = {
    "origin_m", "first_leg_heading_deg", "leg_length_m", "line_spacing_m", "legs", "first_turn"};
const std::vector<std::string> kDepthKeys = {
    "mode",         "depth_m",     "altitude_m",           "max_climb_rate_m_s",
    "look_ahead_m", "min_depth_m", "vertical_smoothing_m", "profile_step_m"};
const std::vector<std::string> kSwayKeys = {"amplitude_m", "period_s", "phase_deg", "yaw_coupling"};
const std::vector<std::string> kAttitudeKeys = {
    "roll_gain",     "max_roll_deg",       "roll_time_constant_s", "pitch_gain",
    "max_pitch_deg", "roll_amplitude_deg", "pitch_amplitude_deg",  "wave_period_s"};
const std::vector<std::string> kNavKeys = {"position_noise_m",
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

}  // namespace

// ---------------------------------------------------------------------------------------------
// defaults and keys

TEST_CASE("vehicle_loader: absent, empty and null give VehicleDesc{}") {
  const VehicleDesc def;
  CHECK(vehicle::validate(def).empty());
  for (const std::string yaml : {"", "{}", "trajectory:\nnav:\n", "trajectory: {}\nnav: {}\n",
                                 "trajectory: {depth: {}, sway: ~, attitude: {}}\n"}) {
    INFO(yaml);
    check_same_vehicle(parse_ok(yaml), def);
  }
  // in a scenario: no vehicle key, a null one, an empty map
  for (const std::string yaml : {"seed: 1\n", "vehicle:\n", "vehicle: {}\n", "vehicle: ~\n"}) {
    INFO(yaml);
    check_same_vehicle(parse_scenario(yaml, "s.yaml").vehicle, def);
  }
  // the default kind's keys without a kind key
  const auto v = parse_ok("trajectory: {length_m: 10, heading_deg: 90}\n");
  CHECK(v.trajectory.kind == TrajectoryKind::kStraight);
  CHECK(v.trajectory.straight_length_m == 10);
  CHECK(v.trajectory.start_heading == rad(90));
}

TEST_CASE("vehicle_loader: every key is parsed and converted to SI") {
  SECTION("straight, constant depth, sway, attitude and nav") {
    const auto v = parse_ok(R"(
trajectory:
  kind: straight
  start_m: [-12.5, 7.25]
  heading_deg: 33.5
  length_m: 321.5
  speed_m_s: 1.75
  max_turn_rate_deg_s: 12.5
  depth:
    mode: depth
    depth_m: 17.25
    profile_step_m: 0.25
  sway:
    amplitude_m: 0.75
    period_s: 12.5
    phase_deg: -45
    yaw_coupling: 0.5
  attitude:
    roll_gain: -1.5
    max_roll_deg: 25
    roll_time_constant_s: 2.5
    pitch_gain: 1.25
    max_pitch_deg: 35
    roll_amplitude_deg: 4
    pitch_amplitude_deg: 2.5
    wave_period_s: 9.5
nav:
  position_noise_m: 0.3
  position_drift_m_per_sqrt_s: 0.07
  heading_bias_deg: -1.5
  heading_noise_deg: 0.25
  heading_drift_deg_per_sqrt_s: 0.02
  attitude_noise_deg: 0.1
  speed_noise_m_s: 0.015
  speed_scale_error: -0.003
  yaw_rate_noise_deg_s: 0.04
  depth_noise_m: 0.05
  altitude_noise_m: 0.12
  noise_step_s: 0.02
  drift_step_s: 0.5
)");
    VehicleDesc e;
    auto& t = e.trajectory;
    t.kind = TrajectoryKind::kStraight;
    t.start = {-12.5, 7.25};
    t.start_heading = rad(33.5);
    t.straight_length_m = 321.5;
    t.speed_m_s = 1.75;
    t.max_turn_rate_rad_s = rad(12.5);
    t.depth.mode = DepthMode::kConstantDepth;
    t.depth.depth_m = 17.25;
    t.depth.profile_step_m = 0.25;
    t.sway = {0.75, 12.5, rad(-45), 0.5};
    t.attitude = {-1.5, rad(25), 2.5, 1.25, rad(35), rad(4), rad(2.5), 9.5};
    auto& n = e.nav;
    n.position_noise_sd_m = 0.3;
    n.position_drift_m_per_sqrt_s = 0.07;
    n.heading_bias = rad(-1.5);
    n.heading_noise_sd = rad(0.25);
    n.heading_drift_rad_per_sqrt_s = rad(0.02);
    n.attitude_noise_sd = rad(0.1);
    n.speed_noise_sd_m_s = 0.015;
    n.speed_scale_factor_error = -0.003;
    n.yaw_rate_noise_sd_rad_s = rad(0.04);
    n.depth_noise_sd_m = 0.05;
    n.altitude_noise_sd_m = 0.12;
    n.noise_step_s = 0.02;
    n.drift_step_s = 0.5;
    check_same_vehicle(v, e);
    // the conversion of a few in plain numbers
    CHECK(v.trajectory.start_heading == Approx(0.584685299418).epsilon(1e-11));
    CHECK(v.trajectory.max_turn_rate_rad_s == Approx(0.218166156499).epsilon(1e-11));
    CHECK(v.nav.heading_bias == Approx(-0.0261799387799).epsilon(1e-11));
  }
  SECTION("waypoints, altitude mode") {
    const auto v = parse_ok(R"(
trajectory:
  kind: waypoints
  start_m: [1, 2]
  heading_deg: 270
  waypoints_m: [[10, 2], [10.5, 40], [-20, 40.25]]
  depth:
    mode: altitude
    altitude_m: 6.5
    max_climb_rate_m_s: 0.75
    look_ahead_m: 80
    min_depth_m: 2.5
    vertical_smoothing_m: 8
    profile_step_m: 1
)");
    VehicleDesc e;
    auto& t = e.trajectory;
    t.kind = TrajectoryKind::kWaypoints;
    t.start = {1, 2};
    t.start_heading = rad(270);
    t.waypoints = {{10, 2}, {10.5, 40}, {-20, 40.25}};
    t.depth.mode = DepthMode::kAltitude;
    t.depth.altitude_m = 6.5;
    t.depth.max_climb_rate_m_s = 0.75;
    t.depth.look_ahead_m = 80;
    t.depth.min_depth_m = 2.5;
    t.depth.vertical_smoothing_m = 8;
    t.depth.profile_step_m = 1;
    check_same_vehicle(v, e);
  }
  SECTION("lawnmower") {
    const auto v = parse_ok(R"(
trajectory:
  kind: lawnmower
  lawnmower:
    origin_m: [-100, 25]
    first_leg_heading_deg: 90
    leg_length_m: 150
    line_spacing_m: 35
    legs: 6
    first_turn: port
)");
    VehicleDesc e;
    auto& m = e.trajectory.lawnmower;
    e.trajectory.kind = TrajectoryKind::kLawnmower;
    m.origin = {-100, 25};
    m.first_leg_heading = rad(90);
    m.leg_length_m = 150;
    m.line_spacing_m = 35;
    m.legs = 6;
    m.first_turn = TurnDirection::kPort;
    check_same_vehicle(v, e);
    // without a lawnmower map: the LawnmowerDesc defaults
    VehicleDesc plain;
    plain.trajectory.kind = TrajectoryKind::kLawnmower;
    check_same_vehicle(parse_ok("trajectory: {kind: lawnmower}\n"), plain);
    check_same_vehicle(parse_ok("trajectory: {kind: lawnmower, lawnmower: {}}\n"), plain);
  }
  SECTION("the bounds themselves are accepted and convert to validate()'s bounds") {
    const auto v = parse_ok(R"(
trajectory:
  speed_m_s: 20
  max_turn_rate_deg_s: 114.59155902616465
  attitude: {roll_gain: -10, max_roll_deg: 89.99999999999999, pitch_gain: 10,
             roll_time_constant_s: 3600, roll_amplitude_deg: 45, pitch_amplitude_deg: 45,
             wave_period_s: 600}
nav: {heading_bias_deg: -180, noise_step_s: 1e-9, drift_step_s: 3600,
      speed_scale_error: -0.49999999999999994}
)");
    CHECK(v.trajectory.max_turn_rate_rad_s == 2.0);
    CHECK(v.trajectory.attitude.max_roll < std::numbers::pi / 2);
    CHECK(v.trajectory.attitude.roll_amplitude == std::numbers::pi / 4);
    CHECK(v.trajectory.attitude.pitch_amplitude == std::numbers::pi / 4);
    CHECK(parse_ok("trajectory: {attitude: {wave_period_s: 1}}\n")
              .trajectory.attitude.wave_period_s == 1);
    CHECK(v.nav.heading_bias == -std::numbers::pi);
    CHECK(parse_ok("nav: {heading_bias_deg: 180}\n").nav.heading_bias == std::numbers::pi);
    CHECK(vehicle::validate(v).empty());
  }
}

TEST_CASE("vehicle_loader: each kind plans the path it describes") {
  const double speed = 2.0;
  SECTION("straight") {
    const auto v = parse_ok("trajectory: {start_m: [5, -5], heading_deg: 90, length_m: 100}\n");
    const vehicle::Trajectory tr(v.trajectory);
    CHECK(tr.length_m() == Approx(100));
    CHECK(tr.duration_s() == Approx(100 / speed));
    const auto end = tr.path().at(100).position_NE;
    CHECK(end.x() == Approx(5).margin(1e-9));
    CHECK(end.y() == Approx(95));
  }
  SECTION("waypoints") {
    const auto v = parse_ok(
        "trajectory: {kind: waypoints, start_m: [0, 0], waypoints_m: [[100, 0], [100, 100]]}\n");
    const vehicle::Trajectory tr(v.trajectory);
    // straight to the first, then a starboard turn of radius 20 m and a tangent line
    CHECK(tr.turn_radius_m() == Approx(20));
    CHECK(tr.length_m() > 200);
    CHECK(tr.length_m() < 200 + 20 * std::numbers::pi);
  }
  SECTION("lawnmower") {
    const auto v = parse_ok(R"(
trajectory:
  kind: lawnmower
  lawnmower: {leg_length_m: 80, line_spacing_m: 20, legs: 3}
  max_turn_rate_deg_s: 15
  depth: {mode: altitude, altitude_m: 7.5}
)");
    const vehicle::Trajectory tr(v.trajectory, flat_seabed);
    const double r = 2.0 / rad(15);
    CHECK(tr.turn_radius_m() == Approx(r));
    CHECK(tr.length_m() == Approx(3 * 80 + 2 * vehicle::u_turn_length_m(20, r)));
    CHECK(tr.min_altitude_m() == Approx(7.5));
    // leg 1 runs south along east = 20 (starboard of a north-going leg 0)
    const auto mid =
        tr.state_at(sonarloop::from_seconds((80 + 40 + vehicle::u_turn_length_m(20, r)) / speed));
    CHECK(mid.leg == 1);
    CHECK(mid.pose.position_W.y() == Approx(20));
  }
}

// ---------------------------------------------------------------------------------------------
// keys of other kinds and modes, unknown keys, wrong types, ranges

TEST_CASE("vehicle_loader: keys of another kind or depth mode are rejected") {
  struct Case {
    std::string kind;
    std::string key;
    std::string value;
    std::string owners;
  };
  const std::vector<Case> cases = {
      {"waypoints", "length_m", "10", "kind straight"},
      {"lawnmower", "length_m", "10", "kind straight"},
      {"straight", "waypoints_m", "[[1, 2]]", "kind waypoints"},
      {"lawnmower", "waypoints_m", "[[1, 2]]", "kind waypoints"},
      {"straight", "lawnmower", "{legs: 2}", "kind lawnmower"},
      {"waypoints", "lawnmower", "{}", "kind lawnmower"},
      {"lawnmower", "start_m", "[1, 2]", "kind straight and waypoints"},
      {"lawnmower", "heading_deg", "10", "kind straight and waypoints"},
  };
  for (const auto& c : cases) {
    INFO(c.kind << " " << c.key);
    std::string yaml = "trajectory:\n  kind: " + c.kind + "\n  " + c.key + ": " + c.value + "\n";
    if (c.kind == "waypoints") yaml += "  waypoints_m: [[5, 5]]\n";
    const auto i = expect_vehicle_error(
        yaml, "trajectory." + c.key,
        {"is a key of " + c.owners + ", but this trajectory is of kind " + c.kind, "(line 3",
         "allowed: the keys of kind " + c.kind + ": kind, "});
    if (c.kind == "lawnmower" && (c.key == "start_m" || c.key == "heading_deg")) {
      CHECK(contains(i.problem, "a lawnmower starts at lawnmower.origin_m"));
    }
  }
  // the default kind says so
  expect_vehicle_error(
      "trajectory: {waypoints_m: [[1, 2]]}\n", "trajectory.waypoints_m",
      {"this trajectory is of kind straight (the default; set kind to choose another)",
       "allowed: the keys of kind straight: kind, start_m, heading_deg, length_m, "
       "speed_m_s, max_turn_rate_deg_s, depth, sway, attitude"});
  // depth modes
  for (const std::string key : {"altitude_m", "max_climb_rate_m_s", "look_ahead_m", "min_depth_m",
                                "vertical_smoothing_m"}) {
    INFO(key);
    expect_vehicle_error("trajectory:\n  depth:\n    mode: depth\n    " + key + ": 1\n",
                         "trajectory.depth." + key,
                         {"is a key of mode altitude, but this depth is of mode depth (line 4",
                          "allowed: the keys of mode depth: mode, depth_m, profile_step_m"});
    expect_vehicle_error("trajectory:\n  depth:\n    " + key + ": 1\n", "trajectory.depth." + key,
                         {"of mode depth (the default; set mode to choose another)"});
  }
  expect_vehicle_error("trajectory:\n  depth: {mode: altitude, depth_m: 10}\n",
                       "trajectory.depth.depth_m",
                       {"is a key of mode depth, but this depth is of mode altitude",
                        "allowed: the keys of mode altitude: mode, altitude_m, max_climb_rate_m_s, "
                        "look_ahead_m, min_depth_m, vertical_smoothing_m, profile_step_m"});
  // profile_step_m belongs to both modes
  CHECK(parse_ok("trajectory: {depth: {mode: altitude, profile_step_m: 2}}\n")
            .trajectory.depth.profile_step_m == 2);
  CHECK(parse_ok("trajectory: {depth: {mode: depth, profile_step_m: 2}}\n")
            .trajectory.depth.profile_step_m == 2);
}

TEST_CASE("vehicle_loader: unknown keys, at every level, with suggestions") {
  auto i = expect_vehicle_error(
      "trajectori: {}\n", "trajectori",
      {"unknown key 'trajectori' (line 1, column 1)", "allowed: trajectory, nav"});
  CHECK(i.suggestion == "trajectory");
  i = expect_vehicle_error(
      "trajectory:\n  knd: straight\n", "trajectory.knd",
      {"allowed: kind, start_m, heading_deg, length_m, waypoints_m, lawnmower, "
       "speed_m_s, max_turn_rate_deg_s, depth, sway, attitude"});
  CHECK(i.suggestion == "kind");
  i = expect_vehicle_error("trajectory:\n  speed_kn: 4\n", "trajectory.speed_kn", {"unknown key"});
  i = expect_vehicle_error(
      "trajectory:\n  kind: lawnmower\n  lawnmower: {leg_lenght_m: 5}\n",
      "trajectory.lawnmower.leg_lenght_m",
      {"allowed: origin_m, first_leg_heading_deg, leg_length_m, line_spacing_m, "
       "legs, first_turn"});
  CHECK(i.suggestion == "leg_length_m");
  i = expect_vehicle_error("trajectory: {depth: {altitude: 5}}\n", "trajectory.depth.altitude",
                           {"allowed: mode, depth_m, altitude_m, max_climb_rate_m_s, look_ahead_m, "
                            "min_depth_m, vertical_smoothing_m, profile_step_m"});
  CHECK(i.suggestion == "altitude_m");
  i = expect_vehicle_error("trajectory: {sway: {amplitude: 1}}\n", "trajectory.sway.amplitude",
                           {"allowed: amplitude_m, period_s, phase_deg, yaw_coupling"});
  CHECK(i.suggestion == "amplitude_m");
  i = expect_vehicle_error("trajectory: {attitude: {max_roll: 10}}\n",
                           "trajectory.attitude.max_roll",
                           {"allowed: roll_gain, max_roll_deg, roll_time_constant_s, pitch_gain, "
                            "max_pitch_deg, roll_amplitude_deg, pitch_amplitude_deg, "
                            "wave_period_s"});
  CHECK(i.suggestion == "max_roll_deg");
  i = expect_vehicle_error(
      "nav: {heading_noise_rad: 0.1}\n", "nav.heading_noise_rad",
      {"allowed: position_noise_m, position_drift_m_per_sqrt_s, heading_bias_deg"});
  CHECK(i.suggestion == "heading_noise_deg");
  // unknown keys are reported before values are read, all of a map together
  try {
    parse_vehicle("nav: {bogus: 1, heading_bias_deg: 999, other: 2}\n", "v.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    REQUIRE(e.issues().size() == 2);
    CHECK(e.issues()[0].path == "nav.bogus");
    CHECK(e.issues()[1].path == "nav.other");
  }
  // in a scenario, under vehicle.
  i = expect_scenario_error("vehicle:\n  nav:\n    depth_noise: 1\n", "vehicle.nav.depth_noise",
                            {"(line 3, column 5)", "(did you mean 'depth_noise_m'?)"});
}

TEST_CASE("vehicle_loader: wrong types") {
  expect_vehicle_error("- 1\n", "", {"is not a map", "allowed: a map with trajectory, nav"});
  expect_vehicle_error("trajectory: 5\n", "trajectory",
                       {"'5' is not a map", "allowed: a map with kind"});
  expect_vehicle_error("nav: [1]\n", "nav", {"is not a map"});
  auto i = expect_vehicle_error(
      "trajectory: {kind: lawnmover}\n", "trajectory.kind",
      {"'lawnmover' is not a trajectory kind", "allowed: straight, waypoints, lawnmower"});
  CHECK(i.suggestion == "lawnmower");
  expect_vehicle_error("trajectory: {kind: [straight]}\n", "trajectory.kind",
                       {"is not a trajectory kind name"});
  expect_vehicle_error("trajectory: {kind: }\n", "trajectory.kind", {"has no value"});
  i = expect_vehicle_error("trajectory: {depth: {mode: altitud}}\n", "trajectory.depth.mode",
                           {"'altitud' is not a depth mode", "allowed: altitude, depth"});
  CHECK(i.suggestion == "altitude");
  expect_vehicle_error("trajectory: {depth: 5}\n", "trajectory.depth", {"is not a map"});
  expect_vehicle_error("trajectory: {kind: lawnmower, lawnmower: {first_turn: right}}\n",
                       "trajectory.lawnmower.first_turn",
                       {"'right' is not a turn direction", "allowed: starboard, port"});
  expect_vehicle_error("trajectory: {kind: lawnmower, lawnmower: {legs: 2.5}}\n",
                       "trajectory.lawnmower.legs",
                       {"'2.5' is not an integer", "an integer 1 .. 10000"});
  expect_vehicle_error("trajectory: {kind: lawnmower, lawnmower: [1]}\n", "trajectory.lawnmower",
                       {"is not a map"});
  expect_vehicle_error(
      "trajectory: {start_m: 5}\n", "trajectory.start_m",
      {"is a single value, not a list", "a list [north, east] of 2 finite numbers"});
  expect_vehicle_error("trajectory: {start_m: [1, 2, 3]}\n", "trajectory.start_m",
                       {"has 3 values"});
  expect_vehicle_error("trajectory: {start_m: [a, 2]}\n", "trajectory.start_m[0]",
                       {"'a' is not a number"});
  expect_vehicle_error("trajectory: {speed_m_s: '2'}\n", "trajectory.speed_m_s",
                       {"is a quoted string, not a number"});
  expect_vehicle_error("trajectory: {speed_m_s: .nan}\n", "trajectory.speed_m_s",
                       {"is not a finite number"});
  expect_vehicle_error("trajectory: {heading_deg: .inf}\n", "trajectory.heading_deg",
                       {"is not a finite number", "allowed: any finite number"});
  expect_vehicle_error("nav: {position_noise_m: }\n", "nav.position_noise_m", {"has no value"});
  expect_vehicle_error("nav: {position_noise_m: true}\n", "nav.position_noise_m",
                       {"is not a number"});
  // waypoints
  const std::string w = "trajectory:\n  kind: waypoints\n";
  expect_vehicle_error(w, "trajectory.waypoints_m",
                       {"is not set (kind waypoints needs at least one waypoint)",
                        "allowed: a list of at least one [north, east] point"});
  expect_vehicle_error(w + "  waypoints_m: []\n", "trajectory.waypoints_m", {"has no waypoints"});
  expect_vehicle_error(w + "  waypoints_m:\n", "trajectory.waypoints_m", {"has no waypoints"});
  expect_vehicle_error(w + "  waypoints_m: 5\n", "trajectory.waypoints_m", {"is not a list"});
  expect_vehicle_error(w + "  waypoints_m: [1, 2]\n", "trajectory.waypoints_m[0]",
                       {"is a single value, not a list"});
  expect_vehicle_error(w + "  waypoints_m: [[1, 2], [3]]\n", "trajectory.waypoints_m[1]",
                       {"has 1 value, not 2"});
  expect_vehicle_error(w + "  waypoints_m: [[1, 2], [3, .nan]]\n", "trajectory.waypoints_m[1][1]",
                       {"is not a finite number"});
}

TEST_CASE("vehicle_loader: out-of-range values name the file, key, value and range") {
  struct Case {
    std::string yaml;
    std::string path;
    std::string value;
    std::string allowed;
  };
  const std::string lm = "trajectory:\n  kind: lawnmower\n  lawnmower:\n    ";
  const std::string alt = "trajectory:\n  depth:\n    mode: altitude\n    ";
  const std::vector<Case> cases = {
      {"trajectory: {length_m: 0}\n", "trajectory.length_m", "0", "> 0"},
      {"trajectory: {length_m: -5}\n", "trajectory.length_m", "-5", "> 0"},
      {lm + "leg_length_m: 0\n", "trajectory.lawnmower.leg_length_m", "0", "> 0"},
      {lm + "line_spacing_m: -1\n", "trajectory.lawnmower.line_spacing_m", "-1", "> 0"},
      {lm + "legs: 0\n", "trajectory.lawnmower.legs", "0", "an integer 1 .. 10000"},
      {lm + "legs: 10001\n", "trajectory.lawnmower.legs", "10001", "an integer 1 .. 10000"},
      {"trajectory: {speed_m_s: 0}\n", "trajectory.speed_m_s", "0", "> 0 and <= 20"},
      {"trajectory: {speed_m_s: 20.000001}\n", "trajectory.speed_m_s", "20.000001",
       "> 0 and <= 20"},
      {"trajectory: {max_turn_rate_deg_s: 0}\n", "trajectory.max_turn_rate_deg_s", "0",
       "> 0 and <= 114.59155902616465 (2 rad/s)"},
      {"trajectory: {max_turn_rate_deg_s: 114.59155902616466}\n", "trajectory.max_turn_rate_deg_s",
       "114.59155902616466", "> 0 and <= 114.59155902616465 (2 rad/s)"},
      {"trajectory: {depth: {depth_m: -0.1}}\n", "trajectory.depth.depth_m", "-0.1", ">= 0"},
      {alt + "altitude_m: 0\n", "trajectory.depth.altitude_m", "0", "> 0"},
      {alt + "max_climb_rate_m_s: 0\n", "trajectory.depth.max_climb_rate_m_s", "0",
       "> 0 and <= 20"},
      {alt + "max_climb_rate_m_s: 21\n", "trajectory.depth.max_climb_rate_m_s", "21",
       "> 0 and <= 20"},
      {alt + "look_ahead_m: -1\n", "trajectory.depth.look_ahead_m", "-1", ">= 0"},
      {alt + "min_depth_m: -1\n", "trajectory.depth.min_depth_m", "-1", ">= 0"},
      {alt + "vertical_smoothing_m: 1001\n", "trajectory.depth.vertical_smoothing_m", "1001",
       "0 .. 1000"},
      {alt + "vertical_smoothing_m: -1\n", "trajectory.depth.vertical_smoothing_m", "-1",
       "0 .. 1000"},
      {"trajectory: {depth: {profile_step_m: 0.04}}\n", "trajectory.depth.profile_step_m", "0.04",
       "0.05 .. 10"},
      {"trajectory: {depth: {profile_step_m: 11}}\n", "trajectory.depth.profile_step_m", "11",
       "0.05 .. 10"},
      {"trajectory: {sway: {amplitude_m: -1}}\n", "trajectory.sway.amplitude_m", "-1",
       ">= 0 (0 = no sway)"},
      {"trajectory: {sway: {period_s: 0}}\n", "trajectory.sway.period_s", "0", "> 0"},
      {"trajectory: {sway: {yaw_coupling: 1.5}}\n", "trajectory.sway.yaw_coupling", "1.5",
       "0 .. 1"},
      {"trajectory: {sway: {yaw_coupling: -0.5}}\n", "trajectory.sway.yaw_coupling", "-0.5",
       "0 .. 1"},
      {"trajectory: {attitude: {roll_gain: 11}}\n", "trajectory.attitude.roll_gain", "11",
       "-10 .. 10"},
      {"trajectory: {attitude: {roll_gain: -10.5}}\n", "trajectory.attitude.roll_gain", "-10.5",
       "-10 .. 10"},
      {"trajectory: {attitude: {max_roll_deg: 0}}\n", "trajectory.attitude.max_roll_deg", "0",
       "> 0 and < 90"},
      {"trajectory: {attitude: {max_roll_deg: 90}}\n", "trajectory.attitude.max_roll_deg", "90",
       "> 0 and < 90"},
      {"trajectory: {attitude: {roll_time_constant_s: 3601}}\n",
       "trajectory.attitude.roll_time_constant_s", "3601", "0 .. 3600 (0 = no lag)"},
      {"trajectory: {attitude: {roll_time_constant_s: -1}}\n",
       "trajectory.attitude.roll_time_constant_s", "-1", "0 .. 3600 (0 = no lag)"},
      {"trajectory: {attitude: {pitch_gain: -0.1}}\n", "trajectory.attitude.pitch_gain", "-0.1",
       "0 .. 10"},
      {"trajectory: {attitude: {max_pitch_deg: 95}}\n", "trajectory.attitude.max_pitch_deg", "95",
       "> 0 and < 90"},
      {"trajectory: {attitude: {roll_amplitude_deg: 50}}\n",
       "trajectory.attitude.roll_amplitude_deg", "50", "0 .. 45"},
      {"trajectory: {attitude: {roll_amplitude_deg: -1}}\n",
       "trajectory.attitude.roll_amplitude_deg", "-1", "0 .. 45"},
      {"trajectory: {attitude: {pitch_amplitude_deg: 45.5}}\n",
       "trajectory.attitude.pitch_amplitude_deg", "45.5", "0 .. 45"},
      {"trajectory: {attitude: {wave_period_s: 0.5}}\n", "trajectory.attitude.wave_period_s", "0.5",
       "1 .. 600"},
      {"trajectory: {attitude: {wave_period_s: 601}}\n", "trajectory.attitude.wave_period_s", "601",
       "1 .. 600"},
      {"nav: {position_noise_m: -0.1}\n", "nav.position_noise_m", "-0.1", ">= 0"},
      {"nav: {position_drift_m_per_sqrt_s: -1}\n", "nav.position_drift_m_per_sqrt_s", "-1", ">= 0"},
      {"nav: {heading_bias_deg: 180.5}\n", "nav.heading_bias_deg", "180.5", "-180 .. 180"},
      {"nav: {heading_bias_deg: -181}\n", "nav.heading_bias_deg", "-181", "-180 .. 180"},
      {"nav: {heading_noise_deg: -1}\n", "nav.heading_noise_deg", "-1", ">= 0"},
      {"nav: {heading_drift_deg_per_sqrt_s: -1}\n", "nav.heading_drift_deg_per_sqrt_s", "-1",
       ">= 0"},
      {"nav: {attitude_noise_deg: -1}\n", "nav.attitude_noise_deg", "-1", ">= 0"},
      {"nav: {speed_noise_m_s: -1}\n", "nav.speed_noise_m_s", "-1", ">= 0"},
      {"nav: {speed_scale_error: 0.5}\n", "nav.speed_scale_error", "0.5", "> -0.5 and < 0.5"},
      {"nav: {speed_scale_error: -0.5}\n", "nav.speed_scale_error", "-0.5", "> -0.5 and < 0.5"},
      {"nav: {yaw_rate_noise_deg_s: -1}\n", "nav.yaw_rate_noise_deg_s", "-1", ">= 0"},
      {"nav: {depth_noise_m: -1}\n", "nav.depth_noise_m", "-1", ">= 0"},
      {"nav: {altitude_noise_m: -1}\n", "nav.altitude_noise_m", "-1", ">= 0"},
      {"nav: {noise_step_s: 0}\n", "nav.noise_step_s", "0", "1e-09 .. 3600 (at least 1 ns)"},
      {"nav: {noise_step_s: 3601}\n", "nav.noise_step_s", "3601", "1e-09 .. 3600"},
      {"nav: {drift_step_s: 1e-10}\n", "nav.drift_step_s", "1e-10", "1e-09 .. 3600"},
  };
  for (const auto& c : cases) {
    INFO(c.path);
    expect_vehicle_error(c.yaml, c.path,
                         {c.value + " is out of range (line ", "allowed: " + c.allowed});
  }
  // every number key is covered above (or has no bounds)
  std::vector<std::string> covered;
  for (const auto& c : cases)
    covered.push_back(c.path.substr(c.path.rfind('.') + 1));
  for (const auto* keys : {&kLawnmowerKeys, &kDepthKeys, &kSwayKeys, &kAttitudeKeys, &kNavKeys}) {
    for (const auto& k : *keys) {
      if (k == "origin_m" || k == "first_leg_heading_deg" || k == "first_turn" || k == "mode" ||
          k == "phase_deg") {
        continue;  // a pair, a word or any finite number
      }
      INFO(k);
      CHECK(std::find(covered.begin(), covered.end(), k) != covered.end());
    }
  }
  // in a scenario the file and the full key path are named
  expect_scenario_error("seed: 1\nvehicle:\n  trajectory:\n    speed_m_s: 25\n",
                        "vehicle.trajectory.speed_m_s",
                        {"25 is out of range (line 4, column 16)", "allowed: > 0 and <= 20"});
}

TEST_CASE("vehicle_loader: validate()'s limits are reported at the YAML key, in its unit") {
  // degrees: the key, its line and column, the value as written, the range in degrees
  const std::string roll = "trajectory:\n  attitude:\n    max_roll_deg: 95\n";
  try {
    parse_vehicle(roll, "vehicle.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()) ==
          "vehicle.yaml: trajectory.attitude.max_roll_deg: 95 is out of range (line 3, column 19); "
          "allowed: > 0 and < 90");
    CHECK(e.first().line == 3);
  }
  // the wave amplitude, in degrees too; the period in seconds
  try {
    parse_vehicle("trajectory:\n  attitude:\n    roll_amplitude_deg: 50\n", "vehicle.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()) ==
          "vehicle.yaml: trajectory.attitude.roll_amplitude_deg: 50 is out of range (line 3, "
          "column 25); allowed: 0 .. 45");
  }
  try {
    parse_vehicle("trajectory:\n  attitude:\n    wave_period_s: 0.5\n", "vehicle.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()) ==
          "vehicle.yaml: trajectory.attitude.wave_period_s: 0.5 is out of range (line 3, "
          "column 20); allowed: 1 .. 600");
  }
  // a value that is not a number is told the same range
  expect_vehicle_error("trajectory: {attitude: {max_pitch_deg: steep}}\n",
                       "trajectory.attitude.max_pitch_deg",
                       {"'steep' is not a number", "allowed: a number > 0 and < 90"});
  expect_vehicle_error("nav: {heading_bias_deg: [1]}\n", "nav.heading_bias_deg",
                       {"allowed: a number -180 .. 180"});
  expect_vehicle_error("trajectory: {attitude: {wave_period_s: long}}\n",
                       "trajectory.attitude.wave_period_s",
                       {"'long' is not a number", "allowed: a number 1 .. 600"});
  // a bound with no short decimal in degrees is also given in SI
  expect_vehicle_error("trajectory: {max_turn_rate_deg_s: 120}\n", "trajectory.max_turn_rate_deg_s",
                       {"120 is out of range (line 1, column 35)",
                        "allowed: > 0 and <= 114.59155902616465 (2 rad/s)"});
  // every violation, one issue each, in validate()'s order, each at its own line
  try {
    parse_vehicle(
        "trajectory:\n  speed_m_s: 0\n  attitude: {max_roll_deg: 0}\n"
        "nav:\n  heading_noise_deg: -1\n",
        "v.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    REQUIRE(e.issues().size() == 3);
    CHECK(e.issues()[0].path == "trajectory.speed_m_s");
    CHECK(e.issues()[0].line == 2);
    CHECK(e.issues()[1].path == "trajectory.attitude.max_roll_deg");
    CHECK(e.issues()[1].line == 3);
    CHECK(e.issues()[2].path == "nav.heading_noise_deg");
    CHECK(e.issues()[2].allowed == ">= 0");
    CHECK(e.issues()[2].line == 5);
  }
}

TEST_CASE("vehicle_loader: validate()'s cross-field rules become errors at the YAML key") {
  const std::string w = "trajectory:\n  kind: waypoints\n  start_m: [0, 0]\n  waypoints_m: ";
  auto i =
      expect_vehicle_error(w + "[[0, 0.005]]\n", "trajectory.waypoints_m[0]",
                           {"a list [0, 0.005] is rejected by the vehicle model: "
                            "trajectory.waypoints[0]: (0, 0.005) is 0.005 m from the start point",
                            "allowed: [north, east]; consecutive points (start_m included) at "
                            "least 0.01 m apart"});
  CHECK(i.line == 4);
  expect_vehicle_error(w + "[[10, 0], [20, 0], [20, 0]]\n", "trajectory.waypoints_m[2]",
                       {"from the previous waypoint"});
  // every violation, one issue each
  try {
    parse_vehicle(w + "[[0, 0], [0, 0.001], [5, 5]]\n", "v.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    REQUIRE(e.issues().size() == 2);
    CHECK(e.issues()[0].path == "trajectory.waypoints_m[0]");
    CHECK(e.issues()[1].path == "trajectory.waypoints_m[1]");
  }
  // exactly 0.01 m apart is fine
  CHECK(parse_ok(w + "[[0, 0.01], [0, 0.02]]\n").trajectory.waypoints.size() == 2);
}

TEST_CASE("vehicle_loader: the planned path's length and duration limits") {
  // 10000 legs of 5000 m: 5e7 m, 1e8 profile steps of 0.5 m
  const std::string big =
      "trajectory:\n  kind: lawnmower\n  lawnmower: {legs: 10000, leg_length_m: 5000}\n";
  expect_vehicle_error(
      big, "trajectory.depth.profile_step_m",
      {"the default 0.5 gives 1.01456e+08 profile steps over the planned path of "
       "5.07282e+07 m",
       "allowed: >= 2.53641 for this path (at most 2e+07 profile steps), or a shorter "
       "path"});
  // with a coarser step it is accepted
  CHECK(parse_ok(big + "  depth: {profile_step_m: 3}\n").trajectory.lawnmower.legs == 10000);
  // a mission longer than 1e9 s
  expect_vehicle_error("trajectory: {length_m: 2000, speed_m_s: 1e-6}\n", "trajectory.speed_m_s",
                       {"1e-06 gives a mission of 2e+09 s over the planned path of 2000 m",
                        "allowed: >= 2e-06 for this path (missions of at most 1e+09 s)"});
  // a path of no finite length
  expect_vehicle_error(
      "trajectory: {kind: lawnmower, lawnmower: {leg_length_m: 1e308, legs: 10}}\n", "trajectory",
      {"the planned path has no finite length"});
}

// ---------------------------------------------------------------------------------------------
// the path and the seabed extent

TEST_CASE("vehicle_loader: find_path_exit") {
  const Vec2 lo(-50, -50);
  const Vec2 hi(50, 50);
  vehicle::TrajectoryDesc t;
  SECTION("a line leaves where it crosses the edge (closed form)") {
    t.start = {-45, 10};
    t.start_heading = rad(45);
    t.straight_length_m = 200;
    const auto exit = find_path_exit(vehicle::plan_path(t), lo, hi);
    REQUIRE(exit);
    // east reaches 50 after 40 / sin(45 deg) m
    CHECK(exit->s_m == Approx(40 * std::sqrt(2.0)));
    CHECK(exit->position_NE.y() == Approx(50));
    CHECK(exit->position_NE.x() == Approx(-5));
    t.straight_length_m = 40 * std::sqrt(2.0) - 1e-9;
    CHECK_FALSE(find_path_exit(vehicle::plan_path(t), lo, hi));
  }
  SECTION("a start outside, an empty box") {
    t.start = {60, 0};
    auto exit = find_path_exit(vehicle::plan_path(t), lo, hi);
    REQUIRE(exit);
    CHECK(exit->s_m == 0);
    t.start = {0, 0};
    exit = find_path_exit(vehicle::plan_path(t), Vec2(1, 1), Vec2(0, 2));
    REQUIRE(exit);
    CHECK(exit->s_m == 0);
  }
  SECTION("arcs: the first exit, against dense sampling of the path") {
    Rng rng(5, RngStream::kDataset, 1);
    int exits = 0;
    for (int k = 0; k < 40; ++k) {
      t.kind = TrajectoryKind::kWaypoints;
      t.start = {rng.uniform(-30, 30), rng.uniform(-30, 30)};
      t.start_heading = rng.uniform(-4, 4);
      t.max_turn_rate_rad_s = rng.uniform(0.05, 0.3);
      t.waypoints.clear();
      for (int j = 0; j < 4; ++j)
        t.waypoints.push_back({rng.uniform(-45, 45), rng.uniform(-45, 45)});
      const auto path = vehicle::plan_path(t);
      const auto exit = find_path_exit(path, lo, hi);
      // the reference: the first of 2 cm samples outside
      std::optional<double> first;
      for (double s = 0; s <= path.length_m(); s += 0.02) {
        const Vec2 p = path.at(s).position_NE;
        if (p.x() < lo.x() || p.x() > hi.x() || p.y() < lo.y() || p.y() > hi.y()) {
          first = s;
          break;
        }
      }
      INFO("path " << k << " of length " << path.length_m());
      if (!first) {
        // no sample left; an exit, if found, grazes the edge between samples
        if (exit) CHECK(exit->position_NE.cwiseAbs().maxCoeff() == Approx(50).margin(1e-4));
        continue;
      }
      ++exits;
      REQUIRE(exit);
      CHECK(exit->s_m <= *first + 1e-9);
      CHECK(exit->s_m >= *first - 0.02 - 1e-9);
      // on the path, on the edge
      const Vec2 p = path.at(exit->s_m).position_NE;
      CHECK((p - exit->position_NE).norm() < 1e-6);
      CHECK(exit->position_NE.cwiseAbs().maxCoeff() == Approx(50).margin(1e-6));
    }
    CHECK(exits > 10);
  }
}

TEST_CASE("vehicle_loader: in altitude mode the path must stay over the seabed") {
  const std::string head = "vehicle:\n  trajectory:\n";
  // 200 m north from [-45, 0] leaves the 100 m seabed at north 50: 95 m, 47.5 s
  const std::string straight = "    start_m: [-45, 0]\n    length_m: 200\n";
  auto i = expect_scenario_error(
      head + straight + "    depth: {mode: altitude, altitude_m: 7.5}\n", "vehicle.trajectory",
      {"the planned path leaves the seabed extent at t = 47.5 s (95 m along the path, on a "
       "straight), position [north, east] = [50, 0] m (line 3, column 5)",
       "allowed: with depth.mode altitude (terrain following), a path that stays over the "
       "modelled seabed: north -50 .. 50, east -50 .. 50 (seabed.origin_m, seabed.extent_m); "
       "turns have radius speed_m_s / max_turn_rate = 20 m"});
  // in constant-depth mode the vehicle may fly beyond the seabed
  CHECK(parse_scenario(head + straight, "s.yaml").vehicle.trajectory.straight_length_m == 200);
  // a larger seabed holds it
  CHECK_NOTHROW(parse_scenario("seabed: {origin_m: [-100, -100], extent_m: [300, 300]}\n" + head +
                                   straight + "    depth: {mode: altitude}\n",
                               "s.yaml"));
  // sway narrows the allowed area on every side
  const std::string inside =
      "    start_m: [-45, 0]\n    length_m: 90\n"
      "    depth: {mode: altitude}\n";
  CHECK_NOTHROW(parse_scenario(head + inside + "    sway: {amplitude_m: 5}\n", "s.yaml"));
  expect_scenario_error(
      head + inside + "    sway: {amplitude_m: 5.5}\n", "vehicle.trajectory",
      {"leaves the seabed extent at t = 0 s", "less sway.amplitude_m 5.5 on every side"});
  // a lawnmower whose keyhole U-turns (radius 20 m, spacing 20 m) overshoot the legs by 46.5 m
  const std::string lm =
      "    kind: lawnmower\n    lawnmower: {origin_m: [-40, -20], leg_length_m: 80, "
      "line_spacing_m: 20, legs: 3}\n    depth: {mode: altitude}\n";
  i = expect_scenario_error(
      head + lm, "vehicle.trajectory",
      {"in the U-turn after lawnmower leg 0", "each U-turn reaches 46.4", "m beyond the leg ends"});
  CHECK(contains(i.problem, "position [north, east] = [50, "));
  // at 15 deg/s the turns have radius 7.6 m and fit
  CHECK_NOTHROW(parse_scenario(head + lm + "    max_turn_rate_deg_s: 15\n", "s.yaml"));
  // a lawnmower leg that leaves
  expect_scenario_error(
      head +
          "    kind: lawnmower\n    lawnmower: {origin_m: [0, 0], leg_length_m: 80, legs: 1}\n"
          "    depth: {mode: altitude}\n",
      "vehicle.trajectory", {"t = 25 s (50 m along the path, on lawnmower leg 0)"});
  // waypoints: the turn towards the second waypoint swings outside
  expect_scenario_error(head +
                            "    kind: waypoints\n    start_m: [0, 0]\n"
                            "    waypoints_m: [[45, 0], [45, -40]]\n"
                            "    depth: {mode: altitude}\n",
                        "vehicle.trajectory", {"in a turn"});
  // the check names the file when loading one
  sonarloop::testing::TempDir dir("config-vehicle-loader-extent");
  {
    std::ofstream out(dir.file("off.yaml"));
    out << head << straight << "    depth: {mode: altitude}\n";
  }
  try {
    load_scenario(dir.file("off.yaml"));
    FAIL("accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(dir.file("off.yaml") + ": vehicle.trajectory: the planned",
                                      0) == 0);
  }
}

// ---------------------------------------------------------------------------------------------
// the shipped files

TEST_CASE("vehicle_loader: the shipped scenarios' vehicles") {
  const std::string dir = SONARLOOP_SOURCE_DIR "/config/";
  // default.yaml: north along east = 0 over the four targets, 7.5 m up, a good INS/DVL
  const auto d = load_scenario(dir + "default.yaml");
  const auto& t = d.vehicle.trajectory;
  CHECK(t.kind == TrajectoryKind::kStraight);
  CHECK(t.start.north_m == -45);
  CHECK(t.start.east_m == 0);
  CHECK(t.start_heading == 0);
  CHECK(t.straight_length_m == 90);
  CHECK(t.speed_m_s == 2);
  CHECK(t.depth.mode == DepthMode::kAltitude);
  CHECK(t.depth.altitude_m == 7.5);
  CHECK(d.vehicle.nav.position_noise_sd_m == 0.1);
  CHECK(d.vehicle.nav.position_drift_m_per_sqrt_s == 0.05);
  CHECK(d.vehicle.nav.heading_noise_sd == rad(0.2));
  CHECK(d.vehicle.nav.heading_bias == rad(0.5));
  for (const auto& target : d.scene.targets) {
    CHECK(target.position_m.x() > t.start.north_m);
    CHECK(target.position_m.x() < t.start.north_m + t.straight_length_m);
  }

  for (const std::string name :
       {"default", "seabed_flat", "seabed_ripples", "seabed_rocky", "seabed_cluttered"}) {
    INFO(name);
    const auto s = load_scenario(dir + name + ".yaml");
    const auto& v = s.vehicle;
    CHECK(v.trajectory.depth.mode == DepthMode::kAltitude);
    CHECK(v.trajectory.depth.altitude_m == 7.5);
    CHECK(v.trajectory.speed_m_s == 2);
    if (name != "default") {
      const auto& m = v.trajectory.lawnmower;
      CHECK(v.trajectory.kind == TrajectoryKind::kLawnmower);
      CHECK(m.legs == 3);
      CHECK(m.leg_length_m == 80);
      CHECK(m.line_spacing_m == 20);
      CHECK(v.trajectory.max_turn_rate_rad_s == rad(15));
      check_same_vehicle(v, load_scenario(dir + "seabed_flat.yaml").vehicle);
    }
    // flown over the real seabed: inside the extent all the way, at the commanded altitude
    const scene::Scene sc(s.scene);
    const vehicle::Trajectory tr(v.trajectory,
                                 [&](double n, double e) { return sc.seabed_z(n, e); });
    const Vec2 lo = s.scene.seabed.origin_m;
    const Vec2 hi = lo + s.scene.seabed.extent_m;
    double min_margin = 1e9;
    for (double ts = 0; ts <= tr.duration_s(); ts += 0.25) {
      const auto st = tr.state_at(sonarloop::from_seconds(ts));
      const Vec2 p = st.pose.position_W.head<2>();
      min_margin =
          std::min({min_margin, p.x() - lo.x(), hi.x() - p.x(), p.y() - lo.y(), hi.y() - p.y()});
      CHECK(st.altitude_m == Approx(7.5).margin(0.5));
    }
    CHECK(min_margin > 2.0);
    CHECK(tr.min_altitude_m() > 7.0);
    CHECK(tr.duration_s() == Approx(name == "default" ? 45.0 : 148.7).margin(0.1));
    // the nav model takes it
    CHECK_NOTHROW(vehicle::NavSensorModel(v.nav, s.scene.seed));
  }
}

namespace {

// The commented-out lines of reference.yaml from the one containing `first` to the one
// containing `last`, uncommented at `column` (where their '#' is).
std::string uncomment(const std::string& text, const std::string& first, const std::string& last,
                      std::size_t column) {
  const auto begin = text.rfind('\n', text.find(first)) + 1;
  const auto end = text.find('\n', text.find(last, begin));
  std::istringstream in(text.substr(begin, end - begin));
  std::string out;
  for (std::string line; std::getline(in, line);) {
    REQUIRE(line.size() > column + 1);
    REQUIRE(line[column] == '#');
    out += line.substr(0, column) + line.substr(column + 2) + "\n";
  }
  return out;
}

}  // namespace

TEST_CASE("vehicle_loader: config/reference.yaml gives exactly the documented defaults") {
  const std::string path = SONARLOOP_SOURCE_DIR "/config/reference.yaml";
  const auto ref = load_scenario(path);
  check_same_vehicle(ref.vehicle, VehicleDesc{});

  // every key of every map is documented in the vehicle section, live or commented out (the keys
  // of the other kinds and mode), each with a comment
  const std::string text = slurp(path);
  const auto section = text.find("\nvehicle:\n");
  REQUIRE(section != std::string::npos);
  const std::string vehicle_text = text.substr(section);
  for (const auto* keys :
       {&kTrajectoryKeys, &kLawnmowerKeys, &kDepthKeys, &kSwayKeys, &kAttitudeKeys, &kNavKeys}) {
    for (const auto& key : *keys) {
      INFO(key);
      const auto at = vehicle_text.find(" " + key + ":");
      REQUIRE(at != std::string::npos);
      const auto bol = vehicle_text.rfind('\n', at) + 1;
      const auto eol = vehicle_text.find('\n', at);
      const std::string line = vehicle_text.substr(bol, eol - bol);
      const bool live = line.find_first_not_of(' ') == line.find(key);
      const bool is_map =
          key == "lawnmower" || key == "depth" || key == "sway" || key == "attitude";
      // a comment after the value (the second '#' on a commented-out line)
      const auto hash = line.find('#', line.find(key));
      if (!is_map) CHECK(hash != std::string::npos);
      if (!live) CHECK(line.find('#') < line.find(key));
    }
  }
  const Field root = parse_document(text, path);
  const Field v = root.child("vehicle");
  REQUIRE(v.is_map());
  const Field traj = v.child("trajectory");
  for (const auto& key : kTrajectoryKeys) {
    if (key != "waypoints_m" && key != "lawnmower") CHECK(traj.has(key));
  }
  const Field nav = v.child("nav");
  for (const auto& key : kNavKeys)
    CHECK(nav.has(key));

  // the commented-out lawnmower block gives the LawnmowerDesc defaults
  VehicleDesc expect_lm;
  expect_lm.trajectory.kind = TrajectoryKind::kLawnmower;
  const auto lm = parse_ok("trajectory:\n    kind: lawnmower\n" +
                           uncomment(text, "    # lawnmower:", "    #   first_turn:", 4));
  check_same_vehicle(lm, expect_lm);
  // and the commented-out altitude keys the DepthDesc defaults
  const auto alt =
      parse_ok("trajectory:\n    depth:\n      mode: altitude\n" +
               uncomment(text, "      # altitude_m:", "      # vertical_smoothing_m:", 6));
  VehicleDesc expect_alt;
  expect_alt.trajectory.depth.mode = DepthMode::kAltitude;
  check_same_vehicle(alt, expect_alt);
  // the waypoints example parses
  const auto wp = parse_ok("trajectory:\n    kind: waypoints\n" +
                           uncomment(text, "    # waypoints_m:", "    # waypoints_m:", 4));
  CHECK(wp.trajectory.waypoints.size() == 2);
}

// ---------------------------------------------------------------------------------------------
// files and formatting

TEST_CASE("vehicle_loader: load_vehicle reads a file and names it in errors") {
  sonarloop::testing::TempDir dir("config-vehicle-loader");
  {
    std::ofstream out(dir.file("auv.yaml"));
    out << "trajectory:\n  kind: lawnmower\n  lawnmower: {legs: 2}\nnav: {heading_bias_deg: 1}\n";
  }
  const auto v = load_vehicle(dir.file("auv.yaml"));
  CHECK(v.trajectory.lawnmower.legs == 2);
  CHECK(v.nav.heading_bias == rad(1));
  try {
    load_vehicle(dir.file("missing.yaml"));
    FAIL("loaded a missing file");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(dir.file("missing.yaml") + ": (file): no such file", 0) == 0);
  }
  {
    std::ofstream out(dir.file("bad.yaml"));
    out << "nav:\n  heading_bias_deg: 200\n";
  }
  try {
    load_vehicle(dir.file("bad.yaml"));
    FAIL("accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(
              dir.file("bad.yaml") +
                  ": nav.heading_bias_deg: 200 is out of range (line 2, column 21)",
              0) == 0);
  }
  // malformed YAML
  expect_vehicle_error("trajectory: {kind: straight\n", "", {"YAML syntax error"});
}

TEST_CASE("vehicle_loader: format_vehicle_yaml writes the keys of the kind and round-trips") {
  VehicleDesc d;
  d.trajectory.kind = TrajectoryKind::kWaypoints;
  d.trajectory.waypoints = {{1.5, 2.25}, {-3, 4}};
  d.trajectory.start_heading = 0.1;  // no short decimal in degrees
  d.trajectory.max_turn_rate_rad_s = rad(15);
  d.trajectory.attitude.max_roll = 0.3;
  d.trajectory.attitude.roll_amplitude = rad(5);
  d.trajectory.attitude.pitch_amplitude = 0.05;  // no short decimal in degrees
  d.trajectory.attitude.wave_period_s = 6.5;
  d.nav.heading_bias = rad(0.5);
  d.nav.heading_noise_sd = 1e-4;
  const std::string yaml = format_vehicle_yaml(d, 2);
  INFO(yaml);
  CHECK(yaml.rfind("  trajectory:\n    kind: waypoints\n", 0) == 0);
  CHECK(contains(yaml, "\n    waypoints_m: [[1.5, 2.25], [-3, 4]]\n"));
  CHECK(contains(yaml, "\n    max_turn_rate_deg_s: 15\n"));
  CHECK(contains(yaml, "\n    heading_bias_deg: 0.5\n"));
  CHECK(contains(yaml,
                 "\n      max_pitch_deg: 28.64788975654116\n      roll_amplitude_deg: 5\n"
                 "      pitch_amplitude_deg: 2.864788975654116\n      wave_period_s: 6.5\n"
                 "  nav:\n"));
  CHECK_FALSE(contains(yaml, "length_m"));
  CHECK_FALSE(contains(yaml, "lawnmower"));
  CHECK_FALSE(contains(yaml, "altitude_m"));
  check_same_vehicle(
      parse_vehicle_node(parse_document("vehicle:\n" + yaml, "f.yaml").child("vehicle")), d);
  // the defaults, and each kind and mode
  check_same_vehicle(parse_ok(format_vehicle_yaml(VehicleDesc{})), VehicleDesc{});
  VehicleDesc l;
  l.trajectory.kind = TrajectoryKind::kLawnmower;
  l.trajectory.lawnmower.first_turn = TurnDirection::kPort;
  l.trajectory.depth.mode = DepthMode::kAltitude;
  l.trajectory.depth.altitude_m = 7.5;
  const std::string lyaml = format_vehicle_yaml(l);
  INFO(lyaml);
  CHECK(contains(lyaml, "\n  lawnmower:\n    origin_m: [0, 0]\n"));
  CHECK(contains(lyaml, "\n    first_turn: port\n"));
  CHECK(contains(lyaml, "\n    mode: altitude\n    altitude_m: 7.5\n"));
  CHECK_FALSE(contains(lyaml, "\n    depth_m:"));
  CHECK_FALSE(contains(lyaml, "start_m"));
  check_same_vehicle(parse_ok(lyaml), l);
  // the defaults in degrees are the shortest exact texts (as in config/reference.yaml)
  const std::string def = format_vehicle_yaml(VehicleDesc{});
  CHECK(contains(def, "max_turn_rate_deg_s: 5.729577951308232\n"));
  CHECK(contains(def, "max_roll_deg: 20.05352282957881\n"));
  CHECK(contains(def, "max_pitch_deg: 28.64788975654116\n"));
  CHECK(contains(def,
                 "\n    roll_amplitude_deg: 0\n    pitch_amplitude_deg: 0\n"
                 "    wave_period_s: 8\nnav:\n"));
}
