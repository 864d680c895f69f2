#include "sim/vehicle/nav_sensor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "units/angles.h"

namespace sonarloop::vehicle {

NavSensorModel::NavSensorModel(const NavNoiseDesc& desc, std::uint64_t seed)
    : desc_(desc), seed_(seed) {
  const std::vector<Problem> problems = validate(desc, "nav");
  if (!problems.empty()) {
    throw std::invalid_argument("invalid navigation noise: " + join_messages(problems));
  }
  noise_step_ns_ = std::max<SimTime>(1, from_seconds(desc.noise_step_s));
  drift_step_ns_ = std::max<SimTime>(1, from_seconds(desc.drift_step_s));
}

double NavSensorModel::white(NavChannel channel, SimTime t) const {
  return hashed_white_noise(seed_, channel, t, noise_step_ns_);
}

double NavSensorModel::wiener(NavChannel channel, SimTime t) const {
  return hashed_wiener(seed_, channel, t, drift_step_ns_);
}

double NavSensorModel::heading_drift(SimTime t) const {
  double e = desc_.heading_bias;
  if (desc_.heading_drift_rad_per_sqrt_s > 0.0) {
    e += desc_.heading_drift_rad_per_sqrt_s * wiener(NavChannel::kHeading, t);
  }
  return e;
}

Vec2 NavSensorModel::position_drift(SimTime t) const {
  const double q = desc_.position_drift_m_per_sqrt_s;
  if (!(q > 0.0)) return Vec2::Zero();
  return {q * wiener(NavChannel::kNorth, t), q * wiener(NavChannel::kEast, t)};
}

NavSolution NavSensorModel::measure(const VehicleState& truth) const {
  const SimTime t = truth.t;
  const NavNoiseDesc& d = desc_;
  // each term is skipped when its coefficient is zero, so perfect nav is exactly the truth
  auto white_term = [&](double sd, NavChannel channel) {
    return sd > 0.0 ? sd * white(channel, t) : 0.0;
  };

  NavErrors e;
  const Vec2 drift = position_drift(t);
  e.north_m = drift.x() + white_term(d.position_noise_sd_m, NavChannel::kNorth);
  e.east_m = drift.y() + white_term(d.position_noise_sd_m, NavChannel::kEast);
  e.horizontal_m = std::hypot(e.north_m, e.east_m);
  e.depth_m = white_term(d.depth_noise_sd_m, NavChannel::kDepth);
  const double heading_error =
      heading_drift(t) + white_term(d.heading_noise_sd, NavChannel::kHeading);
  e.pitch = white_term(d.attitude_noise_sd, NavChannel::kPitch);
  e.roll = white_term(d.attitude_noise_sd, NavChannel::kRoll);
  e.yaw_rate = white_term(d.yaw_rate_noise_sd_rad_s, NavChannel::kYawRate);

  NavSolution nav;
  nav.t = t;
  const Vec3& p = truth.pose.position_W;
  nav.north_m = p.x() + e.north_m;
  nav.east_m = p.y() + e.east_m;
  nav.depth_m = p.z() + e.depth_m;
  nav.heading = wrap_to_two_pi(truth.pose.yaw + heading_error);
  nav.pitch = truth.pose.pitch + e.pitch;
  nav.roll = truth.pose.roll + e.roll;
  nav.yaw_rate = truth.yaw_rate + e.yaw_rate;
  if (std::isnan(truth.altitude_m)) {
    nav.altitude_m = truth.altitude_m;
  } else {
    e.altitude_m = white_term(d.altitude_noise_sd_m, NavChannel::kAltitude);
    nav.altitude_m = truth.altitude_m + e.altitude_m;
  }

  // velocity over ground: body-frame measurement (scale factor) rotated by the erroneous heading
  const Vec2 v_true(truth.velocity_W.x(), truth.velocity_W.y());
  Vec2 v = v_true;
  if (heading_error != 0.0) {
    const double c = std::cos(heading_error), s = std::sin(heading_error);
    v = Vec2(c * v_true.x() - s * v_true.y(), s * v_true.x() + c * v_true.y());
  }
  v *= 1.0 + d.speed_scale_factor_error;
  v += Vec2(white_term(d.speed_noise_sd_m_s, NavChannel::kVelocityNorth),
            white_term(d.speed_noise_sd_m_s, NavChannel::kVelocityEast));
  nav.speed_over_ground_m_s = v.norm();
  nav.course_over_ground = wrap_to_two_pi(std::atan2(v.y(), v.x()));

  // errors as published (angles wrapped)
  e.heading = wrap_to_pi(nav.heading - truth.pose.yaw);
  e.speed_m_s = nav.speed_over_ground_m_s - v_true.norm();
  e.course = wrap_to_pi(nav.course_over_ground - std::atan2(v_true.y(), v_true.x()));
  nav.error = e;
  return nav;
}

}  // namespace sonarloop::vehicle
