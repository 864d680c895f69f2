// The vehicle loader's seeded randomized test (docs/style.md habit 22): random valid vehicles,
// written as YAML in every layout the loader reads (block or flow, standalone or under
// `vehicle:`), round-trip exactly; corruptions of them are always rejected with a ConfigError;
// and random byte edits give a vehicle or a ConfigError, never a crash. (The fixed cases are in
// vehicle_loader_test.cpp.)
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "common/rng.h"
#include "config/loader/scenario_loader.h"
#include "config/loader/vehicle_loader.h"
#include "sim/vehicle/nav_sensor.h"
#include "sim/vehicle/trajectory.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/config_test_text.h"
#include "tests/config/vehicle_checks.h"

using sonarloop::Rng;
using sonarloop::RngStream;
using namespace sonarloop::config;
namespace vehicle = sonarloop::vehicle;
using vehicle::DepthMode;
using vehicle::TrajectoryKind;
using vehicle::TurnDirection;
using vehicle::VehicleDesc;

using sonarloop::testing::check_same_vehicle;
using sonarloop::testing::contains;
using sonarloop::testing::feed_byte_edits;
using sonarloop::testing::flat_seabed;
using sonarloop::testing::real_text;

namespace {

// A YAML map entry: a scalar or flow text, or a nested map.
struct Node {
  std::string key;
  std::string text;
  std::vector<Node> children;
  bool map = false;
};

std::string render_nodes(const std::vector<Node>& nodes, bool flow, int indent) {
  std::string out;
  if (flow) {
    out = "{";
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      out += (i ? ", " : "") + nodes[i].key + ": " +
             (nodes[i].map ? render_nodes(nodes[i].children, true, 0) : nodes[i].text);
    }
    return out + "}";
  }
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  for (const auto& n : nodes) {
    if (n.map) {
      out += pad + n.key + ":";
      if (n.children.empty()) {
        out += " {}\n";
      } else {
        out += "\n";
        out += render_nodes(n.children, false, indent + 2);
      }
    } else {
      out += pad + n.key + ": " + n.text + "\n";
    }
  }
  return out;
}

// How a leaf's value is read, for corrupting it.
enum class Leaf { kReal, kInt, kWord, kPair, kWaypoints };

struct LeafRef {
  std::vector<std::size_t> where;  // indices from the root through the maps
  std::string path;                // relative to the vehicle node
  Leaf kind;
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
};

constexpr double kInf = std::numeric_limits<double>::infinity();

class VehicleGenerator {
 public:
  explicit VehicleGenerator(std::uint64_t sample) : rng_(20240917, RngStream::kDataset, sample) {}
  Rng& rng() { return rng_; }

  // A random valid vehicle map and the VehicleDesc it describes; `leaves` lists every value set.
  void generate(std::vector<Node>& root, VehicleDesc& expect, std::vector<LeafRef>& leaves) {
    for (int attempt = 0;; ++attempt) {
      REQUIRE(attempt < 1000);
      root.clear();
      leaves.clear();
      expect = VehicleDesc{};
      p_ = rng_.uniform();
      build(root, expect);
      if (!vehicle::validate(expect).empty()) continue;
      const double length = vehicle::plan_path(expect.trajectory).length_m();
      if (!(length / expect.trajectory.depth.profile_step_m <= 2e5)) continue;  // keep it quick
      if (!(length / expect.trajectory.speed_m_s <= kMaxMissionDurationS)) continue;
      shuffle(root);
      collect(root, {}, "", leaves);
      return;
    }
  }

