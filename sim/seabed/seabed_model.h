#pragma once
// The synthetic seabed of Pailhas et al. (2010), Sec. 2.1: three layers composed into one
// heightmap, generated lazily in tiles only where asked.
//   partition: sediment regions with fractal borders          (partition.h)
//   elevation: a plane plus smoothed pink noise                 (noise_layer.h, spectra.h),
//              plus the relief of a bathymetry grid when the scenario has one (relief_grid.h)
//   texture:   per region, sand ripples / rocky / clutter rocks (noise_layer.h, clutter.h)
// Elevation is positive UP relative to the mean seabed (frames.h): z_W = depth - elevation.
//
// Lattice: heightmap point (i, j) is at x = i·d (north), y = j·d (east), anchored at the world
// origin, so the seabed's extent only limits where tiles are made. A tile holds T × T points
// i in [ti·T, ti·T + T), j in [tj·T, tj·T + T). Every tile is a pure function of (scenario, seed,
// ti, tj): the same bytes whatever order or thread made it, and seamless with its neighbours
// because every layer is itself a seamless field (noise_layer.h).
//
// Detail levels: level L is the same surface sampled on the coarser lattice of spacing
// d·2^L (point (i, j) of level L is at x = i·d·2^L, y = j·d·2^L, and equals point
// (i·2^L, j·2^L) of level 0: every layer is a continuous field sampled where asked). A renderer
// whose pixels are much larger than d reads a coarser level, so that it makes and reads
// 4^L times fewer points for the same ground (docs/rendering.md, "Level of detail").
//
// Thread-safe: all methods are const; caches are internally locked.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "sim/scene/scene_desc.h"
#include "sim/seabed/clutter.h"
#include "sim/seabed/noise_layer.h"
#include "sim/seabed/partition.h"
#include "sim/seabed/relief_grid.h"
#include "sim/seabed/sediment.h"
#include "sim/seabed/tile_cache.h"

namespace sonarloop::seabed {

inline constexpr int kMaxSeabedLevel = 4;  // spacing up to 16·d

struct HeightTile {
  std::int64_t ti = 0;
  std::int64_t tj = 0;
  int level = 0;                       // detail level: lattice spacing d·2^level
  int size = 0;                        // T
  std::vector<float> elevation_m;      // (T x T), row = north index; positive up
  std::vector<std::uint8_t> sediment;  // (T x T) SedimentId of each point
};

// What the tile caches may hold by default: 192 MB keeps the one-hour soak's run under 400 MB
// (371 MB; 458 MB at 256), with 4.5 % more tiles evicted and no measurable time (docs/rendering.md,
// "Memory").
inline constexpr std::size_t kDefaultSeabedCacheBytes = 192u << 20;
// Each noise layer's share of the budget, and the fewest heightmap tiles kept whatever it is.
inline constexpr std::size_t kNoiseLayerBudgetShare = 16;
inline constexpr std::size_t kMinHeightTiles = 16;

struct SeabedOptions {
  int tile_size = 256;  // T, points per tile side
  // The bytes the seabed's tile caches may hold: each noise layer's tiles up to 1/16 of it, the
  // heightmap tiles (T² x 5 bytes each: 0.33 MB at T = 256) the rest; at least
  // kMinNoiseCachePairs and kMinHeightTiles entries whatever it is. Least recently used tiles
  // are evicted beyond it and made again when asked (the same bytes: tile_cache.h).
  std::size_t cache_bytes = kDefaultSeabedCacheBytes;
};

// The bytes one heightmap tile of T x T points holds (its elevation and sediment arrays).
inline std::size_t height_tile_bytes(int tile_size) {
  return static_cast<std::size_t>(tile_size) * static_cast<std::size_t>(tile_size) *
         (sizeof(float) + sizeof(std::uint8_t));
}

class SeabedModel {
 public:
  explicit SeabedModel(const scene::SceneDesc& desc, SeabedOptions options = {});

  double spacing_m() const { return spacing_m_; }
  // Lattice spacing of detail level `level` (0 .. kMaxSeabedLevel): d·2^level.
  double spacing_m(int level) const { return spacing_m_ * static_cast<double>(1 << level); }
  // A process-unique id of this model (never reused), so that per-thread caches of its tiles
  // can tell one model from another that happens to live at the same address later.
  std::uint64_t uid() const { return uid_; }
  int tile_size() const { return options_.tile_size; }
  double water_depth_m() const { return water_depth_m_; }
  // Modelled area: [min.x, max.x] × [min.y, max.y] (north, east).
  const Vec2& extent_min() const { return extent_min_; }
  const Vec2& extent_max() const { return extent_max_; }

  // Tile (ti, tj) of detail level `level`: lattice points i in [ti·T, ti·T + T) and j likewise,
  // at spacing spacing_m(level). Throws std::out_of_range for a level outside 0..kMaxSeabedLevel.
  std::shared_ptr<const HeightTile> tile(std::int64_t ti, std::int64_t tj, int level = 0) const;
  // Makes tile (ti, tj) of `level` unless it is cached or another thread is making it; never
  // waits (for work ahead of the renders).
  void prefetch_tile(std::int64_t ti, std::int64_t tj, int level) const;
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

  // Heightmap tiles currently cached (for tests and memory reports), and made since construction
  // (every detail level; a tile evicted and made again counts twice).
  std::size_t cached_tile_count() const { return cache_.size(); }
  std::uint64_t tiles_made() const { return tiles_made_.load(std::memory_order_relaxed); }
  SeabedCacheStats cache_stats() const;

  // Makes every tile overlapping [x0, x1] × [y0, y1] using up to `threads` threads.
  // on_progress (optional) is called on the calling thread with the fraction of tiles done.
  void prepare(double x0, double y0, double x1, double y1, int threads,
               const std::function<void(double)>& on_progress = {}, int level = 0) const;

 private:
  std::shared_ptr<const HeightTile> make_tile(std::int64_t ti, std::int64_t tj, int level) const;
  // Every noise layer (the partition's, the elevation's, the regions').
  std::vector<const NoiseLayer*> noise_layers() const;

  struct RegionLayers {
    SedimentId sediment = 0;
    std::unique_ptr<NoiseLayer> ripples;
    std::unique_ptr<NoiseLayer> rocky;
  };

  SeabedOptions options_;
  std::uint64_t uid_;
  double spacing_m_;
  double water_depth_m_;
  Vec2 slope_;
  std::shared_ptr<const ReliefGrid> relief_;  // seabed.bathymetry's grid, or none
  Vec2 extent_min_;
  Vec2 extent_max_;
  std::unique_ptr<NoiseLayer> elevation_;
  Partition partition_;
  std::vector<RegionLayers> regions_;
  Clutter clutter_;
  mutable TileCache<HeightTile> cache_;
  mutable std::atomic<std::uint64_t> tiles_made_{0};
};

}  // namespace sonarloop::seabed
