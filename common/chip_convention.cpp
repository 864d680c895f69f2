#include "common/chip_convention.h"

#include <algorithm>
#include <cmath>

namespace sonarloop::chips {

const char* chip_kind_name(ChipKind kind) {
  return kind == ChipKind::kShadow ? "shadow" : "highlight";
}

std::uint8_t chip_pixel(double level_db, const ChipLevels& levels) {
  const double t = (level_db - levels.min_db) / (levels.max_db - levels.min_db);
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
}

}  // namespace sonarloop::chips
