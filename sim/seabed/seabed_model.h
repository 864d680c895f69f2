#pragma once
// The synthetic seabed of Pailhas et al. (2010), Sec. 2.1: three layers composed into one
// heightmap, generated lazily in tiles only where asked.
//   partition: sediment regions with fractal borders          (partition.h)
//   elevation: a plane plus smoothed pink noise                 (noise_layer.h, spectra.h)
//   texture:   per region, sand ripples / rocky / clutter rocks (noise_layer.h, clutter.h)
// Elevation is positive UP relative to the mean seabed (frames.h): z_W = depth - elevation.
//
// Lattice: heightmap point (i, j) is at x = i·d (north), y = j·d (east), anchored at the world
// origin, so the seabed's extent only limits where tiles are made. A tile holds T × T points
// i in [ti·T, ti·T + T), j in [tj·T, tj·T + T). Every tile is a pure function of (scenario, seed,
// ti, tj): the same bytes whatever order or thread made it, and seamless with its neighbours
// because every layer is itself a seamless field (noise_layer.h).
//
// Thread-safe: all methods are const; caches are internally locked.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "sim/scene/scene_desc.h"
#include "sim/seabed/clutter.h"
#include "sim/seabed/noise_layer.h"
#include "sim/seabed/partition.h"
#include "sim/seabed/sediment.h"
#include "sim/seabed/tile_cache.h"

namespace sonarloop::seabed {

struct HeightTile {
  std::int64_t ti = 0;
  std::int64_t tj = 0;
  int size = 0;                        // T
  std::vector<float> elevation_m;      // (T x T), row = north index; positive up
  std::vector<std::uint8_t> sediment;  // (T x T) SedimentId of each point
};

struct SeabedOptions {
  int tile_size = 256;             // T, points per tile side
  std::size_t cache_tiles = 2048;  // heightmap tiles kept in memory (~0.3 MB each at T = 256)
};

class SeabedModel {
 public:
  explicit SeabedModel(const scene::SceneDesc& desc, SeabedOptions options = {});

  double spacing_m() const { return spacing_m_; }
  int tile_size() const { return options_.tile_size; }
  double water_depth_m() const { return water_depth_m_; }
  // Modelled area: [min.x, max.x] × [min.y, max.y] (north, east).
  const Vec2& extent_min() const { return extent_min_; }
  const Vec2& extent_max() const { return extent_max_; }

  std::shared_ptr<const HeightTile> tile(std::int64_t ti, std::int64_t tj) const;
  // Tile index containing lattice index i.
  std::int64_t tile_of(std::int64_t i) const;

  // Heightmap lookups (bilinear between lattice points; sediment of the nearest point).
  double elevation(double x, double y) const;
  SedimentId sediment_at(double x, double y) const;
  // Copies heights (and optionally sediments) of lattice points [i0, i0+ni) × [j0, j0+nj).
  void copy_region(std::int64_t i0, std::int64_t j0, int ni, int nj, float* elevation,
                   std::uint8_t* sediment) const;

  // Large-scale elevation only (slope + pink noise), without textures: where targets and
  // rocks rest.
  double base_elevation(double x, double y) const;
  int region_at(double x, double y) const { return partition_.region_at(x, y); }
  const Clutter& clutter() const { return clutter_; }

  // Heightmap tiles currently cached (for tests and memory reports).
  std::size_t cached_tile_count() const { return cache_.size(); }

  // Makes every tile overlapping [x0, x1] × [y0, y1] using up to `threads` threads.
  // on_progress (optional) is called on the calling thread with the fraction of tiles done.
  void prepare(double x0, double y0, double x1, double y1, int threads,
               const std::function<void(double)>& on_progress = {}) const;

 private:
  std::shared_ptr<const HeightTile> make_tile(std::int64_t ti, std::int64_t tj) const;

  struct RegionLayers {
    SedimentId sediment = 0;
    std::unique_ptr<NoiseLayer> ripples;
    std::unique_ptr<NoiseLayer> rocky;
  };

  SeabedOptions options_;
  double spacing_m_;
  double water_depth_m_;
  Vec2 slope_;
  Vec2 extent_min_;
  Vec2 extent_max_;
  std::unique_ptr<NoiseLayer> elevation_;
  Partition partition_;
  std::vector<RegionLayers> regions_;
  Clutter clutter_;
  mutable TileCache<HeightTile> cache_;
};

}  // namespace sonarloop::seabed
