#include "sim/acoustics/sonar_equation.h"

#include <algorithm>
#include <cmath>

namespace sonarloop::acoustics {

double echo_level_db(double source_level_db, double one_way_tl_db,
                     double target_or_area_strength_db, double beam_two_way_db) {
  return source_level_db - 2.0 * one_way_tl_db + target_or_area_strength_db + beam_two_way_db;
}

double signal_excess_db(double source_level_db, double one_way_tl_db, double target_strength_db,
                        double directivity_index_db, double noise_level_db,
                        double reverberation_level_db) {
  return source_level_db - 2.0 * one_way_tl_db + target_strength_db + directivity_index_db -
         noise_level_db - reverberation_level_db;
}

double power_sum_db(double a_db, double b_db) {
  // factor out the larger term so that neither exponent overflows
  const double hi = std::max(a_db, b_db);
  const double lo = std::min(a_db, b_db);
  return hi + 10.0 * std::log10(1.0 + std::pow(10.0, (lo - hi) / 10.0));
}

}  // namespace sonarloop::acoustics
