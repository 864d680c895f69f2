// Tests of the vehicle loader (config/loader/vehicle_loader.h): every key and its unit
// conversion, the defaults (VehicleDesc{}), each trajectory kind and depth mode, the shipped
// scenarios' vehicles, config/reference.yaml, reading files and writing YAML. What the loader
// refuses is in vehicle_loader_errors_test.cpp, the seeded randomized test in
// vehicle_loader_random_test.cpp.
#include "config/loader/vehicle_loader.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/config_test_text.h"
#include "tests/config/vehicle_checks.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "config/loader/scenario_loader.h"
#include "sim/scene/scene.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/path.h"
#include "sim/vehicle/trajectory.h"
#include "tests/support/temp_dir.h"

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
using sonarloop::testing::expect_vehicle_error;
using sonarloop::testing::flat_seabed;
using sonarloop::testing::kAttitudeKeys;
using sonarloop::testing::kDepthKeys;
using sonarloop::testing::kLawnmowerKeys;
using sonarloop::testing::kNavKeys;
using sonarloop::testing::kSwayKeys;
using sonarloop::testing::kTrajectoryKeys;
using sonarloop::testing::parse_ok;
using sonarloop::testing::rad;
using sonarloop::testing::slurp;

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
