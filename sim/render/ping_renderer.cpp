#include "sim/render/ping_renderer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/acoustics/beam_pattern.h"
#include "sim/acoustics/noise.h"
#include "sim/acoustics/target_scattering.h"
#include "sim/core/rng.h"
#include "sim/seabed/sediment.h"

namespace sonarloop::render {
namespace {

constexpr double kWaterDensity_kg_m3 = 1027.0;  // physics.md §4 impedance table (Z1)
// Rays are fanned to 5 % beyond the maximum range on a flat seabed, so that rising terrain
// at far range is still reached.
constexpr double kRangeMargin = 1.05;
// Floor for cos(incidence) in dA = r²·dΩ/cos θ: a ray grazing a facet at < 0.06° still has a
// finite footprint (the cross-section goes to 0 there anyway).
constexpr double kMinCosIncidence = 1e-3;
// Truth rays continue through a target at most this many surfaces before giving up.
constexpr int kMaxContinuations = 8;
// A ray's echo is spread over at most this many bins (a ray almost tangent to a surface).
constexpr double kMaxSpreadBins = 32.0;

// Adds `energy` spread uniformly over slant ranges [r - width/2, r + width/2] (in bins) to acc.
void splat(std::vector<double>& acc, double r_bins, double width_bins, double energy) {
  const auto n = static_cast<double>(acc.size());
  if (width_bins <= 1e-6) {
    if (r_bins >= 0.0 && r_bins < n) acc[static_cast<std::size_t>(r_bins)] += energy;
    return;
  }
  const double a = r_bins - 0.5 * width_bins;
  const double b = r_bins + 0.5 * width_bins;
  const double density = energy / width_bins;
  const int k0 = std::max(0, static_cast<int>(std::floor(a)));
  const int k1 = std::min(static_cast<int>(n) - 1, static_cast<int>(std::floor(b)));
  for (int k = k0; k <= k1; ++k) {
    const double overlap = std::min(b, k + 1.0) - std::max(a, static_cast<double>(k));
    acc[static_cast<std::size_t>(k)] += density * overlap;
  }
}

struct Hit {
  bool hit = false;
  double r = 0.0;
  Vec3 n = Vec3::Zero();  // unit geometric normal (view-local = world orientation)
  unsigned geom = RTC_INVALID_GEOMETRY_ID;
};

Hit trace(RTCScene scene, const Vec3& o_local, const Vec3& d, double tnear, double tfar) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(o_local.x());
  rh.ray.org_y = static_cast<float>(o_local.y());
  rh.ray.org_z = static_cast<float>(o_local.z());
  rh.ray.dir_x = static_cast<float>(d.x());
  rh.ray.dir_y = static_cast<float>(d.y());
  rh.ray.dir_z = static_cast<float>(d.z());
  rh.ray.tnear = static_cast<float>(tnear);
  rh.ray.tfar = static_cast<float>(tfar);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.time = 0.0f;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &ctx, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.r = rh.ray.tfar;
  h.n = Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
  h.geom = rh.hit.geomID;
  return h;
}

TargetTrace& trace_for(std::vector<TargetTrace>& traces, int target, int side) {
  for (auto& t : traces) {
    if (t.target == target && t.side == side) return t;
  }
  traces.push_back(TargetTrace{target, side});
  return traces.back();
}

void extend(int& first, int& last, int bin) {
  if (first < 0 || bin < first) first = bin;
  if (last < 0 || bin > last) last = bin;
}

}  // namespace

Fidelity default_fidelity(const SonarSetup& s) {
  Fidelity f;
  f.rays_per_bin = s.desc.rays_per_bin > 0 ? s.desc.rays_per_bin : 2;
  if (s.desc.along_track_rays > 0) {
    f.along_track_rays = s.desc.along_track_rays;
  } else if (s.desc.along_track == AlongTrackModel::kStrip) {
    f.along_track_rays = 2;
  } else {
    // two rays per bin size across the beam's footprint at maximum range
    const double footprint = s.desc.max_range_m * s.horizontal_beamwidth_rad;
    f.along_track_rays =
        std::clamp(static_cast<int>(std::ceil(2.0 * footprint / s.desc.bin_size_m)), 2, 32);
  }
  return f;
}

