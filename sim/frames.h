#pragma once
// Frames and angle conventions, stated once for the whole project (docs/style.md habit 15).
//
// World frame W: local tangent plane, NED. x = north (m), y = east (m), z = down (m), origin at
//   the scenario's geographic origin on the sea surface. The seabed is a heightmap
//   z_W = water_depth - elevation(x, y): elevation is positive UP, relative to the mean seabed.
// Vehicle body frame V: x forward, y starboard, z down (SNAME / NED body). Pose = position of
//   V's origin in W plus yaw ψ (heading, clockwise from north), pitch θ (nose up positive) and
//   roll φ (starboard down positive); R_WV = Rz(ψ)·Ry(θ)·Rx(φ).
// Sonar: port array looks to −y_V, starboard to +y_V; the depression angle is measured down
//   from the horizontal plane of V.
// Angles in code are radians unless the name says _deg. Headings in YAML are degrees clockwise
//   from north.
// Images: north-up, east-right; image row 0 is the northern edge (largest x).
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "common/vectors.h"

namespace sonarloop {

// R_WV from yaw, pitch, roll (radians), ZYX order.
inline Mat3 rotation_from_ypr(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .toRotationMatrix();
}

// Pose of the vehicle frame V in the world frame W at one instant: position of V's origin (the
// sonar's acoustic centre) and yaw ψ (heading), pitch θ, roll φ in radians.
struct Pose {
  Vec3 position_W = Vec3::Zero();
  double yaw = 0.0;
  double pitch = 0.0;
  double roll = 0.0;
  Mat3 R_WV() const { return rotation_from_ypr(yaw, pitch, roll); }
};

// Unit vector in the horizontal plane of W for a heading (radians clockwise from north).
inline Vec2 heading_vector(double heading) {
  return {std::cos(heading), std::sin(heading)};
}

}  // namespace sonarloop
