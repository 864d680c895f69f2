#pragma once
// Placing a target in the world: the pose X_WT of the target frame T (shapes.h: origin at the
// centre of the footprint on the base plane, x along the long axis, y right, z down) in the
// world frame W (sim/frames.h: NED, x north, y east, z down).
#include <Eigen/Geometry>

#include "sim/frames.h"

namespace sonarloop::targets {

// X_WT for a target lying level on a horizontal base plane:
//   position_ne_m   (north, east) of T's origin, the footprint centre (m)
//   heading_rad     direction of the long axis x_T, clockwise from north seen from above, i.e. a
//                   right-handed rotation about the down axis: R_WT = Rz(heading). Heading π/2
//                   points x_T east, y_T south; z_T stays down.
//   base_z_down_m   world z (down, m) of the base plane, see base_plane_z_down_m.
// p_W = X_WT · p_T. The body (z_T in [−height, 0]) then occupies z_W in
// [base_z_down_m − height, base_z_down_m]. Seabed tilt is not modelled: the target stays level.
Eigen::Isometry3d target_pose(const Eigen::Vector2d& position_ne_m, double heading_rad,
                              double base_z_down_m);

// World z (down, m) of a target's base plane: the seabed depth at the target centre plus the
// burial depth (burial_m > 0 sinks the target into the seabed by that much; 0 rests on it).
inline double base_plane_z_down_m(double seabed_z_down_m, double burial_m) {
  return seabed_z_down_m + burial_m;
}

}  // namespace sonarloop::targets
