#pragma once
// The compiled scene: seabed and targets of a SceneDesc (scene_desc.h), and Embree views of it.
//
// Scene is cheap to make and immutable: it holds the lazily tiled seabed (seabed_model.h) and
// the targets placed on it. No terrain is generated and no BVH built until asked for. The
// profile renderer reads heights from the tiles and traces only the targets (target_bvh());
// the ray-traced reference renderer asks for a SceneView: Scene::view(region) makes the
// heightmap tiles covering that region and compiles them, with the targets inside it, into
// one Embree scene (the seabed as Embree grid geometry, one grid per heightmap tile; targets as
// triangle meshes). A view is immutable and thread-safe to query; views of different regions
// can coexist.
//
// Coordinates: world frame W (frames.h: NED, z down). Inside a view, Embree works in
// single precision relative to the view's local origin (its centre) to keep centimetre
// precision kilometres from the world origin; intersect() converts.

#include <memory>
#include <mutex>
#include <vector>

#include "sim/frames.h"
#include "sim/scene/embree_handles.h"
#include "sim/scene/scene_desc.h"
#include "sim/scene/target_bvh.h"
#include "sim/seabed/seabed_model.h"
#include "sim/targets/mesh.h"

namespace sonarloop::scene {

// A target as placed in the world.
struct PlacedTarget {
  int index = 0;                 // into SceneDesc::targets
  TargetDesc desc;               // with size_m resolved (never zero)
  targets::TriangleMesh mesh_T;  // in the target frame T (targets/mesh.h conventions)
  Eigen::Isometry3d X_WT;        // pose of T in W
  Eigen::AlignedBox3d bounds_W;  // world-space bounds
  double impedance_rayl = 0.0;   // density × sound speed
};

struct Box2 {
  Vec2 min = Vec2::Zero();  // (north, east)
  Vec2 max = Vec2::Zero();
};

enum class HitKind { kNone, kSeabed, kTarget };

struct Hit {
  HitKind kind = HitKind::kNone;
  double distance_m = 0.0;  // along the (unit) ray direction
  Vec3 point_W = Vec3::Zero();
  Vec3 normal_W = Vec3::Zero();  // unit geometric normal, facing the ray's origin
  int sediment = -1;             // seabed::SedimentId for seabed hits
  int target = -1;               // PlacedTarget::index for target hits
  explicit operator bool() const { return kind != HitKind::kNone; }
};

class SceneView;

class Scene {
 public:
  explicit Scene(const SceneDesc& desc, seabed::SeabedOptions seabed_options = {});
  // A scene on an existing seabed, shared with other scenes (a dataset places one target per
  // scene on one large lazily tiled seabed, so its noise kernels and tiles are made once).
  // `desc.seabed`, `desc.water` and `desc.seed` must be those the seabed was built from: the
  // seabed is NOT rebuilt or checked against them (only the water depth is, since targets are
  // placed with it); desc() reports `desc` as given. Throws std::invalid_argument if `seabed`
  // is null or its water depth differs from desc.water.depth_m.
  Scene(const SceneDesc& desc, std::shared_ptr<const seabed::SeabedModel> seabed);

  const SceneDesc& desc() const { return desc_; }
  const seabed::SeabedModel& seabed() const { return *seabed_; }
  const std::vector<PlacedTarget>& targets() const { return targets_; }
  // A process-unique id of this scene (never reused): caches keyed by scene use it, since a
  // later scene may live at the address of an earlier one.
  std::uint64_t uid() const { return uid_; }

  // The targets alone in one small Embree scene (target_bvh.h), built on first use
  // (thread-safe).
  const TargetBvh& target_bvh() const;

  // World z (down) of the seabed surface at (x, y) (bilinear heightmap).
  double seabed_z(double x, double y) const;

  // Builds the Embree view of `region` (clipped to the seabed extent), generating the heightmap
  // tiles it needs with up to `threads` threads.
  std::shared_ptr<const SceneView> view(const Box2& region, int threads = 1) const;

 private:
  SceneDesc desc_;
  std::uint64_t uid_;
  std::shared_ptr<const seabed::SeabedModel> seabed_;
  std::vector<PlacedTarget> targets_;
  mutable std::once_flag bvh_once_;
  mutable std::unique_ptr<TargetBvh> bvh_;
};

class SceneView {
 public:
  ~SceneView();
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  // First hit along the ray from origin_W in direction dir_W (any length), within t_max_m
  // metres of the origin.
  Hit intersect(const Vec3& origin_W, const Vec3& dir_W, double t_max_m) const;

  // The covered region (after clipping to the extent) and the Embree scene, whose coordinates
  // are world minus local_origin_W(), for callers that trace ray packets themselves.
  const Box2& region() const { return region_; }
  RTCScene rtc_scene() const { return scene_; }
  const Vec3& local_origin_W() const { return origin_W_; }
  // What an Embree hit (geomID, primID, hit point in local coordinates) was.
  void describe_hit(unsigned geom_id, const Vec3& point_W, Hit& hit) const;

  std::size_t seabed_grids() const { return grids_.size(); }
  std::size_t target_count() const { return target_geoms_.size(); }
  // Bytes held in vertex, index and sediment buffers (not counting Embree's BVH).
  std::size_t buffer_bytes() const;

 private:
  friend class Scene;
  SceneView() = default;

  struct Grid;  // one Embree grid of heightmap tiles (scene.cpp)

  Box2 region_;
  Vec3 origin_W_ = Vec3::Zero();
  double spacing_m_ = 0.0;
  RTCScene scene_ = nullptr;
  std::vector<std::unique_ptr<Grid>> grids_;  // geomID = position in this vector
  std::vector<int> target_geoms_;             // geomID - grids_.size() -> target index
  std::vector<std::vector<float>> target_vertices_;
  std::vector<std::vector<std::uint32_t>> target_indices_;
};

}  // namespace sonarloop::scene
