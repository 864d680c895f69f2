#include <algorithm>
#include <array>

#include "config/loader/vehicle_yaml.h"

namespace sonarloop::config::vehicle_yaml {
namespace {

using vehicle::DepthDesc;
using vehicle::DepthMode;
using vehicle::LawnmowerDesc;
using vehicle::NorthEast;
using vehicle::TrajectoryDesc;
using vehicle::TrajectoryKind;

constexpr std::string_view kNorthEast = "north, east";

// --- keys of one kind or mode -------------------------------------------------------------------

// Every key of the trajectory map, in the order of config/reference.yaml.
constexpr std::array<std::string_view, 11> kTrajectoryKeys{
    "kind",        "start_m",   "heading_deg", "length_m",
    "waypoints_m", "lawnmower", "speed_m_s",   "max_turn_rate_deg_s",
    "depth",       "sway",      "attitude"};

// The kinds a trajectory key belongs to; empty = every kind.
std::vector<TrajectoryKind> kinds_of(std::string_view key) {
  if (key == "start_m" || key == "heading_deg") {
    return {TrajectoryKind::kStraight, TrajectoryKind::kWaypoints};
  }
  if (key == "length_m") return {TrajectoryKind::kStraight};
  if (key == "waypoints_m") return {TrajectoryKind::kWaypoints};
  if (key == "lawnmower") return {TrajectoryKind::kLawnmower};
  return {};
}

bool is_key_of(std::string_view key, TrajectoryKind kind) {
  const auto kinds = kinds_of(key);
  return kinds.empty() || std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}

std::string kind_keys_text(TrajectoryKind kind) {
  std::vector<std::string> keys;
  for (std::string_view key : kTrajectoryKeys) {
    if (is_key_of(key, kind)) keys.emplace_back(key);
  }
  return join_names(keys);
}

std::string depth_keys_text(DepthMode mode) {
  std::vector<std::string> keys{"mode"};
  for (const auto& k : depth_numbers().keys) {
    if (!k.mode || *k.mode == mode) keys.emplace_back(k.key);
  }
  return join_names(keys);
}

// "straight" or "straight and waypoints": the kinds a key belongs to, for a message
std::string owners_text(std::string_view key) {
  std::vector<std::string> names;
  for (auto k : kinds_of(key))
    names.emplace_back(vehicle::to_string(k));
  std::string owners = names.front();
  if (names.size() == 2) owners += " and " + names.back();
  return owners;
}

// Keys of the other kinds are errors: "is a key of kind X, but this trajectory is of kind Y".
void reject_foreign_trajectory_keys(const Field& f, TrajectoryKind kind) {
  const std::string chosen = std::string(vehicle::to_string(kind)) +
                             (f.has("kind") ? "" : " (the default; set kind to choose another)");
  for (std::string_view key : kTrajectoryKeys) {
    if (is_key_of(key, kind) || !f.has(key)) continue;
    std::string hint;
    if (kind == TrajectoryKind::kLawnmower && (key == "start_m" || key == "heading_deg")) {
      hint = " (a lawnmower starts at lawnmower.origin_m, along lawnmower.first_leg_heading_deg)";
    }
    f.child(key).fail(
        "is a key of kind " + owners_text(key) + ", but this trajectory is of kind " + chosen +
            hint,
        "the keys of kind " + std::string(vehicle::to_string(kind)) + ": " + kind_keys_text(kind));
  }
}

void reject_foreign_depth_keys(const Field& f, DepthMode mode) {
  const std::string chosen = std::string(vehicle::to_string(mode)) +
                             (f.has("mode") ? "" : " (the default; set mode to choose another)");
  for (const auto& k : depth_numbers().keys) {
    if (!k.mode || *k.mode == mode || !f.has(k.key)) continue;
    f.child(k.key).fail(
        "is a key of mode " + std::string(vehicle::to_string(*k.mode)) +
            ", but this depth is of mode " + chosen,
        "the keys of mode " + std::string(vehicle::to_string(mode)) + ": " + depth_keys_text(mode));
  }
}

// --- sections -----------------------------------------------------------------------------------

NorthEast north_east(const Vec2& v) {
  return {v.x(), v.y()};
}

// The number of legs, checked as it is read against validate()'s limit: an int cannot hold an
// out-of-range value (1e12) for validate() to judge later.
int read_legs(const Field& f, int def) {
  const Limit legs = vehicle::limit_of(kLegsField).value_or(Limit::whole(1, 1));
  return f.get_int(kLegsKey, def, static_cast<int>(legs.lo), static_cast<int>(legs.hi));
}

LawnmowerDesc parse_lawnmower(const Field& f) {
  f.expect_map(
      "a map with origin_m, first_leg_heading_deg, leg_length_m, line_spacing_m, legs, "
      "first_turn");
  f.declare({"origin_m"});
  declare_numbers(f, lawnmower_numbers());
  f.declare({kLegsKey, "first_turn"});
  f.finish();
  LawnmowerDesc m;
  m.origin = north_east(
      f.get_vec2("origin_m", Vec2(m.origin.north_m, m.origin.east_m), Range::any(), kNorthEast));
  read_numbers(f, lawnmower_numbers(), m);
  m.legs = read_legs(f, m.legs);
  m.first_turn = f.get_enum("first_turn", m.first_turn, turn_names());
  return m;
}

std::vector<NorthEast> parse_waypoints(const Field& f) {
  const std::string allowed =
      "a list of at least one [north, east] point, e.g. [[20.0, 0.0], [20.0, 30.0]] "
      "(finite numbers, m)";
  if (!f.present()) f.fail("is not set (kind waypoints needs at least one waypoint)", allowed);
  f.expect_list(allowed);
  if (f.size() == 0) f.fail("has no waypoints", allowed);
  std::vector<NorthEast> out;
  for (std::size_t i = 0; i < f.size(); ++i) {
    out.push_back(north_east(f.item(i).as_vec2({Range::any(), Range::any()}, kNorthEast)));
  }
  return out;
}

DepthDesc parse_depth(const Field& f) {
  std::vector<std::string> all{"mode"};
  for (const auto& k : depth_numbers().keys)
    all.emplace_back(k.key);
  f.expect_map("a map with " + join_names(all));
  f.declare({"mode"});
  declare_numbers(f, depth_numbers());
  f.finish();
  DepthDesc d;
  d.mode = f.get_enum("mode", d.mode, mode_names());
  reject_foreign_depth_keys(f, d.mode);
  read_numbers(f, depth_numbers(), d, d.mode);
  return d;
}

// The keys that say where the path goes, by kind.
void parse_kind_keys(const Field& f, TrajectoryDesc& t) {
  const auto& numbers = trajectory_numbers();
  if (t.kind != TrajectoryKind::kLawnmower) {
    t.start = north_east(
        f.get_vec2("start_m", Vec2(t.start.north_m, t.start.east_m), Range::any(), kNorthEast));
    read_number(f, numbers, number_key(numbers, "heading_deg"), t);
  }
  switch (t.kind) {
    case TrajectoryKind::kStraight:
      read_number(f, numbers, number_key(numbers, "length_m"), t);
      break;
    case TrajectoryKind::kWaypoints:
      t.waypoints = parse_waypoints(f.child("waypoints_m"));
      break;
    case TrajectoryKind::kLawnmower:
      t.lawnmower = parse_lawnmower(f.child("lawnmower"));
      break;
  }
}

}  // namespace

TrajectoryDesc parse_trajectory(const Field& f) {
  std::vector<std::string> all(kTrajectoryKeys.begin(), kTrajectoryKeys.end());
  f.expect_map("a map with " + join_names(all));
  for (std::string_view key : kTrajectoryKeys)
    f.declare({key});
  f.finish();
  TrajectoryDesc t;
  t.kind = f.get_enum("kind", t.kind, kind_names());
  reject_foreign_trajectory_keys(f, t.kind);
  parse_kind_keys(f, t);
  const auto& numbers = trajectory_numbers();
  read_number(f, numbers, number_key(numbers, "speed_m_s"), t);
  read_number(f, numbers, number_key(numbers, "max_turn_rate_deg_s"), t);
  t.depth = parse_depth(f.child("depth"));
  t.sway = parse_number_map(f.child("sway"), sway_numbers());
  t.attitude = parse_number_map(f.child("attitude"), attitude_numbers());
  return t;
}

}  // namespace sonarloop::config::vehicle_yaml
