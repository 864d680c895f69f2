#pragma once
// Degrees <-> radians, once for the whole project. A header of its own, below every layer
// (scripts/check_layers.sh: any folder may include units/), since the simulator, the drivers,
// the onboard side and the agent all convert angles.
#include <numbers>

namespace sonarloop {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace sonarloop
