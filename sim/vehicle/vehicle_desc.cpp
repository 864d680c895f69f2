#include "sim/vehicle/vehicle_desc.h"

#include <cmath>
#include <iterator>
#include <numbers>
#include <sstream>

namespace sonarloop::vehicle {

namespace {

// hard limits of validate(); the header comments give the sensible (typical) ranges
constexpr double kMaxSpeedMPerS = 20.0;      // far above any AUV (fast ones reach ~5 m/s)
constexpr double kMaxTurnRateRadPerS = 2.0;  // ~115 deg/s
constexpr double kMaxGain = 10.0;            // roll_gain (either sign) and pitch_gain
constexpr double kMaxScaleFactorError = 0.5;
constexpr double kMaxStepS = 3600.0;  // noise and drift steps, the roll time constant
constexpr double kMinStepS = 1e-9;    // at least 1 ns: the steps are used as integer nanoseconds
constexpr int kMaxLegs = 10000;
constexpr double kMinPointSeparationM = 0.01;  // consecutive waypoints closer are an error
constexpr double kMaxWaveAmplitudeRad = std::numbers::pi / 4;  // roll and pitch oscillation
constexpr double kMinWavePeriodS = 1.0;    // shorter swells hardly move a vehicle
constexpr double kMaxWavePeriodS = 600.0;  // far beyond any swell: longer is a trim change

// One hard limit of validate(): a number field of a description D (its path below D), what is
// allowed, and when the rule applies (nullptr = always). The tables below are the one source of
// the limits: validate() applies them and limit_of() reports them.
template <class D>
struct NumberRule {
  std::string_view field;
  Limit allowed;
  double (*get)(const D&);
  bool (*applies)(const D&) = nullptr;
};

using TrajectoryRule = NumberRule<TrajectoryDesc>;
using NavRule = NumberRule<NavNoiseDesc>;

bool starts_at_start(const TrajectoryDesc& d) {
  return d.kind != TrajectoryKind::kLawnmower;
}
bool is_straight(const TrajectoryDesc& d) {
  return d.kind == TrajectoryKind::kStraight;
}
bool is_lawnmower(const TrajectoryDesc& d) {
  return d.kind == TrajectoryKind::kLawnmower;
}
bool at_constant_depth(const TrajectoryDesc& d) {
  return d.depth.mode == DepthMode::kConstantDepth;
}
bool follows_terrain(const TrajectoryDesc& d) {
  return d.depth.mode == DepthMode::kAltitude;
}

// In the order validate() reports them. The sway and wave keys are checked whatever the
// amplitudes, so that a description is valid or not independently of whether they are on.
const std::vector<TrajectoryRule>& trajectory_rules() {
  using T = TrajectoryDesc;
  static const std::vector<TrajectoryRule> rules = {
      {"start.north_m", Limit::finite("m"), [](const T& d) { return d.start.north_m; },
       starts_at_start},
      {"start.east_m", Limit::finite("m"), [](const T& d) { return d.start.east_m; },
       starts_at_start},
      {"start_heading", Limit::finite("rad"), [](const T& d) { return d.start_heading; },
       starts_at_start},
      {"straight_length_m", Limit::above(0.0, "m"), [](const T& d) { return d.straight_length_m; },
       is_straight},
      {"lawnmower.origin.north_m", Limit::finite("m"),
       [](const T& d) { return d.lawnmower.origin.north_m; }, is_lawnmower},
      {"lawnmower.origin.east_m", Limit::finite("m"),
       [](const T& d) { return d.lawnmower.origin.east_m; }, is_lawnmower},
      {"lawnmower.first_leg_heading", Limit::finite("rad"),
       [](const T& d) { return d.lawnmower.first_leg_heading; }, is_lawnmower},
      {"lawnmower.leg_length_m", Limit::above(0.0, "m"),
       [](const T& d) { return d.lawnmower.leg_length_m; }, is_lawnmower},
      {"lawnmower.line_spacing_m", Limit::above(0.0, "m"),
       [](const T& d) { return d.lawnmower.line_spacing_m; }, is_lawnmower},
      {"lawnmower.legs", Limit::whole(1, kMaxLegs),
       [](const T& d) { return static_cast<double>(d.lawnmower.legs); }, is_lawnmower},
      {"speed_m_s", Limit::above_up_to(0.0, kMaxSpeedMPerS, "m/s"),
       [](const T& d) { return d.speed_m_s; }},
      {"max_turn_rate_rad_s", Limit::above_up_to(0.0, kMaxTurnRateRadPerS, "rad/s"),
       [](const T& d) { return d.max_turn_rate_rad_s; }},
      {"depth.depth_m", Limit::at_least(0.0, "m"), [](const T& d) { return d.depth.depth_m; },
       at_constant_depth},
      {"depth.altitude_m", Limit::above(0.0, "m"), [](const T& d) { return d.depth.altitude_m; },
       follows_terrain},
      {"depth.max_climb_rate_m_s", Limit::above_up_to(0.0, kMaxSpeedMPerS, "m/s"),
       [](const T& d) { return d.depth.max_climb_rate_m_s; }, follows_terrain},
      {"depth.look_ahead_m", Limit::at_least(0.0, "m"),
       [](const T& d) { return d.depth.look_ahead_m; }, follows_terrain},
      {"depth.min_depth_m", Limit::at_least(0.0, "m"),
       [](const T& d) { return d.depth.min_depth_m; }, follows_terrain},
      {"depth.vertical_smoothing_m", Limit::closed(0.0, 1000.0, "m"),
       [](const T& d) { return d.depth.vertical_smoothing_m; }, follows_terrain},
      // the step is used in both modes (altitude along the path is precomputed when the seabed
      // is known)
      {"depth.profile_step_m", Limit::closed(0.05, 10.0, "m"),
       [](const T& d) { return d.depth.profile_step_m; }},
      {"sway.amplitude_m", Limit::at_least(0.0, "m"),
       [](const T& d) { return d.sway.amplitude_m; }},
      {"sway.period_s", Limit::above(0.0, "s"), [](const T& d) { return d.sway.period_s; }},
      {"sway.phase", Limit::finite("rad"), [](const T& d) { return d.sway.phase; }},
      {"sway.yaw_coupling", Limit::closed(0.0, 1.0),
       [](const T& d) { return d.sway.yaw_coupling; }},
      {"attitude.roll_gain", Limit::closed(-kMaxGain, kMaxGain),
       [](const T& d) { return d.attitude.roll_gain; }},
      {"attitude.max_roll", Limit::open(0.0, std::numbers::pi / 2, "rad"),
       [](const T& d) { return d.attitude.max_roll; }},
      {"attitude.roll_time_constant_s", Limit::closed(0.0, kMaxStepS, "s"),
       [](const T& d) { return d.attitude.roll_time_constant_s; }},
      {"attitude.pitch_gain", Limit::closed(0.0, kMaxGain),
       [](const T& d) { return d.attitude.pitch_gain; }},
      {"attitude.max_pitch", Limit::open(0.0, std::numbers::pi / 2, "rad"),
       [](const T& d) { return d.attitude.max_pitch; }},
      {"attitude.roll_amplitude", Limit::closed(0.0, kMaxWaveAmplitudeRad, "rad"),
       [](const T& d) { return d.attitude.roll_amplitude; }},
      {"attitude.pitch_amplitude", Limit::closed(0.0, kMaxWaveAmplitudeRad, "rad"),
       [](const T& d) { return d.attitude.pitch_amplitude; }},
      {"attitude.wave_period_s", Limit::closed(kMinWavePeriodS, kMaxWavePeriodS, "s"),
       [](const T& d) { return d.attitude.wave_period_s; }},
  };
  return rules;
}

const std::vector<NavRule>& nav_rules() {
  using N = NavNoiseDesc;
  static const std::vector<NavRule> rules = {
      {"position_noise_sd_m", Limit::at_least(0.0, "m"),
       [](const N& d) { return d.position_noise_sd_m; }},
      {"position_drift_m_per_sqrt_s", Limit::at_least(0.0, "m/sqrt(s)"),
       [](const N& d) { return d.position_drift_m_per_sqrt_s; }},
      {"heading_bias", Limit::closed(-std::numbers::pi, std::numbers::pi, "rad"),
       [](const N& d) { return d.heading_bias; }},
      {"heading_noise_sd", Limit::at_least(0.0, "rad"),
       [](const N& d) { return d.heading_noise_sd; }},
      {"heading_drift_rad_per_sqrt_s", Limit::at_least(0.0, "rad/sqrt(s)"),
       [](const N& d) { return d.heading_drift_rad_per_sqrt_s; }},
      {"attitude_noise_sd", Limit::at_least(0.0, "rad"),
       [](const N& d) { return d.attitude_noise_sd; }},
      {"speed_noise_sd_m_s", Limit::at_least(0.0, "m/s"),
       [](const N& d) { return d.speed_noise_sd_m_s; }},
      {"speed_scale_factor_error", Limit::open(-kMaxScaleFactorError, kMaxScaleFactorError),
       [](const N& d) { return d.speed_scale_factor_error; }},
      {"yaw_rate_noise_sd_rad_s", Limit::at_least(0.0, "rad/s"),
       [](const N& d) { return d.yaw_rate_noise_sd_rad_s; }},
      {"depth_noise_sd_m", Limit::at_least(0.0, "m"),
       [](const N& d) { return d.depth_noise_sd_m; }},
      {"altitude_noise_sd_m", Limit::at_least(0.0, "m"),
       [](const N& d) { return d.altitude_noise_sd_m; }},
      {"noise_step_s", Limit::closed(kMinStepS, kMaxStepS, "s"),
       [](const N& d) { return d.noise_step_s; }},
      {"drift_step_s", Limit::closed(kMinStepS, kMaxStepS, "s"),
       [](const N& d) { return d.drift_step_s; }},
  };
  return rules;
}

// Applies every rule of `rules` that applies to `desc`, appending the violations to `out`.
template <class D>
void apply_rules(const std::vector<NumberRule<D>>& rules, const D& desc, std::string_view prefix,
                 std::vector<Problem>& out) {
  for (const auto& rule : rules) {
    if (rule.applies && !rule.applies(desc)) continue;
    auto problem = check_limit(std::string(prefix) + "." + std::string(rule.field), rule.get(desc),
                               rule.allowed);
    if (problem) out.push_back(std::move(*problem));
  }
}

template <class D>
std::optional<Limit> find_rule(const std::vector<NumberRule<D>>& rules, std::string_view field) {
  for (const auto& rule : rules) {
    if (rule.field == field) return rule.allowed;
  }
  return std::nullopt;
}

std::string point_text(const NorthEast& p) {
  std::ostringstream os;
  os << "(" << p.north_m << ", " << p.east_m << ")";
  return os.str();
}

// Kind waypoints: at least one, each finite, consecutive ones (the start included) apart.
void check_waypoints(const TrajectoryDesc& desc, std::string_view prefix,
                     std::vector<Problem>& out) {
  const std::string list = std::string(prefix) + ".waypoints";
  if (desc.waypoints.empty()) {
    out.push_back({list, std::nullopt, std::nullopt, "at least one waypoint is required"});
  }
  const Limit gap_limit = Limit::at_least(kMinPointSeparationM, "m");
  NorthEast previous = desc.start;
  for (std::size_t i = 0; i < desc.waypoints.size(); ++i) {
    const NorthEast& w = desc.waypoints[i];
    const std::string key = list + "[" + std::to_string(i) + "]";
    for (auto p : {check_limit(key + ".north_m", w.north_m, Limit::finite("m")),
                   check_limit(key + ".east_m", w.east_m, Limit::finite("m"))}) {
      if (p) out.push_back(std::move(*p));
    }
    const double gap = std::hypot(w.north_m - previous.north_m, w.east_m - previous.east_m);
    if (std::isfinite(gap) && !gap_limit.contains(gap)) {
      std::ostringstream os;
      os << point_text(w) << " is " << gap << " m from the "
         << (i == 0 ? "start point" : "previous waypoint")
         << "; consecutive points must be at least " << kMinPointSeparationM << " m apart";
      out.push_back({key, std::nullopt, gap_limit, os.str()});
    }
    previous = w;
  }
}

}  // namespace

std::string_view to_string(TrajectoryKind kind) {
  switch (kind) {
    case TrajectoryKind::kStraight:
      return "straight";
    case TrajectoryKind::kWaypoints:
      return "waypoints";
    case TrajectoryKind::kLawnmower:
      return "lawnmower";
  }
  return "?";
}

std::string_view to_string(TurnDirection direction) {
  return direction == TurnDirection::kStarboard ? "starboard" : "port";
}

std::string_view to_string(DepthMode mode) {
  return mode == DepthMode::kConstantDepth ? "depth" : "altitude";
}

std::optional<TrajectoryKind> trajectory_kind_from_string(std::string_view name) {
  for (auto kind :
       {TrajectoryKind::kStraight, TrajectoryKind::kWaypoints, TrajectoryKind::kLawnmower}) {
    if (name == to_string(kind)) return kind;
  }
  return std::nullopt;
}

std::optional<TurnDirection> turn_direction_from_string(std::string_view name) {
  for (auto direction : {TurnDirection::kStarboard, TurnDirection::kPort}) {
    if (name == to_string(direction)) return direction;
  }
  return std::nullopt;
}

std::optional<DepthMode> depth_mode_from_string(std::string_view name) {
  for (auto mode : {DepthMode::kConstantDepth, DepthMode::kAltitude}) {
    if (name == to_string(mode)) return mode;
  }
  return std::nullopt;
}

std::vector<Problem> validate(const TrajectoryDesc& desc, std::string_view prefix) {
  std::vector<Problem> problems;
  apply_rules(trajectory_rules(), desc, prefix, problems);
  if (desc.kind == TrajectoryKind::kWaypoints) check_waypoints(desc, prefix, problems);
  return problems;
}

std::vector<Problem> validate(const NavNoiseDesc& desc, std::string_view prefix) {
  std::vector<Problem> problems;
  apply_rules(nav_rules(), desc, prefix, problems);
  return problems;
}

std::vector<Problem> validate(const VehicleDesc& desc) {
  std::vector<Problem> problems = validate(desc.trajectory, "trajectory");
  std::vector<Problem> nav = validate(desc.nav, "nav");
  problems.insert(problems.end(), std::make_move_iterator(nav.begin()),
                  std::make_move_iterator(nav.end()));
  return problems;
}

std::optional<Limit> limit_of(std::string_view field) {
  constexpr std::string_view kTrajectory = "trajectory.";
  constexpr std::string_view kNav = "nav.";
  if (field.starts_with(kTrajectory)) {
    return find_rule(trajectory_rules(), field.substr(kTrajectory.size()));
  }
  if (field.starts_with(kNav)) return find_rule(nav_rules(), field.substr(kNav.size()));
  return std::nullopt;
}

}  // namespace sonarloop::vehicle
