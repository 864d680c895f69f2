#include "sim/scene/memory_estimate.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "sim/targets/shapes.h"

namespace sonarloop::scene {
namespace {

// Triangles of a target as build_target_mesh makes it; one mesh per distinct (type, segments).
std::size_t triangles_of(const TargetDesc& t, std::map<std::pair<int, int>, std::size_t>& known) {
  const Vec3 size = targets::resolve_target_size(t.type, t.size_m);
  const int segments = targets::default_segments(t.type, size);
  const std::pair<int, int> key{static_cast<int>(t.type), segments};
  const auto it = known.find(key);
  if (it != known.end()) return it->second;
  const std::size_t n = targets::build_target_mesh(t.type, size).triangles.size();
  known.emplace(key, n);
  return n;
}

// The fewest triangles any target type has at its nominal size (the cuboids: 12-16).
double least_triangles() {
  std::size_t least = SIZE_MAX;
  for (const auto& info : targets::target_type_table())
    least = std::min(least, targets::build_target_mesh(info.type, Vec3::Zero()).triangles.size());
  return static_cast<double>(least);
}

}  // namespace

double least_target_bytes(std::size_t count) {
  static const double triangles = least_triangles();
  return static_cast<double>(count) * (triangles * kTargetBytesPerTriangle + kTargetFixedBytes);
}

MemoryEstimate estimate_memory(const SceneDesc& scene, const PingFan& fan, int tile_size,
                               std::size_t cache_bytes) {
  MemoryEstimate e;
  std::map<std::pair<int, int>, std::size_t> known;
  for (const TargetDesc& t : scene.targets) {
    e.targets_bytes +=
        static_cast<double>(triangles_of(t, known)) * kTargetBytesPerTriangle + kTargetFixedBytes;
  }
  // level-0 tiles over the extent, at most the caches' budget (in double: a 100 km extent at
  // 5 mm is 4e8 tiles)
  const double tile_m = scene.seabed.grid_spacing_m * tile_size;
  const double tiles =
      std::ceil(scene.seabed.extent_m.x() / tile_m) * std::ceil(scene.seabed.extent_m.y() / tile_m);
  e.tiles_bytes = std::min(tiles * tile_size * tile_size * kBytesPerTilePoint,
                           static_cast<double>(cache_bytes));
  e.pings_bytes = 2.0 * fan.bins_per_side * std::max(fan.rays_per_bin, 1) *
                  std::max(fan.along_track_rays, 1) * kBytesPerRay * std::max(fan.workers, 1);
  return e;
}

}  // namespace sonarloop::scene
