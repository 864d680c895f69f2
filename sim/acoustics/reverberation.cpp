#include "sim/acoustics/reverberation.h"

#include <cmath>

namespace sonarloop::acoustics {

double reverberation_cell_area_m2(double range_m, double pulse_length_s, double sound_speed_m_s,
                                  double horizontal_beamwidth_rad) {
  // cτ/2: two-way range extent of the pulse; φ·r: along-track arc at slant range r
  return sound_speed_m_s * pulse_length_s / 2.0 * horizontal_beamwidth_rad * range_m;
}

double boundary_reverberation_level_db(double source_level_db, double one_way_tl_db,
                                       double scattering_strength_db, double area_m2) {
  return source_level_db - 2.0 * one_way_tl_db + scattering_strength_db +
         10.0 * std::log10(area_m2);
}

}  // namespace sonarloop::acoustics
