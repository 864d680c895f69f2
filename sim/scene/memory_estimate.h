#pragma once
// What a scenario will allocate, estimated from its description alone, so that a loader can
// refuse a huge one (1e5 targets, a ray fan of millions per ping) with a clear message before
// anything large is made (config/loader/scenario_loader.h, key memory_limit_gb).
//
// The parts that grow with the scenario (everything else is small and fixed):
//   targets   every target's mesh is built when the Scene is compiled (scene.h), and copied
//             into the target BVH; per target kTargetBytesPerTriangle x its triangle count (the
//             count of build_target_mesh's default rule, shapes.h) + kTargetFixedBytes
//   tiles     heightmap and noise tiles are made lazily, and the seabed's caches hold up to
//             cache_bytes of them (seabed_model.h): min(cache_bytes, the level-0 tiles covering
//             the extent x T² x (4 + 1) bytes: float elevation, byte sediment)
//   pings     per render worker and ping: both sides' bins x the ray fan (rays_per_bin x
//             along_track_rays, auto resolved by the loader's caller) x kBytesPerRay
// Pure: no files, no clock; builds at most one small mesh per distinct (type, segments).
#include <cstddef>
#include <vector>

#include "sim/scene/scene_desc.h"
#include "sim/seabed/seabed_model.h"

namespace sonarloop::scene {

// Calibrated on the peak RSS of `sonarloop run --rate max --duration 1` (Release, 2 threads,
// this machine): 1e5 Mantas (416 triangles each) 5.52 GB, 1e5 boxes (16 triangles) 0.60 GB.
// The difference gives the cost per triangle (the mesh, its world copy and Embree's BVH over
// it: ~120 bytes), the rest the cost per target (its description, YAML nodes and placement).
inline constexpr double kTargetBytesPerTriangle = 120.0;
inline constexpr double kTargetFixedBytes = 4'000.0;
// One Embree ray and hit record (RTCRayHit: 80 bytes) and the renderer's per-ray bookkeeping.
inline constexpr double kBytesPerRay = 128.0;
// Heightmap tile point: a float elevation and a byte sediment id (seabed_model.h HeightTile).
inline constexpr double kBytesPerTilePoint = 5.0;

struct MemoryEstimate {
  double targets_bytes = 0.0;
  double tiles_bytes = 0.0;
  double pings_bytes = 0.0;
  double total_bytes() const { return targets_bytes + tiles_bytes + pings_bytes; }
};

struct PingFan {
  int bins_per_side = 0;
  int rays_per_bin = 0;      // resolved (not 0 = auto)
  int along_track_rays = 0;  // resolved
  int workers = 2;           // render threads, each with its own buffers
};

// Bytes of `count` targets of the cheapest kind (a lower bound, usable before the targets are
// parsed: a list of 1e5 is refused without reading its entries).
double least_target_bytes(std::size_t count);

MemoryEstimate estimate_memory(const SceneDesc& scene, const PingFan& fan, int tile_size = 256,
                               std::size_t cache_bytes = seabed::kDefaultSeabedCacheBytes);

}  // namespace sonarloop::scene
