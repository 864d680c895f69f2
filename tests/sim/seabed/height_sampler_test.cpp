// The profile renderer's height reads: the same bilinear surface as SeabedModel::elevation,
// across tile borders and negative coordinates; gradients; sediments; coarser detail levels
// sample the same surface.
#include "sim/seabed/height_sampler.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace sonarloop;
using namespace sonarloop::seabed;

namespace {

scene::SceneDesc textured_scene() {
  scene::SceneDesc d;
  d.seed = 9;
  d.water.depth_m = 20.0;
  d.seabed.origin_m = Vec2(-40, -40);
  d.seabed.extent_m = Vec2(80, 80);
  d.seabed.grid_spacing_m = 0.05;
  d.seabed.elevation.rms_m = 0.3;
  scene::RegionDesc a, b;
  a.sediment = *find_sediment("very_fine_sand");
  a.centre_m = Vec2(-10, -10);
  a.texture.ripples = scene::RipplesDesc{0.6, 30.0, 2.0, 2.5, 0.04};
  b.sediment = *find_sediment("sandy_gravel");
  b.centre_m = Vec2(10, 10);
  d.seabed.regions = {a, b};
  return d;
}

}  // namespace

TEST_CASE("height sampler: the scene's bilinear surface, anywhere, across tile borders") {
  SeabedOptions o;
  o.tile_size = 32;  // many tile borders in a small area
  const SeabedModel model(textured_scene(), o);
  HeightSampler s;
  s.bind(model, 0);
  std::mt19937_64 gen(4);
  std::uniform_real_distribution<double> u(-12.0, 12.0);
  HeightSample h;
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    // random points, a quarter of them on or right next to a tile border (32 points = 1.6 m)
    double x = u(gen), y = u(gen);
    if (k % 4 == 0) x = std::round(x / 1.6) * 1.6 - 1e-9 * (k % 3);
    if (k % 8 == 0) y = std::round(y / 1.6) * 1.6 + 0.05 * 31.5;
    s.sample(x, y, h);
    INFO("x " << x << " y " << y);
    REQUIRE(h.elevation_m == Approx(model.elevation(x, y)).margin(1e-5));
    ++checked;
  }
  CHECK(checked == 20000);
}

TEST_CASE("height sampler: gradients are the bilinear surface's; sediments the nearest point's") {
  const SeabedModel model(textured_scene());
  HeightSampler s;
  s.bind(model, 0);
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u(-15.0, 15.0);
  HeightSample h, hx, hy;
  const double e = 1e-5;  // well inside a 5 cm cell: the surface is linear along each axis
  for (int k = 0; k < 2000; ++k) {
    double x = u(gen), y = u(gen);
    // keep off the cell edges, where the bilinear gradient jumps
    const double fx = x / 0.05 - std::floor(x / 0.05);
    const double fy = y / 0.05 - std::floor(y / 0.05);
    if (fx < 0.01 || fx > 0.99 || fy < 0.01 || fy > 0.99) continue;
    s.sample(x, y, h);
    s.sample(x + e, y, hx);
    s.sample(x, y + e, hy);
    CHECK(h.dh_dx == Approx((hx.elevation_m - h.elevation_m) / e).margin(1e-3));
    CHECK(h.dh_dy == Approx((hy.elevation_m - h.elevation_m) / e).margin(1e-3));
    // the nearest lattice point's sediment (away from exact half-way ties)
    if (std::abs(fx - 0.5) > 0.01 && std::abs(fy - 0.5) > 0.01)
      CHECK(h.sediment == model.sediment_at(x, y));
  }
}

TEST_CASE("height sampler: a coarser level is the same surface on a coarser lattice") {
  const SeabedModel model(textured_scene());
  for (int level : {1, 2, 3}) {
    HeightSampler fine, coarse;
    fine.bind(model, 0);
    coarse.bind(model, level);
    CHECK(coarse.spacing_m() == Approx(0.05 * (1 << level)));
    HeightSample a, b;
    // at the coarse lattice's points both read the same height
    for (int i = -30; i <= 30; i += 7) {
      for (int j = -30; j <= 30; j += 5) {
        const double x = i * coarse.spacing_m();
        const double y = j * coarse.spacing_m();
        fine.sample(x, y, a);
        coarse.sample(x, y, b);
        INFO("level " << level << " x " << x << " y " << y);
        CHECK(b.elevation_m == Approx(a.elevation_m).margin(1e-5));
      }
    }
  }
  CHECK_THROWS_AS(model.tile(0, 0, kMaxSeabedLevel + 1), std::out_of_range);
}

TEST_CASE("height sampler: binding another model drops the tiles of the first") {
  scene::SceneDesc d1 = textured_scene();
  scene::SceneDesc d2 = d1;
  d2.seed = 10;
  const SeabedModel m1(d1), m2(d2);
  CHECK(m1.uid() != m2.uid());
  HeightSampler s;
  HeightSample h;
  s.bind(m1, 0);
  s.sample(1.234, -2.5, h);
  CHECK(h.elevation_m == Approx(m1.elevation(1.234, -2.5)).margin(1e-5));
  s.bind(m2, 0);
  s.sample(1.234, -2.5, h);
  CHECK(h.elevation_m == Approx(m2.elevation(1.234, -2.5)).margin(1e-5));
  CHECK(m1.elevation(1.234, -2.5) != m2.elevation(1.234, -2.5));
}
