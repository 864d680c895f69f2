#include "sim/targets/rockan.h"

#include <cstddef>

namespace sonarloop::targets {
namespace {

// One level from its half outline (x, y ≥ 0) at the four corners listed in rockan.h, mirrored
// into the full counter-clockwise octagon starting at the right-hand nose corner.
RockanLevel make_level(double height_m, Eigen::Vector2d nose, Eigen::Vector2d chamfer_end,
                       Eigen::Vector2d side_end, Eigen::Vector2d rear) {
  const auto mirror = [](const Eigen::Vector2d& p) { return Eigen::Vector2d(p.x(), -p.y()); };
  return {height_m,
          {mirror(nose), nose, chamfer_end, side_end, rear, mirror(rear), mirror(side_end),
           mirror(chamfer_end)}};
}

// Shoelace area of a counter-clockwise polygon (m²).
double polygon_area(const std::array<Eigen::Vector2d, kRockanOutlineVertices>& p) {
  double twice = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto& a = p[k];
    const auto& b = p[(k + 1) % p.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return twice / 2.0;
}

}  // namespace

std::array<RockanLevel, kRockanLevels> rockan_levels() {
  using V = Eigen::Vector2d;
  return {
      make_level(0.00, V(0.45, 0.025), V(0.10, 0.20), V(-0.39, 0.20), V(-0.45, 0.14)),  // base
      make_level(0.10, V(0.50, 0.05), V(0.10, 0.25), V(-0.40, 0.25), V(-0.50, 0.15)),   // chine
      make_level(0.40, V(0.00, 0.10), V(-0.10, 0.15), V(-0.38, 0.15), V(-0.45, 0.08)),  // top
  };
}

std::array<RockanLevel, kRockanLevels> rockan_levels(const Vec3& size_m) {
  const double sx = size_m.x() / kRockanNominalLengthM;
  const double sy = size_m.y() / kRockanNominalWidthM;
  const double sz = size_m.z() / kRockanNominalHeightM;
  auto levels = rockan_levels();
  for (auto& level : levels) {
    level.height_m *= sz;
    for (auto& p : level.outline_m)
      p = Eigen::Vector2d(sx * p.x(), sy * p.y());
  }
  return levels;
}

double rockan_volume_m3(const Vec3& size_m) {
  // prismatoid formula per part, V = h·(A0 + 4·A_mid + A1)/6; the mid-section of a part with
  // planar trapezoid facets is the polygon of the midpoints of corresponding vertices
  const auto levels = rockan_levels(size_m);
  double volume = 0.0;
  for (std::size_t i = 0; i + 1 < levels.size(); ++i) {
    const auto& lo = levels[i];
    const auto& hi = levels[i + 1];
    std::array<Eigen::Vector2d, kRockanOutlineVertices> mid;
    for (std::size_t k = 0; k < mid.size(); ++k)
      mid[k] = (lo.outline_m[k] + hi.outline_m[k]) / 2.0;
    const double h = hi.height_m - lo.height_m;
    volume += h *
              (polygon_area(lo.outline_m) + 4.0 * polygon_area(mid) + polygon_area(hi.outline_m)) /
              6.0;
  }
  return volume;
}

}  // namespace sonarloop::targets
