#include "sim/vehicle/depth_profile.h"

#include <algorithm>
#include <cmath>
#include <deque>

namespace sonarloop::vehicle {

namespace {

// Sliding-window minimum of v over [k, k + after] (clipped at the end), O(n): the deque holds
// indices in increasing order with increasing values, so its front is the minimum.
std::vector<double> minimum_ahead(const std::vector<double>& v, std::size_t after) {
  const std::size_t n = v.size();
  std::vector<double> out(n);
  std::deque<std::size_t> candidates;
  std::size_t next = 0;  // next index to enter the window
  for (std::size_t k = 0; k < n; ++k) {
    while (next < n && next - k <= after) {
      while (!candidates.empty() && v[candidates.back()] >= v[next])
        candidates.pop_back();
      candidates.push_back(next++);
    }
    while (candidates.front() < k)
      candidates.pop_front();
    out[k] = v[candidates.front()];
  }
  return out;
}

}  // namespace

std::size_t DepthProfile::smoothing_margin_steps(double step_m, double smoothing_m) {
  const double width = std::max(smoothing_m, step_m);
  return static_cast<std::size_t>(std::ceil(0.5 * width / step_m)) + 1;
}

DepthProfile::DepthProfile(std::vector<double> knot_depths_m, double step_m, double smoothing_m,
                           double origin_m)
    : z_(std::move(knot_depths_m)),
      step_m_(step_m),
      width_m_(std::max(smoothing_m, step_m)),
      origin_m_(origin_m) {
  if (z_.empty()) z_.push_back(0.0);
  // trapezoid integrals (exact for the piecewise-linear z_l)
  integral_.resize(z_.size());
  integral_[0] = 0.0;
  for (std::size_t k = 1; k < z_.size(); ++k) {
    integral_[k] = integral_[k - 1] + 0.5 * step_m_ * (z_[k - 1] + z_[k]);
  }
}

double DepthProfile::linear_at(double s_m) const {
  const double x = (s_m - origin_m_) / step_m_;
  if (!(x > 0.0)) return z_.front();
  const double last = static_cast<double>(z_.size() - 1);
  if (x >= last) return z_.back();
  const double k = std::floor(x);
  const auto i = static_cast<std::size_t>(k);
  return z_[i] + (x - k) * (z_[i + 1] - z_[i]);
}

double DepthProfile::integral_to(double s_m) const {
  // from the first knot: only differences of this are used
  const double r = s_m - origin_m_;
  const double x = r / step_m_;
  if (!(x > 0.0)) return z_.front() * r;
  const double last = static_cast<double>(z_.size() - 1);
  if (x >= last) return integral_.back() + z_.back() * (r - last * step_m_);
  const double k = std::floor(x);
  const auto i = static_cast<std::size_t>(k);
  const double sigma = r - k * step_m_;
  return integral_[i] + sigma * z_[i] + 0.5 * sigma * sigma / step_m_ * (z_[i + 1] - z_[i]);
}

double DepthProfile::depth_at(double s_m) const {
  if (z_.size() == 1) return z_.front();
  const double h = 0.5 * width_m_;
  return (integral_to(s_m + h) - integral_to(s_m - h)) / width_m_;
}

double DepthProfile::slope_at(double s_m) const {
  if (z_.size() == 1) return 0.0;
  const double h = 0.5 * width_m_;
  return (linear_at(s_m + h) - linear_at(s_m - h)) / width_m_;
}

std::vector<double> terrain_following_depths(std::span<const double> seabed_depth_m, double step_m,
                                             double speed_m_s, double altitude_m,
                                             double max_climb_rate_m_s, double look_ahead_m,
                                             double min_depth_m) {
  const std::size_t n = seabed_depth_m.size();
  std::vector<double> z(n);
  if (n == 0) return z;
  const double climb_per_step = max_climb_rate_m_s * step_m / speed_m_s;
  // steps seen ahead (at most the whole path)
  const double steps_ahead = std::floor(look_ahead_m / step_m + 1e-9);
  const std::size_t window =
      steps_ahead >= static_cast<double>(n) ? n : static_cast<std::size_t>(steps_ahead);

  // a_j = z_d(j) + j·c, so target(k) = (min of a_j over j in [k, k + window]) - k·c
  std::vector<double> a(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double commanded = std::max(seabed_depth_m[j] - altitude_m, min_depth_m);
    a[j] = commanded + static_cast<double>(j) * climb_per_step;
  }
  const std::vector<double> ahead_min = minimum_ahead(a, window);

  // forward rate limit
  z[0] = ahead_min[0];
  for (std::size_t k = 1; k < n; ++k) {
    const double target = ahead_min[k] - static_cast<double>(k) * climb_per_step;
    z[k] = std::clamp(target, z[k - 1] - climb_per_step, z[k - 1] + climb_per_step);
  }
  return z;
}

}  // namespace sonarloop::vehicle
