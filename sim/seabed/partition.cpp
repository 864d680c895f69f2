#include "sim/seabed/partition.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/seabed/layer_rules.h"
#include "sim/seabed/spectra.h"

namespace sonarloop::seabed {
namespace {

std::unique_ptr<NoiseLayer> make_warp(const scene::SceneDesc& desc, std::uint64_t axis,
                                      std::size_t cache_bytes) {
  const auto& p = desc.seabed.partition;
  NoiseLayerSpec s;
  s.seed = desc.seed;
  s.stream = RngStream::kPartition;
  s.sub_key = axis;
  s.spacing_m = warp_spacing_m(p.border_scale_m);
  s.kernel_size = kernel_size_for(pink_kernel_extent_m(p.border_scale_m), s.spacing_m);
  s.rms = p.border_warp_m;
  const double beta = profile_to_surface_exponent(p.border_beta);
  const double outer = p.border_scale_m;
  const double inner = 2.0 * s.spacing_m;
  s.spectrum = [=](double fx, double fy) { return pink_psd(fx, fy, beta, outer, inner); };
  s.kernel_key = spectrum_key("pink", {beta, outer, inner});
  return std::make_unique<NoiseLayer>(std::move(s), cache_bytes);
}

// classify_grid's warp offsets, kept per thread (as NoiseLayer::sample_grid's buffers are).
struct WarpScratch {
  std::vector<float> wx, wy;
};
WarpScratch& warp_scratch() {
  thread_local WarpScratch w;
  return w;
}

}  // namespace

Partition::Partition(const scene::SceneDesc& desc, std::size_t cache_bytes)
    : blend_width_m_(desc.seabed.partition.blend_width_m) {
  for (const auto& r : desc.seabed.regions)
    centres_.push_back(r.centre_m);
  if (centres_.empty()) centres_.push_back(Vec2::Zero());
  if (centres_.size() > 1 && desc.seabed.partition.border_warp_m > 0.0) {
    warp_x_ = make_warp(desc, 0, cache_bytes);
    warp_y_ = make_warp(desc, 1, cache_bytes);
  }
}

std::vector<const NoiseLayer*> Partition::noise_layers() const {
  std::vector<const NoiseLayer*> out;
  for (const auto* l : {warp_x_.get(), warp_y_.get()})
    if (l) out.push_back(l);
  return out;
}

float Partition::blend_weight(double d_self, double d_other, double w) {
  if (w <= 0.0) return d_self < d_other ? 1.0f : (d_self == d_other ? 0.5f : 0.0f);
  const double t = std::clamp(0.5 + (d_other - d_self) / w, 0.0, 1.0);
  return static_cast<float>(t * t * (3.0 - 2.0 * t));
}

int Partition::region_at(double x, double y) const {
  if (centres_.size() == 1) return 0;
  double px = x;
  double py = y;
  if (warp_x_) {
    px += warp_x_->sample(x, y);
    py += warp_y_->sample(x, y);
  }
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < centres_.size(); ++k) {
    const double dx = px - centres_[k].x();
    const double dy = py - centres_[k].y();
    const double d = std::sqrt(dx * dx + dy * dy);
    if (d < best_d) {
      best_d = d;
      best = static_cast<int>(k);
    }
  }
  return best;
}

int Partition::sole_region(double x_lo, double x_hi, double y_lo, double y_hi) const {
  // A margin for the rounding of the point-by-point distances (far below any blend width).
  constexpr double kMargin_m = 1e-3;
  const auto nearest = [&](Vec2 c) {  // distance from c to the box
    const double dx = std::max({x_lo - c.x(), 0.0, c.x() - x_hi});
    const double dy = std::max({y_lo - c.y(), 0.0, c.y() - y_hi});
    return std::sqrt(dx * dx + dy * dy);
  };
  const auto farthest = [&](Vec2 c) {  // distance from c to the box's farthest corner
    const double dx = std::max(std::fabs(x_lo - c.x()), std::fabs(x_hi - c.x()));
    const double dy = std::max(std::fabs(y_lo - c.y()), std::fabs(y_hi - c.y()));
    return std::sqrt(dx * dx + dy * dy);
  };
  const double need = std::max(blend_width_m_, 0.0) / 2.0 + kMargin_m;
  for (std::size_t k = 0; k < centres_.size(); ++k) {
    const double self = farthest(centres_[k]);
    bool alone = true;
    for (std::size_t q = 0; q < centres_.size() && alone; ++q)
      alone = q == k || nearest(centres_[q]) - self >= need;
    if (alone) return static_cast<int>(k);
  }
  return -1;
}