PingRenderer::PingRenderer(const scene::Scene& scene, const SonarSetup& sonar)
    : scene_(scene), sonar_(sonar), fidelity_(default_fidelity(sonar)) {
  for (std::size_t id = 0; id < seabed::sediment_table().size(); ++id) {
    seabed_sigma_.push_back(acoustics::make_backscatter_table(
        static_cast<seabed::SedimentId>(id), sonar_.desc.frequency_hz, sonar_.desc.bottom_model,
        acoustics::kAplTableSoundSpeed_m_s, sonar_.desc.lambert_mu_db));
  }
  const double z_water = acoustics::acoustic_impedance(kWaterDensity_kg_m3, sonar_.sound_speed_m_s);
  for (const auto& t : scene_.targets()) {
    // design choice (target_scattering.h): Lambert μ = R²/π, R the impedance reflectance
    const double r = acoustics::impedance_reflectance(z_water, t.impedance_rayl);
    target_mu_.push_back(acoustics::lambert_mu_from_reflectance(r));
  }
  source_level_lin_ = std::pow(10.0, sonar_.desc.source_level_db / 10.0);
  // received thermal noise in the receiver band, reduced by the array's directivity index
  const double di = acoustics::directivity_index_rect_db(
      sonar_.desc.array_length_m, sonar_.desc.array_height_m, sonar_.wavelength_m);
  const double nl =
      acoustics::noise_band_level_db(sonar_.desc.frequency_hz, sonar_.bandwidth_hz) - di;
  noise_lin_ = std::pow(10.0, nl / 10.0);
}

scene::Box2 PingRenderer::swath_region(const Pose& pose) const {
  const double r = sonar_.desc.max_range_m;
  const Vec2 c = pose.position_W.head<2>();
  return scene::Box2{c - Vec2(r, r), c + Vec2(r, r)};
}

void PingRenderer::render(const scene::SceneView& view, const Pose& pose, std::uint64_t seed,
                          std::uint64_t ping_index, const RenderOptions& options,
                          PingScratch& scratch, PingLines& out) const {
  const double altitude = generate_rays(view, pose, options, scratch);
  intersect(view, scratch);
  shade(view, seed, ping_index, options, altitude, scratch, out);
}

double PingRenderer::generate_rays(const scene::SceneView& view, const Pose& pose,
                                   const RenderOptions& options, PingScratch& scratch) const {
  scratch.rays.clear();
  scratch.meta.clear();
  scratch.traces.clear();
  scratch.rays_cast = 0;
  // altitude from a ray straight down (fallback: the heightmap below the sonar)
  const Vec3 o_local = pose.position_W - view.local_origin_W();
  const Hit nadir = trace(view.rtc_scene(), o_local, Vec3(0, 0, 1), 0.0, 1e4);
  ++scratch.rays_cast;
  const double altitude =
      nadir.hit ? nadir.r
                : scene_.seabed_z(pose.position_W.x(), pose.position_W.y()) - pose.position_W.z();
  if (!(altitude > 0.05)) return std::numeric_limits<double>::quiet_NaN();  // out of the water
  for (int side = 0; side < 2; ++side) {
    if (options.side_mask & (1 << side))
      generate_side(view, pose, side, altitude, options, scratch);
  }
  return altitude;
}

void PingRenderer::intersect(const scene::SceneView& view, PingScratch& scratch) {
  if (scratch.rays.empty()) return;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  // rays of a fan are coherent: neighbours leave the same origin in nearly the same direction
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1M(view.rtc_scene(), &ctx, scratch.rays.data(),
                 static_cast<unsigned>(scratch.rays.size()), sizeof(RTCRayHit));
  scratch.rays_cast += scratch.rays.size();
}

