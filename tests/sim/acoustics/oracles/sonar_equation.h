#pragma once
// A test oracle (tests/sim/acoustics/oracles/): the textbook dB form of a term the renderer
// computes in linear units inside its sonar equation (sim/render/echo_model.h); the renderer's
// tests check its levels against it (tests/sim/acoustics/*_test.cpp test the oracles
// themselves).
// The energetic (active) sonar equation of Pailhas, Petillot & Capus (2010),
// docs/physics.md §0, §3.
//
//   EL = SL − 2·TL + TS + B2                 echo level of a target (TS) or seabed cell
//                                            (TS → S_b(θ) + 10·log10 A), B2 = two-way beam
//                                            pattern in dB (0 on axis, beam_pattern.h)
//   XS = SL − 2·TL + TS + DI − NL − RL       signal excess, as printed by Pailhas et al.
//
// All levels in dB: SL re 1 µPa @ 1 m, TL one way (spreading.h), NL per Hz or per band
// (noise.h), RL re 1 µPa (reverberation.h). Validity: incoherent (energy) addition, far field.
#include <algorithm>
#include <cmath>

namespace sonarloop::acoustics {

// Echo level, dB re 1 µPa: SL − 2·TL + strength + beam_two_way_db, where strength is TS for a
// target or S_b(θ) + 10·log10(A) for a seabed cell.
double echo_level_db(double source_level_db, double one_way_tl_db,
                     double target_or_area_strength_db, double beam_two_way_db);

// Signal excess XS = SL − 2·TL + TS + DI − NL − RL, dB, exactly as Pailhas et al. (2010) print
// it: noise and reverberation are both subtracted in dB, not power-summed. Use
// power_sum_db(NL − DI, RL) for a combined interference level if that is what is wanted.
double signal_excess_db(double source_level_db, double one_way_tl_db, double target_strength_db,
                        double directivity_index_db, double noise_level_db,
                        double reverberation_level_db);

// 10·log10(10^(a/10) + 10^(b/10)): the level of two incoherent contributions.
double power_sum_db(double a_db, double b_db);

// ---- definitions (header-only: these are test oracles, not simulator code) ----

inline double echo_level_db(double source_level_db, double one_way_tl_db,
                            double target_or_area_strength_db, double beam_two_way_db) {
  return source_level_db - 2.0 * one_way_tl_db + target_or_area_strength_db + beam_two_way_db;
}

inline double signal_excess_db(double source_level_db, double one_way_tl_db,
                               double target_strength_db, double directivity_index_db,
                               double noise_level_db, double reverberation_level_db) {
  return source_level_db - 2.0 * one_way_tl_db + target_strength_db + directivity_index_db -
         noise_level_db - reverberation_level_db;
}

inline double power_sum_db(double a_db, double b_db) {
  // factor out the larger term so that neither exponent overflows
  const double hi = std::max(a_db, b_db);
  const double lo = std::min(a_db, b_db);
  return hi + 10.0 * std::log10(1.0 + std::pow(10.0, (lo - hi) / 10.0));
}

}  // namespace sonarloop::acoustics
