#include "sim/targets/loft.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace sonarloop::targets {
namespace {

std::uint32_t to_index(std::size_t i) {
  return static_cast<std::uint32_t>(i);
}

}  // namespace

TriangleMesh loft(const std::vector<Ring>& rings, const Eigen::Vector3d& start_cap,
                  const Eigen::Vector3d& end_cap) {
  if (rings.empty()) throw std::invalid_argument("loft: at least one ring is required");
  const std::size_t k_count = rings.front().size();
  if (k_count < 3) {
    throw std::invalid_argument("loft: a ring needs at least 3 points, got " +
                                std::to_string(k_count));
  }
  for (std::size_t r = 0; r < rings.size(); ++r) {
    if (rings[r].size() != k_count) {
      throw std::invalid_argument("loft: ring " + std::to_string(r) + " has " +
                                  std::to_string(rings[r].size()) + " points, ring 0 has " +
                                  std::to_string(k_count));
    }
  }

  TriangleMesh mesh;
  const std::size_t ring_count = rings.size();
  mesh.vertices.reserve(k_count * ring_count + 2);
  mesh.triangles.reserve(2 * k_count * ring_count);
  for (const Ring& ring : rings) {
    for (const auto& p : ring)
      mesh.vertices.push_back(p.cast<float>());
  }
  const std::size_t start_index = mesh.vertices.size();
  mesh.vertices.push_back(start_cap.cast<float>());
  const std::size_t end_index = mesh.vertices.size();
  mesh.vertices.push_back(end_cap.cast<float>());

  auto id = [k_count](std::size_t ring, std::size_t k) {
    return to_index(ring * k_count + k % k_count);
  };
  // side quads (p0, p1 on ring r; q0, q1 on ring r+1): with the rings counter-clockwise about
  // the axis, (p1 − p0) × (q1 − p0) points away from the axis
  for (std::size_t r = 0; r + 1 < ring_count; ++r) {
    for (std::size_t k = 0; k < k_count; ++k) {
      const std::uint32_t p0 = id(r, k), p1 = id(r, k + 1);
      const std::uint32_t q0 = id(r + 1, k), q1 = id(r + 1, k + 1);
      mesh.triangles.push_back({p0, p1, q1});
      mesh.triangles.push_back({p0, q1, q0});
    }
  }
  // caps: the start cap runs clockwise about the axis (faces −a), the end cap counter-clockwise
  for (std::size_t k = 0; k < k_count; ++k) {
    mesh.triangles.push_back({to_index(start_index), id(0, k + 1), id(0, k)});
    mesh.triangles.push_back(
        {to_index(end_index), id(ring_count - 1, k), id(ring_count - 1, k + 1)});
  }
  return mesh;
}

Ring ellipse_ring(const Eigen::Vector3d& centre, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                  double ru, double rv, int n) {
  Ring ring;
  ring.reserve(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double theta = 2.0 * std::numbers::pi * k / n;
    ring.push_back(centre + ru * std::cos(theta) * u + rv * std::sin(theta) * v);
  }
  return ring;
}

Ring polygon_ring(const std::vector<Eigen::Vector2d>& polygon_xy, double z) {
  Ring ring;
  ring.reserve(polygon_xy.size());
  for (const auto& p : polygon_xy)
    ring.emplace_back(p.x(), p.y(), z);
  return ring;
}

Eigen::Vector3d ring_centroid(const Ring& ring) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : ring)
    sum += p;
  return ring.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(ring.size()));
}

int ring_turn_sign(const Ring& ring, const Eigen::Vector3d& a) {
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < ring.size(); ++k) {
    twice_area += ring[k].cross(ring[(k + 1) % ring.size()]);
  }
  const double s = a.dot(twice_area);
  return (s > 0.0) - (s < 0.0);
}

}  // namespace sonarloop::targets
