#include "sim/targets/mesh.h"

#include <algorithm>

namespace sonarloop::targets {
namespace {

bool in_range(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const std::size_t n = mesh.vertices.size();
  return t[0] < n && t[1] < n && t[2] < n;
}

Eigen::Vector3d vertex(const TriangleMesh& mesh, std::uint32_t i) {
  return mesh.vertices[i].cast<double>();
}

// a directed edge a→b packed into one sortable key
std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

}  // namespace

double mesh_volume(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return 0.0;
  const Eigen::Vector3d o = vertex(mesh, 0);
  double six_v = 0.0;
  for (const auto& t : mesh.triangles) {
    if (!in_range(mesh, t)) continue;
    const Eigen::Vector3d a = vertex(mesh, t[0]) - o;
    const Eigen::Vector3d b = vertex(mesh, t[1]) - o;
    const Eigen::Vector3d c = vertex(mesh, t[2]) - o;
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6.0;
}

double mesh_area(const TriangleMesh& mesh) {
  double twice_area = 0.0;
  for (const auto& t : mesh.triangles) {
    if (!in_range(mesh, t)) continue;
    const Eigen::Vector3d a = vertex(mesh, t[0]);
    twice_area += (vertex(mesh, t[1]) - a).cross(vertex(mesh, t[2]) - a).norm();
  }
  return twice_area / 2.0;
}

Eigen::AlignedBox3d mesh_bounds(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;  // default-constructed: empty
  for (const auto& v : mesh.vertices)
    box.extend(v.cast<double>());
  return box;
}

bool is_watertight(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return false;
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    if (!in_range(mesh, t)) return false;
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
    for (int k = 0; k < 3; ++k)
      edges.push_back(edge_key(t[k], t[(k + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  // each directed edge at most once (else two triangles run the same way along it, or a third
  // triangle shares the edge) ...
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  // ... and its reverse present exactly once: the edge then joins exactly two triangles with
  // opposite directions, i.e. consistent orientation
  for (const std::uint64_t e : edges) {
    const auto a = static_cast<std::uint32_t>(e >> 32);
    const auto b = static_cast<std::uint32_t>(e & 0xFFFFFFFFULL);
    if (!std::binary_search(edges.begin(), edges.end(), edge_key(b, a))) return false;
  }
  return true;
}

Eigen::Vector3d triangle_normal(const TriangleMesh& mesh, std::size_t i) {
  const auto& t = mesh.triangles[i];
  const Eigen::Vector3d a = vertex(mesh, t[0]);
  const Eigen::Vector3d n = (vertex(mesh, t[1]) - a).cross(vertex(mesh, t[2]) - a);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& X) {
  TriangleMesh out;
  out.triangles = mesh.triangles;
  out.vertices.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices)
    out.vertices.push_back((X * v.cast<double>()).cast<float>());
  return out;
}

}  // namespace sonarloop::targets