void PingRenderer::generate_side(const scene::SceneView& view, const Pose& pose, int side,
                                 double altitude, const RenderOptions& options,
                                 PingScratch& scratch) const {
  const SonarDesc& sd = sonar_.desc;
  const double dr = sd.bin_size_m;
  const int per_bin = fidelity_.rays_per_bin;
  const int n_along = fidelity_.along_track_rays;
  const bool strip = sd.along_track == AlongTrackModel::kStrip;
  const double sign = side == 0 ? -1.0 : 1.0;  // port looks to -y_V
  const Mat3 R = pose.R_WV();
  const Vec3 o_local = pose.position_W - view.local_origin_W();

  // vertical rays: edges at flat-seabed slant ranges, per_bin per bin, from the window start
  // (or the altitude) to the window end plus a margin
  const double r_start = std::max(altitude, std::floor(options.range_min_m / dr) * dr);
  const double r_stop = std::min(options.range_max_m, sd.max_range_m) * kRangeMargin;
  const double r_max = std::min(options.range_max_m, sd.max_range_m);
  if (r_stop <= r_start) return;
  const int n_vert = static_cast<int>(std::ceil((r_stop - r_start) / dr * per_bin));
  auto& edge_sin = scratch.ray_edge;  // sin of world depression at each edge
  edge_sin.resize(static_cast<std::size_t>(n_vert) + 1);
  for (int m = 0; m <= n_vert; ++m) {
    const double r = r_start + m * dr / per_bin;
    edge_sin[static_cast<std::size_t>(m)] = static_cast<float>(std::min(1.0, altitude / r));
  }

  // along-track rays: angles across the main lobe (beam) or offsets across the strip
  auto& along = scratch.along;
  auto& along_w = scratch.along_weight;
  along.resize(static_cast<std::size_t>(n_along));
  along_w.resize(static_cast<std::size_t>(n_along));
  if (strip) {
    const double w = sonar_.along_track_resolution_m;
    for (int j = 0; j < n_along; ++j) {
      along[static_cast<std::size_t>(j)] = static_cast<float>(-0.5 * w + (j + 0.5) * w / n_along);
      along_w[static_cast<std::size_t>(j)] = static_cast<float>(w / n_along);  // metres
    }
  } else {
    const double psi_null = acoustics::first_null_rad(sd.array_length_m, sonar_.wavelength_m);
    double sum = 0.0;
    for (int j = 0; j < n_along; ++j) {
      const double psi = n_along == 1 ? 0.0 : -psi_null + (j + 0.5) * 2.0 * psi_null / n_along;
      const double b = acoustics::line_array_pattern(psi, sd.array_length_m, sonar_.wavelength_m);
      along[static_cast<std::size_t>(j)] = static_cast<float>(psi);
      along_w[static_cast<std::size_t>(j)] = static_cast<float>(b * b * b * b);
      sum += b * b * b * b;
    }
    // the weights integrate the two-way horizontal pattern: Σ w_j = ∫ G_h dψ
    for (auto& w : along_w)
      w = static_cast<float>(w * sonar_.horizontal_beam_integral_rad / sum);
  }

  const double k_half = std::numbers::pi / sonar_.wavelength_m;
  const double cos_dep = std::cos(sonar_.array.depression_rad);
  const double sin_dep = std::sin(sonar_.array.depression_rad);
  const std::size_t first = scratch.rays.size();
  scratch.rays.resize(first + static_cast<std::size_t>(n_along) * static_cast<std::size_t>(n_vert));
  scratch.meta.resize(scratch.rays.size());
  std::size_t k = first;
  for (int j = 0; j < n_along; ++j) {
    const double psi = strip ? 0.0 : along[static_cast<std::size_t>(j)];
    const double sin_psi = std::sin(psi);
    const double cos_psi = std::cos(psi);
    const Vec3 origin =
        strip ? Vec3(o_local + R * Vec3(along[static_cast<std::size_t>(j)], 0, 0)) : o_local;
    // depression in V giving world depression δ_W: A cos δ + B sin δ = sin δ_W − C0
    const double a_coef = R(2, 1) * sign * cos_psi;
    const double b_coef = R(2, 2) * cos_psi;
    const double c0 = R(2, 0) * sin_psi;
    const double amp = std::hypot(a_coef, b_coef);
    const double phase = std::atan2(b_coef, a_coef);
    auto depression_v = [&](double sin_dw) {
      return phase - std::acos(std::clamp((sin_dw - c0) / amp, -1.0, 1.0));
    };
    double d_lo = depression_v(edge_sin[0]);
    for (int i = 0; i < n_vert; ++i, ++k) {
      const double d_hi = depression_v(edge_sin[static_cast<std::size_t>(i) + 1]);
      const double delta = 0.5 * (d_lo + d_hi);
      const double d_delta = std::fabs(d_lo - d_hi);
      d_lo = d_hi;
      const double sin_d = std::sin(delta);
      const double cos_d = std::cos(delta);
      const Vec3 d = R * Vec3(sin_psi, sign * cos_psi * cos_d, cos_psi * sin_d);
      RTCRayHit& rh = scratch.rays[k];
      rh.ray.org_x = static_cast<float>(origin.x());
      rh.ray.org_y = static_cast<float>(origin.y());
      rh.ray.org_z = static_cast<float>(origin.z());
      rh.ray.dir_x = static_cast<float>(d.x());
      rh.ray.dir_y = static_cast<float>(d.y());
      rh.ray.dir_z = static_cast<float>(d.z());
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = static_cast<float>(r_max);
      rh.ray.time = 0.0f;
      rh.ray.mask = 0xFFFFFFFFu;
      rh.ray.id = static_cast<unsigned>(k);
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      // two-way vertical pattern relative to the acoustic axis
      // sin(δ − depression) from the sine and cosine already at hand
      const double off_axis_sin = sin_d * cos_dep - cos_d * sin_dep;
      const double bv = acoustics::sinc(k_half * sd.array_height_m * off_axis_sin);
      RayMeta& m = scratch.meta[k];
      m.pattern = static_cast<float>(bv * bv * bv * bv);
      m.solid_angle = static_cast<float>(d_delta * along_w[static_cast<std::size_t>(j)]);
      m.depression_width = static_cast<float>(d_delta);
      m.side = static_cast<std::uint8_t>(side);
    }
  }
}

