#include "sim/seabed/seabed_model.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "tests/sim/seabed/spectral.h"

using namespace sonarloop;
using namespace sonarloop::seabed;

namespace {

scene::SceneDesc two_region_desc(std::uint64_t seed) {
  scene::SceneDesc d;
  d.seed = seed;
  d.seabed.grid_spacing_m = 0.05;
  scene::RegionDesc sand;
  sand.sediment = *find_sediment("very_fine_sand");
  sand.centre_m = Vec2(-20.0, 0.0);
  sand.texture.ripples = scene::RipplesDesc{};
  scene::RegionDesc rock;
  rock.sediment = *find_sediment("rough_rock");
  rock.centre_m = Vec2(20.0, 0.0);
  rock.texture.rocky = scene::RockyDesc{};
  rock.texture.clutter = scene::ClutterDesc{};
  d.seabed.regions = {sand, rock};
  return d;
}

std::vector<float> heights(const SeabedModel& m, std::int64_t i0, std::int64_t j0, int ni, int nj) {
  std::vector<float> h(static_cast<std::size_t>(ni) * nj);
  m.copy_region(i0, j0, ni, nj, h.data(), nullptr);
  return h;
}

}  // namespace

TEST_CASE("seabed: elevation profiles recover the 1-D exponent beta, the surface beta + 1") {
  for (double beta : {1.3, 1.8}) {
    scene::SceneDesc d;
    d.seed = 17;
    d.seabed.grid_spacing_m = 1.0;
    d.seabed.elevation.spacing_m = 1.0;
    d.seabed.elevation.beta = beta;
    d.seabed.elevation.outer_scale_m = 1e5;
    d.seabed.elevation.inner_scale_m = 0.0;
    const SeabedModel m(d);
    const int n = 512;
    const auto h = heights(m, -n / 2, -n / 2, n, n);
    const double profile = -testing::profile_loglog_slope(h, n, 1.0 / 64.0, 1.0 / 4.0);
    const double surface =
        -testing::radial_loglog_slope(testing::periodogram(h, n), n, 1.0 / 64.0, 1.0 / 4.0);
    INFO("beta " << beta << ": profile " << profile << ", surface " << surface);
    CHECK(std::abs(profile - beta) < 0.1);
    CHECK(std::abs(surface - (beta + 1.0)) < 0.1);
  }
}

TEST_CASE("seabed: same seed gives byte-identical heightmaps, another seed a different one") {
  const SeabedModel a(two_region_desc(1));
  const SeabedModel b(two_region_desc(1));
  const SeabedModel c(two_region_desc(2));
  const auto ha = heights(a, -300, -300, 600, 600);
  const auto hb = heights(b, -300, -300, 600, 600);
  const auto hc = heights(c, -300, -300, 600, 600);
  CHECK(ha == hb);
  CHECK(ha != hc);
}

TEST_CASE("seabed: a point's height does not depend on tile order") {
  SeabedOptions small;
  small.tile_size = 64;
  const SeabedModel a(two_region_desc(5), small);
  const SeabedModel b(two_region_desc(5), small);
  for (int ti = -3; ti <= 3; ++ti) {
    for (int tj = -3; tj <= 3; ++tj)
      a.tile(ti, tj);
  }
  for (int ti = 3; ti >= -3; --ti) {
    for (int tj = 3; tj >= -3; --tj)
      b.tile(tj, ti);
  }
  for (int ti = -3; ti <= 3; ++ti) {
    for (int tj = -3; tj <= 3; ++tj) {
      REQUIRE(a.tile(ti, tj)->elevation_m == b.tile(ti, tj)->elevation_m);
      REQUIRE(a.tile(ti, tj)->sediment == b.tile(ti, tj)->sediment);
    }
  }
}

TEST_CASE("seabed: no seam at tile borders") {
  SeabedOptions opt;
  opt.tile_size = 64;
  const SeabedModel m(two_region_desc(8), opt);
  const int n = 64 * 8;
  const auto h = heights(m, -n / 2 - 400, -n / 2, n, n);  // inside the rippled sand region
  double border = 0, interior = 0;
  long nb = 0, ni = 0;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double dd =
          h[static_cast<std::size_t>(i + 1) * n + j] - h[static_cast<std::size_t>(i) * n + j];
      const std::int64_t gi = -n / 2 - 400 + i + 1;  // global index of the upper point
      if (gi % 64 == 0) {
        border += dd * dd;
        ++nb;
      } else if (((gi % 64) + 64) % 64 == 32) {
        interior += dd * dd;
        ++ni;
      }
    }
  }
  const double ratio = (border / nb) / (interior / ni);
  INFO("border/interior variance ratio " << ratio);
  CHECK(ratio > 0.8);
  CHECK(ratio < 1.25);
}

