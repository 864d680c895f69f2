#pragma once
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

}  // namespace sonarloop::acoustics
