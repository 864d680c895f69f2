#include "sim/targets/rockan.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "sim/targets/mesh.h"
#include "sim/targets/shapes.h"
#include "tests/sim/targets/mesh_checks.h"

using namespace sonarloop::targets;
using sonarloop::Vec3;

TEST_CASE("rockan: the construction table of rockan.h") {
  const auto levels = rockan_levels();
  CHECK(levels[0].height_m == 0.0);
  CHECK(levels[1].height_m == Approx(0.10));
  CHECK(levels[2].height_m == Approx(kRockanNominalHeightM));
  // the chine is the widest outline and spans the 1.00 x 0.50 footprint
  double x_min = 0, x_max = 0, y_max = 0;
  for (const auto& p : levels[1].outline_m) {
    x_min = std::min(x_min, p.x());
    x_max = std::max(x_max, p.x());
    y_max = std::max(y_max, std::abs(p.y()));
  }
  CHECK(x_max - x_min == Approx(kRockanNominalLengthM));
  CHECK(2.0 * y_max == Approx(kRockanNominalWidthM));
  // mirror symmetric about y = 0: vertex k mirrors vertex (9 − k) mod 8 (pairs 0-1, 2-7, 3-6, 4-5)
  for (const auto& level : levels) {
    for (int k = 0; k < kRockanOutlineVertices; ++k) {
      const auto& p = level.outline_m[static_cast<std::size_t>(k)];
      const auto& q = level.outline_m[static_cast<std::size_t>((9 - k) % 8)];
      CHECK(p.x() == Approx(q.x()));
      CHECK(p.y() == Approx(-q.y()));
    }
  }
}

TEST_CASE("rockan: corresponding edges are parallel, so every side facet is planar") {
  const auto levels = rockan_levels();
  for (std::size_t k = 0; k < kRockanOutlineVertices; ++k) {
    const std::size_t next = (k + 1) % kRockanOutlineVertices;
    const Eigen::Vector2d e0 = levels[0].outline_m[next] - levels[0].outline_m[k];
    for (std::size_t i = 1; i < levels.size(); ++i) {
      const Eigen::Vector2d e = levels[i].outline_m[next] - levels[i].outline_m[k];
      INFO("edge " << k << " level " << i);
      CHECK(std::abs(e0.x() * e.y() - e0.y() * e.x()) < 1e-12);  // parallel
      CHECK(e0.dot(e) > 0.0);                                    // same direction
    }
  }
  // and so the two triangles of each side quad are coplanar in the mesh
  const TriangleMesh m = build_target_mesh(TargetType::kRockan, Vec3::Zero());
  const std::size_t side_triangles = 2 * kRockanOutlineVertices * (kRockanLevels - 1);
  for (std::size_t i = 0; i < side_triangles; i += 2) {
    CHECK(triangle_normal(m, i).dot(triangle_normal(m, i + 1)) == Approx(1.0).epsilon(1e-6));
  }
}

TEST_CASE("rockan: exact volume, mesh volume and bounds") {
  // the prismatoid formula reproduces the hand-derived 67319/600000 m³
  CHECK(rockan_volume_m3(Vec3(1.0, 0.5, 0.4)) == Approx(0.11219833333).epsilon(1e-9));
  CHECK(kRockanNominalVolumeM3 == Approx(0.11219833333).epsilon(1e-9));
  const TriangleMesh m = build_target_mesh(TargetType::kRockan, Vec3::Zero());
  CHECK(m.triangles.size() == 48);
  CHECK(m.vertices.size() == 26);
  CHECK(is_watertight(m));
  // a polyhedron: the mesh volume is the exact volume (float vertices only)
  CHECK(mesh_volume(m) == Approx(kRockanNominalVolumeM3).epsilon(1e-6));
  const auto box = mesh_bounds(m);
  CHECK((box.min() - Vec3(-0.5, -0.25, -0.4)).norm() < 1e-6);
  CHECK((box.max() - Vec3(0.5, 0.25, 0.0)).norm() < 1e-6);
  CHECK(test::max_vertex_in_front_of_faces(m) < 1e-6);  // convex, outward
  // scaled: volume ∝ L·W·H
  CHECK(rockan_volume_m3(Vec3(2.0, 0.5, 0.2)) == Approx(kRockanNominalVolumeM3).epsilon(1e-12));
}

TEST_CASE("rockan: silhouette differs from the same-box cuboid from every side") {
  const TriangleMesh rockan = build_target_mesh(TargetType::kRockan, Vec3::Zero());
  const TriangleMesh cuboid = build_target_mesh(TargetType::kLargeCuboid, Vec3::Zero());
  const char* view_name[3] = {"front (along x)", "side (along y)", "top (along z)"};
  for (int axis = 0; axis < 3; ++axis) {
    const double r = test::silhouette_area(rockan, axis);
    const double c = test::silhouette_area(cuboid, axis);
    INFO(view_name[axis] << ": rockan " << r << " m², cuboid " << c << " m²");
    CHECK(c == Approx(Vec3(0.5 * 0.4, 1.0 * 0.4, 1.0 * 0.5)[axis]).epsilon(1e-6));
    CHECK(r < 0.9 * c);  // not a rectangle filling its box in this view
  }
  // the plan view is the chine octagon, 0.41 m² of the 0.50 m² box
  CHECK(test::silhouette_area(rockan, 2) == Approx(0.41).epsilon(1e-6));
}

TEST_CASE("rockan: nose forward, low glacis, high rear") {
  // in T (x forward, z down): the top plateau (z = -0.4) lies in the rear half
  const TriangleMesh m = build_target_mesh(TargetType::kRockan, Vec3::Zero());
  double top_x_min = 1.0, top_x_max = -1.0;
  for (const auto& v : m.vertices) {
    if (std::abs(v.z() + 0.4f) < 1e-6f) {
      top_x_min = std::min(top_x_min, double{v.x()});
      top_x_max = std::max(top_x_max, double{v.x()});
    }
  }
  CHECK(top_x_max == Approx(0.0).margin(1e-6));
  CHECK(top_x_min == Approx(-0.45).epsilon(1e-6));
  // the nose (x = +0.5) is at the chine, 0.10 m up
  for (const auto& v : m.vertices) {
    if (v.x() > 0.5f - 1e-6f) CHECK(v.z() == Approx(-0.10).epsilon(1e-6));
  }
}
