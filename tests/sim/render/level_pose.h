#pragma once
// The flat seabed of the ping renderer and bin label tests: water depth, and a level sonar above
// it.
#include <numbers>

#include "sim/frames.h"

namespace sonarloop::testing {

// The water depth of the flat test seabeds.
inline constexpr double kFlatSeabedDepth_m = 20.0;

// A level sonar at the origin, `altitude` m above the flat seabed, heading `heading_deg`.
inline Pose level_pose(double altitude, double heading_deg = 0.0) {
  Pose p;
  p.position_W = Vec3(0.0, 0.0, kFlatSeabedDepth_m - altitude);
  p.yaw = heading_deg * std::numbers::pi / 180.0;
  return p;
}

}  // namespace sonarloop::testing