  // the spec of a leaf key, for corruptions
  struct Spec {
    Leaf kind;
    double lo, hi;
  };
  static Spec spec_of(const std::string& key) {
    static const std::vector<std::pair<std::string, Spec>> specs = {
        {"kind", {Leaf::kWord, 0, 0}},
        {"start_m", {Leaf::kPair, -kInf, kInf}},
        {"heading_deg", {Leaf::kReal, -kInf, kInf}},
        {"length_m", {Leaf::kReal, 0, kInf}},
        {"waypoints_m", {Leaf::kWaypoints, 0, 0}},
        {"origin_m", {Leaf::kPair, -kInf, kInf}},
        {"first_leg_heading_deg", {Leaf::kReal, -kInf, kInf}},
        {"leg_length_m", {Leaf::kReal, 0, kInf}},
        {"line_spacing_m", {Leaf::kReal, 0, kInf}},
        {"legs", {Leaf::kInt, 1, 10000}},
        {"first_turn", {Leaf::kWord, 0, 0}},
        {"speed_m_s", {Leaf::kReal, 0, 20}},
        {"max_turn_rate_deg_s", {Leaf::kReal, 0, 114.59155902616465}},
        {"mode", {Leaf::kWord, 0, 0}},
        {"depth_m", {Leaf::kReal, 0, kInf}},
        {"altitude_m", {Leaf::kReal, 0, kInf}},
        {"max_climb_rate_m_s", {Leaf::kReal, 0, 20}},
        {"look_ahead_m", {Leaf::kReal, 0, kInf}},
        {"min_depth_m", {Leaf::kReal, 0, kInf}},
        {"vertical_smoothing_m", {Leaf::kReal, 0, 1000}},
        {"profile_step_m", {Leaf::kReal, 0.05, 10}},
        {"amplitude_m", {Leaf::kReal, 0, kInf}},
        {"period_s", {Leaf::kReal, 0, kInf}},
        {"phase_deg", {Leaf::kReal, -kInf, kInf}},
        {"yaw_coupling", {Leaf::kReal, 0, 1}},
        {"roll_gain", {Leaf::kReal, -10, 10}},
        {"max_roll_deg", {Leaf::kReal, 0, 90}},
        {"roll_time_constant_s", {Leaf::kReal, 0, 3600}},
        {"pitch_gain", {Leaf::kReal, 0, 10}},
        {"max_pitch_deg", {Leaf::kReal, 0, 90}},
        {"roll_amplitude_deg", {Leaf::kReal, 0, 45}},
        {"pitch_amplitude_deg", {Leaf::kReal, 0, 45}},
        {"wave_period_s", {Leaf::kReal, 1, 600}},
        {"position_noise_m", {Leaf::kReal, 0, kInf}},
        {"position_drift_m_per_sqrt_s", {Leaf::kReal, 0, kInf}},
        {"heading_bias_deg", {Leaf::kReal, -180, 180}},
        {"heading_noise_deg", {Leaf::kReal, 0, kInf}},
        {"heading_drift_deg_per_sqrt_s", {Leaf::kReal, 0, kInf}},
        {"attitude_noise_deg", {Leaf::kReal, 0, kInf}},
        {"speed_noise_m_s", {Leaf::kReal, 0, kInf}},
        {"speed_scale_error", {Leaf::kReal, -0.5, 0.5}},
        {"yaw_rate_noise_deg_s", {Leaf::kReal, 0, kInf}},
        {"depth_noise_m", {Leaf::kReal, 0, kInf}},
        {"altitude_noise_m", {Leaf::kReal, 0, kInf}},
        {"noise_step_s", {Leaf::kReal, 1e-9, 3600}},
        {"drift_step_s", {Leaf::kReal, 1e-9, 3600}},
    };
    for (const auto& [k, s] : specs) {
      if (k == key) return s;
    }
    FAIL("no spec for " << key);
    return {Leaf::kReal, 0, 0};
  }

 private:
  bool maybe() { return rng_.uniform() < p_; }

  // a value in [lo, hi] (`open` ends excluded), sometimes on a closed bound or an integer;
  // unbounded ranges draw within [soft_lo, soft_hi]
  double draw(double lo, double hi, bool lo_open, bool hi_open, double soft_lo, double soft_hi) {
    const double a = std::isfinite(lo) ? lo : soft_lo;
    const double b = std::isfinite(hi) ? std::min(hi, soft_hi) : soft_hi;
    const double u = rng_.uniform();
    if (u < 0.08 && !lo_open && std::isfinite(lo)) return lo;
    if (u < 0.16 && !hi_open && std::isfinite(hi) && hi <= soft_hi) return hi;
    double v = 0;
    if (u < 0.35) {
      v = std::round(rng_.uniform(a, b));
    } else if (a > 0 && b / a >= 100) {
      v = std::exp(rng_.uniform(std::log(a), std::log(b)));
    } else {
      v = rng_.uniform(a, b);
    }
    // just inside an open bound (not a subnormal number next to 0, which no YAML reader takes)
    if ((lo_open && v <= lo) || v < lo) v = lo == 0 ? 1e-12 : std::nextafter(lo, kInf);
    if ((hi_open && v >= hi) || v > hi) v = std::nextafter(hi, -kInf);
    return v;
  }

