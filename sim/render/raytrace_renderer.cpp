#include "sim/render/raytrace_renderer.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "sim/render/bin_labels.h"
#include "sim/render/echo_model.h"
#include "sim/render/ray_fan.h"
#include "sim/scene/embree_device.h"

namespace sonarloop::render {
namespace {

// Truth rays continue through a target at most this many surfaces before giving up.
constexpr int kMaxContinuations = 8;
// The default view also holds this much ground beyond the beam's along-track footprint.
constexpr double kRaytraceViewMargin_m = 1.0;

struct Hit {
  bool hit = false;
  double r = 0.0;
  unsigned geom = RTC_INVALID_GEOMETRY_ID;
};

Hit trace(RTCScene scene, const Vec3& o_local, const Vec3& d, double tnear, double tfar) {
  const RTCRayHit rh = scene::intersect_one(scene, o_local, d, tnear, tfar);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.r = rh.ray.tfar;
  h.geom = rh.hit.geomID;
  return h;
}

// A target's base on the seabed: its last surface lies this close to the seabed (labels).
constexpr double kBaseOnSeabed_m = 0.02;

// What a ray that hit a target at range r meets when continued through the target's surfaces up
// to r_max: the seabed it hides (negative: none), and the last target surface it passed.
struct Behind {
  double seabed_r = -1.0;
  double exit_r = -1.0;
};

Behind seabed_behind(RTCScene scene, const Vec3& o_local, const Vec3& d, double r, double r_max,
                     std::size_t n_grids, std::uint64_t& rays_cast) {
  Behind b;
  double t = r;
  for (int c = 0; c < kMaxContinuations; ++c) {
    const Hit behind = trace(scene, o_local, d, t + 1e-4, r_max);
    ++rays_cast;
    if (!behind.hit) break;
    t = behind.r;
    if (behind.geom < n_grids) {
      b.seabed_r = t;
      return b;
    }
    b.exit_r = t;
  }
  return b;
}

bool same_box(const scene::Box2& a, const scene::Box2& b) {
  return a.min == b.min && a.max == b.max;
}

}  // namespace

RaytraceRenderer::RaytraceRenderer(const SonarSetup& sonar, const Fidelity& fidelity)
    : PingRenderer(sonar, fidelity),
      build_threads_(static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))) {}

RaytraceRenderer::~RaytraceRenderer() = default;

scene::Box2 RaytraceRenderer::view_region_for(const Pose& pose,
                                              const RenderOptions& options) const {
  if (options.view_region) return *options.view_region;
  // the ground the ping's fans can reach: across track to the range (both sides), along track
  // the beam's footprint there plus the tilt of the beam planes by pitch: a point of a plane
  // within range r lies at most r·sin(pitch) = r·|n_z| along track (it was r·tan(pitch), which
  // at a steep pitch made views of hundreds of metres for ground out of range)
  const double r = std::min(options.range_max_m, sonar_.desc.max_range_m) * kRangeMargin;
  const Mat3 R = pose.R_WV();
  const Vec3 n = R.col(0);
  const double h = std::hypot(n.x(), n.y());
  const Vec2 along = h > 1e-6 ? Vec2(n.x() / h, n.y() / h) : heading_vector(pose.yaw);
  const Vec2 across(-along.y(), along.x());
  double half_along = kRaytraceViewMargin_m + r * std::abs(n.z());
  double widest = 0.0;  // strip: largest offset (m); beam: largest angle (rad)
  for (float a : echo().along())
    widest = std::max(widest, std::abs(static_cast<double>(a)));
  half_along += echo().strip() ? widest : r * std::sin(widest);
  scene::Box2 b{Vec2::Constant(1e300), Vec2::Constant(-1e300)};
  const Vec2 c = pose.position_W.head<2>();
  for (double sa : {-1.0, 1.0}) {
    for (double sc : {-1.0, 1.0}) {
      const Vec2 q = c + sa * half_along * along + sc * r * across;
      b.min = b.min.cwiseMin(q);
      b.max = b.max.cwiseMax(q);
    }
  }
  // snap outwards: the view depends on the grid cells the reach touches, not on the pose itself
  for (int k = 0; k < 2; ++k) {
    b.min[k] = std::floor(b.min[k] / kViewGrid_m) * kViewGrid_m;
    b.max[k] = std::ceil(b.max[k] / kViewGrid_m) * kViewGrid_m;
  }
  return b;
}

