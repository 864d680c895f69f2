#include "sim/scene/scene.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "common/rng.h"
#include "sim/targets/target_type.h"

using namespace sonarloop;
using namespace sonarloop::scene;

namespace {

SceneDesc rippled_scene() {
  SceneDesc d;
  d.seed = 7;
  d.water.depth_m = 20.0;
  d.seabed.grid_spacing_m = 0.05;
  d.seabed.origin_m = Vec2(-30, -30);
  d.seabed.extent_m = Vec2(60, 60);
  RegionDesc sand;
  sand.sediment = *seabed::find_sediment("medium_sand");
  sand.centre_m = Vec2(-10, 0);
  sand.texture.ripples = RipplesDesc{};
  RegionDesc gravel;
  gravel.sediment = *seabed::find_sediment("sandy_gravel");
  gravel.centre_m = Vec2(10, 0);
  gravel.texture.clutter = ClutterDesc{};
  d.seabed.regions = {sand, gravel};
  TargetDesc box;
  box.type = targets::TargetType::kBox;
  box.name = "box-1";
  box.position_m = Vec2(2.0, 3.0);
  box.heading_deg = 30.0;
  d.targets = {box};
  return d;
}

double bilinear_twist(const seabed::SeabedModel& m, double x, double y) {
  const double d = m.spacing_m();
  const auto i = static_cast<std::int64_t>(std::floor(x / d));
  const auto j = static_cast<std::int64_t>(std::floor(y / d));
  float h[4];
  m.copy_region(i, j, 2, 2, h, nullptr);
  return std::abs(h[0] - h[1] - h[2] + h[3]);
}

}  // namespace

TEST_CASE("scene: vertical rays hit the seabed at the heightmap's bilinear elevation") {
  const Scene s(rippled_scene());
  const auto v = s.view(Box2{Vec2(-20, -20), Vec2(20, 20)}, 2);
  Rng rng(1, RngStream::kRayJitter);
  int hits = 0;
  for (int k = 0; k < 2000; ++k) {
    const double x = rng.uniform(-19.0, 19.0);
    const double y = rng.uniform(-19.0, 19.0);
    if ((Vec2(x, y) - Vec2(2.0, 3.0)).norm() < 1.0) continue;  // skip the target
    const Hit h = v->intersect(Vec3(x, y, 0.0), Vec3(0, 0, 1), 100.0);
    REQUIRE(h.kind == HitKind::kSeabed);
    ++hits;
    // a triangulated cell differs from the bilinear surface by at most a quarter of its twist
    const double expected = s.seabed_z(x, y);
    INFO("at " << x << ", " << y);
    CHECK(std::abs(h.point_W.z() - expected) <= 0.25 * bilinear_twist(s.seabed(), x, y) + 2e-4);
    CHECK(h.normal_W.z() < 0.0);  // facing up, towards the ray's origin
    CHECK(h.sediment == s.seabed().sediment_at(x, y));
  }
  CHECK(hits > 1900);
}

TEST_CASE("scene: rays on tile borders and lattice lines never slip through") {
  const Scene s(rippled_scene());
  const auto v = s.view(Box2{Vec2(-15, -15), Vec2(15, 15)}, 2);
  const double tile_m = s.seabed().tile_size() * s.seabed().spacing_m();
  REQUIRE(tile_m < 14.0);
  for (int k = -1; k <= 1; ++k) {
    for (double y = -14.0; y < 14.0; y += 0.0125) {
      const Hit h = v->intersect(Vec3(k * tile_m, y, 0.0), Vec3(0, 0, 1), 100.0);
      REQUIRE(h);
    }
  }
}

TEST_CASE("scene: a ray onto a target's top hits at the target's height") {
  const Scene s(rippled_scene());
  REQUIRE(s.targets().size() == 1);
  const PlacedTarget& box = s.targets()[0];
  const auto v = s.view(Box2{Vec2(-5, -5), Vec2(8, 8)}, 1);
  REQUIRE(v->target_count() == 1);
  const Vec3 top_centre = box.X_WT * Vec3(0, 0, -0.40);
  const Hit h = v->intersect(Vec3(2.0, 3.0, 0.0), Vec3(0, 0, 1), 100.0);
  REQUIRE(h.kind == HitKind::kTarget);
  CHECK(h.target == 0);
  CHECK(h.point_W.z() == Approx(top_centre.z()).margin(1e-4));
  CHECK(h.normal_W.z() == Approx(-1.0).margin(1e-4));
  // the box rests on the mean seabed level at its centre
  CHECK(box.bounds_W.max().z() == Approx(20.0 - s.seabed().base_elevation(2.0, 3.0)).margin(1e-4));
}

