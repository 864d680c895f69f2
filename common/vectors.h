#pragma once
// The project's small fixed-size vector and matrix types (Eigen), shared by the simulator and the
// onboard side. Frames and conventions: sim/frames.h.
#include <Eigen/Core>

namespace sonarloop {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace sonarloop