std::shared_ptr<const scene::SceneView> RaytraceRenderer::get_view(
    const scene::Scene& scene, const scene::Box2& region) const {
  ViewStore& store = *views_;
  std::promise<std::shared_ptr<const scene::SceneView>> promise;
  std::shared_future<std::shared_ptr<const scene::SceneView>> future;
  bool build = false;
  {
    std::lock_guard<std::mutex> lock(store.mu);
    for (auto& e : store.entries) {
      if (e.scene_uid == scene.uid() && same_box(e.region, region)) {
        e.last_use = ++store.use_clock;
        future = e.view;
        break;
      }
    }
    if (!future.valid()) {
      build = true;
      future = promise.get_future().share();
      store.entries.push_back(ViewEntry{scene.uid(), region, future, ++store.use_clock});
      // forget the least recently used built views beyond the capacity
      while (store.entries.size() > kMaxViews) {
        auto victim = store.entries.end();
        for (auto it = store.entries.begin(); it != store.entries.end(); ++it) {
          if (it->view.wait_for(std::chrono::seconds(0)) != std::future_status::ready) continue;
          if (victim == store.entries.end() || it->last_use < victim->last_use) victim = it;
        }
        if (victim == store.entries.end()) break;
        store.entries.erase(victim);
      }
    }
  }
  if (!build) return future.get();  // built, or being built by another thread
  // build it here, outside the lock
  try {
    promise.set_value(scene.view(region, build_threads_));
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(store.mu);
      std::erase_if(store.entries, [&](const ViewEntry& e) {
        return e.scene_uid == scene.uid() && same_box(e.region, region);
      });
    }
    promise.set_exception(std::current_exception());
  }
  return future.get();
}

std::shared_ptr<const scene::SceneView> RaytraceRenderer::view_for(
    const scene::Scene& scene, const Pose& pose, const RenderOptions& options) const {
  return get_view(scene, view_region_for(pose, options));
}

void RaytraceRenderer::prepare(const scene::Scene& scene, const Pose& pose,
                               const RenderOptions& options, PingScratch& /*scratch*/) const {
  view_for(scene, pose, options);
}

void RaytraceRenderer::render(const scene::Scene& scene, const Pose& pose, std::uint64_t seed,
                              std::uint64_t ping_index, const RenderOptions& options,
                              PingScratch& scratch, PingLines& out) const {
  // an abandoned ping returns between the phases and ray batches; the caller discards it
  scratch.rays_cast = 0;
  scratch.samples = 0;
  const auto view = view_for(scene, pose, options);
  if (abandoned(options)) return;
  const double altitude = generate_rays(scene, *view, pose, options, scratch);
  if (!intersect(*view, options, scratch)) return;
  shade(scene, *view, seed, ping_index, options, altitude, scratch, out);
}

double RaytraceRenderer::generate_rays(const scene::Scene& scene, const scene::SceneView& view,
                                       const Pose& pose, const RenderOptions& options,
                                       PingScratch& scratch) const {
  scratch.rays.clear();
  scratch.meta.clear();
  scratch.traces.clear();
  scratch.rays_cast = 0;
  scratch.samples = 0;
  // altitude from a ray straight down (fallback: the heightmap below the sonar)
  const Vec3 o_local = pose.position_W - view.local_origin_W();
  const Hit nadir = trace(view.rtc_scene(), o_local, Vec3(0, 0, 1), 0.0, 1e4);
  ++scratch.rays_cast;
  const double altitude =
      nadir.hit ? nadir.r
                : scene.seabed_z(pose.position_W.x(), pose.position_W.y()) - pose.position_W.z();
  if (!(altitude > 0.05)) return std::numeric_limits<double>::quiet_NaN();  // out of the water
  const FanEdges fan =
      fan_edges(sonar_, fidelity_.rays_per_bin, altitude, options, scratch.ray_edge);
  if (fan.n_vert == 0) return altitude;
  const Mat3 R = pose.R_WV();
  const auto n_along = static_cast<int>(echo().along().size());
  for (int side = 0; side < 2; ++side) {
    if (!(options.side_mask & (1 << side))) continue;
    const std::size_t first = scratch.rays.size();
    scratch.rays.resize(first +
                        static_cast<std::size_t>(n_along) * static_cast<std::size_t>(fan.n_vert));
    scratch.meta.resize(scratch.rays.size());
    std::size_t k = first;
    for (int j = 0; j < n_along; ++j) {
      const FanPlane plane(echo(), R, side, j, o_local);
      double d_lo = plane.depression_v(scratch.ray_edge[0]);
      for (int i = 0; i < fan.n_vert; ++i, ++k) {
        const double d_hi = plane.depression_v(scratch.ray_edge[static_cast<std::size_t>(i) + 1]);
        plane.make_ray(d_lo, d_hi, fan.r_max, static_cast<unsigned>(k), scratch.rays[k],
                       scratch.meta[k]);
        d_lo = d_hi;
      }
    }
  }
  return altitude;
}

