#include "sim/vehicle/trajectory.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "units/angles.h"

namespace sonarloop::vehicle {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void throw_errors(const std::vector<std::string>& errors) {
  std::string message = "invalid vehicle trajectory: ";
  for (std::size_t i = 0; i < errors.size(); ++i)
    message += (i ? "; " : "") + errors[i];
  throw std::invalid_argument(message);
}

// First-order lag from value0 towards a constant command after dt seconds (τ = 0: no lag).
double lag(double value0, double command, double dt_s, double tau_s) {
  if (!(tau_s > 0.0)) return command;
  return command + (value0 - command) * std::exp(-dt_s / tau_s);
}

}  // namespace

Trajectory::Trajectory(const TrajectoryDesc& desc, const SeabedDepthFn& seabed_depth_m,
                       const PlanProgressFn& progress)
    : desc_(desc), min_altitude_m_(kNaN) {
  std::vector<std::string> errors;
  for (const Problem& p : validate(desc, "trajectory"))
    errors.push_back(p.message());
  if (desc.depth.mode == DepthMode::kAltitude && !seabed_depth_m) {
    errors.push_back(
        "trajectory.depth.mode = altitude: terrain following needs the seabed depth (from the "
        "scene), but none was given");
  }
  if (!errors.empty()) throw_errors(errors);

  speed_m_s_ = desc.speed_m_s;
  radius_m_ = vehicle::turn_radius_m(desc.speed_m_s, desc.max_turn_rate_rad_s);
  path_ = plan_path(desc);
  duration_s_ = path_.length_m() / speed_m_s_;
  if (desc.sway.amplitude_m > 0.0) sway_omega_ = 2.0 * std::numbers::pi / desc.sway.period_s;
  if (desc.attitude.roll_amplitude > 0.0 || desc.attitude.pitch_amplitude > 0.0) {
    wave_omega_ = 2.0 * std::numbers::pi / desc.attitude.wave_period_s;
  }

  // profile knots: a whole number of equal steps no longer than profile_step_m
  const double length = path_.length_m();
  const double steps = std::max(1.0, std::ceil(length / desc.depth.profile_step_m));
  if (steps > kMaxProfileSteps) {
    std::ostringstream os;
    os << "the path is " << length
       << " m long: at trajectory.depth.profile_step_m = " << desc.depth.profile_step_m
       << " m that is " << steps << " profile steps, more than the " << kMaxProfileSteps
       << " allowed; raise profile_step_m or shorten the mission";
    throw_errors({os.str()});
  }
  const auto n_steps = static_cast<std::size_t>(steps);
  knot_step_m_ = length > 0.0 ? length / steps : desc.depth.profile_step_m;
  end_time_ = from_seconds(duration_s_);
  // terrain following: knots also on the run-in and run-out, so that the smoothing of the
  // profile is not affected by its ends anywhere on the path
  const DepthDesc& d = desc.depth;
  if (d.mode == DepthMode::kAltitude) {
    pad_steps_ = DepthProfile::smoothing_margin_steps(knot_step_m_, d.vertical_smoothing_m);
  }
  const double origin_m = -static_cast<double>(pad_steps_) * knot_step_m_;

  // the seabed below the vehicle (sway included) at each knot
  if (seabed_depth_m) {
    seabed_m_.resize(n_steps + 1 + 2 * pad_steps_);
    for (std::size_t k = 0; k < seabed_m_.size(); ++k) {
      if (progress && k % kPlanProgressKnots == 0) progress(k, seabed_m_.size());
      const double s = origin_m + static_cast<double>(k) * knot_step_m_;
      const Vec2 p = horizontal_position(s, s / speed_m_s_);
      const double b = seabed_depth_m(p.x(), p.y());
      if (!std::isfinite(b)) {
        std::ostringstream os;
        os << "the seabed depth at (north " << p.x() << ", east " << p.y() << ") m, " << s
           << " m along the path, is " << b << ": must be finite (is the point outside the scene?)";
        throw_errors({os.str()});
      }
      seabed_m_[k] = b;
    }
    if (progress) progress(seabed_m_.size(), seabed_m_.size());
  }

  if (d.mode == DepthMode::kAltitude) {
    profile_ =
        DepthProfile(terrain_following_depths(seabed_m_, knot_step_m_, speed_m_s_, d.altitude_m,
                                              d.max_climb_rate_m_s, d.look_ahead_m, d.min_depth_m),
                     knot_step_m_, d.vertical_smoothing_m, origin_m);
  } else {
    profile_ = DepthProfile(d.depth_m);
  }
  if (!seabed_m_.empty()) {
    min_altitude_m_ = std::numeric_limits<double>::infinity();
    for (std::size_t k = pad_steps_; k <= pad_steps_ + n_steps; ++k) {
      const double s = origin_m + static_cast<double>(k) * knot_step_m_;
      min_altitude_m_ = std::min(min_altitude_m_, seabed_m_[k] - profile_.depth_at(s));
    }
  }

  // roll at each segment start, lagging behind each segment's constant command
  const double tau = desc.attitude.roll_time_constant_s;
  double roll = 0.0;  // flying straight before the start
  for (const PathSegment& seg : path_.segments()) {
    const double command = roll_command(seg.curvature_per_m);
    roll_start_.push_back(roll);
    roll_command_.push_back(command);
    roll = lag(roll, command, seg.length_m / speed_m_s_, tau);
  }
  roll_end_ = roll;
}

