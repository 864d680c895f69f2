// ProfileRenderer's target rays: only the depressions the targets' boxes span in a beam plane
// are cast, as the ray tracer's fan would cast them, into the target-only Embree scene
// (profile_renderer.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/render/echo_model.h"
#include "sim/render/profile_line.h"
#include "sim/render/ray_fan.h"

namespace sonarloop::render {
namespace {

// At most this many target rays per beam plane (a target filling the whole fan of a long range).
constexpr std::int64_t kMaxTargetRays = 1 << 16;

}  // namespace

void ProfileRenderer::cast_target_rays(const scene::Scene& scene, const Line& line,
                                       PingScratch& scratch) const {
  ProfileLineScratch& ls = scratch.own_as<ProfileScratch>().line;
  ls.edge_tan.clear();
  ls.ray_tan.clear();
  ls.ray_s.clear();
  ls.hit_r.clear();
  scratch.rays.clear();
  scratch.meta.clear();
  const scene::TargetBvh& bvh = scene.target_bvh();
  if (bvh.empty() || !(line.r_max > line.r_start)) return;
  // The ray tracer's fan continued as far as needed either way: edge m (any integer) at
  // flat-seabed range r_start + m·bin/rays_per_bin, sin(world depression) = altitude / range
  // (ray_fan.h). The rays whose depressions a target's bounding box covers, where the plane
  // meets its bounding sphere.
  const double a = line.altitude;
  const double step_r = sonar_.desc.bin_size_m / fidelity_.rays_per_bin;
  // the shallowest ray worth casting: one that can meet something 4x lower than the sonar's
  // altitude within the window (kMinClearanceFraction of chip_renderer.cpp)
  const double r_cap = 4.0 * line.r_max * kRangeMargin;
  const auto edge_of = [&](double r) { return (r - line.r_start) / step_r; };
  std::int64_t m_min = std::numeric_limits<std::int64_t>::max(), m_max = -1;
  for (const scene::BoundingSphere& sp : bvh.spheres()) {
    const Vec3 c = sp.centre_W - line.o;
    const double dist = c.norm();
    if (dist - sp.radius_m > line.r_max) continue;
    if (c.dot(line.u) < -sp.radius_m) continue;  // on the other side
    const double off_plane =
        line.strip ? c.dot(line.n) - line.alpha : c.dot(line.n) - dist * line.sin_psi;
    if (std::abs(off_plane) > sp.radius_m) continue;
    // the directions it can be seen in: sin(depression) = z / sqrt(h² + z²) is monotone in the
    // depth z below the transducer and in the horizontal distance h, so its extremes over the
    // box lie at its top or bottom and its nearest or farthest horizontal distance
    const Eigen::AlignedBox3d& box = sp.box_W;
    const Vec2 o2 = line.o.head<2>();
    const Vec2 nearest = o2.cwiseMax(box.min().head<2>()).cwiseMin(box.max().head<2>());
    const double h_near = (nearest - o2).norm();
    const double h_far =
        std::hypot(std::max(std::abs(box.min().x() - o2.x()), std::abs(box.max().x() - o2.x())),
                   std::max(std::abs(box.min().y() - o2.y()), std::abs(box.max().y() - o2.y())));
    double sin_lo = 1.0, sin_hi = -1.0;
    for (const double z : {box.min().z() - line.o.z(), box.max().z() - line.o.z()}) {
      for (const double h : {h_near, h_far}) {
        const double len = std::hypot(h, z);
        const double sn = len > 0.0 ? z / len : 1.0;
        sin_lo = std::min(sin_lo, sn);
        sin_hi = std::max(sin_hi, sn);
      }
    }
    const double r_near = sin_hi >= 1.0 ? a : std::max(a, a / sin_hi);
    const double r_far = sin_lo > a / r_cap ? a / sin_lo : r_cap;
    if (r_far <= r_near) continue;
    // one tube more either side: a box face seen edge-on can reach just past its corners
    m_min = std::min(m_min, static_cast<std::int64_t>(std::floor(edge_of(r_near))) - 1);
    m_max = std::max(m_max, static_cast<std::int64_t>(std::ceil(edge_of(r_far))) + 1);
  }
  if (m_max <= m_min) return;
  auto& edge_sin = scratch.ray_edge;
  const auto count =
      static_cast<std::size_t>(std::min<std::int64_t>(m_max - m_min, kMaxTargetRays));
  edge_sin.resize(count + 1);
  for (std::size_t k = 0; k <= count; ++k) {
    const double r =
        line.r_start + static_cast<double>(m_min + static_cast<std::int64_t>(k)) * step_r;
    edge_sin[k] = static_cast<float>(r > a ? a / r : 1.0);
  }

  // the rays, as the ray tracer would cast them, into the target-only scene
  const FanPlane plane(echo(), *line.R, line.side, line.j, line.o - bvh.local_origin_W());
  scratch.rays.resize(count);
  scratch.meta.resize(count);
  ls.edge_tan.resize(count + 1);
  const auto in_plane_tan = [&](double d) {
    const Vec3 dir = plane.direction(d);
    return static_cast<float>(dir.dot(line.w) / std::max(dir.dot(line.u), 1e-12));
  };
  double d_lo = plane.depression_v(edge_sin[0]);
  ls.edge_tan[0] = in_plane_tan(d_lo);
  for (std::size_t k = 0; k < count; ++k) {
    const double d_hi = plane.depression_v(edge_sin[k + 1]);
    plane.make_ray(d_lo, d_hi, line.r_max, static_cast<unsigned>(k), scratch.rays[k],
                   scratch.meta[k]);
    ls.edge_tan[k + 1] = in_plane_tan(d_hi);
    d_lo = d_hi;
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1M(bvh.rtc_scene(), &ctx, scratch.rays.data(), static_cast<unsigned>(count),
                 sizeof(RTCRayHit));
  scratch.rays_cast += count;
  ls.ray_tan.resize(count);
  ls.ray_s.resize(count);
  ls.hit_r.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const RTCRayHit& rh = scratch.rays[k];
    const Vec3 dir(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
    const double du = dir.dot(line.u);
    ls.ray_tan[k] = static_cast<float>(dir.dot(line.w) / std::max(du, 1e-12));
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      ls.hit_r[k] = std::numeric_limits<float>::infinity();
      ls.ray_s[k] = 0.0f;
    } else {
      ls.hit_r[k] = rh.ray.tfar;
      ls.ray_s[k] = static_cast<float>(rh.ray.tfar * du);  // the strip's offset is along n ⟂ u
    }
  }
}

}  // namespace sonarloop::render