TEST_CASE("seabed: the heightmap spacing resamples the same surface") {
  auto fine = two_region_desc(3);
  fine.seabed.grid_spacing_m = 0.025;
  auto coarse = two_region_desc(3);
  coarse.seabed.grid_spacing_m = 0.05;
  const SeabedModel mf(fine);
  const SeabedModel mc(coarse);
  double max_diff = 0.0;
  for (int i = -200; i < 200; i += 7) {
    for (int j = -200; j < 200; j += 5) {
      // lattice point (i, j) of the coarse grid is (2i, 2j) of the fine one; rocks are
      // rasterised per grid point, so compare off-rock points only
      const double hc = heights(mc, i, j, 1, 1)[0];
      const double hf = heights(mf, 2 * i, 2 * j, 1, 1)[0];
      max_diff = std::max(max_diff, std::abs(hc - hf));
    }
  }
  CHECK(max_diff < 1e-4);
}

TEST_CASE("seabed: both sediments appear and their border is fractal, not straight") {
  const SeabedModel m(two_region_desc(4));
  // walk lines of constant east position; find where the sediment switches
  std::vector<double> border_x;
  const int n = 1600;  // 80 m at 5 cm
  std::set<int> seen;
  for (int j = -800; j < 800; j += 40) {
    std::vector<std::uint8_t> s(n);
    m.copy_region(-n / 2, j, n, 1, nullptr, s.data());
    for (int i = 1; i < n; ++i) {
      seen.insert(s[i]);
      if (s[i] != s[i - 1]) {
        border_x.push_back((i - n / 2) * 0.05);
        break;
      }
    }
  }
  CHECK(seen.size() == 2);
  REQUIRE(border_x.size() > 20);
  double mean = 0, var = 0;
  for (double x : border_x)
    mean += x;
  mean /= border_x.size();
  for (double x : border_x)
    var += (x - mean) * (x - mean);
  const double rms = std::sqrt(var / border_x.size());
  INFO("border rms deviation from a straight line " << rms << " m");
  CHECK(rms > 0.5);   // warped: a straight bisector would give 0
  CHECK(rms < 20.0);  // but still a border between the two centres
  CHECK(std::abs(mean) < 15.0);
}

TEST_CASE("seabed: clutter counts are Poisson in mean and variance") {
  // one region with clutter only; count rocks in a 40 m x 40 m window over many seeds
  const double density = 0.05;
  const double area = 40.0 * 40.0;
  const int trials = 300;
  double s1 = 0, s2 = 0;
  for (int t = 0; t < trials; ++t) {
    scene::SceneDesc d;
    d.seed = 1000 + t;
    scene::RegionDesc r;
    r.sediment = *find_sediment("medium_sand");
    r.texture.clutter = scene::ClutterDesc{};
    r.texture.clutter->density_per_m2 = density;
    d.seabed.regions = {r};
    d.seabed.elevation.rms_m = 0.0;
    const SeabedModel m(d);
    // cells tile the plane, so count rocks whose centre is in [0, 40)^2 (5 x 5 cells)
    double n = 0;
    for (int ci = 0; ci < 5; ++ci) {
      for (int cj = 0; cj < 5; ++cj)
        n += m.clutter().rocks_in_cell(ci, cj).size();
    }
    s1 += n;
    s2 += n * n;
  }
  const double mean = s1 / trials;
  const double var = s2 / trials - mean * mean;
  const double expected = density * area;  // 80
  INFO("mean " << mean << " var " << var << " expected " << expected);
  CHECK(std::abs(mean - expected) < 3.0 * std::sqrt(expected / trials));
  // the sample variance of a Poisson count has sd ~ sqrt(2 lambda^2 / trials)
  CHECK(std::abs(var - expected) < 3.0 * expected * std::sqrt(2.0 / trials));
}

TEST_CASE("seabed: clutter thinning follows each region's density") {
  auto d = two_region_desc(6);
  d.seabed.partition.border_warp_m = 0.0;
  d.seabed.regions[0].texture.clutter = scene::ClutterDesc{};
  d.seabed.regions[0].texture.clutter->density_per_m2 = 0.02;
  d.seabed.regions[1].texture.clutter->density_per_m2 = 0.08;
  const SeabedModel m(d);
  double north = 0, south = 0;
  for (int ci = -12; ci < 12; ++ci) {
    for (int cj = -12; cj < 12; ++cj) {
      for (const auto& r : m.clutter().rocks_in_cell(ci, cj))
        (r.x_m > 0 ? north : south) += 1;
    }
  }
  // equal areas (96 m x 192 m each side of the bisector x = 0): ratio 4
  INFO("north " << north << " south " << south);
  CHECK(north / south == Approx(4.0).epsilon(0.2));
}

