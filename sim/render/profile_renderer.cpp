#include "sim/render/profile_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/render/echo_model.h"
#include "sim/render/profile_line.h"

namespace sonarloop::render {
namespace {

// [lo, hi] ∩ {s : a + s·b inside [min, max]} (one axis of a slab clip)
void clip_axis(double a, double b, double min, double max, double& lo, double& hi) {
  if (std::abs(b) < 1e-12) {
    if (a < min || a > max) hi = lo - 1.0;  // empty
    return;
  }
  double t0 = (min - a) / b;
  double t1 = (max - a) / b;
  if (t0 > t1) std::swap(t0, t1);
  lo = std::max(lo, t0);
  hi = std::min(hi, t1);
}

}  // namespace

ProfileRenderer::ProfileRenderer(const SonarSetup& sonar, const Fidelity& fidelity)
    : PingRenderer(sonar, fidelity) {}

void ProfileRenderer::prepare(const scene::Scene& scene, const Pose& pose,
                              const RenderOptions& options, PingScratch& /*scratch*/) const {
  const seabed::SeabedModel& sb = scene.seabed();
  const MarchPlan plan = march_plan(fidelity_, sb.spacing_m(), sonar_.desc.bin_size_m);
  scene.target_bvh();
  // the tiles along each side's ground line, at half a tile's width apart
  const double r = std::min(options.range_max_m, sonar_.desc.max_range_m);
  const double tile_m = sb.tile_size() * plan.spacing_m;
  const Vec3 n = pose.R_WV().col(0);
  const double h = std::hypot(n.x(), n.y());
  const Vec2 along = h > 1e-6 ? Vec2(n.x() / h, n.y() / h) : heading_vector(pose.yaw);
  const Vec2 across(-along.y(), along.x());
  const Vec2 lo = sb.extent_min();
  const Vec2 hi = sb.extent_max();
  // tiles another thread is making are left to it: work ahead never waits
  const auto tile_of = [&](double v) {
    return sb.tile_of(static_cast<std::int64_t>(std::floor(v / plan.spacing_m)));
  };
  for (int side = 0; side < 2; ++side) {
    if (!(options.side_mask & (1 << side))) continue;
    const double sign = side == 0 ? -1.0 : 1.0;
    for (double s = 0.0; s <= r + 0.5 * tile_m; s += 0.5 * tile_m) {
      const Vec2 p = pose.position_W.head<2>() + sign * std::min(s, r) * across;
      if (p.x() < lo.x() || p.y() < lo.y() || p.x() > hi.x() || p.y() > hi.y()) continue;
      sb.prefetch_tile(tile_of(p.x()), tile_of(p.y()), plan.level);
    }
  }
}

void ProfileRenderer::render(const scene::Scene& scene, const Pose& pose, std::uint64_t seed,
                             std::uint64_t ping_index, const RenderOptions& options,
                             PingScratch& scratch, PingLines& out) const {
  scratch.traces.clear();
  scratch.rays_cast = 0;
  scratch.samples = 0;
  echo().start_lines(options, scratch);
  const seabed::SeabedModel& sb = scene.seabed();
  const MarchPlan plan = march_plan(fidelity_, sb.spacing_m(), sonar_.desc.bin_size_m);
  seabed::HeightSampler& heights = scratch.own_as<ProfileScratch>().heights;
  heights.bind(sb, plan.level);
  const Vec3 o = pose.position_W;

  // altitude: the heightfield below the sonar, or a target straight below it
  double altitude = options.nadir_altitude_m;
  const scene::TargetBvh& bvh = scene.target_bvh();
  if (std::isnan(altitude)) {
    const Vec2 lo = sb.extent_min();
    const Vec2 hi = sb.extent_max();
    if (o.x() >= lo.x() && o.y() >= lo.y() && o.x() <= hi.x() && o.y() <= hi.y()) {
      seabed::HeightSample hs;
      heights.sample(o.x(), o.y(), hs);
      altitude = sb.water_depth_m() - hs.elevation_m - o.z();
    } else {
      altitude = scene.seabed_z(o.x(), o.y()) - o.z();
    }
    if (!bvh.empty() && altitude > 0.0) {
      const double t = bvh.first_hit_m(o, Vec3(0, 0, 1), altitude);
      ++scratch.rays_cast;
      if (t >= 0.0) altitude = t;
    }
  }
  if (!(altitude > 0.05)) {  // out of the water
    echo().finish_lines(options, seed, ping_index, std::numeric_limits<double>::quiet_NaN(),
                        scratch, out);
    return;
  }

  const Mat3 R = pose.R_WV();
  const Vec3 n = R.col(0);
  const double h = std::hypot(n.x(), n.y());
  if (h < 1e-6) {  // pointing straight up or down: no beam plane meets the seabed as a line
    echo().finish_lines(options, seed, ping_index, altitude, scratch, out);
    return;
  }
  const Vec3 ey = R.col(1);
  const Vec3 ez = R.col(2);
  const Vec3 u_stbd(-n.y() / h, n.x() / h, 0.0);
  const Vec3 w = n.cross(u_stbd);
  const double cos_dep = std::cos(sonar_.array.depression_rad);
  const double sin_dep = std::sin(sonar_.array.depression_rad);
  const double dr = sonar_.desc.bin_size_m;
  const double r_hi = std::min(options.range_max_m, sonar_.desc.max_range_m);
  const double r_lo = std::max(0.0, std::floor(options.range_min_m / dr) * dr);

  Line line;
  line.R = &R;
  line.o = o;
  line.n = n;
  line.w = w;
  line.strip = echo().strip();
  line.altitude = altitude;
  line.depth = sb.water_depth_m();
  line.step = plan.step_m;
  // the ray tracer's fan (ray_fan.h) starts here; target rays are laid out on it
  line.r_start = std::max(altitude, r_lo);
  line.r_max = r_hi;
  for (int side = 0; side < 2; ++side) {
    if (!(options.side_mask & (1 << side))) continue;
    line.side = side;
    line.sign = side == 0 ? -1.0 : 1.0;
    line.u = line.sign * u_stbd;
    // sin(off axis) = sin δ cos δ0 − cos δ sin δ0 with sin δ = z_V / ρ, cos δ = ±y_V / ρ, and
    // (y_V, z_V) the in-plane point (s, β) turned into the vehicle frame
    const double uy = line.u.dot(ey), uz = line.u.dot(ez), wy = w.dot(ey), wz = w.dot(ez);
    line.pat_a = uz * cos_dep - line.sign * uy * sin_dep;
    line.pat_b = wz * cos_dep - line.sign * wy * sin_dep;
    for (int j = 0; j < static_cast<int>(echo().along().size()); ++j) {
      if (abandoned(options)) return;  // the caller discards the ping
      line.j = j;
      const double a = echo().along()[static_cast<std::size_t>(j)];
      line.alpha = line.strip ? a : 0.0;
      line.sin_psi = line.strip ? 0.0 : std::sin(a);
      line.inv_cos_psi = line.strip ? 1.0 : 1.0 / std::cos(a);
      line.weight = echo().along_weight()[static_cast<std::size_t>(j)];
      // the march: from nadir (or the shadow margin before the window) to the window's end,
      // clipped to the modelled seabed
      double s_lo = 0.0;
      if (std::isfinite(options.shadow_margin_m)) {
        const double deep = altitude + kSeabedSlack_m;
        const double g = std::sqrt(std::max(0.0, r_lo * r_lo - deep * deep));
        s_lo = std::max(0.0, g - options.shadow_margin_m);
      }
      double s_hi = r_hi / line.inv_cos_psi;  // beyond it every point is out of range
      const Vec2 base = o.head<2>() + line.alpha * n.head<2>() + altitude * w.head<2>();
      clip_axis(base.x(), line.u.x(), sb.extent_min().x(), sb.extent_max().x(), s_lo, s_hi);
      clip_axis(base.y(), line.u.y(), sb.extent_min().y(), sb.extent_max().y(), s_lo, s_hi);
      if (!(s_hi > s_lo)) continue;
      line.s_start = s_lo;
      line.samples = static_cast<int>(std::ceil((s_hi - s_lo) / line.step)) + 1;
      cast_target_rays(scene, line, scratch);
      march(scene, line, options, scratch);
    }
  }
  echo().finish_lines(options, seed, ping_index, altitude, scratch, out);
}

}  // namespace sonarloop::render
