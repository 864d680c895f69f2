#include "config/loader/vehicle_yaml.h"

#include <utility>

namespace sonarloop::config::vehicle_yaml {

using vehicle::AttitudeDesc;
using vehicle::DepthDesc;
using vehicle::DepthMode;
using vehicle::LawnmowerDesc;
using vehicle::NavNoiseDesc;
using vehicle::SwayDesc;
using vehicle::TrajectoryDesc;
using vehicle::TrajectoryKind;
using vehicle::TurnDirection;

// --- tables of number keys ----------------------------------------------------------------------

const NumberTable<TrajectoryDesc>& trajectory_numbers() {
  static const NumberTable<TrajectoryDesc> table = {
      "trajectory",
      {
          {"heading_deg", "start_heading", YamlUnit::kDegree, &TrajectoryDesc::start_heading},
          {"length_m", "straight_length_m", YamlUnit::kSi, &TrajectoryDesc::straight_length_m},
          {"speed_m_s", "speed_m_s", YamlUnit::kSi, &TrajectoryDesc::speed_m_s},
          {"max_turn_rate_deg_s", "max_turn_rate_rad_s", YamlUnit::kDegree,
           &TrajectoryDesc::max_turn_rate_rad_s},
      }};
  return table;
}

const NumberTable<LawnmowerDesc>& lawnmower_numbers() {
  static const NumberTable<LawnmowerDesc> table = {
      "trajectory.lawnmower",
      {
          {"first_leg_heading_deg", "first_leg_heading", YamlUnit::kDegree,
           &LawnmowerDesc::first_leg_heading},
          {"leg_length_m", "leg_length_m", YamlUnit::kSi, &LawnmowerDesc::leg_length_m},
          {"line_spacing_m", "line_spacing_m", YamlUnit::kSi, &LawnmowerDesc::line_spacing_m},
      }};
  return table;
}

const NumberTable<DepthDesc>& depth_numbers() {
  static const NumberTable<DepthDesc> table = {
      "trajectory.depth",
      {
          {"depth_m", "depth_m", YamlUnit::kSi, &DepthDesc::depth_m, DepthMode::kConstantDepth},
          {"altitude_m", "altitude_m", YamlUnit::kSi, &DepthDesc::altitude_m, DepthMode::kAltitude},
          {"max_climb_rate_m_s", "max_climb_rate_m_s", YamlUnit::kSi,
           &DepthDesc::max_climb_rate_m_s, DepthMode::kAltitude},
          {"look_ahead_m", "look_ahead_m", YamlUnit::kSi, &DepthDesc::look_ahead_m,
           DepthMode::kAltitude},
          {"min_depth_m", "min_depth_m", YamlUnit::kSi, &DepthDesc::min_depth_m,
           DepthMode::kAltitude},
          {"vertical_smoothing_m", "vertical_smoothing_m", YamlUnit::kSi,
           &DepthDesc::vertical_smoothing_m, DepthMode::kAltitude},
          {"profile_step_m", "profile_step_m", YamlUnit::kSi, &DepthDesc::profile_step_m},
      }};
  return table;
}

const NumberTable<SwayDesc>& sway_numbers() {
  static const NumberTable<SwayDesc> table = {
      "trajectory.sway",
      {
          {"amplitude_m", "amplitude_m", YamlUnit::kSi, &SwayDesc::amplitude_m, std::nullopt,
           "0 = no sway"},
          {"period_s", "period_s", YamlUnit::kSi, &SwayDesc::period_s},
          {"phase_deg", "phase", YamlUnit::kDegree, &SwayDesc::phase},
          {"yaw_coupling", "yaw_coupling", YamlUnit::kSi, &SwayDesc::yaw_coupling},
      }};
  return table;
}

const NumberTable<AttitudeDesc>& attitude_numbers() {
  static const NumberTable<AttitudeDesc> table = {
      "trajectory.attitude",
      {
          {"roll_gain", "roll_gain", YamlUnit::kSi, &AttitudeDesc::roll_gain},
          {"max_roll_deg", "max_roll", YamlUnit::kDegree, &AttitudeDesc::max_roll},
          {"roll_time_constant_s", "roll_time_constant_s", YamlUnit::kSi,
           &AttitudeDesc::roll_time_constant_s, std::nullopt, "0 = no lag"},
          {"pitch_gain", "pitch_gain", YamlUnit::kSi, &AttitudeDesc::pitch_gain},
          {"max_pitch_deg", "max_pitch", YamlUnit::kDegree, &AttitudeDesc::max_pitch},
          {"roll_amplitude_deg", "roll_amplitude", YamlUnit::kDegree,
           &AttitudeDesc::roll_amplitude},
          {"pitch_amplitude_deg", "pitch_amplitude", YamlUnit::kDegree,
           &AttitudeDesc::pitch_amplitude},
          {"wave_period_s", "wave_period_s", YamlUnit::kSi, &AttitudeDesc::wave_period_s},
      }};
  return table;
}

const NumberTable<NavNoiseDesc>& nav_numbers() {
  static const NumberTable<NavNoiseDesc> table = {
      "nav",
      {
          {"position_noise_m", "position_noise_sd_m", YamlUnit::kSi,
           &NavNoiseDesc::position_noise_sd_m},
          {"position_drift_m_per_sqrt_s", "position_drift_m_per_sqrt_s", YamlUnit::kSi,
           &NavNoiseDesc::position_drift_m_per_sqrt_s},
          {"heading_bias_deg", "heading_bias", YamlUnit::kDegree, &NavNoiseDesc::heading_bias},
          {"heading_noise_deg", "heading_noise_sd", YamlUnit::kDegree,
           &NavNoiseDesc::heading_noise_sd},
          {"heading_drift_deg_per_sqrt_s", "heading_drift_rad_per_sqrt_s", YamlUnit::kDegree,
           &NavNoiseDesc::heading_drift_rad_per_sqrt_s},
          {"attitude_noise_deg", "attitude_noise_sd", YamlUnit::kDegree,
           &NavNoiseDesc::attitude_noise_sd},
          {"speed_noise_m_s", "speed_noise_sd_m_s", YamlUnit::kSi,
           &NavNoiseDesc::speed_noise_sd_m_s},
          {"speed_scale_error", "speed_scale_factor_error", YamlUnit::kSi,
           &NavNoiseDesc::speed_scale_factor_error},
          {"yaw_rate_noise_deg_s", "yaw_rate_noise_sd_rad_s", YamlUnit::kDegree,
           &NavNoiseDesc::yaw_rate_noise_sd_rad_s},
          {"depth_noise_m", "depth_noise_sd_m", YamlUnit::kSi, &NavNoiseDesc::depth_noise_sd_m},
          {"altitude_noise_m", "altitude_noise_sd_m", YamlUnit::kSi,
           &NavNoiseDesc::altitude_noise_sd_m},
          {"noise_step_s", "noise_step_s", YamlUnit::kSi, &NavNoiseDesc::noise_step_s, std::nullopt,
           "at least 1 ns"},
          {"drift_step_s", "drift_step_s", YamlUnit::kSi, &NavNoiseDesc::drift_step_s, std::nullopt,
           "at least 1 ns"},
      }};
  return table;
}

Range allowed_range(std::string_view field, YamlUnit unit, std::string_view note) {
  const std::optional<Limit> limit = vehicle::limit_of(field);
  return yaml_range(limit.value_or(Limit::finite()), unit, std::string(note));
}

// --- words --------------------------------------------------------------------------------------

namespace {

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

}  // namespace

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

}  // namespace sonarloop::config::vehicle_yaml
