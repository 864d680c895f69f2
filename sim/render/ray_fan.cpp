#include "sim/render/ray_fan.h"

#include "sim/scene/embree_device.h"

#include <algorithm>
#include <cmath>

namespace sonarloop::render {

FanEdges fan_edges(const SonarSetup& sonar, int rays_per_bin, double altitude,
                   const RenderOptions& options, std::vector<float>& edge_sin) {
  const SonarDesc& sd = sonar.desc;
  const double dr = sd.bin_size_m;
  FanEdges f;
  // from the window start (or the altitude) to the window end plus a margin
  const double r_start = std::max(altitude, std::floor(options.range_min_m / dr) * dr);
  const double r_stop = std::min(options.range_max_m, sd.max_range_m) * kRangeMargin;
  f.r_max = std::min(options.range_max_m, sd.max_range_m);
  if (r_stop <= r_start) return f;
  f.n_vert = static_cast<int>(std::ceil((r_stop - r_start) / dr * rays_per_bin));
  edge_sin.resize(static_cast<std::size_t>(f.n_vert) + 1);
  for (int m = 0; m <= f.n_vert; ++m) {
    const double r = r_start + m * dr / rays_per_bin;
    edge_sin[static_cast<std::size_t>(m)] = static_cast<float>(std::min(1.0, altitude / r));
  }
  return f;
}

FanPlane::FanPlane(const EchoModel& echo, const Mat3& R_WV, int side, int j,
                   const Vec3& origin_local)
    : echo_(echo), R_(R_WV), sign_(side == 0 ? -1.0 : 1.0) {  // port looks to -y_V
  const bool strip = echo.strip();
  const auto jj = static_cast<std::size_t>(j);
  const double psi = strip ? 0.0 : echo.along()[jj];
  sin_psi_ = std::sin(psi);
  cos_psi_ = std::cos(psi);
  origin_ = strip ? Vec3(origin_local + R_ * Vec3(echo.along()[jj], 0, 0)) : origin_local;
  // depression in V giving world depression δ_W: A cos δ + B sin δ = sin δ_W − C0
  a_coef_ = R_(2, 1) * sign_ * cos_psi_;
  b_coef_ = R_(2, 2) * cos_psi_;
  c0_ = R_(2, 0) * sin_psi_;
  amp_ = std::hypot(a_coef_, b_coef_);
  phase_ = std::atan2(b_coef_, a_coef_);
  cos_dep_ = std::cos(echo.sonar().array.depression_rad);
  sin_dep_ = std::sin(echo.sonar().array.depression_rad);
  weight_ = echo.along_weight()[jj];
  side_ = static_cast<std::uint8_t>(side);
}

double FanPlane::depression_v(double sin_dw) const {
  return phase_ - std::acos(std::clamp((sin_dw - c0_) / amp_, -1.0, 1.0));
}

Vec3 FanPlane::direction(double d) const {
  return R_ * Vec3(sin_psi_, sign_ * cos_psi_ * std::cos(d), cos_psi_ * std::sin(d));
}

void FanPlane::make_ray(double d_lo, double d_hi, double r_max, unsigned id, RTCRayHit& rh,
                        RayMeta& m) const {
  const double delta = 0.5 * (d_lo + d_hi);
  const double d_delta = std::fabs(d_lo - d_hi);
  const double sin_d = std::sin(delta);
  const double cos_d = std::cos(delta);
  const Vec3 d = R_ * Vec3(sin_psi_, sign_ * cos_psi_ * cos_d, cos_psi_ * sin_d);
  scene::set_ray(rh, origin_, d, 0.0, r_max, id);
  // two-way vertical pattern relative to the acoustic axis:
  // sin(δ − depression) from the sine and cosine already at hand
  const double off_axis_sin = sin_d * cos_dep_ - cos_d * sin_dep_;
  m.pattern = static_cast<float>(echo_.vertical_pattern(off_axis_sin));
  m.solid_angle = static_cast<float>(d_delta * weight_);
  m.depression_width = static_cast<float>(d_delta);
  m.side = side_;
}

}  // namespace sonarloop::render
