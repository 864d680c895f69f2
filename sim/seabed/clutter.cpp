#include "sim/seabed/clutter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/rng.h"

namespace sonarloop::seabed {

Clutter::Clutter(const scene::SceneDesc& desc, std::function<int(double, double)> region_at,
                 std::function<double(double, double)> base_at)
    : seed_(desc.seed), region_at_(std::move(region_at)), base_at_(std::move(base_at)) {
  for (const auto& r : desc.seabed.regions) {
    per_region_.push_back(r.texture.clutter);
    if (r.texture.clutter) {
      max_density_ = std::max(max_density_, r.texture.clutter->density_per_m2);
      max_diameter_m_ = std::max(max_diameter_m_, r.texture.clutter->max_diameter_m);
    }
  }
}

std::vector<Rock> Clutter::rocks_in_cell(std::int64_t ci, std::int64_t cj) const {
  std::vector<Rock> out;
  if (empty()) return out;
  Rng rng(seed_, RngStream::kClutter, static_cast<std::uint64_t>(ci),
          static_cast<std::uint64_t>(cj));
  const std::uint64_t n = rng.poisson(max_density_ * kClutterCell_m * kClutterCell_m);
  for (std::uint64_t k = 0; k < n; ++k) {
    // draw every number of a candidate before deciding, so thinning never shifts the stream
    const double x = (static_cast<double>(ci) + rng.uniform()) * kClutterCell_m;
    const double y = (static_cast<double>(cj) + rng.uniform()) * kClutterCell_m;
    const double keep_u = rng.uniform();
    const double z = rng.normal();
    const double aspect = rng.uniform(0.6, 1.0);
    const double orientation = rng.uniform(0.0, std::numbers::pi);
    const double exponent = rng.uniform(2.0, 3.5);
    const double sink = rng.uniform(0.0, 0.3);
    const int region = region_at_(x, y);
    const auto& c = per_region_[static_cast<std::size_t>(region)];
    if (!c || keep_u >= c->density_per_m2 / max_density_) continue;
    Rock r;
    r.x_m = x;
    r.y_m = y;
    const double diameter =
        std::min(c->max_diameter_m, c->median_diameter_m * std::exp(c->sigma_ln * z));
    r.semi_major_m = 0.5 * diameter;
    r.semi_minor_m = r.semi_major_m * aspect;
    r.orientation_rad = orientation;
    r.exponent = exponent;
    r.height_m = c->height_ratio * diameter;
    r.sink_m = sink * r.height_m;
    r.base_m = base_at_(x, y);
    r.region = region;
    out.push_back(r);
  }
  return out;
}

std::vector<Rock> Clutter::rocks_near(double x0, double y0, double x1, double y1) const {
  std::vector<Rock> out;
  if (empty()) return out;
  const double reach = 0.5 * max_diameter_m_;
  const auto cell = [](double v) {
    return static_cast<std::int64_t>(std::floor(v / kClutterCell_m));
  };
  for (std::int64_t ci = cell(x0 - reach); ci <= cell(x1 + reach); ++ci) {
    for (std::int64_t cj = cell(y0 - reach); cj <= cell(y1 + reach); ++cj) {
      for (const Rock& r : rocks_in_cell(ci, cj)) {
        if (r.x_m + r.semi_major_m >= x0 && r.x_m - r.semi_major_m <= x1 &&
            r.y_m + r.semi_major_m >= y0 && r.y_m - r.semi_major_m <= y1) {
          out.push_back(r);
        }
      }
    }
  }
  return out;
}

double Clutter::rock_surface(const Rock& rock, double x, double y) {
  // rotate into the rock's axes (u along the major axis)
  const double dx = x - rock.x_m;
  const double dy = y - rock.y_m;
  const double c = std::cos(rock.orientation_rad);
  const double s = std::sin(rock.orientation_rad);
  const double u = (c * dx + s * dy) / rock.semi_major_m;
  const double v = (-s * dx + c * dy) / rock.semi_minor_m;
  const double rho = std::pow(std::fabs(u), rock.exponent) + std::pow(std::fabs(v), rock.exponent);
  if (rho >= 1.0) return -std::numeric_limits<double>::infinity();
  return rock.height_m * std::pow(1.0 - rho, 1.0 / rock.exponent) - rock.sink_m;
}

void Clutter::rasterize(const std::vector<Rock>& rocks, double x0, double y0, double d, int nx,
                        int ny, float* height, std::size_t stride) const {
  for (const Rock& rock : rocks) {
    const auto lo = [&](double v, double o) { return static_cast<int>(std::ceil((v - o) / d)); };
    const auto hi = [&](double v, double o) { return static_cast<int>(std::floor((v - o) / d)); };
    const int r0 = std::max(0, lo(rock.x_m - rock.semi_major_m, x0));
    const int r1 = std::min(nx - 1, hi(rock.x_m + rock.semi_major_m, x0));
    const int c0 = std::max(0, lo(rock.y_m - rock.semi_major_m, y0));
    const int c1 = std::min(ny - 1, hi(rock.y_m + rock.semi_major_m, y0));
    for (int r = r0; r <= r1; ++r) {
      for (int cc = c0; cc <= c1; ++cc) {
        const double s = rock_surface(rock, x0 + r * d, y0 + cc * d);
        if (s <= -rock.sink_m) continue;
        float& h = height[static_cast<std::size_t>(r) * stride + static_cast<std::size_t>(cc)];
        h = std::max(h, static_cast<float>(rock.base_m + s));
      }
    }
  }
}

}  // namespace sonarloop::seabed
