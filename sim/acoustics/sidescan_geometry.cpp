#include "sim/acoustics/sidescan_geometry.h"

#include <cmath>
#include <numbers>

namespace sonarloop::acoustics {

double slant_range_m(double two_way_time_s, double sound_speed_m_s) {
  return sound_speed_m_s * two_way_time_s / 2.0;
}

double ground_range_m(double slant_range_m, double altitude_m) {
  if (slant_range_m <= altitude_m) return 0.0;
  return std::sqrt(slant_range_m * slant_range_m - altitude_m * altitude_m);
}

double grazing_angle_rad(double slant_range_m, double altitude_m) {
  if (slant_range_m <= altitude_m) return std::numbers::pi / 2.0;
  return std::asin(altitude_m / slant_range_m);
}

double range_resolution_cw_m(double pulse_length_s, double sound_speed_m_s) {
  return sound_speed_m_s * pulse_length_s / 2.0;
}

double range_resolution_chirp_m(double bandwidth_hz, double sound_speed_m_s) {
  return sound_speed_m_s / (2.0 * bandwidth_hz);
}

double ground_range_resolution_m(double slant_resolution_m, double grazing_rad) {
  return slant_resolution_m / std::cos(grazing_rad);
}

double along_track_resolution_m(double slant_range_m, double beamwidth_rad) {
  return slant_range_m * beamwidth_rad;
}

double far_field_range_m(double length_m, double wavelength_m) {
  return length_m * length_m / wavelength_m;
}

double min_ping_interval_s(double max_range_m, double sound_speed_m_s) {
  return 2.0 * max_range_m / sound_speed_m_s;
}

double max_tow_speed_m_s(double target_length_m, double sound_speed_m_s, double max_range_m,
                         double pings_on_target) {
  return target_length_m * sound_speed_m_s / (2.0 * max_range_m * pings_on_target);
}

}  // namespace sonarloop::acoustics
