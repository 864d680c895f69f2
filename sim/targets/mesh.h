#pragma once
// Closed triangle meshes for targets, and pure utilities on them (volume, area, bounds,
// watertightness, rigid transforms). Used by the shape builders (shapes.h) and handed to the
// Embree scene as float vertex and index buffers.
//
// Orientation convention: the outward normal of triangle (v0, v1, v2) is (v1 − v0) × (v2 − v0).
// In a right-handed frame this means the vertices run counter-clockwise seen from outside.
// All builders in sim/targets/ follow it; tests check it through the signed volume (> 0) and,
// for convex shapes, that every face plane has the whole body behind it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sonarloop::targets {

struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;                // (m), in the frame the caller states
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices
};

// Signed volume enclosed by the mesh (m³), by the divergence theorem: the sum over triangles
// of the signed tetrahedron volumes (a − o)·((b − o) × (c − o))/6 about a reference point o
// (the first vertex, which keeps the float → double sums well conditioned far from the origin).
// Positive when the normals point outward. Meaningful only for a closed mesh (is_watertight);
// 0 for an empty mesh. Triangles with an index out of range are skipped.
double mesh_volume(const TriangleMesh& mesh);

// Total surface area (m²): sum of |(v1 − v0) × (v2 − v0)| / 2. Skips out-of-range triangles.
double mesh_area(const TriangleMesh& mesh);

// Axis-aligned bounds of all vertices (referenced or not). Empty box (isEmpty()) if no vertices.
Eigen::AlignedBox3d mesh_bounds(const TriangleMesh& mesh);

// True when the mesh is a closed, consistently oriented 2-manifold surface in the edge sense:
// every index is in range, no triangle repeats a vertex index, and every undirected edge is used
// by exactly two triangles, once in each direction (a→b in one, b→a in the other). An empty
// mesh is not watertight. Vertices are matched by index, not by position: a mesh with
// duplicated (unwelded) vertices is reported as open.
bool is_watertight(const TriangleMesh& mesh);

// Unit outward normal of triangle i: normalised (v1 − v0) × (v2 − v0); zero for a degenerate
// triangle. Precondition: i < triangles.size() and its indices are in range.
Eigen::Vector3d triangle_normal(const TriangleMesh& mesh, std::size_t i);

// The mesh with every vertex mapped by the rigid transform X (p ↦ X·p, computed in double and
// stored as float). Triangles are copied unchanged: a proper rotation keeps the orientation.
// Typical use: transformed(mesh_T, X_WT) moves a target mesh from its frame T to the world W.
TriangleMesh transformed(const TriangleMesh& mesh, const Eigen::Isometry3d& X);

}  // namespace sonarloop::targets
