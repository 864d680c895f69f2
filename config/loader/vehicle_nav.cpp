#include "config/loader/vehicle_yaml.h"

namespace sonarloop::config::vehicle_yaml {

// Every key of nav is a number; all are optional (all zero = perfect navigation).
vehicle::NavNoiseDesc parse_nav(const Field& f) {
  return parse_number_map(f, nav_numbers());
}

}  // namespace sonarloop::config::vehicle_yaml
