// The partition layer's grids against the same rule applied point by point: the region whose
// warped distance is least, and smoothstep blend weights summing to 1 (docs/physics.md §5).
// Grids well inside one region take a shortcut in classify_grid; these tests hold it to the
// point-by-point rule too.
#include "sim/seabed/partition.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace sonarloop;
using namespace sonarloop::seabed;

namespace {

scene::SceneDesc three_regions(double blend_width_m, double warp_m = 4.0) {
  scene::SceneDesc d;
  d.seed = 11;
  for (const Vec2& c : {Vec2(-40.0, 0.0), Vec2(40.0, 0.0), Vec2(0.0, 60.0)}) {
    scene::RegionDesc r;
    r.centre_m = c;
    d.seabed.regions.push_back(r);
  }
  d.seabed.partition.blend_width_m = blend_width_m;
  d.seabed.partition.border_warp_m = warp_m;
  return d;
}

struct PointWeights {
  int region = 0;
  std::array<double, kMaxRegions> weight{};
};

// The rule of partition.h for one point, written out with the warp layers' one-point sampler.
PointWeights reference(const scene::SceneDesc& d, const Partition& p, double x, double y) {
  const auto layers = p.noise_layers();
  REQUIRE(layers.size() == (d.seabed.partition.border_warp_m > 0.0 ? 2u : 0u));
  const double px = x + (layers.empty() ? 0.0 : layers[0]->sample(x, y));
  const double py = y + (layers.empty() ? 0.0 : layers[1]->sample(x, y));
  const std::size_t n = d.seabed.regions.size();
  std::array<double, kMaxRegions> dist{};
  PointWeights out;
  for (std::size_t k = 0; k < n; ++k) {
    dist[k] = (Vec2(px, py) - d.seabed.regions[k].centre_m).norm();
    if (dist[k] < dist[static_cast<std::size_t>(out.region)]) out.region = static_cast<int>(k);
  }
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    double other = std::numeric_limits<double>::infinity();
    for (std::size_t q = 0; q < n; ++q)
      if (q != k) other = std::min(other, dist[q]);
    out.weight[k] = Partition::blend_weight(dist[k], other, d.seabed.partition.blend_width_m);
    sum += out.weight[k];
  }
  for (std::size_t k = 0; k < n; ++k)
    out.weight[k] /= sum;
  return out;
}

struct GridCheck {
  int points = 0;
  int regions_seen_mask = 0;
  int blended = 0;  // points with a weight strictly between 0 and 1
};

GridCheck check_grid(const scene::SceneDesc& d, double x0, double y0, double step, int nx, int ny) {
  const Partition p(d);
  std::vector<std::uint8_t> region;
  std::array<std::vector<float>, kMaxRegions> weights;
  p.classify_grid(x0, y0, step, nx, ny, region, weights);
  GridCheck c;
  const int every = nx * ny > 4096 ? 3 : 1;  // every point of a small grid
  for (int r = 0; r < nx; r += every) {
    for (int col = 0; col < ny; col += every) {
      const auto m = static_cast<std::size_t>(r * ny + col);
      const PointWeights ref = reference(d, p, x0 + r * step, y0 + col * step);
      INFO("point " << r << ", " << col);
      CHECK(region[m] == ref.region);
      float sum = 0.0f;
      for (std::size_t k = 0; k < d.seabed.regions.size(); ++k) {
        CHECK(weights[k][m] == Approx(ref.weight[k]).margin(1e-4));
        sum += weights[k][m];
        if (weights[k][m] > 0.0f && weights[k][m] < 1.0f) ++c.blended;
      }
      CHECK(sum == Approx(1.0f).margin(1e-6));
      c.regions_seen_mask |= 1 << region[m];
      ++c.points;
    }
  }
  return c;
}

}  // namespace

TEST_CASE("partition: a grid well inside one region is that region at weight 1, point by point") {
  // 12.8 m squares about 35 m from region 0's centre and 75 m or more from the others; the
  // warp moves points by 4 m rms
  for (double blend : {0.5, 0.0}) {
    const auto d = three_regions(blend);
    const GridCheck c = check_grid(d, -45.0, -6.0, 0.05, 256, 256);
    CHECK(c.regions_seen_mask == 1);
    CHECK(c.blended == 0);
    const GridCheck far = check_grid(d, 30.0, 55.0, 0.05, 256, 256);
    CHECK(far.regions_seen_mask == 1 << 2);
  }
}

TEST_CASE("partition: a grid across a border has both regions and blends, point by point") {
  const auto d = three_regions(2.0);
  // a 25.6 m square centred on the border between regions 0 and 1 (x = 0, y < 30)
  const GridCheck c = check_grid(d, -12.8, -12.8, 0.1, 256, 256);
  CHECK((c.regions_seen_mask & 3) == 3);
  CHECK(c.blended > 0);
  // the three-region corner near (0, 15): the warp decides which meet where
  const GridCheck corner = check_grid(d, -25.6, -10.0, 0.2, 256, 256);
  CHECK(corner.regions_seen_mask == 7);
}

TEST_CASE("partition: small grids sliding across a border agree with the point-by-point rule") {
  // Grids 0.2 m wide stepped by 1 cm across the straight border of regions 0 and 1 (no warp),
  // whose blend band is 2 m wide: the shortcut may only take the grids whose every point is
  // saturated
  const auto d = three_regions(2.0, 0.0);
  int saturated = 0;
  int blended = 0;
  for (double x0 = -1.5; x0 <= 1.5; x0 += 0.01) {
    const GridCheck c = check_grid(d, x0, 0.0, 0.05, 5, 5);
    (c.blended > 0 ? blended : saturated) += 1;
  }
  CHECK(saturated > 10);
  CHECK(blended > 3);
}
