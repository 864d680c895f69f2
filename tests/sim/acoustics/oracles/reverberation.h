#pragma once
// A test oracle (tests/sim/acoustics/oracles/): the textbook dB form of a term the renderer
// computes in linear units inside its sonar equation (sim/render/echo_model.h); the renderer's
// tests check its levels against it (tests/sim/acoustics/*_test.cpp test the oracles
// themselves).
// Boundary (seabed) reverberation level of the Pailhas sonar equation (docs/physics.md §0, §2.6).
//
//   RL = SL − 2·TL + S_s(θ) + 10·log10 A ,   A = (c·τ/2)·φ·r
// Source: Pailhas, Petillot & Capus (2010) as given in docs/physics.md §0; Urick (1983) ch. 8
// (boundary reverberation). A is the insonified seabed area of one resolution cell with r the SLANT
// range: the ground extent cτ/(2cosθ) times the arc φ·r·cosθ, the cosines cancel, so it holds at
// any grazing angle (docs/physics.md §0 notes). Validity: pulse short against range (cτ/2 << r),
// beam narrow (φ << 1 rad), flat bottom across the cell.
#include <cmath>

namespace sonarloop::acoustics {

// Insonified area of one cell, m²: (c·τ/2)·φ·r. range_m is slant range, pulse_length_s the CW
// pulse length τ (use 1/B for a compressed chirp of bandwidth B), horizontal_beamwidth_rad the
// along-track beamwidth φ.
double reverberation_cell_area_m2(double range_m, double pulse_length_s, double sound_speed_m_s,
                                  double horizontal_beamwidth_rad);

// Boundary reverberation level, dB re 1 µPa: SL − 2·TL + S_s + 10·log10(A).
// source_level_db re 1 µPa @ 1 m; one_way_tl_db from spreading.h; scattering_strength_db
// S_s(θ) at the cell's grazing angle; area_m2 from reverberation_cell_area_m2 (> 0).
double boundary_reverberation_level_db(double source_level_db, double one_way_tl_db,
                                       double scattering_strength_db, double area_m2);

// ---- definitions (header-only: these are test oracles, not simulator code) ----

inline double reverberation_cell_area_m2(double range_m, double pulse_length_s,
                                         double sound_speed_m_s, double horizontal_beamwidth_rad) {
  // cτ/2: two-way range extent of the pulse; φ·r: along-track arc at slant range r
  return sound_speed_m_s * pulse_length_s / 2.0 * horizontal_beamwidth_rad * range_m;
}

inline double boundary_reverberation_level_db(double source_level_db, double one_way_tl_db,
                                              double scattering_strength_db, double area_m2) {
  return source_level_db - 2.0 * one_way_tl_db + scattering_strength_db +
         10.0 * std::log10(area_m2);
}

}  // namespace sonarloop::acoustics
