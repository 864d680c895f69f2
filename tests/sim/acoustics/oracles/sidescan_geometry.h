#pragma once
// A test oracle (tests/sim/acoustics/oracles/): the closed forms of sidescan geometry on a flat
// seabed, against which tests check what the renderers compute per surface element (their
// slant ranges, grazing angles and resolutions) and what the docs state (docs/physics.md §3).
// Sidescan sonar geometry and resolution (docs/physics.md §3, standard; e.g. Blondel, "The Handbook
// of Sidescan Sonar", Springer 2009, ch. 2). Flat seabed, straight rays, altitude h above it.
#include <cmath>
#include <numbers>

namespace sonarloop::acoustics {

// Slant range of an echo received two_way_time_s after transmission: R = c·t/2.
double slant_range_m(double two_way_time_s, double sound_speed_m_s);

// Ground (horizontal) range x = sqrt(R² − h²); 0 inside the water column (R <= h).
double ground_range_m(double slant_range_m, double altitude_m);

// Grazing angle at the seabed θ_g = asin(h/R), rad; π/2 for R <= h.
double grazing_angle_rad(double slant_range_m, double altitude_m);

// Slant-range resolution of a CW pulse of length τ: δR = c·τ/2.
double range_resolution_cw_m(double pulse_length_s, double sound_speed_m_s);

// Slant-range resolution of a matched-filtered chirp of bandwidth B: δR = c/(2B).
double range_resolution_chirp_m(double bandwidth_hz, double sound_speed_m_s);

// Ground-range resolution δx = δR / cos θ_g.
double ground_range_resolution_m(double slant_resolution_m, double grazing_rad);

// Along-track resolution in the far field, δy = R·β (β the one-way −3 dB beamwidth, rad).
double along_track_resolution_m(double slant_range_m, double beamwidth_rad);

// Far-field (Fraunhofer) distance L²/λ of an aperture of length L (some texts use 2L²/λ).
double far_field_range_m(double length_m, double wavelength_m);

// Shortest ping interval that lets echoes from max_range_m return: 2·R_max/c.
double min_ping_interval_s(double max_range_m, double sound_speed_m_s);

// Fastest tow speed giving pings_on_target pings on a target of along-track length ℓ at slant
// range R, with one ping per 2R/c: v = ℓ·c/(2·R·N) (NOAA/IHO rule; docs/physics.md §3).
double max_tow_speed_m_s(double target_length_m, double sound_speed_m_s, double max_range_m,
                         double pings_on_target);

// ---- definitions (header-only: these are test oracles, not simulator code) ----

inline double slant_range_m(double two_way_time_s, double sound_speed_m_s) {
  return sound_speed_m_s * two_way_time_s / 2.0;
}

inline double ground_range_m(double slant_range_m, double altitude_m) {
  if (slant_range_m <= altitude_m) return 0.0;
  return std::sqrt(slant_range_m * slant_range_m - altitude_m * altitude_m);
}

inline double grazing_angle_rad(double slant_range_m, double altitude_m) {
  if (slant_range_m <= altitude_m) return std::numbers::pi / 2.0;
  return std::asin(altitude_m / slant_range_m);
}

inline double range_resolution_cw_m(double pulse_length_s, double sound_speed_m_s) {
  return sound_speed_m_s * pulse_length_s / 2.0;
}

inline double range_resolution_chirp_m(double bandwidth_hz, double sound_speed_m_s) {
  return sound_speed_m_s / (2.0 * bandwidth_hz);
}

inline double ground_range_resolution_m(double slant_resolution_m, double grazing_rad) {
  return slant_resolution_m / std::cos(grazing_rad);
}

inline double along_track_resolution_m(double slant_range_m, double beamwidth_rad) {
  return slant_range_m * beamwidth_rad;
}

inline double far_field_range_m(double length_m, double wavelength_m) {
  return length_m * length_m / wavelength_m;
}

inline double min_ping_interval_s(double max_range_m, double sound_speed_m_s) {
  return 2.0 * max_range_m / sound_speed_m_s;
}

inline double max_tow_speed_m_s(double target_length_m, double sound_speed_m_s, double max_range_m,
                                double pings_on_target) {
  return target_length_m * sound_speed_m_s / (2.0 * max_range_m * pings_on_target);
}

}  // namespace sonarloop::acoustics
