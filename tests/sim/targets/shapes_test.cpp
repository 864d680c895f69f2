#include "sim/targets/shapes.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "sim/targets/mesh.h"
#include "sim/targets/rockan.h"
#include "sim/targets/target_type.h"
#include "tests/sim/targets/mesh_checks.h"

using namespace sonarloop::targets;
using sonarloop::Vec3;

namespace {

// Checks the mesh of `type` at size_m (0 = nominal) against the frame convention of shapes.h:
// closed, outward, convex, bounds = [−L/2, L/2] × [−W/2, W/2] × [−H, 0] within 1 % of each
// dimension, volume within volume_tolerance (1 %) of the analytic value. Returns the relative
// volume error.
double check_target(TargetType type, const Vec3& size_m, int segments = 0,
                    double volume_tolerance = 0.01) {
  const Vec3 s = resolve_target_size(type, size_m);
  const TriangleMesh m = build_target_mesh(type, size_m, segments);
  INFO(target_type_info(type).key << " size " << s.transpose() << " segments " << segments);
  CHECK(is_watertight(m));
  const double volume = mesh_volume(m);
  CHECK(volume > 0.0);  // outward normals
  const double analytic = nominal_volume_m3(type, size_m);
  const double rel_error = (volume - analytic) / analytic;
  CHECK(std::abs(rel_error) < volume_tolerance);
  // every target is convex: all vertices behind every face plane, faces away from the centroid
  CHECK(test::max_vertex_in_front_of_faces(m) < 1e-5 * s.maxCoeff());
  CHECK(test::faces_facing_point(m, test::vertex_centroid(m)) == 0);
  const auto box = mesh_bounds(m);
  const Vec3 lo(-s.x() / 2.0, -s.y() / 2.0, -s.z());
  const Vec3 hi(s.x() / 2.0, s.y() / 2.0, 0.0);
  for (int i = 0; i < 3; ++i) {
    INFO("axis " << i);
    CHECK(std::abs(box.min()[i] - lo[i]) < 0.01 * s[i]);
    CHECK(std::abs(box.max()[i] - hi[i]) < 0.01 * s[i]);
    CHECK(std::abs(box.sizes()[i] - s[i]) < 0.01 * s[i]);
  }
  return rel_error;
}

}  // namespace

TEST_CASE("shapes: every target at nominal size") {
  std::printf("%-18s %9s %9s %11s %11s %10s\n", "target", "segments", "triangles", "volume_m3",
              "analytic_m3", "error_%");
  for (const auto& info : target_type_table()) {
    const double err = check_target(info.type, Vec3::Zero());
    const TriangleMesh m = build_target_mesh(info.type, Vec3::Zero());
    std::printf("%-18s %9d %9zu %11.6f %11.6f %10.4f\n", std::string(info.key).c_str(),
                effective_segments(info.type, Vec3::Zero(), 0), m.triangles.size(), mesh_volume(m),
                nominal_volume_m3(info.type, Vec3::Zero()), 100.0 * err);
    // default meshes stay modest for the Embree scene
    CHECK(m.triangles.size() <= 6000);
  }
}

