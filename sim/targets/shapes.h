#pragma once
// Triangle meshes of the Pailhas et al. (2010) targets (target_type.h), at their nominal size or
// at any size, with their analytic volumes.
//
// Target frame T (the frame of every mesh returned here):
//   origin at the centre of the target's footprint on its base plane (the plane it rests on);
//   x along the target's long axis (its heading direction), y to its right, z DOWN, like the
//   NED world frame W of sim/frames.h. The body occupies z in [−height, 0]; its footprint spans
//   x in [−length/2, length/2] and y in [−width/2, width/2]. placement.h maps T into W.
// Normals: outward, with the mesh.h convention n = (v1 − v0) × (v2 − v0).
//
// Shapes (size = length L along x, width W along y, height H; nominal sizes in target_type.cpp):
//   kManta            truncated cone, base diameter 0.98 on z = 0, top diameter 0.49 at height
//                     0.47; closed top and bottom. At other sizes the base is an ellipse of axes
//                     L × W and the top keeps the nominal top/base ratio 49/98.
//   kRockan           faceted flattened wedge in a 1.00 × 0.50 × 0.40 box, see rockan.h.
//   kCylinder         lying cylinder, axis along x, length L, cross-section W × H (0.30 round),
//                     resting on z = 0.
//   kStandingCylinder cylinder with a vertical axis, footprint L × W (0.30 round), height H (1.0).
//   kCuboid           1.00 × 0.30 × 0.30 box.       kLargeCuboid  1.00 × 0.50 × 0.40 box.
//   kHemisphere       half (ellipsoid) of diameter 1.00, flat face down on z = 0, height 0.50.
//   kSmallHemisphere  the same with diameter 0.50, height 0.25.
//   kBox              0.70 × 0.70 × 0.40 plain box (no lid detail: the paper gives only the
//                     dimensions, and a plain box keeps it convex and exactly analytic).
// A size override scales each axis of the nominal shape independently, so round sections become
// ellipses; every builder is affine in (L, W, H), hence volume ∝ L·W·H.
//
// Tessellation (curved surfaces only; flat faces are exact and are not subdivided):
//   segments N = vertices around each circle/ellipse, always a multiple of 4 so that the polygon
//   reaches the extremes of the curve (exact bounding box). Vertices lie on the true surface
//   (inscribed polygons), so meshed volumes are slightly low. A hemisphere uses N longitudes and
//   N/4 latitude steps of 2π/N (equal angular steps) plus a pole vertex. Default rule:
//     N = round_up_to_multiple_of_4( max(N_volume, ceil(2π·r_max / kMaxFacetChordM)) ),
//     capped at kMaxCurvedSegments,
//   with r_max the largest semi-axis of the curved surface at the requested size, and N_volume
//   the smallest multiple of 4 whose volume deficit is below 0.3 %:
//     cone and cylinders  kMinCurvedSegments = 48: an inscribed N-gon loses
//                         1 − sin(2π/N)/(2π/N) ≈ (2π/N)²/6 of the area, 0.286 % at N = 48;
//     hemispheres         kMinHemisphereSegments = 76: the lat/long polyhedron loses 0.285 % at
//                         N = 76 (0.317 % at 72), about 1.7·(2π/N)²/6 (both directions facet).
//   The chord term keeps every edge across the curvature (ring chords, and meridian chords of
//   the hemispheres) ≤ 3 cm, the finest pixel of the Pailhas study, so faceting stays below the
//   image resolution. Flat faces (caps, cuboid and Rockan facets, cylinder generators) are left
//   as large triangles: subdividing them would not change the geometry a ray sees.
#include "sim/frames.h"
#include "sim/targets/mesh.h"
#include "sim/targets/target_type.h"

namespace sonarloop::targets {

// Largest chord across a curved surface for the default tessellation (m): the finest pixel size
// (3 cm) of the resolution study of Pailhas et al. (2010) (pixels of 3–30 cm, docs/design.md).
inline constexpr double kMaxFacetChordM = 0.03;
// Fewest default segments around a curve: inscribed 48-gon area deficit 0.286 % (< 0.3 %).
inline constexpr int kMinCurvedSegments = 48;
// Fewest default segments for a hemisphere: lat/long volume deficit 0.285 % at 76 (< 0.3 %).
inline constexpr int kMinHemisphereSegments = 76;
// Most segments accepted (explicit or default): bounds the mesh size of very large overrides.
inline constexpr int kMaxCurvedSegments = 1024;
// Manta: top diameter / base diameter = 49 cm / 98 cm (the issue, after Pailhas et al. 2010).
inline constexpr double kMantaTopToBaseRatio = 0.49 / 0.98;

// The size actually built: each component of size_m that is exactly 0 takes the type's nominal
// value (so Vec3::Zero() means nominal, and e.g. (0, 0, 0.3) overrides only the height).
// Throws std::invalid_argument naming the type and component if a component is negative or not
// finite.
Vec3 resolve_target_size(TargetType type, const Vec3& size_m);

// True for the types with a curved surface (Manta, both cylinders, both hemispheres).
bool has_curved_surface(TargetType type);

// The default segment count for this type and size (the rule above); 0 for a type with no curved
// surface. size_m as in resolve_target_size.
int default_segments(TargetType type, const Vec3& size_m);

// The segment count that build_target_mesh uses: 0 → default_segments; otherwise segments rounded
// up to a multiple of 4 and at least 8. 0 for a type with no curved surface. Throws
// std::invalid_argument if segments is negative or above kMaxCurvedSegments.
int effective_segments(TargetType type, const Vec3& size_m, int segments);

// Analytic volume (m³) of the ideal shape at the resolved size (L, W, H):
//   Manta      frustum with elliptic sections: π·H·(a·b)(1 + k + k²)/3, a = L/2, b = W/2,
//              k = kMantaTopToBaseRatio (for a = b = R this is πH(R² + Rr + r²)/3, r = kR)
//   kCylinder  π·(W/2)·(H/2)·L;   kStandingCylinder π·(L/2)·(W/2)·H
//   cuboids, box  L·W·H
//   hemispheres   (2/3)·π·(L/2)·(W/2)·H (= 2πr³/3 when round)
//   kRockan    the exact polyhedron volume of its construction (rockan_volume_m3).
// The meshes approach these from below as segments grow (exactly equal for the polyhedra).
double nominal_volume_m3(TargetType type, const Vec3& size_m);

// Watertight, outward-oriented mesh of the target in its frame T.
//   size_m    zero → nominal (per component, see resolve_target_size)
//   segments  0 → default rule; else see effective_segments. Ignored by flat-faced types.
// Default triangle counts at nominal size (volume deficit vs analytic): Manta 416 (N = 104,
// 0.061 %), cylinder and standing cylinder 192 (N = 48, 0.286 %), hemisphere 5832 (N = 108,
// 0.141 %), small hemisphere 2888 (N = 76, 0.285 %), cuboids and box 16, Rockan 48 (0: exact).
// Throws std::invalid_argument for a bad size or segment count.
TriangleMesh build_target_mesh(TargetType type, const Eigen::Vector3d& size_m, int segments = 0);

}  // namespace sonarloop::targets
