#include "sim/acoustics/transmit_ringdown.h"

#include <cmath>

namespace sonarloop::acoustics {

int ringdown_bins(double ringdown_s, double sound_speed_m_s, double bin_size_m) {
  if (!(ringdown_s > 0.0)) return 0;
  // centre of bin k before the ring-down ends: k + 0.5 < c·T / (2·dr)
  const double reach = sound_speed_m_s * ringdown_s / (2.0 * bin_size_m) - 0.5;
  return reach > 0.0 ? static_cast<int>(std::ceil(reach)) : 0;
}

}  // namespace sonarloop::acoustics