void PingRenderer::shade(const scene::SceneView& view, std::uint64_t seed, std::uint64_t ping_index,
                         const RenderOptions& options, double altitude, PingScratch& scratch,
                         PingLines& out) const {
  const int bins = sonar_.bins;
  const auto nb = static_cast<std::size_t>(bins);
  const double dr = sonar_.desc.bin_size_m;
  out.port.assign(nb, 0.0f);
  out.stbd.assign(nb, 0.0f);
  out.altitude_m = altitude;
  scratch.accum[0].assign(nb, 0.0);
  scratch.accum[1].assign(nb, 0.0);
  if (!(altitude > 0.0)) return;
  const bool strip = sonar_.desc.along_track == AlongTrackModel::kStrip;
  const double alpha_np = 0.2 * std::numbers::ln10 * sonar_.alpha_db_per_m;  // two-way, per metre
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
    const double cos_i = std::max(std::fabs(d.dot(n)), kMinCosIncidence);
    const double d_omega = m.solid_angle / (strip ? r : 1.0);
    const double spread =
        source_level_lin_ * m.pattern * d_omega * std::exp(-alpha_np * r) / (r * r);
    double intensity = 0.0;
    if (rh.hit.geomID < n_grids) {
      const Vec3 o(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z);
      view.describe_hit(rh.hit.geomID, view.local_origin_W() + o + r * d, info);
      const double grazing = std::asin(std::min(1.0, cos_i));
      intensity =
          spread * seabed_sigma_[static_cast<std::size_t>(info.sediment)].sigma(grazing) / cos_i;
    } else {
      view.describe_hit(rh.hit.geomID, Vec3::Zero(), info);
      intensity = spread * target_mu_[static_cast<std::size_t>(info.target)] * cos_i;
      if (options.truth) {
        TargetTrace& tr = trace_for(scratch.traces, info.target, m.side);
        extend(tr.highlight_first, tr.highlight_last, bin);
        tr.energy += intensity;
        // continue the ray through the target to the seabed it hides
        const Vec3 o(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z);
        double t = r;
        for (int c = 0; c < kMaxContinuations; ++c) {
          const Hit behind = trace(view.rtc_scene(), o, d, t + 1e-4, r_max);
          ++scratch.rays_cast;
          if (!behind.hit) break;
          t = behind.r;
          if (behind.geom < n_grids) {
            extend(tr.shadow_first, tr.shadow_last, static_cast<int>(t / dr));
            break;
          }
        }
      }
    }
    // the tube's slant-range extent on the surface: r·dδ·tan θ
    const double tan_i = std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i)) / cos_i;
    const double width = std::min(r * m.depression_width * tan_i / dr, kMaxSpreadBins);
    splat(scratch.accum[m.side], r / dr, width, intensity);
  }
  // noise, pulse length, speckle
  const int k0 = std::clamp(static_cast<int>(std::floor(options.range_min_m / dr)), 0, bins);
  const int k1 = std::clamp(static_cast<int>(std::ceil(r_max / dr)), 0, bins);
  const bool speckle = options.speckle && sonar_.desc.speckle;
  const bool noise = options.noise && sonar_.desc.noise;
  const int blur = std::max(1, static_cast<int>(std::lround(sonar_.range_resolution_m / dr)));
  for (int side = 0; side < 2; ++side) {
    if (!(options.side_mask & (1 << side))) continue;
    auto& acc = scratch.accum[side];
    auto& line = side == 0 ? out.port : out.stbd;
    if (noise) {
      for (int k = k0; k < k1; ++k)
        acc[static_cast<std::size_t>(k)] += noise_lin_;
    }
    // pulse longer than a bin: moving average over the range resolution (energy preserving)
    if (blur > 1) {
      double s = 0.0;
      for (int k = 0; k < bins; ++k) {
        s += acc[static_cast<std::size_t>(k)];
        if (k >= blur) s -= acc[static_cast<std::size_t>(k - blur)];
        line[static_cast<std::size_t>(k)] = static_cast<float>(s / blur);
      }
      for (std::size_t k = 0; k < nb; ++k)
        acc[k] = line[k];
    }
    if (speckle) {
      Rng rng(seed, RngStream::kSpeckle, ping_index, static_cast<std::uint64_t>(side));
      for (std::size_t k = 0; k < nb; ++k)
        line[k] = static_cast<float>(acc[k] * rng.exponential(1.0));
    } else {
      for (std::size_t k = 0; k < nb; ++k)
        line[k] = static_cast<float>(acc[k]);
    }
  }
}

}  // namespace sonarloop::render
