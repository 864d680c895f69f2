#include "sim/targets/loft.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sim/targets/mesh.h"
#include "tests/sim/targets/mesh_checks.h"

using namespace sonarloop::targets;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {
const Vector3d kX = Vector3d::UnitX();
const Vector3d kY = Vector3d::UnitY();
const Vector3d kZ = Vector3d::UnitZ();
}  // namespace

TEST_CASE("loft: square prism is watertight, outward, with the stated counts") {
  const std::vector<Vector2d> square{{1, -1}, {1, 1}, {-1, 1}, {-1, -1}};  // ccw about +z
  const std::vector<Ring> rings{polygon_ring(square, 0.0), polygon_ring(square, 0.5),
                                polygon_ring(square, 2.0)};
  REQUIRE(ring_turn_sign(rings[0], kZ) == 1);
  const TriangleMesh m = loft(rings, ring_centroid(rings.front()), ring_centroid(rings.back()));
  CHECK(m.triangles.size() == 2 * 4 * (3 - 1) + 2 * 4);
  CHECK(m.vertices.size() == 4 * 3 + 2);
  CHECK(is_watertight(m));
  CHECK(mesh_volume(m) == Approx(4.0 * 2.0).epsilon(1e-9));
  CHECK(test::max_vertex_in_front_of_faces(m) < 1e-6);
}

TEST_CASE("loft: an apex cap makes a pyramid") {
  const std::vector<Vector2d> square{{1, -1}, {1, 1}, {-1, 1}, {-1, -1}};
  const TriangleMesh m = loft({polygon_ring(square, 0.0)}, Vector3d::Zero(), 3.0 * kZ);
  CHECK(is_watertight(m));
  CHECK(mesh_volume(m) == Approx(4.0 * 3.0 / 3.0).epsilon(1e-9));
  CHECK(test::max_vertex_in_front_of_faces(m) < 1e-6);
}

TEST_CASE("loft: ellipse rings turn with the basis and reach the extremes") {
  const Ring r = ellipse_ring(Vector3d(0, 0, 2), kX, kY, 3.0, 1.5, 16);
  REQUIRE(r.size() == 16);
  CHECK(ring_turn_sign(r, kZ) == 1);
  CHECK(ring_turn_sign(ellipse_ring(Vector3d::Zero(), kY, kX, 1.0, 1.0, 8), kZ) == -1);
  // multiples of 4 contain the points at θ = 0, π/2, π, 3π/2
  CHECK(r[0].isApprox(Vector3d(3, 0, 2)));
  CHECK((r[4] - Vector3d(0, 1.5, 2)).norm() < 1e-12);
  CHECK((r[8] - Vector3d(-3, 0, 2)).norm() < 1e-12);
  CHECK((r[12] - Vector3d(0, -1.5, 2)).norm() < 1e-12);
  for (const auto& p : r) {
    CHECK(std::pow(p.x() / 3.0, 2) + std::pow(p.y() / 1.5, 2) == Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("loft: a cylinder along x from rings with y × z = x") {
  const int n = 64;
  const Vector3d c(0, 0, 0.5);
  const TriangleMesh m =
      loft({ellipse_ring(c - kX, kY, kZ, 0.5, 0.5, n), ellipse_ring(c + kX, kY, kZ, 0.5, 0.5, n)},
           c - kX, c + kX);
  CHECK(is_watertight(m));
  // inscribed 64-gon: area (n/2)·r²·sin(2π/n), times the length 2
  const double expected = 2.0 * (n / 2.0) * 0.25 * std::sin(2.0 * std::numbers::pi / n);
  CHECK(mesh_volume(m) == Approx(expected).epsilon(1e-6));
  CHECK(test::max_vertex_in_front_of_faces(m) < 1e-6);
}

TEST_CASE("loft: rings against the axis give an inside-out mesh (contract check)") {
  const std::vector<Vector2d> cw{{1, 1}, {1, -1}, {-1, -1}, {-1, 1}};  // clockwise about +z
  const TriangleMesh m =
      loft({polygon_ring(cw, 0.0), polygon_ring(cw, 1.0)}, Vector3d(0, 0, 0), Vector3d(0, 0, 1));
  CHECK(is_watertight(m));                // still consistent ...
  CHECK(mesh_volume(m) == Approx(-4.0));  // ... but inward
}

TEST_CASE("loft: invalid input throws") {
  CHECK_THROWS_AS(loft({}, Vector3d::Zero(), Vector3d::Zero()), std::invalid_argument);
  const Ring two{Vector3d::Zero(), kX};
  CHECK_THROWS_AS(loft({two}, Vector3d::Zero(), kZ), std::invalid_argument);
  const Ring tri{Vector3d::Zero(), kX, kY};
  const Ring quad{Vector3d::Zero(), kX, kX + kY, kY};
  CHECK_THROWS_WITH(loft({tri, quad}, Vector3d::Zero(), kZ),
                    Catch::Contains("ring 1 has 4 points, ring 0 has 3"));
}

TEST_CASE("loft: ring centroid") {
  const Ring r = ellipse_ring(Vector3d(1, 2, 3), kX, kY, 2.0, 1.0, 12);
  CHECK((ring_centroid(r) - Vector3d(1, 2, 3)).norm() < 1e-12);
}
