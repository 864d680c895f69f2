#pragma once
// Lofting: the one mesh construction behind every target shape. A solid is described by a
// sequence of closed rings (polygons of the same vertex count K, vertex k of one ring joined to
// vertex k of the next) plus a cap point at each end. Consecutive rings are joined by quads
// (two triangles each); each end ring is closed by a fan of K triangles to its cap point. The
// cap point is the ring's centroid for a flat end (cylinder and cone ends, polygon prisms) or an
// apex off the ring's plane (the pole of a hemisphere).
//
// Orientation contract: every ring runs counter-clockwise about the loft axis `a` (right-hand
// rule), where `a` points from the first ring towards the last; the start cap faces −a and the
// end cap +a. With that input the result is watertight with outward normals (mesh.h
// convention). Triangle count: 2·K·(rings − 1) + 2·K. Vertex count: K·rings + 2.
//
// The frame of the points is the caller's; the target builders use a z-up build frame and
// rotate into the target frame afterwards (shapes.h).
#include <vector>

#include <Eigen/Core>

#include "sim/targets/mesh.h"

namespace sonarloop::targets {

using Ring = std::vector<Eigen::Vector3d>;

// Throws std::invalid_argument if there is no ring, a ring has fewer than 3 points, or the
// rings differ in size. Orientation is not checked here (ring_turn_sign() lets callers do it).
TriangleMesh loft(const std::vector<Ring>& rings, const Eigen::Vector3d& start_cap,
                  const Eigen::Vector3d& end_cap);

// n points on the ellipse centre + ru·cos θ·u + rv·sin θ·v, θ_k = 2πk/n, k = 0..n−1. With
// u × v = a (unit, orthogonal) the ring runs counter-clockwise about a. Points at θ = 0, π/2,
// π, 3π/2 are present when n is a multiple of 4, so the ring reaches the ellipse's extremes.
Ring ellipse_ring(const Eigen::Vector3d& centre, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                  double ru, double rv, int n);

// A horizontal ring at height z from a polygon given in the (x, y) plane (counter-clockwise
// about +z for a z-up loft).
Ring polygon_ring(const std::vector<Eigen::Vector2d>& polygon_xy, double z);

// Mean of the ring's points: the cap point of a flat end for a convex or star-shaped ring.
Eigen::Vector3d ring_centroid(const Ring& ring);

// Sign (+1, −1, or 0 for a degenerate ring) of a · Σ p_k × p_(k+1): +1 when the ring turns
// counter-clockwise about a.
int ring_turn_sign(const Ring& ring, const Eigen::Vector3d& a);

}  // namespace sonarloop::targets
