#pragma once
// Shadow chips in height coordinates (ours; beyond Pailhas, Petillot & Capus 2010, Sec. 4.2).
//
// A target's shadow is its silhouette seen from the sonar, stretched in range by the geometry:
// on a flat seabed, a point of the target at height h above the seabed and ground range G casts
// its shadow to the ground range G + x with
//     h / x = a / (G + x)     (similar triangles, a the sonar's altitude)
// so the same target casts a shadow 1.25 m long from 10 m altitude and 8.3 m long from 2 m (at
// G = 25 m, a 0.5 m target). An eigen-subspace classifier cannot follow such a stretch: trained
// and tested at one fixed altitude, shadows are misidentified about half as often as over the
// 2–10 m of the paper's chips (docs/sweep.md). The altitude and the contact's range are known
// on board (the sonar's altimeter, the contact's slant range), so the stretch can be undone
// before eq. 9: resample each row from ground distance behind the target to the height
//     h(x) = a·x / (G + x),   x(h) = h·G / (a − h)
// whose shadow ends there. Then a target's shadow has the same extent in the chip whatever the
// altitude (its shape still changes with the grazing angle, through what the top hides).
//
// The projected chip has the input's size. Its first columns keep the ground in front of the
// target's centre (kShadowHeightFront_m, at the input's pixel spacing in ground range: the
// highlight); the rest are heights from 0 to kShadowHeightMax_m (the paper's targets are at most
// 0.47 m tall). Each output pixel interpolates linearly between the two input columns around
// its slant range sqrt(a² + (G + x)²); where that falls outside the input chip (or h >= a),
// the pixel is the chip's median level (the seabed, since the target covers a small part of a
// chip). Rows (pings along track) are unchanged. Flat-seabed geometry: slopes and relief under
// the shadow bend it (not corrected). Pure: the same chip and geometry give the same bytes.
#include "atr/chip.h"

namespace sonarloop::atr {

inline constexpr double kShadowHeightMax_m = 0.6;
inline constexpr double kShadowHeightFront_m = 1.0;

// Where a shadow chip lies: the sonar's altitude above the target's base plane, the horizontal
// distance from the track to the target's centre, and the slant range of column 0's near edge
// with the column width (slant-range bin).
struct ShadowChipGeometry {
  double altitude_m = 0.0;
  double ground_range_m = 0.0;
  double range_start_m = 0.0;
  double bin_m = 0.0;
};

// h(x) and x(h) above (x: ground distance behind the target's centre; x(h) is +inf for h >= a).
double shadow_height_m(double behind_m, double altitude_m, double ground_range_m);
double shadow_distance_m(double height_m, double altitude_m, double ground_range_m);

// The chip resampled to height coordinates (above). Throws std::invalid_argument for an empty
// chip or a geometry that is not positive and finite.
Chip shadow_height_chip(ChipView chip, const ShadowChipGeometry& g);

}  // namespace sonarloop::atr
