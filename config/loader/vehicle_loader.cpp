#include "config/loader/vehicle_loader.h"

#include <algorithm>

#include "config/loader/vehicle_yaml.h"

namespace sonarloop::config {

using vehicle::DepthMode;
using vehicle::TrajectoryDesc;
using vehicle::TrajectoryKind;
using vehicle::VehicleDesc;
using vehicle_yaml::attitude_numbers;
using vehicle_yaml::depth_numbers;
using vehicle_yaml::lawnmower_numbers;
using vehicle_yaml::nav_numbers;
using vehicle_yaml::NumberTable;
using vehicle_yaml::sway_numbers;

VehicleDesc parse_vehicle_node(const Field& f) {
  f.expect_map("a map with trajectory, nav");
  f.declare({"trajectory", "nav"});
  f.finish();
  VehicleDesc d;
  d.trajectory = vehicle_yaml::parse_trajectory(f.child("trajectory"));
  d.nav = vehicle_yaml::parse_nav(f.child("nav"));
  vehicle_yaml::check_with_model(f, d);
  vehicle_yaml::check_path(f, d);
  return d;
}

VehicleDesc parse_vehicle(const std::string& yaml_text, const std::string& source_name) {
  return with_yaml_errors(
      source_name, [&] { return parse_vehicle_node(parse_document(yaml_text, source_name)); });
}

VehicleDesc load_vehicle(const std::string& path) {
  return parse_vehicle(read_text_file(path), path);
}

namespace {

// "[north, east]" (appended piece by piece: GCC 12 at -O3 warns falsely, -Wrestrict, on
// "[" + std::string)
std::string pair_text(double north, double east) {
  std::string out = "[";
  out += format_number(north);
  out += ", ";
  out += format_number(east);
  out += "]";
  return out;
}

template <class S>
void put_numbers(std::string& out, const std::string& pad, const NumberTable<S>& table,
                 const S& value, std::optional<DepthMode> mode = std::nullopt) {
  for (const auto& k : table.keys) {
    if (k.mode && mode && *k.mode != *mode) continue;
    append_yaml_line(out, pad, k.key, unit_text(value.*k.member, k.unit));
  }
}

}  // namespace

std::string format_vehicle_yaml(const VehicleDesc& v, int indent) {
  const std::string p0(static_cast<std::size_t>(std::max(indent, 0)), ' ');
  const std::string p1 = p0 + "  ";
  const std::string p2 = p1 + "  ";
  const TrajectoryDesc& t = v.trajectory;
  std::string out;
  append_yaml_line(out, p0, "trajectory", "");
  append_yaml_line(out, p1, "kind", vehicle::to_string(t.kind));
  if (t.kind != TrajectoryKind::kLawnmower) {
    append_yaml_line(out, p1, "start_m", pair_text(t.start.north_m, t.start.east_m));
    append_yaml_line(out, p1, "heading_deg", unit_text(t.start_heading, YamlUnit::kDegree));
  }
  switch (t.kind) {
    case TrajectoryKind::kStraight:
      append_yaml_line(out, p1, "length_m", format_number(t.straight_length_m));
      break;
    case TrajectoryKind::kWaypoints: {
      std::string list = "[";
      for (std::size_t i = 0; i < t.waypoints.size(); ++i) {
        list += (i ? ", " : "") + pair_text(t.waypoints[i].north_m, t.waypoints[i].east_m);
      }
      append_yaml_line(out, p1, "waypoints_m", list + "]");
      break;
    }
    case TrajectoryKind::kLawnmower:
      append_yaml_line(out, p1, "lawnmower", "");
      append_yaml_line(out, p2, "origin_m",
                       pair_text(t.lawnmower.origin.north_m, t.lawnmower.origin.east_m));
      put_numbers(out, p2, lawnmower_numbers(), t.lawnmower);
      append_yaml_line(out, p2, "legs", std::to_string(t.lawnmower.legs));
      append_yaml_line(out, p2, "first_turn", vehicle::to_string(t.lawnmower.first_turn));
      break;
  }
  append_yaml_line(out, p1, "speed_m_s", format_number(t.speed_m_s));
  append_yaml_line(out, p1, "max_turn_rate_deg_s",
                   unit_text(t.max_turn_rate_rad_s, YamlUnit::kDegree));
  append_yaml_line(out, p1, "depth", "");
  append_yaml_line(out, p2, "mode", vehicle::to_string(t.depth.mode));
  put_numbers(out, p2, depth_numbers(), t.depth, t.depth.mode);
  append_yaml_line(out, p1, "sway", "");
  put_numbers(out, p2, sway_numbers(), t.sway);
  append_yaml_line(out, p1, "attitude", "");
  put_numbers(out, p2, attitude_numbers(), t.attitude);
  append_yaml_line(out, p0, "nav", "");
  put_numbers(out, p1, nav_numbers(), v.nav);
  return out;
}

}  // namespace sonarloop::config