  // adds `key: value` (a number) to `map` with probability p (or always), returns the value
  void number(std::vector<Node>& map, const std::string& key, double& out, double si_factor,
              double lo, double hi, bool lo_open, bool hi_open, double soft_lo, double soft_hi,
              bool always = false) {
    if (!always && !maybe()) return;
    const double v = draw(lo, hi, lo_open, hi_open, soft_lo, soft_hi);
    const std::string text = real_text(v);
    map.push_back({key, text, {}, false});
    out = si_factor == 1.0 ? std::stod(text) : std::stod(text) * si_factor;
  }

  std::string pair(double& north, double& east, double range) {
    north = std::round(rng_.uniform(-range, range) * 8) / 8;
    east = rng_.uniform(-range, range);
    const std::string e = real_text(east);
    east = std::stod(e);
    return std::string("[").append(real_text(north)).append(", ").append(e).append("]");
  }

  void build(std::vector<Node>& root, VehicleDesc& d) {
    const double deg = std::numbers::pi / 180.0;
    auto& t = d.trajectory;
    Node traj{"trajectory", "", {}, true};
    auto& tm = traj.children;
    const auto kind = static_cast<int>(rng_.below(3));
    t.kind = static_cast<TrajectoryKind>(kind);
    if (t.kind != TrajectoryKind::kStraight || rng_.uniform() < 0.5) {
      tm.push_back({"kind", std::string(vehicle::to_string(t.kind)), {}, false});
    }
    if (t.kind != TrajectoryKind::kLawnmower) {
      if (maybe()) tm.push_back({"start_m", pair(t.start.north_m, t.start.east_m, 500), {}, false});
      number(tm, "heading_deg", t.start_heading, deg, -kInf, kInf, false, false, -720, 720);
    }
    if (t.kind == TrajectoryKind::kStraight) {
      number(tm, "length_m", t.straight_length_m, 1, 0, kInf, true, false, 0.01, 3000);
    } else if (t.kind == TrajectoryKind::kWaypoints) {
      const auto n = 1 + rng_.below(5);
      std::string list = "[";
      vehicle::NorthEast prev = t.start;
      for (std::uint64_t i = 0; i < n; ++i) {
        const double step = rng_.uniform(1, 300);
        const double dir = rng_.uniform(-4, 4);
        vehicle::NorthEast w{prev.north_m + step * std::cos(dir),
                             prev.east_m + step * std::sin(dir)};
        const std::string tn = real_text(w.north_m);
        const std::string te = real_text(w.east_m);
        w = {std::stod(tn), std::stod(te)};
        list += (i ? ", [" : "[") + tn + ", " + te + "]";
        t.waypoints.push_back(w);
        prev = w;
      }
      tm.push_back({"waypoints_m", list + "]", {}, false});
    } else if (maybe()) {
      Node lm{"lawnmower", "", {}, true};
      auto& m = t.lawnmower;
      if (maybe())
        lm.children.push_back(
            {"origin_m", pair(m.origin.north_m, m.origin.east_m, 500), {}, false});
      number(lm.children, "first_leg_heading_deg", m.first_leg_heading, deg, -kInf, kInf, false,
             false, -400, 400);
      number(lm.children, "leg_length_m", m.leg_length_m, 1, 0, kInf, true, false, 0.01, 2000);
      number(lm.children, "line_spacing_m", m.line_spacing_m, 1, 0, kInf, true, false, 0.01, 500);
      if (maybe()) {
        m.legs = 1 + static_cast<int>(rng_.below(12));
        lm.children.push_back({"legs", std::to_string(m.legs), {}, false});
      }
      if (maybe()) {
        m.first_turn = rng_.uniform() < 0.5 ? TurnDirection::kStarboard : TurnDirection::kPort;
        lm.children.push_back(
            {"first_turn", std::string(vehicle::to_string(m.first_turn)), {}, false});
      }
      tm.push_back(lm);
    }
    number(tm, "speed_m_s", t.speed_m_s, 1, 0, 20, true, false, 0.2, 20);
    number(tm, "max_turn_rate_deg_s", t.max_turn_rate_rad_s, deg, 0, 114.59155902616465, true,
           false, 1, 114.59155902616465);
    if (maybe()) {
      Node dn{"depth", "", {}, true};
      auto& dd = t.depth;
      auto& c = dn.children;
      dd.mode = rng_.uniform() < 0.5 ? DepthMode::kAltitude : DepthMode::kConstantDepth;
      if (dd.mode == DepthMode::kAltitude || rng_.uniform() < 0.5) {
        c.push_back({"mode", std::string(vehicle::to_string(dd.mode)), {}, false});
      }
      if (dd.mode == DepthMode::kConstantDepth) {
        number(c, "depth_m", dd.depth_m, 1, 0, kInf, false, false, 0, 6000);
      } else {
        number(c, "altitude_m", dd.altitude_m, 1, 0, kInf, true, false, 0.1, 100);
        number(c, "max_climb_rate_m_s", dd.max_climb_rate_m_s, 1, 0, 20, true, false, 0.01, 20);
        number(c, "look_ahead_m", dd.look_ahead_m, 1, 0, kInf, false, false, 0, 500);
        number(c, "min_depth_m", dd.min_depth_m, 1, 0, kInf, false, false, 0, 50);
        number(c, "vertical_smoothing_m", dd.vertical_smoothing_m, 1, 0, 1000, false, false, 0,
               1000);
      }
      number(c, "profile_step_m", dd.profile_step_m, 1, 0.05, 10, false, false, 0.05, 10);
      tm.push_back(dn);
    }
    if (maybe()) {
      Node sn{"sway", "", {}, true};
      auto& s = t.sway;
      number(sn.children, "amplitude_m", s.amplitude_m, 1, 0, kInf, false, false, 0, 5);
      number(sn.children, "period_s", s.period_s, 1, 0, kInf, true, false, 0.5, 120);
      number(sn.children, "phase_deg", s.phase, deg, -kInf, kInf, false, false, -360, 360);
      number(sn.children, "yaw_coupling", s.yaw_coupling, 1, 0, 1, false, false, 0, 1);
      tm.push_back(sn);
    }
    if (maybe()) {
      Node an{"attitude", "", {}, true};
      auto& a = t.attitude;
      number(an.children, "roll_gain", a.roll_gain, 1, -10, 10, false, false, -10, 10);
      number(an.children, "max_roll_deg", a.max_roll, deg, 0, 90, true, true, 0, 90);
      number(an.children, "roll_time_constant_s", a.roll_time_constant_s, 1, 0, 3600, false, false,
             0, 3600);
      number(an.children, "pitch_gain", a.pitch_gain, 1, 0, 10, false, false, 0, 10);
      number(an.children, "max_pitch_deg", a.max_pitch, deg, 0, 90, true, true, 0, 90);
      number(an.children, "roll_amplitude_deg", a.roll_amplitude, deg, 0, 45, false, false, 0, 45);
      number(an.children, "pitch_amplitude_deg", a.pitch_amplitude, deg, 0, 45, false, false, 0,
             45);
      number(an.children, "wave_period_s", a.wave_period_s, 1, 1, 600, false, false, 1, 600);
      tm.push_back(an);
    }
    if (!tm.empty() || rng_.uniform() < 0.5) root.push_back(traj);
    if (maybe()) {
      Node nn{"nav", "", {}, true};
      auto& n = d.nav;
      auto& c = nn.children;
      number(c, "position_noise_m", n.position_noise_sd_m, 1, 0, kInf, false, false, 0, 5);
      number(c, "position_drift_m_per_sqrt_s", n.position_drift_m_per_sqrt_s, 1, 0, kInf, false,
             false, 0, 0.5);
      number(c, "heading_bias_deg", n.heading_bias, deg, -180, 180, false, false, -180, 180);
      number(c, "heading_noise_deg", n.heading_noise_sd, deg, 0, kInf, false, false, 0, 2);
      number(c, "heading_drift_deg_per_sqrt_s", n.heading_drift_rad_per_sqrt_s, deg, 0, kInf, false,
             false, 0, 0.1);
      number(c, "attitude_noise_deg", n.attitude_noise_sd, deg, 0, kInf, false, false, 0, 1);
      number(c, "speed_noise_m_s", n.speed_noise_sd_m_s, 1, 0, kInf, false, false, 0, 0.1);
      number(c, "speed_scale_error", n.speed_scale_factor_error, 1, -0.5, 0.5, true, true, -0.5,
             0.5);
      number(c, "yaw_rate_noise_deg_s", n.yaw_rate_noise_sd_rad_s, deg, 0, kInf, false, false, 0,
             0.5);
      number(c, "depth_noise_m", n.depth_noise_sd_m, 1, 0, kInf, false, false, 0, 0.5);
      number(c, "altitude_noise_m", n.altitude_noise_sd_m, 1, 0, kInf, false, false, 0, 0.5);
      number(c, "noise_step_s", n.noise_step_s, 1, 1e-9, 3600, false, false, 1e-9, 3600);
      number(c, "drift_step_s", n.drift_step_s, 1, 1e-9, 3600, false, false, 1e-9, 3600);
      root.push_back(nn);
    }
  }

