#include "sim/scene/scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/scene/embree_device.h"
#include "sim/targets/placement.h"
#include "sim/targets/shapes.h"
#include "sim/targets/target_type.h"
#include "units/angles.h"

namespace sonarloop::scene {

struct SceneView::Grid {
  std::int64_t i0 = 0;  // first lattice row (north index)
  std::int64_t j0 = 0;  // first lattice column (east index)
  int ni = 0;
  int nj = 0;
  std::vector<float> vertices;         // (ni*nj + 1) x 3 (one spare for Embree's SSE loads)
  std::vector<std::uint8_t> sediment;  // (ni x nj)
  RTCGrid grid{};
};

namespace {

// Scene ids: a counter, not randomness (ids never reach an output).
std::atomic<std::uint64_t> g_next_scene_uid{1};

PlacedTarget place_target(const TargetDesc& t, int index, const seabed::SeabedModel& seabed,
                          double water_depth_m) {
  PlacedTarget p;
  p.index = index;
  p.desc = t;
  if (p.desc.size_m.isZero()) p.desc.size_m = targets::target_type_info(t.type).size_m;
  p.mesh_T = targets::build_target_mesh(t.type, p.desc.size_m);
  // the base rests on the mean seabed level (slope + large-scale relief; textures are
  // zero-mean) at the target's centre, sunk by the burial depth
  const double seabed_z = water_depth_m - seabed.base_elevation(t.position_m.x(), t.position_m.y());
  p.X_WT = targets::target_pose(t.position_m, t.heading_deg * kRadPerDeg,
                                targets::base_plane_z_down_m(seabed_z, t.burial_m));
  p.bounds_W.setEmpty();
  for (const auto& v : p.mesh_T.vertices)
    p.bounds_W.extend(p.X_WT * v.cast<double>());
  p.impedance_rayl = t.material.density_kg_m3 * t.material.sound_speed_m_s;
  return p;
}

bool overlaps(const Eigen::AlignedBox3d& b, const Box2& r) {
  return b.max().x() >= r.min.x() && b.min().x() <= r.max.x() && b.max().y() >= r.min.y() &&
         b.min().y() <= r.max.y();
}

}  // namespace

Scene::Scene(const SceneDesc& desc, seabed::SeabedOptions seabed_options)
    : desc_(desc),
      uid_(g_next_scene_uid++),
      seabed_(std::make_shared<seabed::SeabedModel>(desc, seabed_options)) {
  for (std::size_t k = 0; k < desc_.targets.size(); ++k) {
    targets_.push_back(
        place_target(desc_.targets[k], static_cast<int>(k), *seabed_, desc_.water.depth_m));
  }
}

Scene::Scene(const SceneDesc& desc, std::shared_ptr<const seabed::SeabedModel> seabed)
    : desc_(desc), uid_(g_next_scene_uid++), seabed_(std::move(seabed)) {
  if (!seabed_) throw std::invalid_argument("Scene: the shared seabed is null");
  if (seabed_->water_depth_m() != desc_.water.depth_m) {
    throw std::invalid_argument("Scene: the shared seabed was built for water depth " +
                                std::to_string(seabed_->water_depth_m()) + " m, the scene says " +
                                std::to_string(desc_.water.depth_m) + " m");
  }
  for (std::size_t k = 0; k < desc_.targets.size(); ++k) {
    targets_.push_back(
        place_target(desc_.targets[k], static_cast<int>(k), *seabed_, desc_.water.depth_m));
  }
}

const TargetBvh& Scene::target_bvh() const {
  std::call_once(bvh_once_, [this] { bvh_ = std::make_unique<TargetBvh>(targets_); });
  return *bvh_;
}

double Scene::seabed_z(double x, double y) const {
  return desc_.water.depth_m - seabed_->elevation(x, y);
}

std::shared_ptr<const SceneView> Scene::view(const Box2& region, int threads) const {
  auto v = std::shared_ptr<SceneView>(new SceneView());
  const seabed::SeabedModel& sb = *seabed_;
  const double d = sb.spacing_m();
  v->spacing_m_ = d;
  // clip to the modelled extent
  Box2 r;
  r.min = region.min.cwiseMax(sb.extent_min());
  r.max = region.max.cwiseMin(sb.extent_max());
  v->region_ = r;
  v->origin_W_ = Vec3(std::round(0.5 * (r.min.x() + r.max.x())),
                      std::round(0.5 * (r.min.y() + r.max.y())), std::round(desc_.water.depth_m));
  RTCDevice device = embree_device();
  v->scene_ = rtcNewScene(device);
  // Default (non-robust) traversal: RTC_SCENE_FLAG_ROBUST cost 30 % of the renderer's ray
  // throughput here and no ray slipped between grid cells without it (645,734 rays aimed at
  // lattice points, cell edges and tile borders; scene_test keeps a check of this).
  unsigned geom_id = 0;
  if (r.max.x() > r.min.x() && r.max.y() > r.min.y()) {
    sb.prepare(r.min.x(), r.min.y(), r.max.x(), r.max.y(), threads);
    // lattice points inside the region
    const auto ia = static_cast<std::int64_t>(std::ceil(r.min.x() / d - 1e-9));
    const auto ib = static_cast<std::int64_t>(std::floor(r.max.x() / d + 1e-9));
    const auto ja = static_cast<std::int64_t>(std::ceil(r.min.y() / d - 1e-9));
    const auto jb = static_cast<std::int64_t>(std::floor(r.max.y() / d + 1e-9));
    const int t = sb.tile_size();
    // one Embree grid per heightmap tile, each including the first row and column of its
    // neighbours so that adjacent grids share their border vertices exactly (watertight)
    for (std::int64_t ti = sb.tile_of(ia); ti <= sb.tile_of(ib); ++ti) {
      for (std::int64_t tj = sb.tile_of(ja); tj <= sb.tile_of(jb); ++tj) {
        auto g = std::make_unique<SceneView::Grid>();
        g->i0 = std::max(ia, ti * t);
        g->j0 = std::max(ja, tj * t);
        const std::int64_t i1 = std::min(ib, ti * t + t);
        const std::int64_t j1 = std::min(jb, tj * t + t);
        if (i1 <= g->i0 || j1 <= g->j0) continue;  // a single row or column: no cells
        g->ni = static_cast<int>(i1 - g->i0 + 1);
        g->nj = static_cast<int>(j1 - g->j0 + 1);
        const auto n = static_cast<std::size_t>(g->ni) * static_cast<std::size_t>(g->nj);
        std::vector<float> h(n);
        g->sediment.resize(n);
        sb.copy_region(g->i0, g->j0, g->ni, g->nj, h.data(), g->sediment.data());
        g->vertices.resize(3 * (n + 1));
        for (int a = 0; a < g->ni; ++a) {
          for (int b = 0; b < g->nj; ++b) {
            const std::size_t m = static_cast<std::size_t>(a) * static_cast<std::size_t>(g->nj) +
                                  static_cast<std::size_t>(b);
            g->vertices[3 * m + 0] =
                static_cast<float>(static_cast<double>(g->i0 + a) * d - v->origin_W_.x());
            g->vertices[3 * m + 1] =
                static_cast<float>(static_cast<double>(g->j0 + b) * d - v->origin_W_.y());
            g->vertices[3 * m + 2] =
                static_cast<float>(desc_.water.depth_m - h[m] - v->origin_W_.z());
          }
        }
        // width runs along a vertex row (east, contiguous), height across rows (north)
        g->grid.startVertexID = 0;
        g->grid.stride = static_cast<unsigned>(g->nj);
        g->grid.width = static_cast<unsigned short>(g->nj);
        g->grid.height = static_cast<unsigned short>(g->ni);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_GRID);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, &g->grid, 0,
                                   sizeof(RTCGrid), 1);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                   g->vertices.data(), 0, 3 * sizeof(float), n);
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(v->scene_, geom, geom_id++);
        rtcReleaseGeometry(geom);
        v->grids_.push_back(std::move(g));
      }
    }
  }
  // targets whose bounds reach into the region
  for (const PlacedTarget& p : targets_) {
    if (!overlaps(p.bounds_W, r)) continue;
    std::vector<float> verts;
    std::vector<std::uint32_t> idx;
    attach_target_mesh(v->scene_, geom_id++, p, v->origin_W_, verts, idx);
    v->target_geoms_.push_back(p.index);
    v->target_vertices_.push_back(std::move(verts));
    v->target_indices_.push_back(std::move(idx));
  }
  // Embree builds the BVH here; the scene must be committed before any query
  rtcCommitScene(v->scene_);
  check_embree("building the scene view");
  return v;
}

