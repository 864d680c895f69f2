// Tests of what the vehicle loader (config/loader/vehicle_loader.h) refuses: keys of other kinds
// and modes, unknown keys, wrong types, every validation rule (per-key ranges, validate()'s
// cross-field rules, the path limits, the seabed extent in altitude mode), each error at its YAML
// key with the allowed values. The accepted documents are in vehicle_loader_test.cpp.
#include "config/loader/vehicle_loader.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/config_test_text.h"
#include "tests/config/scenario_checks.h"
#include "tests/config/vehicle_checks.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/rng.h"
#include "config/loader/scenario_loader.h"
#include "sim/vehicle/path.h"
#include "sim/vehicle/trajectory.h"
#include "tests/support/temp_dir.h"

using sonarloop::Rng;
using sonarloop::RngStream;
using sonarloop::Vec2;
using namespace sonarloop::config;
namespace vehicle = sonarloop::vehicle;
using vehicle::TrajectoryKind;

using sonarloop::testing::contains;
using sonarloop::testing::expect_scenario_error;
using sonarloop::testing::expect_vehicle_error;
using sonarloop::testing::kAttitudeKeys;
using sonarloop::testing::kDepthKeys;
using sonarloop::testing::kLawnmowerKeys;
using sonarloop::testing::kNavKeys;
using sonarloop::testing::kSwayKeys;
using sonarloop::testing::parse_ok;
using sonarloop::testing::rad;
using sonarloop::testing::slurp;

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