TEST_CASE("shapes: analytic volumes at nominal size") {
  const Vec3 z = Vec3::Zero();
  // frustum πh(R² + Rr + r²)/3 with R = 0.49, r = 0.245, h = 0.47
  CHECK(nominal_volume_m3(TargetType::kManta, z) ==
        Approx(std::numbers::pi * 0.47 * (0.49 * 0.49 + 0.49 * 0.245 + 0.245 * 0.245) / 3.0)
            .epsilon(1e-12));
  CHECK(nominal_volume_m3(TargetType::kCylinder, z) ==
        Approx(std::numbers::pi * 0.15 * 0.15 * 1.0));
  CHECK(nominal_volume_m3(TargetType::kStandingCylinder, z) ==
        Approx(std::numbers::pi * 0.15 * 0.15 * 1.0));
  CHECK(nominal_volume_m3(TargetType::kCuboid, z) == Approx(1.0 * 0.3 * 0.3));
  CHECK(nominal_volume_m3(TargetType::kLargeCuboid, z) == Approx(1.0 * 0.5 * 0.4));
  CHECK(nominal_volume_m3(TargetType::kBox, z) == Approx(0.7 * 0.7 * 0.4));
  CHECK(nominal_volume_m3(TargetType::kHemisphere, z) ==
        Approx(2.0 / 3.0 * std::numbers::pi * 0.125));
  CHECK(nominal_volume_m3(TargetType::kSmallHemisphere, z) ==
        Approx(2.0 / 3.0 * std::numbers::pi * 0.25 * 0.25 * 0.25));
  CHECK(nominal_volume_m3(TargetType::kRockan, z) == Approx(kRockanNominalVolumeM3));
}

TEST_CASE("shapes: Manta, cylinders and hemisphere follow the issue's geometry") {
  const Vec3 z = Vec3::Zero();
  SECTION("Manta: 98 cm base on z = 0, 49 cm top at z = -0.47") {
    const TriangleMesh m = build_target_mesh(TargetType::kManta, z);
    double base_r = 0.0, top_r = 0.0;
    for (const auto& v : m.vertices) {
      const double r = std::hypot(v.x(), v.y());
      if (std::abs(v.z()) < 1e-6) base_r = std::max(base_r, r);
      if (std::abs(v.z() + 0.47) < 1e-6) top_r = std::max(top_r, r);
    }
    CHECK(base_r == Approx(0.49).epsilon(1e-6));
    CHECK(top_r == Approx(0.245).epsilon(1e-6));
  }
  SECTION("lying cylinder: axis along x, radius 0.15 about (x, 0, -0.15)") {
    const TriangleMesh m = build_target_mesh(TargetType::kCylinder, z);
    for (const auto& v : m.vertices) {
      const double r = std::hypot(v.y(), v.z() + 0.15);
      CHECK((r < 1e-6 || std::abs(r - 0.15) < 1e-6));  // cap centres or on the surface
      CHECK(std::abs(std::abs(v.x()) - 0.5) < 1e-6);
    }
  }
  SECTION("standing cylinder: vertical axis, radius 0.15, height 1") {
    const TriangleMesh m = build_target_mesh(TargetType::kStandingCylinder, z);
    for (const auto& v : m.vertices) {
      const double r = std::hypot(v.x(), v.y());
      CHECK((r < 1e-6 || std::abs(r - 0.15) < 1e-6));
      CHECK((std::abs(v.z()) < 1e-6 || std::abs(v.z() + 1.0) < 1e-6));
    }
  }
  SECTION("hemisphere: vertices on the sphere of radius 0.5 or on the base disc") {
    const TriangleMesh m = build_target_mesh(TargetType::kHemisphere, z);
    int on_base = 0;
    for (const auto& v : m.vertices) {
      CHECK(v.z() <= 1e-7f);  // above the base plane (z down)
      if (std::abs(v.z()) < 1e-7) ++on_base;
      if (v.norm() > 1e-6) CHECK(v.cast<double>().norm() == Approx(0.5).epsilon(1e-6));
    }
    CHECK(on_base == default_segments(TargetType::kHemisphere, z) + 1);  // equator + centre
  }
}

TEST_CASE("shapes: size override scales bounds and volume") {
  for (const auto& info : target_type_table()) {
    const Vec3 nominal = info.size_m;
    const Vec3 scale(1.7, 0.6, 1.3);
    const Vec3 size = nominal.cwiseProduct(scale);
    INFO(info.key);
    check_target(info.type, size);  // bounds = size, volume vs analytic
    // the analytic volume scales by the product of the axis factors
    CHECK(nominal_volume_m3(info.type, size) ==
          Approx(nominal_volume_m3(info.type, Vec3::Zero()) * scale.prod()).epsilon(1e-12));
    // and so does the mesh volume, at a fixed segment count
    const double v0 = mesh_volume(build_target_mesh(info.type, Vec3::Zero(), 64));
    const double v1 = mesh_volume(build_target_mesh(info.type, size, 64));
    CHECK(v1 == Approx(v0 * scale.prod()).epsilon(1e-5));
  }
}

