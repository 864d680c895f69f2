#pragma once
// Test helpers for target meshes: convexity/outwardness, edge lists and silhouettes.
#include <algorithm>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sim/targets/mesh.h"

namespace sonarloop::targets::test {

// Largest signed distance (m) of any vertex in front of any face plane. For a convex mesh with
// outward normals this is ~0 (all vertices behind or on every face plane); an inward face or a
// concavity makes it clearly positive.
inline double max_vertex_in_front_of_faces(const TriangleMesh& mesh) {
  double worst = -1.0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Eigen::Vector3d n = triangle_normal(mesh, i);
    const Eigen::Vector3d p0 = mesh.vertices[mesh.triangles[i][0]].cast<double>();
    for (const auto& v : mesh.vertices)
      worst = std::max(worst, n.dot(v.cast<double>() - p0));
  }
  return worst;
}

// Mean of the vertices.
inline Eigen::Vector3d vertex_centroid(const TriangleMesh& mesh) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices)
    sum += v.cast<double>();
  return sum / static_cast<double>(mesh.vertices.size());
}

// Number of faces whose normal does not point away from c: n·(face centroid − c) <= 0.
inline int faces_facing_point(const TriangleMesh& mesh, const Eigen::Vector3d& c) {
  int count = 0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3d fc =
        (mesh.vertices[t[0]].cast<double>() + mesh.vertices[t[1]].cast<double>() +
         mesh.vertices[t[2]].cast<double>()) /
        3.0;
    if (triangle_normal(mesh, i).dot(fc - c) <= 0.0) ++count;
  }
  return count;
}

// Unique undirected edges (i < j).
inline std::vector<std::pair<std::uint32_t, std::uint32_t>> unique_edges(const TriangleMesh& mesh) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto a = t[k];
      const auto b = t[(k + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return {edges.begin(), edges.end()};
}

// Area of the convex hull of 2-D points (Andrew's monotone chain, then the shoelace formula).
inline double convex_hull_area(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return 0.0;
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0)
      --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0.0)
      --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  double twice = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % hull.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return twice / 2.0;
}

// Silhouette area of a convex mesh seen along one coordinate axis (0 = x, 1 = y, 2 = z): the
// hull of the vertices projected on the other two axes.
inline double silhouette_area(const TriangleMesh& mesh, int view_axis) {
  const int a = (view_axis + 1) % 3;
  const int b = (view_axis + 2) % 3;
  std::vector<Eigen::Vector2d> p;
  for (const auto& v : mesh.vertices) {
    p.emplace_back(static_cast<double>(v[a]), static_cast<double>(v[b]));
  }
  return convex_hull_area(p);
}

}  // namespace sonarloop::targets::test
