#include "sim/scene/target_bvh.h"

#include <cmath>

#include "sim/scene/embree_device.h"
#include "sim/scene/scene.h"

namespace sonarloop::scene {

void attach_target_mesh(RTCScene scene, unsigned geom_id, const PlacedTarget& p,
                        const Vec3& origin_W, std::vector<float>& verts,
                        std::vector<std::uint32_t>& idx) {
  verts.assign(3 * (p.mesh_T.vertices.size() + 1), 0.0f);  // +1: Embree's SSE loads
  for (std::size_t k = 0; k < p.mesh_T.vertices.size(); ++k) {
    const Vec3 w = p.X_WT * p.mesh_T.vertices[k].cast<double>() - origin_W;
    for (int c = 0; c < 3; ++c)
      verts[3 * k + static_cast<std::size_t>(c)] = static_cast<float>(w[c]);
  }
  idx.clear();
  idx.reserve(3 * p.mesh_T.triangles.size());
  for (const auto& tri : p.mesh_T.triangles)
    idx.insert(idx.end(), tri.begin(), tri.end());
  RTCGeometry geom = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, verts.data(), 0,
                             3 * sizeof(float), p.mesh_T.vertices.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, idx.data(), 0,
                             3 * sizeof(std::uint32_t), p.mesh_T.triangles.size());
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(scene, geom, geom_id);
  rtcReleaseGeometry(geom);
}

TargetBvh::TargetBvh(const std::vector<PlacedTarget>& targets) {
  if (targets.empty()) return;
  Eigen::AlignedBox3d all;
  all.setEmpty();
  for (const PlacedTarget& p : targets)
    all.extend(p.bounds_W);
  const Vec3 c = all.center();
  origin_W_ = Vec3(std::round(c.x()), std::round(c.y()), std::round(c.z()));
  scene_ = rtcNewScene(embree_device());
  unsigned geom_id = 0;
  for (const PlacedTarget& p : targets) {
    BoundingSphere s;
    s.centre_W = p.bounds_W.center();
    s.box_W = p.bounds_W;
    for (const auto& v : p.mesh_T.vertices)
      s.radius_m = std::max(s.radius_m, (p.X_WT * v.cast<double>() - s.centre_W).norm());
    // float rounding of the vertices: a hair more than the exact radius
    s.radius_m = s.radius_m * (1.0 + 1e-6) + 1e-4;
    std::vector<float> verts;
    std::vector<std::uint32_t> idx;
    attach_target_mesh(scene_, geom_id++, p, origin_W_, verts, idx);
    spheres_.push_back(s);
    vertices_.push_back(std::move(verts));
    indices_.push_back(std::move(idx));
  }
  // Embree builds the BVH here; the scene must be committed before any query
  rtcCommitScene(scene_);
  check_embree("building the target BVH");
}

TargetBvh::~TargetBvh() {
  if (scene_) rtcReleaseScene(scene_);
}

double TargetBvh::first_hit_m(const Vec3& origin_W, const Vec3& dir_W, double t_max_m) const {
  if (!scene_) return -1.0;
  const RTCRayHit rh = intersect_one(scene_, origin_W - origin_W_, dir_W, 0.0, t_max_m);
  return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0 : static_cast<double>(rh.ray.tfar);
}

}  // namespace sonarloop::scene
