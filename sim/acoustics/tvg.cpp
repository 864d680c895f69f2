#include "sim/acoustics/tvg.h"

#include <cmath>

namespace sonarloop::acoustics {

double tvg_db(double range_m, double alpha_db_per_m, double spreading_coeff) {
  // absorption counted twice: out and back
  return spreading_coeff * std::log10(range_m) + 2.0 * alpha_db_per_m * range_m;
}

double tvg_spreading_coeff(TvgLaw law) {
  switch (law) {
    case TvgLaw::kArea:
      return kTvgAreaCoeff;
    case TvgLaw::kPoint:
      return kTvgPointCoeff;
    case TvgLaw::kSpherical:
      return kTvgSphericalCoeff;
  }
  return kTvgAreaCoeff;
}

double tvg_db(double range_m, double alpha_db_per_m, TvgLaw law) {
  return tvg_db(range_m, alpha_db_per_m, tvg_spreading_coeff(law));
}

}  // namespace sonarloop::acoustics
