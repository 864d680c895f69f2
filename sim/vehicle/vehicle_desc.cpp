#include "sim/vehicle/vehicle_desc.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace sonarloop::vehicle {

namespace {

// hard limits of validate(); the header comments give the sensible (typical) ranges
constexpr double kMaxSpeedMPerS = 20.0;      // far above any AUV (fast ones reach ~5 m/s)
constexpr double kMaxTurnRateRadPerS = 2.0;  // ~115 deg/s
constexpr double kMaxRollGain = 10.0;
constexpr double kMaxPitchGain = 10.0;
constexpr double kMaxScaleFactorError = 0.5;
constexpr double kMaxNoiseStepS = 3600.0;
constexpr int kMaxLegs = 10000;
constexpr double kMinPointSeparationM = 0.01;  // consecutive waypoints closer are an error

class Checker {
 public:
  explicit Checker(std::string_view prefix) : prefix_(prefix) {}

  // value must be finite and satisfy lo (<|<=) value (<|<=) hi
  void range(std::string_view key, double value, double lo, bool lo_open, double hi, bool hi_open,
             std::string_view unit) {
    const bool ok = std::isfinite(value) && (lo_open ? value > lo : value >= lo) &&
                    (hi_open ? value < hi : value <= hi);
    if (ok) return;
    std::ostringstream os;
    os << prefix_ << "." << key << " = " << value << ": must be in " << (lo_open ? "(" : "[") << lo
       << ", " << hi << (hi_open ? ")" : "]");
    if (!unit.empty()) os << " " << unit;
    errors_.push_back(os.str());
  }
  void finite(std::string_view key, double value, std::string_view unit) {
    if (std::isfinite(value)) return;
    std::ostringstream os;
    os << prefix_ << "." << key << " = " << value << ": must be a finite number";
    if (!unit.empty()) os << " (" << unit << ")";
    errors_.push_back(os.str());
  }
  void fail(const std::string& message) { errors_.push_back(prefix_ + "." + message); }
  std::vector<std::string> take() { return std::move(errors_); }

