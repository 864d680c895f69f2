#pragma once
// The scene's targets alone in one small Embree scene, for the profile renderer: the seabed is a
// heightfield it marches itself (render/profile_renderer.h), so only the targets, a few thousand
// triangles, need a BVH. Built once per Scene (on first use), immutable, thread-safe to query.
//
// Coordinates: Embree works in single precision relative to local_origin_W() (the rounded centre
// of the targets' bounds), as SceneView does, to keep millimetre precision far from the world
// origin. Geometry ids are indices into Scene::targets().
#include <cstdint>
#include <vector>

#include "sim/frames.h"
#include "sim/scene/embree_handles.h"

namespace sonarloop::scene {

struct PlacedTarget;

// A sphere holding a target's mesh, for cheap culling against a ping's beam planes, and its
// axis-aligned box, for the range of directions it can be seen in.
struct BoundingSphere {
  Vec3 centre_W = Vec3::Zero();
  double radius_m = 0.0;
  Eigen::AlignedBox3d box_W;
};

// A target's mesh in world coordinates less origin_W, attached to `scene` as triangle geometry
// `geom_id`. The buffers are shared with Embree: the caller keeps `vertices` and `indices` (filled
// here) alive as long as the scene.
void attach_target_mesh(RTCScene scene, unsigned geom_id, const PlacedTarget& target,
                        const Vec3& origin_W, std::vector<float>& vertices,
                        std::vector<std::uint32_t>& indices);

class TargetBvh {
 public:
  explicit TargetBvh(const std::vector<PlacedTarget>& targets);
  ~TargetBvh();
  TargetBvh(const TargetBvh&) = delete;
  TargetBvh& operator=(const TargetBvh&) = delete;

  bool empty() const { return spheres_.empty(); }
  // null when empty
  RTCScene rtc_scene() const { return scene_; }
  const Vec3& local_origin_W() const { return origin_W_; }
  // per target (Scene::targets() order)
  const std::vector<BoundingSphere>& spheres() const { return spheres_; }

  // Distance to the first target surface along the unit direction dir_W from origin_W within
  // t_max_m, or a negative number if none.
  double first_hit_m(const Vec3& origin_W, const Vec3& dir_W, double t_max_m) const;

 private:
  RTCScene scene_ = nullptr;
  Vec3 origin_W_ = Vec3::Zero();
  std::vector<BoundingSphere> spheres_;
  std::vector<std::vector<float>> vertices_;
  std::vector<std::vector<std::uint32_t>> indices_;
};

}  // namespace sonarloop::scene