double Trajectory::roll_command(double curvature_per_m) const {
  const AttitudeDesc& a = desc_.attitude;
  // coordinated-turn bank: tan φ = u·ψ̇/g with ψ̇ = u·κ
  const double bank = std::atan(speed_m_s_ * speed_m_s_ * curvature_per_m / kStandardGravityMPerS2);
  return std::clamp(a.roll_gain * bank, -a.max_roll, a.max_roll);
}

double Trajectory::roll_at(int segment, double s_m) const {
  const double tau = desc_.attitude.roll_time_constant_s;
  if (segment < 0) return 0.0;
  const auto n = path_.segments().size();
  if (static_cast<std::size_t>(segment) >= n) {
    return lag(roll_end_, 0.0, (s_m - path_.length_m()) / speed_m_s_, tau);
  }
  const auto i = static_cast<std::size_t>(segment);
  const PathSegment& seg = path_.segments()[i];
  return lag(roll_start_[i], roll_command_[i], (s_m - seg.s0_m) / speed_m_s_, tau);
}

double Trajectory::sway_offset_m(double t_s) const {
  if (sway_omega_ == 0.0) return 0.0;
  return desc_.sway.amplitude_m * std::sin(sway_omega_ * t_s + desc_.sway.phase);
}

Vec2 Trajectory::horizontal_position(double s_m, double t_s) const {
  const PathPoint p = path_.at(s_m);
  const Vec2 starboard(-std::sin(p.heading), std::cos(p.heading));
  return p.position_NE + sway_offset_m(t_s) * starboard;
}

VehicleState Trajectory::state_at(SimTime t) const {
  const double t_s = to_seconds(t);
  const double u = speed_m_s_;
  const double s = u * t_s;
  const PathPoint p = path_.at(s);
  const Vec2 tangent = heading_vector(p.heading);
  const Vec2 starboard(-tangent.y(), tangent.x());
  const double path_rate = u * p.curvature_per_m;

  // sway y(t) and its derivatives
  double y = 0.0, y_dot = 0.0, y_ddot = 0.0;
  if (sway_omega_ != 0.0) {
    const double phase = sway_omega_ * t_s + desc_.sway.phase;
    const double a = desc_.sway.amplitude_m;
    y = a * std::sin(phase);
    y_dot = a * sway_omega_ * std::cos(phase);
    y_ddot = -a * sway_omega_ * sway_omega_ * std::sin(phase);
  }

  VehicleState state;
  state.t = t;
  state.path_s_m = s;
  const Vec2 horizontal = p.position_NE + y * starboard;
  const double z = profile_.depth_at(s);
  const double w = u * profile_.slope_at(s);
  state.pose.position_W = Vec3(horizontal.x(), horizontal.y(), z);
  const Vec2 v = (u - path_rate * y) * tangent + y_dot * starboard;
  state.velocity_W = Vec3(v.x(), v.y(), w);
  state.speed_m_s = v.norm();

  // yaw: the path tangent, plus the part of the sway's track angle the heading follows
  const double k = desc_.sway.yaw_coupling;
  const double q = y_dot / u;
  state.pose.yaw = wrap_to_pi(p.heading + (k != 0.0 ? k * std::atan(q) : 0.0));
  state.yaw_rate = path_rate + (k != 0.0 ? k * (y_ddot / u) / (1.0 + q * q) : 0.0);

  const AttitudeDesc& a = desc_.attitude;
  if (wave_omega_ == 0.0) {
    state.pose.pitch = std::clamp(a.pitch_gain * std::atan2(-w, u), -a.max_pitch, a.max_pitch);
    state.pose.roll = roll_at(p.segment, s);
  } else {
    // the wave-induced oscillation, pitch a quarter period ahead of roll
    const double wave_phase = wave_omega_ * t_s;
    double pitch = a.pitch_gain * std::atan2(-w, u);
    if (a.pitch_amplitude != 0.0) pitch += a.pitch_amplitude * std::cos(wave_phase);
    state.pose.pitch = std::clamp(pitch, -a.max_pitch, a.max_pitch);
    double roll = roll_at(p.segment, s);
    if (a.roll_amplitude != 0.0) {
      roll = std::clamp(roll + a.roll_amplitude * std::sin(wave_phase), -a.max_roll, a.max_roll);
    }
    state.pose.roll = roll;
  }

  if (!seabed_m_.empty() && t >= 0 && t <= end_time_) {
    // (s may pass the path length by rounding at t = end_time_)
    const double x =
        std::clamp(s, 0.0, path_.length_m()) / knot_step_m_ + static_cast<double>(pad_steps_);
    const auto i = std::min(static_cast<std::size_t>(x), seabed_m_.size() - 2);
    const double f = x - static_cast<double>(i);
    const double seabed = seabed_m_[i] + f * (seabed_m_[i + 1] - seabed_m_[i]);
    state.altitude_m = seabed - z;
  }
  if (p.segment >= 0 && static_cast<std::size_t>(p.segment) < path_.segments().size()) {
    state.leg = path_.segments()[static_cast<std::size_t>(p.segment)].leg;
  }
  return state;
}

}  // namespace sonarloop::vehicle