SceneView::~SceneView() {
  if (scene_) rtcReleaseScene(scene_);
}

std::size_t SceneView::buffer_bytes() const {
  std::size_t b = 0;
  for (const auto& g : grids_)
    b += g->vertices.size() * sizeof(float) + g->sediment.size();
  for (const auto& v : target_vertices_)
    b += v.size() * sizeof(float);
  for (const auto& i : target_indices_)
    b += i.size() * sizeof(std::uint32_t);
  return b;
}

void SceneView::describe_hit(unsigned geom_id, const Vec3& point_W, Hit& hit) const {
  if (geom_id < grids_.size()) {
    const Grid& g = *grids_[geom_id];
    hit.kind = HitKind::kSeabed;
    const auto a =
        std::clamp<std::int64_t>(std::llround(point_W.x() / spacing_m_) - g.i0, 0, g.ni - 1);
    const auto b =
        std::clamp<std::int64_t>(std::llround(point_W.y() / spacing_m_) - g.j0, 0, g.nj - 1);
    hit.sediment = g.sediment[static_cast<std::size_t>(a) * static_cast<std::size_t>(g.nj) +
                              static_cast<std::size_t>(b)];
    hit.target = -1;
  } else {
    hit.kind = HitKind::kTarget;
    hit.target = target_geoms_[geom_id - grids_.size()];
    hit.sediment = -1;
  }
}

Hit SceneView::intersect(const Vec3& origin_W, const Vec3& dir_W, double t_max_m) const {
  Hit hit;
  const double len = dir_W.norm();
  if (!(len > 0.0)) return hit;
  const Vec3 dir = dir_W / len;
  const RTCRayHit rh = intersect_one(scene_, origin_W - origin_W_, dir, 0.0, t_max_m);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.distance_m = rh.ray.tfar;
  hit.point_W = origin_W + hit.distance_m * dir;
  Vec3 n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  n.normalize();
  if (n.dot(dir) > 0.0) n = -n;
  hit.normal_W = n;
  describe_hit(rh.hit.geomID, hit.point_W, hit);
  return hit;
}

}  // namespace sonarloop::scene