  void shuffle(std::vector<Node>& nodes) {
    for (std::size_t i = nodes.size(); i > 1; --i)
      std::swap(nodes[i - 1], nodes[rng_.below(i)]);
    for (auto& n : nodes) {
      if (n.map) shuffle(n.children);
    }
  }

  static void collect(const std::vector<Node>& nodes, std::vector<std::size_t> where,
                      const std::string& prefix, std::vector<LeafRef>& out) {
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      auto w = where;
      w.push_back(i);
      const std::string path = prefix + nodes[i].key;
      if (nodes[i].map) {
        collect(nodes[i].children, w, path + ".", out);
      } else {
        const Spec s = spec_of(nodes[i].key);
        out.push_back({w, path, s.kind, s.lo, s.hi});
      }
    }
  }

  Rng rng_;
  double p_ = 0.5;
};

Node& node_at(std::vector<Node>& root, const std::vector<std::size_t>& where) {
  std::vector<Node>* level = &root;
  Node* n = nullptr;
  for (std::size_t i : where) {
    n = &(*level)[i];
    level = &n->children;
  }
  return *n;
}

// the map at a key path (created if missing), for adding keys
std::vector<Node>& map_at(std::vector<Node>& root, const std::vector<std::string>& keys) {
  std::vector<Node>* level = &root;
  for (const auto& k : keys) {
    auto it = std::find_if(level->begin(), level->end(), [&](const Node& n) { return n.key == k; });
    if (it == level->end()) {
      level->push_back({k, "", {}, true});
      it = level->end() - 1;
    }
    level = &it->children;
  }
  return *level;
}

