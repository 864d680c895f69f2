#include "autonomy/vehicle_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sonarloop::autonomy {
namespace {

void require_positive(double v, const char* name) {
  if (!(std::isfinite(v) && v > 0.0)) {
    throw std::invalid_argument(std::string("vehicle: ") + name + " must be > 0 and finite, got " +
                                std::to_string(v));
  }
}

double clamp_magnitude(double v, double limit) {
  return std::clamp(v, -limit, limit);
}

}  // namespace

void VehicleParams::validate() const {
  require_positive(speed_m_s, "speed_m_s");
  require_positive(max_turn_rate_rad_s, "max_turn_rate_rad_s");
  require_positive(max_vertical_rate_m_s, "max_vertical_rate_m_s");
}

VehicleState step_vehicle(const VehicleState& s, const VehicleCommand& c, const VehicleParams& p,
                          double dt_s) {
  if (!(dt_s > 0.0)) return s;
  VehicleState n = s;
  n.t_s = s.t_s + dt_s;
  // heading: the shorter way round, at most the turn rate
  const double turn =
      clamp_magnitude(wrap_to_pi(c.heading_rad - s.heading_rad), p.max_turn_rate_rad_s * dt_s);
  n.heading_rad = wrap_to_pi(s.heading_rad + turn);
  n.turn_rate_rad_s = turn / dt_s;
  // depth: at most the vertical rate; pitch is the climb angle (+ nose up when rising)
  const double dz = clamp_magnitude(c.depth_m - s.depth_m, p.max_vertical_rate_m_s * dt_s);
  n.depth_m = s.depth_m + dz;
  const double vz_m_s = dz / dt_s;
  n.pitch_rad = std::asin(std::clamp(-vz_m_s / p.speed_m_s, -1.0, 1.0));
  // position: along the step's mean heading, horizontal speed of the inclined path
  const double horizontal_m =
      std::sqrt(std::max(0.0, p.speed_m_s * p.speed_m_s - vz_m_s * vz_m_s)) * dt_s;
  n.position = s.position + horizontal_m * direction(s.heading_rad + 0.5 * turn);
  return n;
}

}  // namespace sonarloop::autonomy
