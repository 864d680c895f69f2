#include "config/loader/vehicle_loader.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string_view>
#include <vector>

#include "sim/vehicle/trajectory.h"
#include "units/angles.h"

namespace sonarloop::config {
namespace {

using vehicle::AttitudeDesc;
using vehicle::DepthDesc;
using vehicle::DepthMode;
using vehicle::LawnmowerDesc;
using vehicle::NavNoiseDesc;
using vehicle::NorthEast;
using vehicle::Path;
using vehicle::PathSegment;
using vehicle::SwayDesc;
using vehicle::TrajectoryDesc;
using vehicle::TrajectoryKind;
using vehicle::TurnDirection;
using vehicle::VehicleDesc;

constexpr std::string_view kNorthEast = "north, east";

// --- YAML units --------------------------------------------------------------------------------

// Keys in degrees (deg, deg/s, deg/sqrt(s)) hold radians in VehicleDesc. The conversion is one
// multiplication by the double nearest π/180, so 180 -> π, 90 -> π/2 and 114.59155902616465 -> 2
// exactly: the ranges below in degrees are validate()'s ranges in radians, bound for bound.
enum class Unit { kSi, kDegree };

double to_si(double v, Unit u) {
  return u == Unit::kDegree ? v * kRadPerDeg : v;
}
double from_si(double v, Unit u) {
  return u == Unit::kDegree ? v / kRadPerDeg : v;
}

// The shortest decimal text, in unit `u`, that converts back to exactly `si`; the plain
// conversion when no text does.
std::string unit_text(double si, Unit u) {
  const double v = from_si(si, u);
  if (u == Unit::kSi) return format_number(v);
  for (int digits = 1; digits <= 17; ++digits) {
    char buf[40];
    const auto printed =
        std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
    double candidate = 0.0;
    std::from_chars(buf, printed.ptr, candidate);
    if (to_si(candidate, u) == si) return format_number(candidate);
  }
  return format_number(v);
}

// a derived value for a message: 6 significant digits
std::string approx(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// --- hard limits (vehicle_desc.cpp's validate(), in YAML units) ---------------------------------

constexpr double kMaxSpeedMPerS = 20.0;
constexpr double kMaxTurnRateRadPerS = 2.0;
constexpr double kMaxGain = 10.0;
constexpr double kMaxTimeConstantS = 3600.0;
constexpr double kMaxScaleFactorError = 0.5;
constexpr double kMinStepS = 1e-9;  // noise steps are whole nanoseconds
constexpr double kMaxStepS = 3600.0;
constexpr int kMaxLegs = 10000;
constexpr double kMinWaypointGapM = 0.01;

Range positive() {
  return Range::above(0.0);
}
Range non_negative() {
  return Range::at_least(0.0);
}
Range below_90_deg() {
  return Range{0.0, 90.0, true, true, {}};
}

// --- tables of number keys ----------------------------------------------------------------------

// One number key of a map: its YAML name, its VehicleDesc field (validate()'s name), the unit of
// the YAML value and its range in YAML units. `mode`: a key of one depth mode only.
template <class S>
struct NumberKey {
  std::string_view key;
  std::string_view field;
  Unit unit;
  Range range;
  double S::*member;
  std::optional<DepthMode> mode = std::nullopt;
};

const std::vector<NumberKey<LawnmowerDesc>>& lawnmower_numbers() {
  static const std::vector<NumberKey<LawnmowerDesc>> keys = {
      {"first_leg_heading_deg", "first_leg_heading", Unit::kDegree, Range::any(),
       &LawnmowerDesc::first_leg_heading},
      {"leg_length_m", "leg_length_m", Unit::kSi, positive(), &LawnmowerDesc::leg_length_m},
      {"line_spacing_m", "line_spacing_m", Unit::kSi, positive(), &LawnmowerDesc::line_spacing_m},
  };
  return keys;
}

const std::vector<NumberKey<DepthDesc>>& depth_numbers() {
  static const std::vector<NumberKey<DepthDesc>> keys = {
      {"depth_m", "depth_m", Unit::kSi, non_negative(), &DepthDesc::depth_m,
       DepthMode::kConstantDepth},
      {"altitude_m", "altitude_m", Unit::kSi, positive(), &DepthDesc::altitude_m,
       DepthMode::kAltitude},
      {"max_climb_rate_m_s", "max_climb_rate_m_s", Unit::kSi,
       Range{0.0, kMaxSpeedMPerS, true, false, {}}, &DepthDesc::max_climb_rate_m_s,
       DepthMode::kAltitude},
      {"look_ahead_m", "look_ahead_m", Unit::kSi, non_negative(), &DepthDesc::look_ahead_m,
       DepthMode::kAltitude},
      {"min_depth_m", "min_depth_m", Unit::kSi, non_negative(), &DepthDesc::min_depth_m,
       DepthMode::kAltitude},
      {"vertical_smoothing_m", "vertical_smoothing_m", Unit::kSi, Range::closed(0.0, 1000.0),
       &DepthDesc::vertical_smoothing_m, DepthMode::kAltitude},
      {"profile_step_m", "profile_step_m", Unit::kSi, Range::closed(0.05, 10.0),
       &DepthDesc::profile_step_m},
  };
  return keys;
}

const std::vector<NumberKey<SwayDesc>>& sway_numbers() {
  static const std::vector<NumberKey<SwayDesc>> keys = {
      {"amplitude_m", "amplitude_m", Unit::kSi, non_negative().with_note("0 = no sway"),
       &SwayDesc::amplitude_m},
      {"period_s", "period_s", Unit::kSi, positive(), &SwayDesc::period_s},
      {"phase_deg", "phase", Unit::kDegree, Range::any(), &SwayDesc::phase},
      {"yaw_coupling", "yaw_coupling", Unit::kSi, Range::closed(0.0, 1.0), &SwayDesc::yaw_coupling},
  };
  return keys;
}

const std::vector<NumberKey<AttitudeDesc>>& attitude_numbers() {
  static const std::vector<NumberKey<AttitudeDesc>> keys = {
      {"roll_gain", "roll_gain", Unit::kSi, Range::closed(-kMaxGain, kMaxGain),
       &AttitudeDesc::roll_gain},
      {"max_roll_deg", "max_roll", Unit::kDegree, below_90_deg(), &AttitudeDesc::max_roll},
      {"roll_time_constant_s", "roll_time_constant_s", Unit::kSi,
       Range::closed(0.0, kMaxTimeConstantS).with_note("0 = no lag"),
       &AttitudeDesc::roll_time_constant_s},
      {"pitch_gain", "pitch_gain", Unit::kSi, Range::closed(0.0, kMaxGain),
       &AttitudeDesc::pitch_gain},
      {"max_pitch_deg", "max_pitch", Unit::kDegree, below_90_deg(), &AttitudeDesc::max_pitch},
  };
  return keys;
}

const std::vector<NumberKey<NavNoiseDesc>>& nav_numbers() {
  static const std::vector<NumberKey<NavNoiseDesc>> keys = {
      {"position_noise_m", "position_noise_sd_m", Unit::kSi, non_negative(),
       &NavNoiseDesc::position_noise_sd_m},
      {"position_drift_m_per_sqrt_s", "position_drift_m_per_sqrt_s", Unit::kSi, non_negative(),
       &NavNoiseDesc::position_drift_m_per_sqrt_s},
      {"heading_bias_deg", "heading_bias", Unit::kDegree, Range::closed(-180.0, 180.0),
       &NavNoiseDesc::heading_bias},
      {"heading_noise_deg", "heading_noise_sd", Unit::kDegree, non_negative(),
       &NavNoiseDesc::heading_noise_sd},
      {"heading_drift_deg_per_sqrt_s", "heading_drift_rad_per_sqrt_s", Unit::kDegree,
       non_negative(), &NavNoiseDesc::heading_drift_rad_per_sqrt_s},
      {"attitude_noise_deg", "attitude_noise_sd", Unit::kDegree, non_negative(),
       &NavNoiseDesc::attitude_noise_sd},
      {"speed_noise_m_s", "speed_noise_sd_m_s", Unit::kSi, non_negative(),
       &NavNoiseDesc::speed_noise_sd_m_s},
      {"speed_scale_error", "speed_scale_factor_error", Unit::kSi,
       Range{-kMaxScaleFactorError, kMaxScaleFactorError, true, true, {}},
       &NavNoiseDesc::speed_scale_factor_error},
      {"yaw_rate_noise_deg_s", "yaw_rate_noise_sd_rad_s", Unit::kDegree, non_negative(),
       &NavNoiseDesc::yaw_rate_noise_sd_rad_s},
      {"depth_noise_m", "depth_noise_sd_m", Unit::kSi, non_negative(),
       &NavNoiseDesc::depth_noise_sd_m},
      {"altitude_noise_m", "altitude_noise_sd_m", Unit::kSi, non_negative(),
       &NavNoiseDesc::altitude_noise_sd_m},
      {"noise_step_s", "noise_step_s", Unit::kSi,
       Range::closed(kMinStepS, kMaxStepS).with_note("at least 1 ns"), &NavNoiseDesc::noise_step_s},
      {"drift_step_s", "drift_step_s", Unit::kSi,
       Range::closed(kMinStepS, kMaxStepS).with_note("at least 1 ns"), &NavNoiseDesc::drift_step_s},
  };
  return keys;
}

// The trajectory's own number keys (the others are read explicitly).
Range start_heading_range() {
  return Range::any();
}
Range length_range() {
  return positive();
}
Range speed_range() {
  return Range{0.0, kMaxSpeedMPerS, true, false, {}};
}
Range turn_rate_range() {
  return Range{0.0, kMaxTurnRateRadPerS / kRadPerDeg, true, false, {}}.with_note("2 rad/s");
}

// Reads every number key of `table` present in `f` into `out` (missing keys keep their value).
// Keys of the other depth mode are skipped (reject_foreign_keys has reported them).
template <class S>
void read_numbers(const Field& f, const std::vector<NumberKey<S>>& table, S& out,
                  std::optional<DepthMode> mode = std::nullopt) {
  for (const auto& k : table) {
    if (k.mode && mode && *k.mode != *mode) continue;
    const Field c = f.child(k.key);
    if (c.present()) out.*k.member = to_si(c.as_double(k.range), k.unit);
  }
}

template <class S>
void declare_numbers(const Field& f, const std::vector<NumberKey<S>>& table) {
  for (const auto& k : table)
    f.declare({k.key});
}

// --- words --------------------------------------------------------------------------------------

template <class T, class ToString, class FromString>
NameTable<T> enum_table(std::string noun, std::initializer_list<T> values, ToString to_string,
                        FromString from_string) {
  NameTable<T> t;
  t.noun = std::move(noun);
  for (T v : values)
    t.names.emplace_back(to_string(v));
  t.allowed = join_names(t.names);
  t.find = [from_string](std::string_view s) -> std::optional<T> { return from_string(s); };
  return t;
}

const NameTable<TrajectoryKind>& kind_names() {
  static const auto t = enum_table<TrajectoryKind>(
      "trajectory kind",
      {TrajectoryKind::kStraight, TrajectoryKind::kWaypoints, TrajectoryKind::kLawnmower},
      [](TrajectoryKind k) { return vehicle::to_string(k); },
      [](std::string_view s) { return vehicle::trajectory_kind_from_string(s); });
  return t;
}

const NameTable<TurnDirection>& turn_names() {
  static const auto t = enum_table<TurnDirection>(
      "turn direction", {TurnDirection::kStarboard, TurnDirection::kPort},
      [](TurnDirection d) { return vehicle::to_string(d); },
      [](std::string_view s) { return vehicle::turn_direction_from_string(s); });
  return t;
}

const NameTable<DepthMode>& mode_names() {
  static const auto t = enum_table<DepthMode>(
      "depth mode", {DepthMode::kAltitude, DepthMode::kConstantDepth},
      [](DepthMode m) { return vehicle::to_string(m); },
      [](std::string_view s) { return vehicle::depth_mode_from_string(s); });
  return t;
}

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

std::string kind_keys_text(TrajectoryKind kind) {
  std::vector<std::string> keys;
  for (std::string_view key : kTrajectoryKeys) {
    const auto kinds = kinds_of(key);
    if (kinds.empty() || std::find(kinds.begin(), kinds.end(), kind) != kinds.end()) {
      keys.emplace_back(key);
    }
  }
  return join_names(keys);
}

std::string depth_keys_text(DepthMode mode) {
  std::vector<std::string> keys{"mode"};
  for (const auto& k : depth_numbers()) {
    if (!k.mode || *k.mode == mode) keys.emplace_back(k.key);
  }
  return join_names(keys);
}

// Keys of the other kinds are errors: "is a key of kind X, but this trajectory is of kind Y".
void reject_foreign_trajectory_keys(const Field& f, TrajectoryKind kind) {
  const std::string chosen = std::string(vehicle::to_string(kind)) +
                             (f.has("kind") ? "" : " (the default; set kind to choose another)");
  for (std::string_view key : kTrajectoryKeys) {
    const auto kinds = kinds_of(key);
    if (kinds.empty() || std::find(kinds.begin(), kinds.end(), kind) != kinds.end()) continue;
    if (!f.has(key)) continue;
    std::vector<std::string> names;
    for (auto k : kinds)
      names.emplace_back(vehicle::to_string(k));
    std::string owners = names.front();
    if (names.size() == 2) owners += " and " + names.back();
    std::string hint;
    if (kind == TrajectoryKind::kLawnmower && (key == "start_m" || key == "heading_deg")) {
      hint = " (a lawnmower starts at lawnmower.origin_m, along lawnmower.first_leg_heading_deg)";
    }
    f.child(key).fail(
        "is a key of kind " + owners + ", but this trajectory is of kind " + chosen + hint,
        "the keys of kind " + std::string(vehicle::to_string(kind)) + ": " + kind_keys_text(kind));
  }
}

void reject_foreign_depth_keys(const Field& f, DepthMode mode) {
  const std::string chosen = std::string(vehicle::to_string(mode)) +
                             (f.has("mode") ? "" : " (the default; set mode to choose another)");
  for (const auto& k : depth_numbers()) {
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

LawnmowerDesc parse_lawnmower(const Field& f) {
  f.expect_map(
      "a map with origin_m, first_leg_heading_deg, leg_length_m, line_spacing_m, legs, "
      "first_turn");
  f.declare({"origin_m"});
  declare_numbers(f, lawnmower_numbers());
  f.declare({"legs", "first_turn"});
  f.finish();
  LawnmowerDesc m;
  m.origin = north_east(
      f.get_vec2("origin_m", Vec2(m.origin.north_m, m.origin.east_m), Range::any(), kNorthEast));
  read_numbers(f, lawnmower_numbers(), m);
  m.legs = f.get_int("legs", m.legs, 1, kMaxLegs);
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
  for (const auto& k : depth_numbers())
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

template <class S>
S parse_number_map(const Field& f, const std::vector<NumberKey<S>>& table) {
  std::vector<std::string> keys;
  for (const auto& k : table)
    keys.emplace_back(k.key);
  f.expect_map("a map with " + join_names(keys));
  declare_numbers(f, table);
  f.finish();
  S out;
  read_numbers(f, table, out);
  return out;
}

TrajectoryDesc parse_trajectory(const Field& f) {
  std::vector<std::string> all(kTrajectoryKeys.begin(), kTrajectoryKeys.end());
  f.expect_map("a map with " + join_names(all));
  for (std::string_view key : kTrajectoryKeys)
    f.declare({key});
  f.finish();
  TrajectoryDesc t;
  t.kind = f.get_enum("kind", t.kind, kind_names());
  reject_foreign_trajectory_keys(f, t.kind);
  if (t.kind != TrajectoryKind::kLawnmower) {
    t.start = north_east(
        f.get_vec2("start_m", Vec2(t.start.north_m, t.start.east_m), Range::any(), kNorthEast));
    const Field h = f.child("heading_deg");
    if (h.present()) t.start_heading = to_si(h.as_double(start_heading_range()), Unit::kDegree);
  }
  switch (t.kind) {
    case TrajectoryKind::kStraight:
      t.straight_length_m = f.get_double("length_m", t.straight_length_m, length_range());
      break;
    case TrajectoryKind::kWaypoints:
      t.waypoints = parse_waypoints(f.child("waypoints_m"));
      break;
    case TrajectoryKind::kLawnmower:
      t.lawnmower = parse_lawnmower(f.child("lawnmower"));
      break;
  }
  t.speed_m_s = f.get_double("speed_m_s", t.speed_m_s, speed_range());
  const Field r = f.child("max_turn_rate_deg_s");
  if (r.present()) t.max_turn_rate_rad_s = to_si(r.as_double(turn_rate_range()), Unit::kDegree);
  t.depth = parse_depth(f.child("depth"));
  t.sway = parse_number_map(f.child("sway"), sway_numbers());
  t.attitude = parse_number_map(f.child("attitude"), attitude_numbers());
  return t;
}

// --- validate() messages as ConfigErrors --------------------------------------------------------

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

struct KeyRef {
  std::string yaml;  // relative to the vehicle node
  std::string allowed;
};

template <class S>
std::optional<KeyRef> find_number(std::string_view field, std::string_view prefix,
                                  const std::vector<NumberKey<S>>& table) {
  for (const auto& k : table) {
    if (std::string(prefix) + std::string(k.field) == field) {
      return KeyRef{std::string(prefix) + std::string(k.key), k.range.describe()};
    }
  }
  return std::nullopt;
}

// The YAML key of a validate() key ("trajectory.attitude.max_roll" ->
// "trajectory.attitude.max_roll_deg").
KeyRef yaml_key_of(std::string_view field) {
  const auto starts = [&](std::string_view p) { return field.substr(0, p.size()) == p; };
  if (starts("trajectory.waypoints[")) {
    // "trajectory.waypoints[3].north_m" -> "trajectory.waypoints_m[3]"
    const auto open = field.find('[');
    const auto close = field.find(']');
    return {"trajectory.waypoints_m" + std::string(field.substr(open, close - open + 1)),
            "[north, east]; consecutive points (start_m included) at least " +
                format_number(kMinWaypointGapM) + " m apart"};
  }
  if (starts("trajectory.waypoints")) {
    return {"trajectory.waypoints_m", "a list of at least one [north, east] point"};
  }
  if (starts("trajectory.start.")) return {"trajectory.start_m", "finite numbers"};
  if (field == "trajectory.start_heading") {
    return {"trajectory.heading_deg", start_heading_range().describe()};
  }
  if (field == "trajectory.straight_length_m") {
    return {"trajectory.length_m", length_range().describe()};
  }
  if (starts("trajectory.lawnmower.origin.")) return {"trajectory.lawnmower.origin_m", "finite"};
  if (field == "trajectory.lawnmower.legs") {
    return {"trajectory.lawnmower.legs", "an integer 1 .. " + std::to_string(kMaxLegs)};
  }
  if (field == "trajectory.speed_m_s") return {"trajectory.speed_m_s", speed_range().describe()};
  if (field == "trajectory.max_turn_rate_rad_s") {
    return {"trajectory.max_turn_rate_deg_s", turn_rate_range().describe()};
  }
  if (auto k = find_number(field, "trajectory.lawnmower.", lawnmower_numbers())) return *k;
  if (auto k = find_number(field, "trajectory.depth.", depth_numbers())) return *k;
  if (auto k = find_number(field, "trajectory.sway.", sway_numbers())) return *k;
  if (auto k = find_number(field, "trajectory.attitude.", attitude_numbers())) return *k;
  if (auto k = find_number(field, "nav.", nav_numbers())) return *k;
  return {"", "a vehicle that passes the vehicle model's checks (config/reference.yaml)"};
}

// Each message of validate() reads "<field> = <value>: <problem>" or "<field>: <problem>".
void check_with_model(const Field& f, const VehicleDesc& d) {
  const std::vector<std::string> errors = vehicle::validate(d);
  if (errors.empty()) return;
  std::vector<ConfigIssue> issues;
  for (const std::string& e : errors) {
    const std::size_t end = std::min(e.find(" = "), e.find(": "));
    const KeyRef ref = yaml_key_of(std::string_view(e).substr(0, end));
    const Field at = field_at(f, ref.yaml);
    const std::string value = at.present() ? at.describe_value() : "the default";
    issues.push_back(at.issue(value + " is rejected by the vehicle model: " + e, ref.allowed));
  }
  throw ConfigError(std::move(issues));
}

// The rules on the planned path (see vehicle_loader.h).
void check_path(const Field& f, const VehicleDesc& d) {
  const TrajectoryDesc& t = d.trajectory;
  const double length = vehicle::plan_path(t).length_m();
  const Field traj = f.child("trajectory");
  if (!std::isfinite(length)) {
    traj.fail("the planned path has no finite length (" + approx(length) + " m)",
              "lengths, spacings, speed and turn rate that give a path of finite length");
  }
  const double steps = std::max(1.0, std::ceil(length / t.depth.profile_step_m));
  if (!(steps <= vehicle::Trajectory::kMaxProfileSteps)) {
    const Field step = traj.child("depth").child("profile_step_m");
    step.fail((step.present() ? format_number(t.depth.profile_step_m)
                              : "the default " + format_number(t.depth.profile_step_m)) +
                  " gives " + approx(steps) + " profile steps over the planned path of " +
                  approx(length) + " m",
              ">= " + approx(length / vehicle::Trajectory::kMaxProfileSteps) +
                  " for this path (at most " + approx(vehicle::Trajectory::kMaxProfileSteps) +
                  " profile steps), or a shorter path");
  }
  const double duration = length / t.speed_m_s;
  if (!(duration <= kMaxMissionDurationS)) {
    const Field speed = traj.child("speed_m_s");
    speed.fail((speed.present() ? format_number(t.speed_m_s)
                                : "the default " + format_number(t.speed_m_s)) +
                   " gives a mission of " + approx(duration) + " s over the planned path of " +
                   approx(length) + " m",
               ">= " + approx(length / kMaxMissionDurationS) +
                   " for this path (missions of at most " + approx(kMaxMissionDurationS) + " s)");
  }
}

// --- the path and the seabed extent -------------------------------------------------------------

bool inside(const Vec2& p, const Vec2& lo, const Vec2& hi) {
  return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
}

// Most samples taken along one arc when looking for its exit point.
constexpr double kMaxArcSamples = 1e6;
constexpr double kArcSampleStepM = 0.01;
constexpr double kArcSampleRadiusFraction = 0.01;

// Where an arc that starts inside first leaves the box; nullopt if it stays inside. Whether it
// leaves is decided exactly from its end point and its extreme points (the points of heading a
// multiple of π/2, where north or east is extreme); the exit point is then sampled and bisected.
std::optional<PathExit> arc_exit(const Path& path, const PathSegment& seg, const Vec2& lo,
                                 const Vec2& hi) {
  const double kappa = seg.curvature_per_m;
  const double length = seg.length_m;
  const auto at = [&](double u) { return path.at(seg.s0_m + u).position_NE; };
  std::optional<double> first_outside;  // smallest u of an extreme or end point outside
  const auto consider = [&](double u) {
    u = std::clamp(u, 0.0, length);
    if (!inside(at(u), lo, hi) && (!first_outside || u < *first_outside)) first_outside = u;
  };
  consider(length);
  const double h0 = seg.start_heading;
  const double h1 = seg.start_heading + kappa * length;
  const double quarter = 0.5 * std::numbers::pi;
  const double m_lo = std::ceil(std::min(h0, h1) / quarter);
  const double m_hi = std::floor(std::max(h0, h1) / quarter);
  for (double m = m_lo; m <= m_hi && m - m_lo < 64.0; m += 1.0)
    consider((m * quarter - h0) / kappa);
  if (!first_outside) return std::nullopt;

  // sample up to the first known outside point, then bisect the first step that leaves
  const double radius = 1.0 / std::abs(kappa);
  const double step = std::min(kArcSampleStepM, kArcSampleRadiusFraction * radius);
  const double n = std::clamp(std::ceil(*first_outside / step), 1.0, kMaxArcSamples);
  double u_in = 0.0;
  double u_out = *first_outside;
  for (double i = 1.0; i <= n; i += 1.0) {
    const double u = *first_outside * (i / n);
    if (!inside(at(u), lo, hi)) {
      u_out = u;
      break;
    }
    u_in = u;
  }
  for (int k = 0; k < 200 && u_out - u_in > 0.0; ++k) {
    const double mid = 0.5 * (u_in + u_out);
    if (mid <= u_in || mid >= u_out) break;
    (inside(at(mid), lo, hi) ? u_in : u_out) = mid;
  }
  return PathExit{seg.s0_m + u_out, at(u_out)};
}

// Where a line that starts inside first leaves the box (closed form); nullopt if it stays inside.
std::optional<PathExit> line_exit(const PathSegment& seg, const Vec2& lo, const Vec2& hi) {
  const Vec2 dir = heading_vector(seg.start_heading);
  const Vec2 end = seg.start_NE + seg.length_m * dir;
  if (inside(end, lo, hi)) return std::nullopt;
  double u = seg.length_m;
  for (int a = 0; a < 2; ++a) {
    if (dir[a] > 0.0 && end[a] > hi[a]) u = std::min(u, (hi[a] - seg.start_NE[a]) / dir[a]);
    if (dir[a] < 0.0 && end[a] < lo[a]) u = std::min(u, (lo[a] - seg.start_NE[a]) / dir[a]);
  }
  u = std::clamp(u, 0.0, seg.length_m);
  return PathExit{seg.s0_m + u, seg.start_NE + u * dir};
}

// Where along the path a point at arc length s lies, for a message.
std::string where_on_path(const Path& path, const TrajectoryDesc& t, double s) {
  const auto& segs = path.segments();
  if (segs.empty()) return "at the start";
  const int i = std::clamp(path.segment_index(s), 0, static_cast<int>(segs.size()) - 1);
  const PathSegment& seg = segs[static_cast<std::size_t>(i)];
  if (seg.leg >= 0) return "on lawnmower leg " + std::to_string(seg.leg);
  if (t.kind == TrajectoryKind::kLawnmower) {
    for (int j = i; j >= 0; --j) {
      const int leg = segs[static_cast<std::size_t>(j)].leg;
      if (leg >= 0) return "in the U-turn after lawnmower leg " + std::to_string(leg);
    }
  }
  return seg.curvature_per_m == 0.0 ? "on a straight" : "in a turn";
}

}  // namespace

std::optional<PathExit> find_path_exit(const Path& path, const Vec2& lo, const Vec2& hi) {
  const Vec2 start = path.at(0.0).position_NE;
  if (!inside(start, lo, hi)) return PathExit{0.0, start};
  for (const PathSegment& seg : path.segments()) {
    // every segment starts inside: where the previous one ended, or at the checked start
    const auto exit =
        seg.curvature_per_m == 0.0 ? line_exit(seg, lo, hi) : arc_exit(path, seg, lo, hi);
    if (exit) return exit;
  }
  return std::nullopt;
}

VehicleDesc parse_vehicle_node(const Field& f) {
  f.expect_map("a map with trajectory, nav");
  f.declare({"trajectory", "nav"});
  f.finish();
  VehicleDesc d;
  d.trajectory = parse_trajectory(f.child("trajectory"));
  d.nav = parse_number_map(f.child("nav"), nav_numbers());
  check_with_model(f, d);
  check_path(f, d);
  return d;
}

VehicleDesc parse_vehicle(const std::string& yaml_text, const std::string& source_name) {
  return with_yaml_errors(
      source_name, [&] { return parse_vehicle_node(parse_document(yaml_text, source_name)); });
}

VehicleDesc load_vehicle(const std::string& path) {
  return parse_vehicle(read_text_file(path), path);
}

void check_vehicle_over_seabed(const Field& f, const VehicleDesc& v,
                               const scene::SeabedDesc& seabed) {
  const TrajectoryDesc& t = v.trajectory;
  if (t.depth.mode != DepthMode::kAltitude) return;
  const double margin = t.sway.amplitude_m;
  const Vec2 lo = seabed.origin_m + Vec2(margin, margin);
  const Vec2 hi = seabed.origin_m + seabed.extent_m - Vec2(margin, margin);
  const Path path = vehicle::plan_path(t);
  const auto exit = find_path_exit(path, lo, hi);
  if (!exit) return;

  const Vec2 box_lo = seabed.origin_m;
  const Vec2 box_hi = seabed.origin_m + seabed.extent_m;
  const double radius = vehicle::turn_radius_m(t.speed_m_s, t.max_turn_rate_rad_s);
  std::string allowed =
      "with depth.mode altitude (terrain following), a path that stays over the modelled seabed: "
      "north " +
      format_number(box_lo.x()) + " .. " + format_number(box_hi.x()) + ", east " +
      format_number(box_lo.y()) + " .. " + format_number(box_hi.y()) +
      " (seabed.origin_m, seabed.extent_m)";
  if (margin > 0.0) {
    allowed += ", less sway.amplitude_m " + format_number(margin) + " on every side";
  }
  allowed += "; turns have radius speed_m_s / max_turn_rate = " + approx(radius) + " m";
  if (t.kind == TrajectoryKind::kLawnmower && t.lawnmower.legs > 1) {
    allowed += ", and each U-turn reaches " +
               approx(vehicle::u_turn_overshoot_m(t.lawnmower.line_spacing_m, radius)) +
               " m beyond the leg ends";
  }
  const Field traj = f.child("trajectory");
  traj.fail("the planned path leaves the seabed extent at t = " + approx(exit->s_m / t.speed_m_s) +
                " s (" + approx(exit->s_m) + " m along the path, " +
                where_on_path(path, t, exit->s_m) + "), position [north, east] = [" +
                approx(exit->position_NE.x()) + ", " + approx(exit->position_NE.y()) + "] m",
            allowed);
}

namespace {

void put(std::string& out, const std::string& pad, std::string_view key, std::string_view value) {
  out += pad;
  out += key;
  out += ":";
  if (!value.empty()) {
    out += " ";
    out += value;
  }
  out += "\n";
}

std::string pair_text(double north, double east) {
  return "[" + format_number(north) + ", " + format_number(east) + "]";
}

template <class S>
void put_numbers(std::string& out, const std::string& pad, const std::vector<NumberKey<S>>& table,
                 const S& value, std::optional<DepthMode> mode = std::nullopt) {
  for (const auto& k : table) {
    if (k.mode && mode && *k.mode != *mode) continue;
    put(out, pad, k.key, unit_text(value.*k.member, k.unit));
  }
}

}  // namespace

std::string format_vehicle_yaml(const VehicleDesc& v, int indent) {
  const std::string p0(static_cast<std::size_t>(std::max(indent, 0)), ' ');
  const std::string p1 = p0 + "  ";
  const std::string p2 = p1 + "  ";
  const TrajectoryDesc& t = v.trajectory;
  std::string out;
  put(out, p0, "trajectory", "");
  put(out, p1, "kind", vehicle::to_string(t.kind));
  if (t.kind != TrajectoryKind::kLawnmower) {
    put(out, p1, "start_m", pair_text(t.start.north_m, t.start.east_m));
    put(out, p1, "heading_deg", unit_text(t.start_heading, Unit::kDegree));
  }
  switch (t.kind) {
    case TrajectoryKind::kStraight:
      put(out, p1, "length_m", format_number(t.straight_length_m));
      break;
    case TrajectoryKind::kWaypoints: {
      std::string list = "[";
      for (std::size_t i = 0; i < t.waypoints.size(); ++i) {
        list += (i ? ", " : "") + pair_text(t.waypoints[i].north_m, t.waypoints[i].east_m);
      }
      put(out, p1, "waypoints_m", list + "]");
      break;
    }
    case TrajectoryKind::kLawnmower:
      put(out, p1, "lawnmower", "");
      put(out, p2, "origin_m", pair_text(t.lawnmower.origin.north_m, t.lawnmower.origin.east_m));
      put_numbers(out, p2, lawnmower_numbers(), t.lawnmower);
      put(out, p2, "legs", std::to_string(t.lawnmower.legs));
      put(out, p2, "first_turn", vehicle::to_string(t.lawnmower.first_turn));
      break;
  }
  put(out, p1, "speed_m_s", format_number(t.speed_m_s));
  put(out, p1, "max_turn_rate_deg_s", unit_text(t.max_turn_rate_rad_s, Unit::kDegree));
  put(out, p1, "depth", "");
  put(out, p2, "mode", vehicle::to_string(t.depth.mode));
  put_numbers(out, p2, depth_numbers(), t.depth, t.depth.mode);
  put(out, p1, "sway", "");
  put_numbers(out, p2, sway_numbers(), t.sway);
  put(out, p1, "attitude", "");
  put_numbers(out, p2, attitude_numbers(), t.attitude);
  put(out, p0, "nav", "");
  put_numbers(out, p1, nav_numbers(), v.nav);
  return out;
}

}  // namespace sonarloop::config
