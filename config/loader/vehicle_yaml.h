#pragma once
// Internal to the vehicle loader (vehicle_loader.h is its interface): the YAML names and units of
// the vehicle's keys, and the steps of a load, one file each:
//   vehicle_yaml.cpp         the tables below (YAML name, VehicleDesc field, unit)
//   vehicle_trajectory.cpp   the trajectory map and its sub-maps -> TrajectoryDesc
//   vehicle_nav.cpp          the nav map -> NavNoiseDesc
//   vehicle_problems.cpp     validate()'s problems -> ConfigErrors at the YAML keys
//   vehicle_path_check.cpp   the rules on the planned path and the seabed extent
//   vehicle_loader.cpp       the whole vehicle, and format_vehicle_yaml
//
// The limits are not here: they are validate()'s (sim/vehicle/vehicle_desc.h), in SI. Numbers
// are read as plain finite numbers and converted to SI; validate() then judges them, and each of
// its problems is reported at the key it concerns, in the key's unit. What a key allows is
// described from vehicle::limit_of(), the same limits, so that a value that is not even a number
// is told the range too.
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "config/loader/units_text.h"
#include "config/loader/yaml_fields.h"
#include "sim/vehicle/vehicle_desc.h"

namespace sonarloop::config::vehicle_yaml {

// One number key of a map: its YAML name, its field in the description (validate()'s name), the
// unit of the YAML value, and a note on a special value for "allowed" texts ("0 = no sway").
// `mode`: a key of one depth mode only.
template <class S>
struct NumberKey {
  std::string_view key;
  std::string_view field;
  YamlUnit unit;
  double S::*member;
  std::optional<vehicle::DepthMode> mode = std::nullopt;
  std::string_view note = {};
};

// The number keys of one map. `path` is the map's key path below the vehicle node, which is also
// the path of its fields in validate()'s problems ("trajectory.sway").
template <class S>
struct NumberTable {
  std::string_view path;
  std::vector<NumberKey<S>> keys;
};

// The trajectory's own number keys (read one by one: some belong to one kind only).
const NumberTable<vehicle::TrajectoryDesc>& trajectory_numbers();
const NumberTable<vehicle::LawnmowerDesc>& lawnmower_numbers();
const NumberTable<vehicle::DepthDesc>& depth_numbers();
const NumberTable<vehicle::SwayDesc>& sway_numbers();
const NumberTable<vehicle::AttitudeDesc>& attitude_numbers();
const NumberTable<vehicle::NavNoiseDesc>& nav_numbers();

// The YAML name of the lawnmower's integer key, and its path in validate()'s problems.
inline constexpr std::string_view kLegsKey = "legs";
inline constexpr std::string_view kLegsField = "trajectory.lawnmower.legs";

// What validate() allows for `field` (a path of its problems), as a range in `unit` with `note`;
// any finite number for a field without a limit.
Range allowed_range(std::string_view field, YamlUnit unit, std::string_view note = {});

// The range of key `k` of `table`.
template <class S>
Range allowed_range(const NumberTable<S>& table, const NumberKey<S>& k) {
  return allowed_range(std::string(table.path) + "." + std::string(k.field), k.unit, k.note);
}

// Reads number key `k` of map `f` into out.*k.member, in SI, if it is present: any finite number
// (validate() checks the range).
template <class S>
void read_number(const Field& f, const NumberTable<S>& table, const NumberKey<S>& k, S& out) {
  const Field c = f.child(k.key);
  if (c.present()) out.*k.member = to_si(c.as_number(allowed_range(table, k)), k.unit);
}

// Reads every number key of `table` present in `f` into `out` (missing keys keep their value).
// Keys of the other depth mode are skipped (the trajectory reader has reported them).
template <class S>
void read_numbers(const Field& f, const NumberTable<S>& table, S& out,
                  std::optional<vehicle::DepthMode> mode = std::nullopt) {
  for (const auto& k : table.keys) {
    if (k.mode && mode && *k.mode != *mode) continue;
    read_number(f, table, k, out);
  }
}

template <class S>
void declare_numbers(const Field& f, const NumberTable<S>& table) {
  for (const auto& k : table.keys)
    f.declare({k.key});
}

// The key `key` of `table`; throws std::logic_error for a name the table does not have.
template <class S>
const NumberKey<S>& number_key(const NumberTable<S>& table, std::string_view key) {
  for (const auto& k : table.keys) {
    if (k.key == key) return k;
  }
  throw std::logic_error("vehicle_yaml: no number key " + std::string(key));
}

// A map made of the number keys of `table` only (sway, attitude, nav).
template <class S>
S parse_number_map(const Field& f, const NumberTable<S>& table) {
  std::vector<std::string> keys;
  for (const auto& k : table.keys)
    keys.emplace_back(k.key);
  f.expect_map("a map with " + join_names(keys));
  declare_numbers(f, table);
  f.finish();
  S out;
  read_numbers(f, table, out);
  return out;
}

// Names of the enumerations, for get_enum.
const NameTable<vehicle::TrajectoryKind>& kind_names();
const NameTable<vehicle::TurnDirection>& turn_names();
const NameTable<vehicle::DepthMode>& mode_names();

// The trajectory map `f` (vehicle_trajectory.cpp), the nav map `f` (vehicle_nav.cpp).
vehicle::TrajectoryDesc parse_trajectory(const Field& f);
vehicle::NavNoiseDesc parse_nav(const Field& f);

// Runs validate() on `d`, parsed from the vehicle node `f`; its problems -> one ConfigError with
// an issue at each YAML key concerned (vehicle_problems.cpp).
void check_with_model(const Field& f, const vehicle::VehicleDesc& d);

// The rules on the planned path: its length, profile steps and duration (vehicle_path_check.cpp).
void check_path(const Field& f, const vehicle::VehicleDesc& d);

}  // namespace sonarloop::config::vehicle_yaml