 private:
  std::string prefix_;
  std::vector<std::string> errors_;
};

constexpr double kInf = std::numeric_limits<double>::infinity();

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

std::vector<std::string> validate(const TrajectoryDesc& desc, std::string_view prefix) {
  constexpr double kPi = std::numbers::pi;
  Checker c(prefix);

  switch (desc.kind) {
    case TrajectoryKind::kStraight:
      c.finite("start.north_m", desc.start.north_m, "m");
      c.finite("start.east_m", desc.start.east_m, "m");
      c.finite("start_heading", desc.start_heading, "rad");
      c.range("straight_length_m", desc.straight_length_m, 0.0, true, kInf, true, "m");
      break;
    case TrajectoryKind::kWaypoints: {
      c.finite("start.north_m", desc.start.north_m, "m");
      c.finite("start.east_m", desc.start.east_m, "m");
      c.finite("start_heading", desc.start_heading, "rad");
      if (desc.waypoints.empty()) c.fail("waypoints: at least one waypoint is required");
      NorthEast previous = desc.start;
      for (std::size_t i = 0; i < desc.waypoints.size(); ++i) {
        const NorthEast& w = desc.waypoints[i];
        const std::string key = "waypoints[" + std::to_string(i) + "]";
        c.finite(key + ".north_m", w.north_m, "m");
        c.finite(key + ".east_m", w.east_m, "m");
        const double gap = std::hypot(w.north_m - previous.north_m, w.east_m - previous.east_m);
        if (std::isfinite(gap) && gap < kMinPointSeparationM) {
          std::ostringstream os;
          os << key << " = (" << w.north_m << ", " << w.east_m << "): is " << gap << " m from the "
             << (i == 0 ? "start point" : "previous waypoint")
             << "; consecutive points must be at least " << kMinPointSeparationM << " m apart";
          c.fail(os.str());
        }
        previous = w;
      }
      break;
    }
    case TrajectoryKind::kLawnmower:
      c.finite("lawnmower.origin.north_m", desc.lawnmower.origin.north_m, "m");
      c.finite("lawnmower.origin.east_m", desc.lawnmower.origin.east_m, "m");
      c.finite("lawnmower.first_leg_heading", desc.lawnmower.first_leg_heading, "rad");
      c.range("lawnmower.leg_length_m", desc.lawnmower.leg_length_m, 0.0, true, kInf, true, "m");
      c.range("lawnmower.line_spacing_m", desc.lawnmower.line_spacing_m, 0.0, true, kInf, true,
              "m");
      if (desc.lawnmower.legs < 1 || desc.lawnmower.legs > kMaxLegs) {
        c.fail("lawnmower.legs = " + std::to_string(desc.lawnmower.legs) + ": must be in [1, " +
               std::to_string(kMaxLegs) + "]");
      }
      break;
  }

  c.range("speed_m_s", desc.speed_m_s, 0.0, true, kMaxSpeedMPerS, false, "m/s");
  c.range("max_turn_rate_rad_s", desc.max_turn_rate_rad_s, 0.0, true, kMaxTurnRateRadPerS, false,
          "rad/s");

  const DepthDesc& d = desc.depth;
  if (d.mode == DepthMode::kConstantDepth) {
    c.range("depth.depth_m", d.depth_m, 0.0, false, kInf, true, "m");
  } else {
    c.range("depth.altitude_m", d.altitude_m, 0.0, true, kInf, true, "m");
    c.range("depth.max_climb_rate_m_s", d.max_climb_rate_m_s, 0.0, true, kMaxSpeedMPerS, false,
            "m/s");
    c.range("depth.look_ahead_m", d.look_ahead_m, 0.0, false, kInf, true, "m");
    c.range("depth.min_depth_m", d.min_depth_m, 0.0, false, kInf, true, "m");
    c.range("depth.vertical_smoothing_m", d.vertical_smoothing_m, 0.0, false, 1000.0, false, "m");
  }
  // the step is used in both modes (altitude along the path is precomputed when the seabed is
  // known)
  c.range("depth.profile_step_m", d.profile_step_m, 0.05, false, 10.0, false, "m");

  const SwayDesc& s = desc.sway;
  c.range("sway.amplitude_m", s.amplitude_m, 0.0, false, kInf, true, "m");
  if (s.amplitude_m > 0.0) {
    c.range("sway.period_s", s.period_s, 0.0, true, kInf, true, "s");
    c.finite("sway.phase", s.phase, "rad");
    c.range("sway.yaw_coupling", s.yaw_coupling, 0.0, false, 1.0, false, "");
  }

  const AttitudeDesc& a = desc.attitude;
  c.range("attitude.roll_gain", a.roll_gain, -kMaxRollGain, false, kMaxRollGain, false, "");
  c.range("attitude.max_roll", a.max_roll, 0.0, true, kPi / 2, true, "rad");
  c.range("attitude.roll_time_constant_s", a.roll_time_constant_s, 0.0, false, kMaxNoiseStepS,
          false, "s");
  c.range("attitude.pitch_gain", a.pitch_gain, 0.0, false, kMaxPitchGain, false, "");
  c.range("attitude.max_pitch", a.max_pitch, 0.0, true, kPi / 2, true, "rad");
  return c.take();
}

std::vector<std::string> validate(const NavNoiseDesc& desc, std::string_view prefix) {
  Checker c(prefix);
  c.range("position_noise_sd_m", desc.position_noise_sd_m, 0.0, false, kInf, true, "m");
  c.range("position_drift_m_per_sqrt_s", desc.position_drift_m_per_sqrt_s, 0.0, false, kInf, true,
          "m/sqrt(s)");
  c.range("heading_bias", desc.heading_bias, -std::numbers::pi, false, std::numbers::pi, false,
          "rad");
  c.range("heading_noise_sd", desc.heading_noise_sd, 0.0, false, kInf, true, "rad");
  c.range("heading_drift_rad_per_sqrt_s", desc.heading_drift_rad_per_sqrt_s, 0.0, false, kInf, true,
          "rad/sqrt(s)");
  c.range("attitude_noise_sd", desc.attitude_noise_sd, 0.0, false, kInf, true, "rad");
  c.range("speed_noise_sd_m_s", desc.speed_noise_sd_m_s, 0.0, false, kInf, true, "m/s");
  c.range("speed_scale_factor_error", desc.speed_scale_factor_error, -kMaxScaleFactorError, true,
          kMaxScaleFactorError, true, "");
  c.range("yaw_rate_noise_sd_rad_s", desc.yaw_rate_noise_sd_rad_s, 0.0, false, kInf, true, "rad/s");
  c.range("depth_noise_sd_m", desc.depth_noise_sd_m, 0.0, false, kInf, true, "m");
  c.range("altitude_noise_sd_m", desc.altitude_noise_sd_m, 0.0, false, kInf, true, "m");
  // at least 1 ns: the steps are used as integer nanoseconds
  c.range("noise_step_s", desc.noise_step_s, 1e-9, false, kMaxNoiseStepS, false, "s");
  c.range("drift_step_s", desc.drift_step_s, 1e-9, false, kMaxNoiseStepS, false, "s");
  return c.take();
}

std::vector<std::string> validate(const VehicleDesc& desc) {
  std::vector<std::string> errors = validate(desc.trajectory, "trajectory");
  std::vector<std::string> nav = validate(desc.nav, "nav");
  errors.insert(errors.end(), nav.begin(), nav.end());
  return errors;
}

}  // namespace sonarloop::vehicle
