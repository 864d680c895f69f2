#include "sim/targets/mesh.h"

#include <catch2/catch.hpp>
#include <cmath>

using sonarloop::targets::is_watertight;
using sonarloop::targets::mesh_area;
using sonarloop::targets::mesh_bounds;
using sonarloop::targets::mesh_volume;
using sonarloop::targets::transformed;
using sonarloop::targets::triangle_normal;
using sonarloop::targets::TriangleMesh;

namespace {

// Unit right tetrahedron at the origin, outward faces.
TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

// Axis-aligned cube [o, o + 1]^3, 12 outward triangles.
TriangleMesh cube(const Eigen::Vector3f& o) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.push_back(o + Eigen::Vector3f(static_cast<float>(i & 1),
                                             static_cast<float>((i >> 1) & 1),
                                             static_cast<float>((i >> 2) & 1)));
  }
  // faces as quads (a, b, c, d) counter-clockwise seen from outside
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    const auto u = [&](int k) { return static_cast<std::uint32_t>(q[k]); };
    m.triangles.push_back({u(0), u(1), u(2)});
    m.triangles.push_back({u(0), u(2), u(3)});
  }
  return m;
}

}  // namespace

TEST_CASE("mesh: tetrahedron volume, area, bounds, normals") {
  const TriangleMesh m = tetrahedron();
  CHECK(is_watertight(m));
  CHECK(mesh_volume(m) == Approx(1.0 / 6.0).epsilon(1e-12));
  CHECK(mesh_area(m) == Approx(1.5 + std::sqrt(3.0) / 2.0).epsilon(1e-7));
  const auto box = mesh_bounds(m);
  CHECK(box.min().isApprox(Eigen::Vector3d::Zero()));
  CHECK(box.max().isApprox(Eigen::Vector3d::Ones()));
  // outward normals: the three coordinate faces point along −x, −y, −z, the slanted one along
  // (1, 1, 1)/√3
  CHECK(triangle_normal(m, 0).isApprox(Eigen::Vector3d(0, 0, -1)));
  CHECK(triangle_normal(m, 1).isApprox(Eigen::Vector3d(0, -1, 0)));
  CHECK(triangle_normal(m, 2).isApprox(Eigen::Vector3d(-1, 0, 0)));
  CHECK(triangle_normal(m, 3).isApprox(Eigen::Vector3d::Ones().normalized()));
}

TEST_CASE("mesh: reversed orientation gives negative volume but stays consistent") {
  TriangleMesh m = tetrahedron();
  for (auto& t : m.triangles)
    std::swap(t[1], t[2]);
  CHECK(mesh_volume(m) == Approx(-1.0 / 6.0).epsilon(1e-12));
  CHECK(is_watertight(m));  // consistently (inward) oriented closed surface
}

TEST_CASE("mesh: cube volume is exact far from the origin") {
  const TriangleMesh m = cube({1000.0f, -2000.0f, 30.0f});
  CHECK(is_watertight(m));
  CHECK(mesh_volume(m) == Approx(1.0).epsilon(1e-12));
  CHECK(mesh_area(m) == Approx(6.0).epsilon(1e-9));
  const auto box = mesh_bounds(m);
  CHECK(box.sizes().isApprox(Eigen::Vector3d::Ones()));
  CHECK(box.min().isApprox(Eigen::Vector3d(1000, -2000, 30)));
}

TEST_CASE("mesh: is_watertight rejects open, inconsistent and broken meshes") {
  SECTION("empty") {
    CHECK_FALSE(is_watertight(TriangleMesh{}));
  }
  SECTION("one face removed (open)") {
    TriangleMesh m = tetrahedron();
    m.triangles.pop_back();
    CHECK_FALSE(is_watertight(m));
  }
  SECTION("one face flipped (inconsistent orientation)") {
    TriangleMesh m = tetrahedron();
    std::swap(m.triangles[3][1], m.triangles[3][2]);
    CHECK_FALSE(is_watertight(m));
  }
  SECTION("face duplicated (edge used by more than two triangles)") {
    TriangleMesh m = tetrahedron();
    m.triangles.push_back(m.triangles[0]);
    CHECK_FALSE(is_watertight(m));
  }
  SECTION("two tetrahedra sharing one edge (non-manifold edge)") {
    TriangleMesh m = tetrahedron();
    // a mirrored tetrahedron on the edge 0-3: vertices 0, 3 shared, new (−1, 0, 0), (0, −1, 0)
    m.vertices.push_back({-1, 0, 0});  // 4
    m.vertices.push_back({0, -1, 0});  // 5
    m.triangles.push_back({0, 5, 4});
    m.triangles.push_back({0, 4, 3});
    m.triangles.push_back({0, 3, 5});
    m.triangles.push_back({4, 5, 3});
    CHECK(mesh_volume(m) == Approx(2.0 / 6.0));  // each half is fine on its own ...
    CHECK_FALSE(is_watertight(m));               // ... but edge 0-3 joins four triangles
  }
  SECTION("index out of range") {
    TriangleMesh m = tetrahedron();
    m.triangles[3][2] = 4;
    CHECK_FALSE(is_watertight(m));
    CHECK(std::isfinite(mesh_volume(m)));  // skipped, no out-of-bounds read
    CHECK(std::isfinite(mesh_area(m)));
  }
  SECTION("repeated index (degenerate triangle)") {
    TriangleMesh m = tetrahedron();
    m.triangles.push_back({1, 1, 2});
    CHECK_FALSE(is_watertight(m));
  }
  SECTION("unwelded duplicate vertex") {
    TriangleMesh m = tetrahedron();
    m.vertices.push_back(m.vertices[3]);  // same position, new index
    m.triangles[3][2] = 4;
    CHECK_FALSE(is_watertight(m));
  }
}

TEST_CASE("mesh: empty mesh utilities") {
  const TriangleMesh m;
  CHECK(mesh_volume(m) == 0.0);
  CHECK(mesh_area(m) == 0.0);
  CHECK(mesh_bounds(m).isEmpty());
}

TEST_CASE("mesh: transformed() is a rigid motion") {
  const TriangleMesh m = cube({-0.5f, -0.5f, -0.5f});
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  X.translation() = Eigen::Vector3d(123.4, -56.7, 30.0);
  const TriangleMesh w = transformed(m, X);
  CHECK(w.triangles == m.triangles);
  CHECK(is_watertight(w));
  CHECK(mesh_volume(w) == Approx(1.0).epsilon(1e-5));  // float vertices at ~100 m
  CHECK(mesh_area(w) == Approx(6.0).epsilon(1e-5));
  CHECK(mesh_bounds(w).center().isApprox(X.translation(), 1e-6));
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    CHECK((w.vertices[i].cast<double>() - X * m.vertices[i].cast<double>()).norm() < 1e-5);
  }
  // the identity changes nothing
  const TriangleMesh same = transformed(m, Eigen::Isometry3d::Identity());
  CHECK(same.vertices == m.vertices);
}
