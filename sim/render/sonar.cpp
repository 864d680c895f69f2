#include "sim/render/sonar.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sim/acoustics/absorption.h"
#include "sim/acoustics/noise.h"
#include "units/angles.h"

namespace sonarloop::render {
namespace {

// ∫ sinc⁴(π·L/λ·sin ψ) dψ over the forward half-space, by the midpoint rule on a grid fine
// enough to resolve the main lobe (the integrand is negligible beyond a few nulls).
double horizontal_beam_integral(double length_m, double wavelength_m) {
  const double null = acoustics::first_null_rad(length_m, wavelength_m);
  const double span = std::min(std::numbers::pi / 2.0, 12.0 * null);
  const int n = 20000;
  const double h = 2.0 * span / n;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double psi = -span + (k + 0.5) * h;
    const double b = acoustics::line_array_pattern(psi, length_m, wavelength_m);
    sum += b * b * b * b;
  }
  return sum * h;
}

}  // namespace

SonarSetup make_sonar_setup(const SonarDesc& desc, const scene::WaterDesc& water) {
  SonarSetup s;
  s.desc = desc;
  s.sound_speed_m_s =
      acoustics::sound_speed_fg_m_s(water.temperature_c, water.salinity_ppt, water.depth_m);
  s.wavelength_m = s.sound_speed_m_s / desc.frequency_hz;
  s.alpha_db_per_m =
      acoustics::francois_garrison_db_per_km(desc.frequency_hz, water.temperature_c,
                                             water.salinity_ppt, water.depth_m, water.ph) /
      acoustics::kMetresPerKilometre;
  if (!(desc.bin_size_m > 0.0) || !(desc.max_range_m > desc.bin_size_m)) {
    throw std::invalid_argument("sonar: need 0 < bin_size_m < max_range_m");
  }
  // pulse: CW of length tau has resolution c·tau/2; a chirp of bandwidth B has c/(2B)
  if (desc.chirp_bandwidth_hz > 0.0) {
    s.bandwidth_hz = desc.chirp_bandwidth_hz;
    s.range_resolution_m = s.sound_speed_m_s / (2.0 * desc.chirp_bandwidth_hz);
    s.pulse_length_s = desc.pulse_length_s;
  } else {
    s.pulse_length_s =
        desc.pulse_length_s > 0.0 ? desc.pulse_length_s : 2.0 * desc.bin_size_m / s.sound_speed_m_s;
    s.range_resolution_m = s.sound_speed_m_s * s.pulse_length_s / 2.0;
    s.bandwidth_hz = 1.0 / s.pulse_length_s;
  }
  s.bins = static_cast<int>(std::floor(desc.max_range_m / desc.bin_size_m + 1e-9));
  s.ping_period_s =
      desc.ping_period_s > 0.0 ? desc.ping_period_s : 2.0 * desc.max_range_m / s.sound_speed_m_s;
  s.along_track_resolution_m =
      desc.along_track_resolution_m > 0.0 ? desc.along_track_resolution_m : desc.bin_size_m;
  s.array = {desc.array_length_m, desc.array_height_m, desc.depression_deg * kRadPerDeg};
  s.horizontal_beamwidth_rad =
      acoustics::beamwidth_3db_two_way_rad(desc.array_length_m, s.wavelength_m);
  s.horizontal_beam_integral_rad = horizontal_beam_integral(desc.array_length_m, s.wavelength_m);
  s.vertical_beamwidth_rad =
      acoustics::beamwidth_3db_one_way_rad(desc.array_height_m, s.wavelength_m);
  s.noise_spectrum_db = acoustics::thermal_noise_spectrum_db(desc.frequency_hz);
  s.tvg = desc.tvg.value_or(desc.along_track == AlongTrackModel::kStrip ? acoustics::TvgLaw::kPoint
                                                                        : acoustics::TvgLaw::kArea);
  return s;
}

}  // namespace sonarloop::render