TEST_CASE("scene: a ray that misses everything says so") {
  const Scene s(rippled_scene());
  const auto v = s.view(Box2{Vec2(-5, -5), Vec2(5, 5)}, 1);
  CHECK_FALSE(v->intersect(Vec3(0, 0, 5), Vec3(0, 0, -1), 100.0));  // pointing up
  CHECK_FALSE(v->intersect(Vec3(0, 0, 5), Vec3(0, 0, 1), 3.0));     // too short
  CHECK_FALSE(v->intersect(Vec3(20, 0, 5), Vec3(0, 0, 1), 100.0));  // outside the view
  CHECK(v->intersect(Vec3(0, 0, 5), Vec3(0, 0, 1), 100.0).kind == HitKind::kSeabed);
}

TEST_CASE("scene: views are clipped to the seabed extent and built lazily") {
  const Scene s(rippled_scene());
  CHECK(s.seabed().cached_tile_count() == 0);
  const auto v = s.view(Box2{Vec2(25, 25), Vec2(40, 40)}, 1);
  CHECK(v->region().max.x() == Approx(30.0));
  CHECK(v->region().max.y() == Approx(30.0));
  CHECK_FALSE(v->intersect(Vec3(35, 35, 0), Vec3(0, 0, 1), 100.0));
  CHECK(v->intersect(Vec3(27, 27, 0), Vec3(0, 0, 1), 100.0));
  CHECK(s.seabed().cached_tile_count() <= 4);
}

TEST_CASE("scene: slant rays hit where a ray march over the heightmap says") {
  // independent oracle: march along the ray in 1 mm steps against the bilinear heightmap
  const Scene s(rippled_scene());
  const auto v = s.view(Box2{Vec2(-20, -20), Vec2(20, 20)}, 2);
  Rng rng(3, RngStream::kRayJitter);
  for (int k = 0; k < 50; ++k) {
    const Vec3 o(rng.uniform(-5.0, 5.0), rng.uniform(-10.0, -5.0), 12.0);
    const double grazing = rng.uniform(0.3, 0.9);
    const Vec3 dir = Vec3(0.0, std::cos(grazing), std::sin(grazing));
    const Hit h = v->intersect(o, dir, 200.0);
    REQUIRE(h);
    if (h.kind != HitKind::kSeabed) continue;
    double t = 0.0;
    for (; t < 200.0; t += 0.001) {
      const Vec3 p = o + t * dir;
      if (p.z() >= s.seabed_z(p.x(), p.y())) break;
    }
    CHECK(h.distance_m == Approx(t).margin(0.01));
  }
}

TEST_CASE("scene: a scene on a shared seabed equals one that builds its own") {
  const SceneDesc desc = rippled_scene();
  const Scene own(desc);
  auto shared = std::make_shared<const seabed::SeabedModel>(desc);
  // two scenes on one seabed, with different targets: the seabed (and its tiles) is shared
  SceneDesc other = desc;
  other.targets[0].type = targets::TargetType::kCylinder;
  other.targets[0].position_m = Vec2(-4.0, 1.0);
  const Scene a(desc, shared);
  const Scene b(other, shared);
  CHECK(&a.seabed() == shared.get());
  CHECK(&b.seabed() == shared.get());
  REQUIRE(a.targets().size() == 1);
  CHECK(a.targets()[0].X_WT.matrix() == own.targets()[0].X_WT.matrix());
  CHECK(a.targets()[0].bounds_W.min() == own.targets()[0].bounds_W.min());
  CHECK(b.targets()[0].desc.type == targets::TargetType::kCylinder);
  // the same rays hit the same points, on the seabed and on the target
  const Box2 region{Vec2(-10, -10), Vec2(10, 10)};
  const auto va = a.view(region, 1);
  const auto vo = own.view(region, 1);
  const std::size_t tiles = shared->cached_tile_count();
  CHECK(tiles > 0);
  b.view(region, 1);  // b finds a's tiles in the shared cache
  CHECK(shared->cached_tile_count() == tiles);
  Rng rng(5, RngStream::kRayJitter);
  for (int k = 0; k < 200; ++k) {
    const Vec3 o(rng.uniform(-8.0, 8.0), rng.uniform(-8.0, 8.0), 10.0);
    const Vec3 dir(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 1.0);
    const Hit ha = va->intersect(o, dir, 100.0);
    const Hit ho = vo->intersect(o, dir, 100.0);
    REQUIRE(ha.kind == ho.kind);
    CHECK(ha.distance_m == ho.distance_m);
    CHECK(ha.target == ho.target);
  }
  CHECK(vo->intersect(Vec3(2.0, 3.0, 10.0), Vec3(0, 0, 1), 100.0).kind == HitKind::kTarget);
  CHECK(a.seabed_z(1.5, -2.5) == own.seabed_z(1.5, -2.5));
}

TEST_CASE("scene: a shared seabed must exist and match the water depth") {
  const SceneDesc desc = rippled_scene();
  CHECK_THROWS_AS(Scene(desc, std::shared_ptr<const seabed::SeabedModel>()), std::invalid_argument);
  SceneDesc deeper = desc;
  deeper.water.depth_m = 30.0;
  auto shared = std::make_shared<const seabed::SeabedModel>(desc);
  CHECK_THROWS_WITH(Scene(deeper, shared), Catch::Contains("water depth"));
}
