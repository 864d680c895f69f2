// validate()'s problems (sim/vehicle/vehicle_desc.h, in SI and C++ field names) as ConfigErrors
// at the YAML keys they concern, in the keys' units.
#include <charconv>
#include <optional>

#include "config/loader/vehicle_yaml.h"

namespace sonarloop::config::vehicle_yaml {
namespace {

// Where a field of validate() is in the YAML: its key path below the vehicle node, and the unit
// and note of a number key. `number`: a key holding just that number (its range is reported as
// "allowed"); pairs, points and lists are not.
struct YamlKey {
  std::string path;
  YamlUnit unit = YamlUnit::kSi;
  std::string note = {};
  bool number = false;
};

template <class S>
std::optional<YamlKey> find_number(std::string_view field, const NumberTable<S>& table) {
  for (const auto& k : table.keys) {
    const std::string path = std::string(table.path) + ".";
    if (path + std::string(k.field) == field) {
      return YamlKey{path + std::string(k.key), k.unit, std::string(k.note), true};
    }
  }
  return std::nullopt;
}

std::optional<YamlKey> find_any_number(std::string_view field) {
  if (auto k = find_number(field, trajectory_numbers())) return k;
  if (auto k = find_number(field, lawnmower_numbers())) return k;
  if (auto k = find_number(field, depth_numbers())) return k;
  if (auto k = find_number(field, sway_numbers())) return k;
  if (auto k = find_number(field, attitude_numbers())) return k;
  if (auto k = find_number(field, nav_numbers())) return k;
  if (field == kLegsField) return YamlKey{std::string(kLegsField), YamlUnit::kSi, {}, true};
  return std::nullopt;
}

// The YAML key of a validate() field: "trajectory.attitude.max_roll" ->
// "trajectory.attitude.max_roll_deg", "trajectory.waypoints[3].north_m" ->
// "trajectory.waypoints_m[3]"; "" (the vehicle node) for a field the YAML does not name.
YamlKey yaml_key_of(std::string_view field) {
  if (auto k = find_any_number(field)) return *k;
  const auto starts = [&](std::string_view p) { return field.starts_with(p); };
  if (starts("trajectory.waypoints[")) {
    const auto open = field.find('[');
    const auto close = field.find(']');
    return {"trajectory.waypoints_m" + std::string(field.substr(open, close - open + 1))};
  }
  if (starts("trajectory.waypoints")) return {"trajectory.waypoints_m"};
  if (starts("trajectory.start.")) return {"trajectory.start_m"};
  if (starts("trajectory.lawnmower.origin.")) return {"trajectory.lawnmower.origin_m"};
  return {};
}

// The field of `vehicle` at a relative key path such as "trajectory.waypoints_m[2]" (or the
// deepest one that exists). Recursive: a Field must not be assigned to, because assigning a
// YAML::Node rebinds the node inside the document.
Field field_at(const Field& f, std::string_view path) {
  if (path.empty() || (!f.is_null() && !f.is_map())) return f;
  const auto dot = path.find('.');
  std::string_view part = path.substr(0, dot);
  const std::string_view rest =
      dot == std::string_view::npos ? std::string_view{} : path.substr(dot + 1);
  std::optional<std::size_t> index;
  if (const auto bracket = part.find('['); bracket != std::string_view::npos) {
    std::size_t i = 0;
    std::from_chars(part.data() + bracket + 1, part.data() + part.size(), i);
    index = i;
    part = part.substr(0, bracket);
  }
  const Field c = f.child(part);
  if (!index) return field_at(c, rest);
  if (!c.is_list() || *index >= c.size()) return c;
  return field_at(c.item(*index), rest);
}

// What `key` allows, in its unit: "an integer 1 .. 10000", "> 0 and < 90 (...)".
std::string allowed_text(const Limit& limit, const YamlKey& key) {
  if (limit.integer) {
    return "an integer " + format_number(limit.lo) + " .. " + format_number(limit.hi);
  }
  return yaml_range(limit, key.unit, key.note).describe();
}

// A number out of its range: "<value> is out of range", the value as the YAML writes it.
ConfigIssue range_issue(const Field& at, const Problem& p, const YamlKey& key) {
  const std::string value = at.present() && at.is_scalar()
                                ? at.node().Scalar()
                                : "the default " + unit_text(*p.value, key.unit);
  return at.issue(value + " is out of range", allowed_text(*p.allowed, key));
}

// Any other problem: the model's own words, and what the key allows.
ConfigIssue model_issue(const Field& at, const Problem& p, const YamlKey& key) {
  const std::string value = at.present() ? at.describe_value() : "the default";
  std::string allowed = "a vehicle that passes the vehicle model's checks (config/reference.yaml)";
  if (key.path.starts_with("trajectory.waypoints_m[") && p.allowed) {
    allowed = "[north, east]; consecutive points (start_m included) at least " +
              format_number(p.allowed->lo) + " m apart";
  } else if (key.path == "trajectory.waypoints_m") {
    allowed = "a list of at least one [north, east] point";
  } else if (p.allowed && !p.allowed->bounded()) {
    allowed = "finite numbers";
  }
  return at.issue(value + " is rejected by the vehicle model: " + p.message(), allowed);
}

ConfigIssue issue_of(const Field& vehicle_node, const Problem& p) {
  const YamlKey key = yaml_key_of(p.field);
  const Field at = field_at(vehicle_node, key.path);
  if (key.number && p.value && p.allowed && p.allowed->bounded()) return range_issue(at, p, key);
  return model_issue(at, p, key);
}

}  // namespace

void check_with_model(const Field& f, const vehicle::VehicleDesc& d) {
  const std::vector<Problem> problems = vehicle::validate(d);
  if (problems.empty()) return;
  std::vector<ConfigIssue> issues;
  for (const Problem& p : problems)
    issues.push_back(issue_of(f, p));
  throw ConfigError(std::move(issues));
}

}  // namespace sonarloop::config::vehicle_yaml