void Partition::classify_grid(double x0, double y0, double d, int nx, int ny,
                              std::vector<std::uint8_t>& region,
                              std::array<std::vector<float>, kMaxRegions>& weights) const {
  const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  region.assign(n, 0);
  const std::size_t nr = centres_.size();
  for (std::size_t k = 0; k < kMaxRegions; ++k)
    weights[k].assign(k < nr ? n : 0, k == 0 ? 1.0f : 0.0f);
  if (nr == 1) return;
  WarpScratch& scratch = warp_scratch();
  std::vector<float>& wx = scratch.wx;
  std::vector<float>& wy = scratch.wy;
  wx.assign(n, 0.0f);
  wy.assign(n, 0.0f);
  if (warp_x_) {
    warp_x_->sample_grid(x0, y0, d, nx, ny, wx.data(), static_cast<std::size_t>(ny));
    warp_y_->sample_grid(x0, y0, d, nx, ny, wy.data(), static_cast<std::size_t>(ny));
  }
  // Most grids lie well inside one region: every warped point of the grid is in the box below,
  // and if one centre is nearer than every other by more than half the blend width across the
  // whole box, each point's weights are exactly 1 and 0 (blend_weight saturates), as the loop
  // below would find point by point.
  const auto [wx_min, wx_max] = std::minmax_element(wx.begin(), wx.end());
  const auto [wy_min, wy_max] = std::minmax_element(wy.begin(), wy.end());
  const int sole = sole_region(x0 + *wx_min, x0 + (nx - 1) * d + *wx_max, y0 + *wy_min,
                               y0 + (ny - 1) * d + *wy_max);
  if (sole >= 0) {
    const auto k = static_cast<std::size_t>(sole);
    std::fill(region.begin(), region.end(), static_cast<std::uint8_t>(k));
    for (std::size_t q = 0; q < nr; ++q)
      std::fill(weights[q].begin(), weights[q].end(), q == k ? 1.0f : 0.0f);
    return;
  }
  std::array<double, kMaxRegions> dist{};
  for (int r = 0; r < nx; ++r) {
    for (int c = 0; c < ny; ++c) {
      const std::size_t m =
          static_cast<std::size_t>(r) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(c);
      const double px = x0 + r * d + wx[m];
      const double py = y0 + c * d + wy[m];
      std::size_t best = 0;
      for (std::size_t k = 0; k < nr; ++k) {
        {
          const double dx = px - centres_[k].x();
          const double dy = py - centres_[k].y();
          dist[k] =
              std::sqrt(dx * dx + dy * dy);  // not std::hypot: 5x slower, no overflow risk here
        }
        if (dist[k] < dist[best]) best = k;
      }
      region[m] = static_cast<std::uint8_t>(best);
      float sum = 0.0f;
      for (std::size_t k = 0; k < nr; ++k) {
        double other = std::numeric_limits<double>::infinity();
        for (std::size_t q = 0; q < nr; ++q) {
          if (q != k) other = std::min(other, dist[q]);
        }
        weights[k][m] = blend_weight(dist[k], other, blend_width_m_);
        sum += weights[k][m];
      }
      for (std::size_t k = 0; k < nr; ++k)
        weights[k][m] /= sum;
    }
  }
}

}  // namespace sonarloop::seabed
