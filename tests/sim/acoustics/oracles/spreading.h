#pragma once
// A test oracle (tests/sim/acoustics/oracles/): the textbook dB form of a term the renderer
// computes in linear units inside its sonar equation (sim/render/echo_model.h); the renderer's
// tests check its levels against it (tests/sim/acoustics/*_test.cpp test the oracles
// themselves).
// Transmission loss: spherical spreading plus absorption (docs/physics.md §0; Urick, "Principles of
// Underwater Sound", 3rd ed. 1983, ch. 5, with α in dB/m).
//
//   TL(r) = 20·log10(r / 1 m) + α·r      dB re 1 m, one way
//
// Validity: far field of the transducer (r above a few array lengths) in a homogeneous medium
// with straight rays; r > 0 is required (r = 0 gives -inf). α comes from absorption.h in dB/km:
// pass α_dB/km / kMetresPerKilometre.
#include <cmath>

namespace sonarloop::acoustics {

// One-way spherical transmission loss, dB. range_m > 0 (slant range), alpha_db_per_m >= 0.
double transmission_loss_db(double range_m, double alpha_db_per_m);

// Two-way (out and back) loss 2·TL, dB, as used in the sonar equation (docs/physics.md §0).
double two_way_transmission_loss_db(double range_m, double alpha_db_per_m);

// ---- definitions (header-only: these are test oracles, not simulator code) ----

inline double transmission_loss_db(double range_m, double alpha_db_per_m) {
  // 20 log10 r: spherical spreading of intensity as 1/r² re 1 m
  return 20.0 * std::log10(range_m) + alpha_db_per_m * range_m;
}

inline double two_way_transmission_loss_db(double range_m, double alpha_db_per_m) {
  return 2.0 * transmission_loss_db(range_m, alpha_db_per_m);
}

}  // namespace sonarloop::acoustics