// A vehicle map under `vehicle:` in a larger document, or a standalone document.
VehicleDesc parse_either(const std::vector<Node>& root, bool nested, bool flow,
                         const std::string& file) {
  const std::string body =
      flow ? render_nodes(root, true, 0) + "\n" : render_nodes(root, false, nested ? 2 : 0);
  if (!nested) return parse_vehicle(body, file);
  const std::string text = "other: 1\nvehicle:" + (flow ? " " + body : "\n" + body);
  return parse_vehicle_node(parse_document(text, file).child("vehicle"));
}

}  // namespace

TEST_CASE("vehicle_loader: random valid vehicles round-trip, corruptions are rejected") {
  constexpr int kSamples = 400;
  constexpr int kCorruptionsPerSample = 6;
  int corruptions = 0;
  int kinds[3] = {0, 0, 0};
  int altitude = 0;
  for (int sample = 0; sample < kSamples; ++sample) {
    VehicleGenerator gen(static_cast<std::uint64_t>(sample));
    std::vector<Node> root;
    VehicleDesc expect;
    std::vector<LeafRef> leaves;
    gen.generate(root, expect, leaves);
    Rng& rng = gen.rng();
    const bool nested = rng.uniform() < 0.5;
    const bool flow = rng.uniform() < 0.3;
    const std::string file = "random-" + std::to_string(sample) + ".yaml";
    INFO("sample " << sample << " (nested " << nested << ", flow " << flow << "):\n"
                   << render_nodes(root, false, 0));
    VehicleDesc got;
    try {
      got = parse_either(root, nested, flow, file);
    } catch (const ConfigError& e) {
      FAIL("valid vehicle rejected: " << e.what());
    }
    check_same_vehicle(got, expect);
    ++kinds[static_cast<int>(got.trajectory.kind)];
    // written out and read back, bit for bit
    const std::string written = format_vehicle_yaml(got);
    INFO("written:\n" << written);
    check_same_vehicle(parse_vehicle(written, "written.yaml"), got);
    // the planner and the nav model accept every vehicle the loader accepts
    try {
      const bool alt = got.trajectory.depth.mode == DepthMode::kAltitude;
      altitude += alt ? 1 : 0;
      const vehicle::Trajectory tr(got.trajectory,
                                   alt ? vehicle::SeabedDepthFn(flat_seabed) : nullptr);
      CHECK(tr.duration_s() > 0);
      const vehicle::NavSensorModel nav(got.nav, 1);
      CHECK(std::isfinite(nav.measure(tr.state_at(tr.end_time() / 2)).north_m));
    } catch (const std::exception& e) {
      FAIL("the vehicle model rejected a loaded vehicle: " << e.what());
    }

    for (int c = 0; c < kCorruptionsPerSample; ++c) {
      std::vector<Node> bad = root;
      std::string expect_path;
      std::string what;
      const double u = rng.uniform();
      if (u < 0.15 || leaves.empty()) {
        // an unknown key in one of the maps
        static const std::vector<std::vector<std::string>> maps = {{},
                                                                   {"trajectory"},
                                                                   {"trajectory", "depth"},
                                                                   {"trajectory", "sway"},
                                                                   {"trajectory", "attitude"},
                                                                   {"nav"}};
        const auto& keys = maps[rng.below(maps.size())];
        map_at(bad, keys).push_back({"zz_unknown", "1", {}, false});
        for (const auto& k : keys)
          expect_path += k + ".";
        expect_path += "zz_unknown";
        what = "unknown key";
      } else if (u < 0.3) {
        // a key of another kind or depth mode
        const auto kind = expect.trajectory.kind;
        auto& traj = map_at(bad, {"trajectory"});
        if (rng.uniform() < 0.5) {
          const bool has_kind =
              std::any_of(traj.begin(), traj.end(), [](const Node& n) { return n.key == "kind"; });
          if (!has_kind) traj.push_back({"kind", std::string(vehicle::to_string(kind)), {}, false});
          if (kind == TrajectoryKind::kStraight) {
            traj.push_back({"waypoints_m", "[[1, 2]]", {}, false});
            expect_path = "trajectory.waypoints_m";
          } else if (kind == TrajectoryKind::kWaypoints) {
            traj.push_back({"lawnmower", "{}", {}, false});
            expect_path = "trajectory.lawnmower";
          } else {
            traj.push_back({"length_m", "10", {}, false});
            expect_path = "trajectory.length_m";
          }
        } else {
          auto& depth = map_at(bad, {"trajectory", "depth"});
          if (expect.trajectory.depth.mode == DepthMode::kAltitude) {
            depth.push_back({"depth_m", "10", {}, false});
            expect_path = "trajectory.depth.depth_m";
          } else {
            depth.push_back({"look_ahead_m", "10", {}, false});
            expect_path = "trajectory.depth.look_ahead_m";
          }
        }
        what = "foreign key " + expect_path;
      } else {
        const LeafRef& leaf = leaves[rng.below(leaves.size())];
        Node& n = node_at(bad, leaf.where);
        expect_path = leaf.path;
        std::vector<std::pair<std::string, std::string>> options;  // text, path suffix
        switch (leaf.kind) {
          case Leaf::kReal:
            options = {{"abc", ""},    {".nan", ""}, {".inf", ""},  {"'5'", ""}, {"[1, 2]", ""},
                       {"{a: 1}", ""}, {"~", ""},    {"1e999", ""}, {"true", ""}};
            if (std::isfinite(leaf.lo)) {
              options.push_back({real_text(leaf.lo - 0.5 * std::max(std::fabs(leaf.lo), 1.0)), ""});
              if (leaf.lo == 0 && leaf.hi > 0) options.push_back({"-1e-300", ""});
            }
            if (std::isfinite(leaf.hi)) {
              options.push_back({real_text(leaf.hi + 0.5 * std::max(std::fabs(leaf.hi), 1.0)), ""});
              options.push_back({real_text(std::nextafter(leaf.hi, kInf) +
                                           1e-9 * std::max(std::fabs(leaf.hi), 1.0)),
                                 ""});
            }
            break;
          case Leaf::kInt:
            options = {{"1.5", ""}, {"abc", ""}, {"0", ""},          {"10001", ""},
                       {"~", ""},   {"[1]", ""}, {"99999999999", ""}};
            break;
          case Leaf::kWord:
            options = {{"zz_word", ""}, {"[1, 2]", ""}, {"{a: 1}", ""}, {"~", ""}, {"7", ""}};
            break;
          case Leaf::kPair:
            options = {{"5", ""},      {"[1]", ""},       {"[1, 2, 3]", ""},   {"~", ""},
                       {"{a: 1}", ""}, {"[a, 1]", "[0]"}, {"[1, .nan]", "[1]"}};
            break;
          case Leaf::kWaypoints:
            options = {{"[]", ""},       {"5", ""},      {"~", ""},
                       {"[[1]]", "[0]"}, {"[7]", "[0]"}, {"[[5, 5], [5, 5]]", "[1]"},
                       {"{a: 1}", ""}};
            break;
        }
        const auto& o = options[rng.below(options.size())];
        n.text = o.first;
        expect_path += o.second;
        what = "set " + leaf.path + " to '" + n.text + "'";
      }
      INFO("corruption: " << what << "\n" << render_nodes(bad, false, 0));
      ++corruptions;
      try {
        parse_either(bad, nested, flow, file);
        FAIL("corrupted vehicle accepted");
      } catch (const ConfigError& e) {
        const std::string msg = e.what();
        INFO("message: " << msg);
        CHECK(msg.rfind(file + ": ", 0) == 0);
        CHECK(contains(msg, "; allowed: "));
        CHECK(e.first().path == (nested ? "vehicle." : "") + expect_path);
      } catch (const std::exception& e) {
        FAIL("not a ConfigError: " << e.what());
      }
    }
  }
  CHECK(corruptions == kSamples * kCorruptionsPerSample);
  for (int k : kinds)
    CHECK(k > 50);
  CHECK(altitude > 50);
}

TEST_CASE("vehicle_loader: random byte edits give a vehicle or a ConfigError, never a crash") {
  VehicleDesc base;
  base.trajectory.kind = TrajectoryKind::kLawnmower;
  base.trajectory.depth.mode = DepthMode::kAltitude;
  base.trajectory.sway.amplitude_m = 1;
  base.nav.position_noise_sd_m = 0.1;
  Rng rng(12, RngStream::kDataset, 8);
  const auto n = feed_byte_edits(
      format_vehicle_yaml(base), rng, 3000, [](const std::string& text, const char* name) {
        const auto d = parse_vehicle(text, name);
        CHECK(vehicle::validate(d).empty());
        const double length = vehicle::plan_path(d.trajectory).length_m();
        if (length / d.trajectory.depth.profile_step_m < 1e5) {
          const bool alt = d.trajectory.depth.mode == DepthMode::kAltitude;
          CHECK_NOTHROW(vehicle::Trajectory(d.trajectory,
                                            alt ? vehicle::SeabedDepthFn(flat_seabed) : nullptr));
        }
      });
  CHECK(n.accepted > 0);
  CHECK(n.rejected > 0);
}
