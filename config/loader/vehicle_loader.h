#pragma once
// Loads the vehicle (vehicle::VehicleDesc: the mission trajectory and the navigation sensor
// errors) from YAML: the `vehicle:` section of a scenario, or a standalone vehicle file holding
// the same map at its top level. Every key, its default and its range is documented in
// config/reference.yaml under `vehicle:`. Keys carry YAML-friendly units in their names
// (heading_deg, max_turn_rate_deg_s, heading_noise_deg, ...); the result is in SI units and
// radians (sim/vehicle/vehicle_desc.h). A missing key takes the VehicleDesc default; an absent or
// empty section is VehicleDesc{}.
//
//   vehicle:
//     trajectory: {kind, start_m, heading_deg, length_m, waypoints_m, lawnmower: {...},
//                  speed_m_s, max_turn_rate_deg_s, depth: {...}, sway: {...}, attitude: {...}}
//     nav: {position_noise_m, position_drift_m_per_sqrt_s, heading_bias_deg, ...}
//
// The limits are validate()'s (sim/vehicle/vehicle_desc.h), the one source of them: each number
// is read as a plain finite number and converted to SI, validate() runs on the result, and each
// of its problems becomes an issue at the YAML key it concerns, with its line, the value as
// written and the allowed range in the key's unit (degrees for *_deg keys). All of them are
// reported in one ConfigError. Further rules:
// - Keys of another trajectory kind are errors (length_m with kind: waypoints, ...), and so are
//   keys of the other depth mode (depth_m with mode: altitude, altitude_m with mode: depth, ...).
//   start_m and heading_deg belong to straight and waypoints (a lawnmower starts at
//   lawnmower.origin_m); waypoints_m is required for kind: waypoints.
// - validate()'s cross-field rules (e.g. consecutive waypoints, start_m included, at least
//   0.01 m apart) are reported the same way, at the waypoint concerned.
// - The planned path (path.h) may have at most Trajectory::kMaxProfileSteps profile steps
//   (path length / depth.profile_step_m), and the mission (path length / speed_m_s) may last at
//   most kMaxMissionDurationS, so that every loaded vehicle can be planned.
// - In a scenario, with depth.mode: altitude (terrain following), the planned path widened by
//   sway.amplitude_m to either side must stay inside the seabed extent (check_vehicle_over_seabed).
//   In constant-depth mode the vehicle does not depend on the seabed and may fly beyond it (e.g. a
//   run-in from outside the modelled patch).
//
// Unknown keys are reported first in each map (one ConfigError listing all of them, with "did
// you mean" suggestions), before its values are read.
#include <optional>
#include <string>

#include "config/loader/yaml_fields.h"
#include "sim/frames.h"
#include "sim/scene/scene_desc.h"
#include "sim/vehicle/path.h"
#include "sim/vehicle/vehicle_desc.h"

namespace sonarloop::config {

// Longest mission accepted, s (about 32 years): far beyond any survey, and well inside SimTime's
// int64 nanoseconds (about ±292 years).
inline constexpr double kMaxMissionDurationS = 1e9;

// Parses the vehicle node `f` (absent or empty: VehicleDesc{}). Reports unknown keys of every map
// in it. Does not check the path against a seabed (check_vehicle_over_seabed does).
vehicle::VehicleDesc parse_vehicle_node(const Field& f);

// Parses a standalone vehicle document; `source_name` is used in messages.
vehicle::VehicleDesc parse_vehicle(const std::string& yaml_text, const std::string& source_name);

// Reads and parses a standalone vehicle file. A missing file -> "<path>: (file): no such file".
vehicle::VehicleDesc load_vehicle(const std::string& path);

// The scenario rule above: in altitude mode, the planned path (sway included) must stay inside
// the extent of `seabed`. `f` is the vehicle node the description was parsed from (absent is
// fine); a violation is a ConfigError at <f.path()>.trajectory naming the time, the distance
// along the path and the position where the vehicle leaves the extent.
void check_vehicle_over_seabed(const Field& f, const vehicle::VehicleDesc& vehicle,
                               const scene::SeabedDesc& seabed);

// Where a path first leaves the box [lo, hi] (north, east; edges inside), if it does.
struct PathExit {
  double s_m = 0.0;                 // arc length along the path
  Vec2 position_NE = Vec2::Zero();  // the path point at s_m (on the box edge, or outside it)
};
// Exact for lines (closed form) and for whether an arc leaves (its extreme points); on an arc the
// exit point is found by sampling at most 1 cm (and 1 % of the radius) apart, then bisection.
// An empty box (lo > hi in either axis) is left at s = 0.
std::optional<PathExit> find_path_exit(const vehicle::Path& path, const Vec2& lo, const Vec2& hi);

// The vehicle as a YAML block map in YAML units, each line prefixed by `indent` spaces: the keys
// of its trajectory kind and depth mode, every number the shortest text that converts back to
// the same SI value, so parse_vehicle reads a loaded vehicle back bit for bit.
std::string format_vehicle_yaml(const vehicle::VehicleDesc& vehicle, int indent = 0);

}  // namespace sonarloop::config