TEST_CASE("shapes: a zero component keeps the nominal value") {
  const Vec3 s = resolve_target_size(TargetType::kManta, Vec3(0.0, 0.0, 0.30));
  CHECK(s.isApprox(Vec3(0.98, 0.98, 0.30)));
  CHECK(resolve_target_size(TargetType::kBox, Vec3::Zero()).isApprox(Vec3(0.7, 0.7, 0.4)));
  check_target(TargetType::kManta, Vec3(0.0, 0.0, 0.30));
}

TEST_CASE("shapes: invalid sizes, segments and types are rejected with a clear message") {
  CHECK_THROWS_WITH(build_target_mesh(TargetType::kManta, Vec3(-1.0, 0.0, 0.0)),
                    Catch::Contains("'manta'") && Catch::Contains("length"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(build_target_mesh(TargetType::kBox, Vec3(0.0, nan, 0.0)), std::invalid_argument);
  const double inf = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(nominal_volume_m3(TargetType::kCuboid, Vec3(0.0, 0.0, inf)),
                    Catch::Contains("height"));
  CHECK_THROWS_WITH(build_target_mesh(TargetType::kCylinder, Vec3::Zero(), -4),
                    Catch::Contains("segments -4"));
  CHECK_THROWS_AS(build_target_mesh(TargetType::kCylinder, Vec3::Zero(), kMaxCurvedSegments + 1),
                  std::invalid_argument);
  CHECK_THROWS_WITH(build_target_mesh(static_cast<TargetType>(42), Vec3::Zero()),
                    Catch::Contains("unknown target type id 42"));
}

TEST_CASE("shapes: default tessellation rule") {
  const Vec3 z = Vec3::Zero();
  // N = multiple of 4 >= max(48, ceil(2π r_max / 3 cm)) at nominal size
  CHECK(default_segments(TargetType::kManta, z) == 104);            // r 0.49 -> 102.6
  CHECK(default_segments(TargetType::kCylinder, z) == 48);          // r 0.15 -> 31.4
  CHECK(default_segments(TargetType::kStandingCylinder, z) == 48);  // r 0.15
  CHECK(default_segments(TargetType::kHemisphere, z) == 108);       // r 0.5 -> 104.7
  CHECK(default_segments(TargetType::kSmallHemisphere, z) == 76);   // 52.4; min 76
  for (auto t :
       {TargetType::kRockan, TargetType::kCuboid, TargetType::kLargeCuboid, TargetType::kBox}) {
    CHECK_FALSE(has_curved_surface(t));
    CHECK(default_segments(t, z) == 0);
    CHECK(effective_segments(t, z, 64) == 0);  // ignored by flat-faced types
    CHECK(build_target_mesh(t, z, 64).triangles.size() == build_target_mesh(t, z).triangles.size());
  }
  // the size enters the rule; the cap bounds huge overrides
  CHECK(default_segments(TargetType::kStandingCylinder, Vec3(2.0, 2.0, 1.0)) == 212);  // 209.4
  CHECK(default_segments(TargetType::kHemisphere, Vec3(40.0, 40.0, 20.0)) == kMaxCurvedSegments);
  // explicit counts: rounded up to a multiple of 4, at least 8
  CHECK(effective_segments(TargetType::kManta, z, 3) == 8);
  CHECK(effective_segments(TargetType::kManta, z, 50) == 52);
  CHECK(effective_segments(TargetType::kManta, z, 64) == 64);

  // the rule's promises, for every curved type at several sizes: volume deficit < 0.3 % and
  // every edge across the curvature (ring chords; meridian chords of the hemispheres) <= 3 cm
  for (const auto& info : target_type_table()) {
    if (!has_curved_surface(info.type)) continue;
    for (double f : {0.5, 1.0, 2.5}) {
      const Vec3 size = f * info.size_m;
      const TriangleMesh m = build_target_mesh(info.type, size);
      const int n = default_segments(info.type, size);
      const bool hemi =
          info.type == TargetType::kHemisphere || info.type == TargetType::kSmallHemisphere;
      INFO(info.key << " x" << f << " N " << n);
      CHECK(n % 4 == 0);
      CHECK(n >= (hemi ? kMinHemisphereSegments : kMinCurvedSegments));
      const double deficit = 1.0 - mesh_volume(m) / nominal_volume_m3(info.type, size);
      CHECK(deficit > 0.0);  // inscribed: slightly low
      CHECK(deficit < 0.003);
      const bool along_x = info.type == TargetType::kCylinder;  // rings lie in x = const planes
      double longest_curved = 0.0;
      for (const auto& [a, b] : test::unique_edges(m)) {
        const Eigen::Vector3d p = m.vertices[a].cast<double>();
        const Eigen::Vector3d q = m.vertices[b].cast<double>();
        // the last two vertices are the loft's cap points: their edges are flat cap radii,
        // except the hemisphere's pole, which is on the curved surface
        const auto cap_start = static_cast<std::uint32_t>(m.vertices.size() - 2);
        if (a == cap_start || b == cap_start) continue;
        if (!hemi && b == cap_start + 1) continue;
        const bool ring_edge =
            along_x ? std::abs(p.x() - q.x()) < 1e-6 : std::abs(p.z() - q.z()) < 1e-6;
        const bool meridian =
            hemi && (b == cap_start + 1 ||
                     std::abs(std::atan2(p.y(), p.x()) - std::atan2(q.y(), q.x())) < 1e-5);
        if (ring_edge || meridian) longest_curved = std::max(longest_curved, (p - q).norm());
      }
      CHECK(longest_curved > 0.0);
      CHECK(longest_curved <= kMaxFacetChordM + 1e-6);
    }
  }
}

TEST_CASE("shapes: finer explicit tessellation converges to the analytic volume") {
  for (const auto& info : target_type_table()) {
    if (!has_curved_surface(info.type)) continue;
    const double analytic = nominal_volume_m3(info.type, Vec3::Zero());
    const double coarse = mesh_volume(build_target_mesh(info.type, Vec3::Zero(), 16));
    const double fine = mesh_volume(build_target_mesh(info.type, Vec3::Zero(), 512));
    INFO(info.key);
    CHECK(analytic - fine < 0.1 * (analytic - coarse));
    CHECK(std::abs(fine / analytic - 1.0) < 1e-4);
    // the coarsest count allowed (8) is still closed, outward, convex and exactly bounded; an
    // inscribed octagon loses 1 − sin(π/4)/(π/4) = 10 % of the area, an 8 x 2 lat/long
    // hemisphere 23 %
    check_target(info.type, Vec3::Zero(), 8, 0.3);
  }
}

TEST_CASE("shapes: transformed() preserves the target volume") {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(2.1, Vec3(0.3, -0.4, 0.8).normalized()).toRotationMatrix();
  X.translation() = Vec3(-35.0, 48.0, 29.5);
  for (const auto& info : target_type_table()) {
    const TriangleMesh m = build_target_mesh(info.type, Vec3::Zero());
    const TriangleMesh w = transformed(m, X);
    INFO(info.key);
    CHECK(is_watertight(w));
    CHECK(mesh_volume(w) == Approx(mesh_volume(m)).epsilon(1e-4));
    CHECK(mesh_area(w) == Approx(mesh_area(m)).epsilon(1e-5));
  }
}
