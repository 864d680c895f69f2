#include "sim/targets/placement.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "sim/targets/mesh.h"
#include "sim/targets/shapes.h"

using namespace sonarloop::targets;
using sonarloop::Vec2;
using sonarloop::Vec3;

TEST_CASE("placement: heading 90 degrees points the long axis east, z stays down") {
  const Eigen::Isometry3d X_WT = target_pose(Vec2(10.0, -5.0), std::numbers::pi / 2.0, 30.0);
  const Eigen::Matrix3d R = X_WT.linear();
  CHECK((R * Vec3::UnitX() - Vec3(0, 1, 0)).norm() < 1e-12);   // x_T -> east
  CHECK((R * Vec3::UnitY() - Vec3(-1, 0, 0)).norm() < 1e-12);  // y_T (right) -> south
  CHECK((R * Vec3::UnitZ() - Vec3(0, 0, 1)).norm() < 1e-12);   // z_T -> down
  CHECK(R.determinant() == Approx(1.0));
  CHECK((X_WT.translation() - Vec3(10.0, -5.0, 30.0)).norm() < 1e-12);
}

TEST_CASE("placement: heading 0 is the identity rotation; other headings follow frames.h") {
  CHECK(target_pose(Vec2::Zero(), 0.0, 0.0).linear().isIdentity(1e-15));
  for (double h : {0.3, 1.2, std::numbers::pi, -2.0, 5.5}) {
    const Eigen::Matrix3d R = target_pose(Vec2(1, 2), h, 3).linear();
    const Vec2 heading = sonarloop::heading_vector(h);
    CHECK((R * Vec3::UnitX() - Vec3(heading.x(), heading.y(), 0.0)).norm() < 1e-12);
    CHECK((R * Vec3::UnitZ() - Vec3::UnitZ()).norm() < 1e-12);
  }
}

TEST_CASE("placement: a placed cuboid occupies the expected world box") {
  // 1.0 x 0.3 x 0.3 cuboid, heading east, footprint centre (10, -5), base plane 30 m down
  const TriangleMesh m_T = build_target_mesh(TargetType::kCuboid, Vec3::Zero());
  const TriangleMesh m_W =
      transformed(m_T, target_pose(Vec2(10.0, -5.0), std::numbers::pi / 2.0, 30.0));
  const auto box = mesh_bounds(m_W);
  CHECK((box.min() - Vec3(9.85, -5.5, 29.7)).norm() < 1e-5);
  CHECK((box.max() - Vec3(10.15, -4.5, 30.0)).norm() < 1e-5);
  CHECK(is_watertight(m_W));
  CHECK(mesh_volume(m_W) == Approx(0.09).epsilon(1e-5));
}

TEST_CASE("placement: burial lowers the base plane below the seabed") {
  const double seabed_z = 25.0;
  CHECK(base_plane_z_down_m(seabed_z, 0.0) == 25.0);
  CHECK(base_plane_z_down_m(seabed_z, 0.2) == Approx(25.2));
  // a 0.47 m Manta buried 0.2 m: its top is 0.27 m above the seabed (smaller z)
  const TriangleMesh m_W =
      transformed(build_target_mesh(TargetType::kManta, Vec3::Zero()),
                  target_pose(Vec2::Zero(), 0.0, base_plane_z_down_m(seabed_z, 0.2)));
  const auto box = mesh_bounds(m_W);
  CHECK(box.max().z() == Approx(25.2).epsilon(1e-6));
  CHECK(seabed_z - box.min().z() == Approx(0.27).epsilon(1e-4));
}