bool RaytraceRenderer::intersect(const scene::SceneView& view, const RenderOptions& options,
                                 PingScratch& scratch) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  // rays of a fan are coherent: neighbours leave the same origin in nearly the same direction
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  // in batches, so that an abandoned ping stops between them
  constexpr std::size_t kBatch = 16384;
  for (std::size_t first = 0; first < scratch.rays.size(); first += kBatch) {
    if (abandoned(options)) return false;
    const std::size_t n = std::min(kBatch, scratch.rays.size() - first);
    rtcIntersect1M(view.rtc_scene(), &ctx, scratch.rays.data() + first, static_cast<unsigned>(n),
                   sizeof(RTCRayHit));
    scratch.rays_cast += n;
  }
  return !abandoned(options);
}

void RaytraceRenderer::copy_rays(const PingScratch& from, PingScratch& to) {
  to.rays = from.rays;
}

void RaytraceRenderer::intersect_one_by_one(const scene::SceneView& view, PingScratch& scratch) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (RTCRayHit& rh : scratch.rays)
    rtcIntersect1(view.rtc_scene(), &ctx, &rh);
}

std::size_t RaytraceRenderer::ray_count(const PingScratch& scratch) {
  return scratch.rays.size();
}

void RaytraceRenderer::shade(const scene::Scene& scene, const scene::SceneView& view,
                             std::uint64_t seed, std::uint64_t ping_index,
                             const RenderOptions& options, double altitude, PingScratch& scratch,
                             PingLines& out) const {
  echo().start_lines(options, scratch);
  if (!(altitude > 0.0)) {
    echo().finish_lines(options, seed, ping_index, altitude, scratch, out);
    return;
  }
  const int bins = sonar_.bins;
  const double dr = sonar_.desc.bin_size_m;
  const std::size_t n_grids = view.seabed_grids();
  const double r_max = std::min(options.range_max_m, sonar_.desc.max_range_m);
  scene::Hit info;
  // the ray loop may append continuation rays' traces but never new primary rays
  const std::size_t n_rays = scratch.rays.size();
  for (std::size_t k = 0; k < n_rays; ++k) {
    const RTCRayHit& rh = scratch.rays[k];
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    const double r = rh.ray.tfar;
    const int bin = static_cast<int>(r / dr);
    if (bin >= bins) continue;
    const RayMeta& m = scratch.meta[k];
    const Vec3 d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
    const Vec3 n = Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
    const double cos_i = std::fabs(d.dot(n));
    EchoModel::TubeEcho e;
    if (rh.hit.geomID < n_grids) {
      const Vec3 o(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z);
      view.describe_hit(rh.hit.geomID, view.local_origin_W() + o + r * d, info);
      e = echo().seabed_tube(m, r, cos_i, info.sediment);
      if (options.labels) count_seabed_sample(scratch.labels, m.side, bin, false);
    } else {
      view.describe_hit(rh.hit.geomID, Vec3::Zero(), info);
      e = echo().target_tube(m, r, cos_i, echo().target_scatter(scene, info.target));
      if (options.labels)
        splat(scratch.labels.target_energy[m.side], r / dr, e.width_bins, e.intensity);
      if (options.truth || options.labels) {
        // continue the ray through the target to the seabed it hides
        const Vec3 o(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z);
        const Behind behind =
            seabed_behind(view.rtc_scene(), o, d, r, r_max, n_grids, scratch.rays_cast);
        if (options.truth) {
          TargetTrace& tr = trace_of(scratch.traces, info.target, m.side);
          extend_bins(tr.highlight_first, tr.highlight_last, bin);
          tr.energy += e.intensity;
          if (behind.seabed_r >= 0.0) {
            extend_bins(tr.shadow_first, tr.shadow_last, static_cast<int>(behind.seabed_r / dr));
          }
        }
        if (options.labels) {
          // the seabed under a target's base: the continuation steps past it where the base
          // lies on it (the same surface twice), so the base's own range stands for it
          double hidden_r = behind.seabed_r;
          if (hidden_r < 0.0 && behind.exit_r >= 0.0) {
            const Vec3 p = view.local_origin_W() + o + behind.exit_r * d;
            if (std::abs(scene.seabed_z(p.x(), p.y()) - p.z()) <= kBaseOnSeabed_m) {
              hidden_r = behind.exit_r;
            }
          }
          if (hidden_r >= 0.0) {
            count_seabed_sample(scratch.labels, m.side, static_cast<int>(hidden_r / dr), true);
          }
        }
      }
    }
    splat(scratch.accum[m.side], r / dr, e.width_bins, e.intensity);
  }
  echo().finish_lines(options, seed, ping_index, altitude, scratch, out);
}

}  // namespace sonarloop::render
