#pragma once
// The Rockan target: a designed, recognisable approximation, not a measured shape.
//
// What is known. The project's issue, after Pailhas et al. (2010), gives only the Rockan's box,
// 100 × 50 × 40 cm, and calls its shape flattened and angular. From general knowledge (the
// search tool found no public drawing, photograph description or dimension table, so treat this
// as unsourced): Rockan is a Swedish ground (bottom) influence mine whose low, flat,
// wedge-like shell has angled, faceted sides meant to deflect sonar energy; "rocka" is Swedish
// for a ray, the flat fish. The facet layout below is therefore our own design, constrained by
// the box and by that description only.
//
// Construction (z-up build frame: x forward = heading, y left, height h up; shapes.h rotates it
// into the target frame T, where y is right and z = −h). Three horizontal octagons with
// pairwise parallel edges, joined by planar quadrilateral facets:
//
//   level   h (m)  nose flat x, ±y    nose chamfer end   side end          rear flat x, ±y
//   base    0.00   0.45, ±0.025       (0.10, ±0.20)      (−0.39, ±0.20)    −0.45, ±0.14
//   chine   0.10   0.50, ±0.05        (0.10, ±0.25)      (−0.40, ±0.25)    −0.50, ±0.15
//   top     0.40   0.00, ±0.10        (−0.10, ±0.15)     (−0.38, ±0.15)    −0.45, ±0.08
//
// Each octagon: a short flat nose, two nose chamfers of slope 2:1 (x:y) in plan, two straight
// sides, two 45° rear chamfers and a flat rear. Edge directions are the same on all three
// levels, so every side facet is a planar trapezoid.
// Rationale:
//   * chine at h = 0.10 is the widest outline and spans the full 1.00 × 0.50 box; the base is
//     inset 4–5 cm (lower hull slopes inward at 63°–67°), so the body rests on a smaller
//     footprint with a small overhang under the chine;
//   * the top plateau (0.45 × 0.30 m, at full height 0.40) sits towards the rear: the nose facet
//     is a long 31° glacis and the nose chamfers slope at ~59°, the sides at 72°, the rear
//     chamfers at 74° and the rear at 80.5°. Side view: a low-nosed wedge; front view: an
//     elongated hexagon (chine at 0.10); plan view: an octagon with a pointed nose. No view is a
//     rectangle, so its silhouette and shadow differ from the cuboids from every side.
//   * it is convex (each edge's inset grows away from the chine both upwards and downwards).
// Volume (exact): all vertices of each part lie in two horizontal planes, so each part is a
// prismatoid with V = h·(A₀ + 4·A_mid + A₁)/6, A_mid being the section halfway up (the polygon of
// edge midpoints, exact because the facets are planar). Outline areas (m²): base 0.29515, chine
// 0.41, top 0.1251; mid-sections 0.3507875 (lower) and 0.251525 (upper).
//   V = 0.10·(0.29515 + 4·0.3507875 + 0.41)/6 + 0.30·(0.41 + 4·0.251525 + 0.1251)/6
//     = 0.0351383 + 0.0770600 = 0.1121983 m³ (exactly 67319/600000), 56.1 % of the box.
// Mesh: 3 rings of 8 vertices plus two cap centres: 26 vertices, 48 triangles.
#include <array>

#include <Eigen/Core>

#include "sim/frames.h"

namespace sonarloop::targets {

inline constexpr int kRockanOutlineVertices = 8;
inline constexpr int kRockanLevels = 3;

// The nominal (1.00 × 0.50 × 0.40 m) size the construction is drawn at.
inline constexpr double kRockanNominalLengthM = 1.00;
inline constexpr double kRockanNominalWidthM = 0.50;
inline constexpr double kRockanNominalHeightM = 0.40;

// Exact volume of the nominal construction (m³), derived by hand above.
inline constexpr double kRockanNominalVolumeM3 = 67319.0 / 600000.0;

struct RockanLevel {
  double height_m;  // above the base plane
  // (x, y) in the z-up build frame (y left), counter-clockwise about +h; vertex k of every level
  // corresponds (same edge directions)
  std::array<Eigen::Vector2d, kRockanOutlineVertices> outline_m;
};

// The three levels (base, chine, top) of the nominal construction, as tabulated above.
std::array<RockanLevel, kRockanLevels> rockan_levels();

// The levels scaled to size (length, width, height), each axis independently; size must be
// positive (shapes.h resolve_target_size gives it).
std::array<RockanLevel, kRockanLevels> rockan_levels(const Vec3& size_m);

// Exact volume (m³) of the construction at size (length, width, height), from the prismatoid
// formula on the scaled levels: kRockanNominalVolumeM3 · L·W·H / (1.00·0.50·0.40).
double rockan_volume_m3(const Vec3& size_m);

}  // namespace sonarloop::targets
