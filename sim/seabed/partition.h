#pragma once
// Partition layer (Pailhas et al. 2010, Sec. 2.1): which sediment region each point belongs to.
// A point belongs to the region whose centre is nearest AFTER displacing the point by a smooth
// fractal warp field (two pink-noise layers, one per axis), so region borders are fractal
// curves rather than the straight lines of a plain Voronoi partition. Textures of neighbouring
// regions cross-fade over a blend width around each border so the heightmap has no step.
#include <array>
#include <memory>
#include <vector>

#include "sim/frames.h"
#include "sim/scene/scene_desc.h"
#include "sim/seabed/noise_layer.h"

namespace sonarloop::seabed {

inline constexpr int kMaxRegions = 3;

class Partition {
 public:
  // cache_bytes: each warp layer's tile cache (noise_layer.h).
  Partition(const scene::SceneDesc& desc, std::size_t cache_bytes = kDefaultNoiseCacheBytes);

  int region_count() const { return static_cast<int>(centres_.size()); }

  // Region index of one point (slow path: one warp sample per call).
  int region_at(double x, double y) const;

  // For the nx × ny grid points (x0 + r·d, y0 + c·d): the region index of each point, and the
  // blend weight of every region (weights[k][r * ny + c], summing to 1 at each point).
  void classify_grid(double x0, double y0, double d, int nx, int ny,
                     std::vector<std::uint8_t>& region,
                     std::array<std::vector<float>, kMaxRegions>& weights) const;

  // Smoothstep cross-fade weight of a region whose warped distance is d_self, given the nearest
  // other region's distance d_other, over the blend width w (0.5 on the border).
  static float blend_weight(double d_self, double d_other, double w);

  // Its warp layers (none with one region or no warp).
  std::vector<const NoiseLayer*> noise_layers() const;

 private:
  // The region whose weight is 1 at every point of the box [x_lo, x_hi] x [y_lo, y_hi]
  // (warped positions), or -1 when no region is alone there.
  int sole_region(double x_lo, double x_hi, double y_lo, double y_hi) const;

  std::vector<Vec2> centres_;
  double blend_width_m_;
  std::unique_ptr<NoiseLayer> warp_x_;
  std::unique_ptr<NoiseLayer> warp_y_;
};

}  // namespace sonarloop::seabed
