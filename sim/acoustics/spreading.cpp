#include "sim/acoustics/spreading.h"

#include <cmath>

namespace sonarloop::acoustics {

double transmission_loss_db(double range_m, double alpha_db_per_m) {
  // 20 log10 r: spherical spreading of intensity as 1/r² re 1 m
  return 20.0 * std::log10(range_m) + alpha_db_per_m * range_m;
}

double two_way_transmission_loss_db(double range_m, double alpha_db_per_m) {
  return 2.0 * transmission_loss_db(range_m, alpha_db_per_m);
}

}  // namespace sonarloop::acoustics
