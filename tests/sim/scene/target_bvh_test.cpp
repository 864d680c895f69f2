// The targets alone in a small Embree scene (the profile renderer's target rays).
#include "sim/scene/target_bvh.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "sim/scene/scene.h"

using namespace sonarloop;
using namespace sonarloop::scene;

namespace {

SceneDesc scene_with(std::vector<TargetDesc> targets) {
  SceneDesc d;
  d.seed = 2;
  d.water.depth_m = 20.0;
  d.seabed.origin_m = Vec2(-500, -500);
  d.seabed.extent_m = Vec2(1000, 1000);
  d.seabed.elevation.rms_m = 0.0;
  scene::RegionDesc r;
  r.sediment = *seabed::find_sediment("medium_sand");
  d.seabed.regions = {r};
  d.targets = std::move(targets);
  return d;
}

TargetDesc box_at(double north, double east) {
  TargetDesc t;
  t.type = targets::TargetType::kBox;  // 0.7 x 0.7 x 0.4 m
  t.name = "box";
  t.position_m = Vec2(north, east);
  return t;
}

}  // namespace

TEST_CASE("target bvh: a ray straight down meets a box's top at its height") {
  // far from the world origin too: the BVH's local origin keeps millimetres
  for (const Vec2& at : {Vec2(3.0, -2.0), Vec2(420.0, -380.0)}) {
    const Scene sc(scene_with({box_at(at.x(), at.y())}));
    const TargetBvh& bvh = sc.target_bvh();
    REQUIRE_FALSE(bvh.empty());
    REQUIRE(bvh.spheres().size() == 1);
    const double top = 20.0 - 0.4;  // z of the box's top (flat seabed at 20 m)
    const Vec3 o(at.x() + 0.1, at.y() - 0.1, 10.0);
    CHECK(bvh.first_hit_m(o, Vec3(0, 0, 1), 50.0) == Approx(top - 10.0).margin(1e-4));
    // beside the box: nothing (the seabed is not in this scene)
    CHECK(bvh.first_hit_m(o + Vec3(1.0, 0, 0), Vec3(0, 0, 1), 50.0) < 0.0);
    // not beyond t_max
    CHECK(bvh.first_hit_m(o, Vec3(0, 0, 1), top - 10.5) < 0.0);
  }
}

TEST_CASE("target bvh: each bounding sphere holds its target's whole mesh") {
  std::vector<TargetDesc> ts;
  for (int k = 0; k < 9; ++k) {
    TargetDesc t;
    t.type = static_cast<targets::TargetType>(k);
    t.name = std::string(1, static_cast<char>('a' + k));
    t.position_m = Vec2(5.0 * k, -3.0 * k);
    t.heading_deg = 37.0 * k;
    ts.push_back(t);
  }
  const Scene sc(scene_with(ts));
  const TargetBvh& bvh = sc.target_bvh();
  REQUIRE(bvh.spheres().size() == sc.targets().size());
  for (std::size_t k = 0; k < sc.targets().size(); ++k) {
    const PlacedTarget& p = sc.targets()[k];
    const BoundingSphere& s = bvh.spheres()[k];
    for (const auto& v : p.mesh_T.vertices)
      CHECK((p.X_WT * v.cast<double>() - s.centre_W).norm() <= s.radius_m);
  }
}

TEST_CASE("target bvh: a scene without targets has an empty one") {
  const Scene sc(scene_with({}));
  CHECK(sc.target_bvh().empty());
  CHECK(sc.target_bvh().rtc_scene() == nullptr);
  CHECK(sc.target_bvh().first_hit_m(Vec3::Zero(), Vec3(0, 0, 1), 100.0) < 0.0);
}
