#include "sim/acoustics/beam_pattern.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sonarloop::acoustics {
namespace {

// full width 2·asin(x_3dB·λ/(π·l)); π (omnidirectional) when no -3 dB point exists
double full_width_rad(double x_half_power, double length_m, double wavelength_m) {
  const double s = x_half_power * wavelength_m / (std::numbers::pi * length_m);
  if (s >= 1.0) return std::numbers::pi;
  return 2.0 * std::asin(s);
}

}  // namespace

double line_array_pattern(double off_axis_rad, double length_m, double wavelength_m) {
  return sinc(std::numbers::pi * length_m / wavelength_m * std::sin(off_axis_rad));
}

double line_array_pattern_db(double off_axis_rad, double length_m, double wavelength_m) {
  const double b = std::fabs(line_array_pattern(off_axis_rad, length_m, wavelength_m));
  if (b <= 0.0) return kPatternFloorDb;
  return std::max(20.0 * std::log10(b), kPatternFloorDb);
}

double two_way_pattern_db(double off_axis_rad, double length_m, double wavelength_m) {
  const double b = std::fabs(line_array_pattern(off_axis_rad, length_m, wavelength_m));
  if (b <= 0.0) return kPatternFloorDb;
  return std::max(40.0 * std::log10(b), kPatternFloorDb);
}

double directivity_index_line_db(double length_m, double wavelength_m) {
  return 10.0 * std::log10(2.0 * length_m / wavelength_m);
}

double directivity_index_rect_db(double length_m, double width_m, double wavelength_m) {
  return 10.0 *
         std::log10(4.0 * std::numbers::pi * length_m * width_m / (wavelength_m * wavelength_m));
}

double beamwidth_3db_one_way_rad(double length_m, double wavelength_m) {
  return full_width_rad(kSincHalfPowerX, length_m, wavelength_m);
}

double beamwidth_3db_two_way_rad(double length_m, double wavelength_m) {
  return full_width_rad(kSincSquaredHalfPowerX, length_m, wavelength_m);
}

double first_null_rad(double length_m, double wavelength_m) {
  const double s = wavelength_m / length_m;
  if (s >= 1.0) return std::numbers::pi / 2.0;
  return std::asin(s);
}

}  // namespace sonarloop::acoustics
