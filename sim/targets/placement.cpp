#include "sim/targets/placement.h"

namespace sonarloop::targets {

Eigen::Isometry3d target_pose(const Eigen::Vector2d& position_ne_m, double heading_rad,
                              double base_z_down_m) {
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();
  // yaw only, the same convention as the vehicle's R_WV = Rz(ψ)·Ry(θ)·Rx(φ) in frames.h
  X_WT.linear() = rotation_from_ypr(heading_rad, 0.0, 0.0);
  X_WT.translation() = Vec3(position_ne_m.x(), position_ne_m.y(), base_z_down_m);
  return X_WT;
}

}  // namespace sonarloop::targets