TEST_CASE("seabed: rocks stand above the seabed where they lie") {
  scene::SceneDesc d;
  d.seed = 12;
  scene::RegionDesc r;
  r.sediment = *find_sediment("cobble");
  r.texture.clutter = scene::ClutterDesc{};
  r.texture.clutter->density_per_m2 = 0.1;
  d.seabed.regions = {r};
  d.seabed.grid_spacing_m = 0.02;
  const SeabedModel m(d);
  const auto rocks = m.clutter().rocks_in_cell(0, 0);
  REQUIRE(!rocks.empty());
  for (const auto& rock : rocks) {
    const double top = rock.base_m + rock.height_m - rock.sink_m;
    CHECK(m.elevation(rock.x_m, rock.y_m) == Approx(top).margin(0.02 + 0.05 * rock.height_m));
    CHECK(m.base_elevation(rock.x_m, rock.y_m) == Approx(rock.base_m).margin(1e-6));
  }
}

namespace {

// A 1 km x 100 m survey line's seabed at 2.5 cm.
scene::SceneDesc line_desc() {
  scene::SceneDesc d = two_region_desc(2);
  d.seabed.grid_spacing_m = 0.025;
  d.seabed.extent_m = Vec2(1000.0, 100.0);
  d.seabed.origin_m = Vec2(0.0, -50.0);
  return d;
}

}  // namespace

TEST_CASE("seabed: the caches hold at most their byte budget; evicted tiles come back equal") {
  const scene::SceneDesc d = line_desc();
  SeabedOptions opt;
  opt.tile_size = 64;
  // 64 MB: each of the five noise layers up to 4 MB, the heightmap tiles the rest
  opt.cache_bytes = 64u << 20;
  const SeabedCacheStats full = SeabedModel(d, opt).cache_stats();
  CHECK(full.budget_bytes <= opt.cache_bytes);
  CHECK(full.budget_bytes >= opt.cache_bytes * 15 / 16);
  CHECK(full.heightmap.capacity * height_tile_bytes(64) >= opt.cache_bytes / 2);
  // 1 MB: below what the noise layers need at least (kMinNoiseCachePairs each): they keep that,
  // the heightmap kMinHeightTiles
  opt.cache_bytes = 1u << 20;
  const SeabedModel m(d, opt);
  CHECK(m.cache_stats().heightmap.capacity == kMinHeightTiles);
  const float first = m.tile(0, 0)->elevation_m[100];
  // 1,000 tiles of 64² points (20 kB each, 20 MB) along the line
  for (int k = 0; k < 1000; ++k)
    m.tile(k, 0);
  const SeabedCacheStats s = m.cache_stats();
  INFO("held " << s.bytes << " of " << s.budget_bytes << " B; heightmap " << s.heightmap.tiles
               << " of " << s.heightmap.capacity << " tiles, noise " << s.noise.tiles << " of "
               << s.noise.capacity);
  CHECK(s.noise.capacity == kMinNoiseCachePairs * 5);
  CHECK(s.bytes <= s.budget_bytes);
  CHECK(s.heightmap.misses == 1000);  // tile (0, 0) was asked for twice in a row
  CHECK(s.heightmap.evictions >= 1000 - s.heightmap.capacity);
  CHECK(s.heightmap.tiles <= s.heightmap.capacity);
  CHECK(s.noise.hits + s.noise.misses > 0);
  // tile (0, 0) was evicted long ago: made again, the same heights
  CHECK(m.tile(0, 0)->elevation_m[100] == first);
  CHECK(m.tiles_made() == 1001);
}

TEST_CASE("seabed: tiles are made only where asked") {
  // a 1 km survey line at 2.5 cm: asking for a few points far apart makes a few tiles
  const scene::SceneDesc d = line_desc();
  SeabedOptions opt;
  opt.tile_size = 128;
  const SeabedModel m(d, opt);
  for (double x : {10.0, 500.0, 990.0})
    m.elevation(x, 0.0);
  // each bilinear lookup touches at most 4 tiles; the full 1 km x 100 m grid would be 9,800
  const std::size_t n0 = m.cached_tile_count();
  CHECK(n0 <= 12);
  // preparing a 10 m x 10 m patch makes the tiles covering it (3.2 m tiles: 4 to 5 per side)
  m.prepare(400.0, -5.0, 410.0, 5.0, 2);
  CHECK(m.cached_tile_count() - n0 >= 16);
  CHECK(m.cached_tile_count() - n0 <= 25);
}
