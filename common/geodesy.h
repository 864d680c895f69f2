#pragma once
// The world frame W (sim/frames.h: local tangent plane, x north, y east) <-> WGS84 geodetic
// latitude/longitude, for the few kilometres a scenario covers.
//
// Definition. The local coordinates (north_m, east_m) of a point of the ellipsoid are the north
// and east components of its ECEF offset from the origin, rotated into the origin's ENU frame
// (the standard ECEF -> ENU rotation, e.g. Hofmann-Wellenhof, Lichtenegger & Wasle, "GNSS",
// Springer 2008): an orthographic projection onto the plane tangent to the ellipsoid at
// the origin. to_geodetic() is its inverse: the point of the ellipsoid (height 0) whose local
// coordinates are (north_m, east_m). The simulator's world is flat, so depth (z_W) does not enter:
// a vehicle at (x, y, z) is reported at the latitude/longitude of (x, y) and depth z.
//
// Method. Instead of the ECEF round trip, the mapping is a third-order Taylor series in
// (Δφ, Δλ) about the origin, written with the radii of curvature at the origin
//   M = a(1 − e²)/W³   meridional radius,   N = a/W   prime-vertical radius,   W² = 1 − e² sin²φ
// and the latitude derivatives M' = dM/dφ, M'' (standard results of ellipsoidal geometry; the
// WGS84 a and f are those of NIMA TR8350.2, 3rd ed. 2000, Table 3.1):
//   north = M Δφ + ½ M' Δφ² + (M'' − M)/6 Δφ³ + ½ N sinφ cosφ Δλ² − ½ M sin²φ Δφ Δλ²
//   east  = N cosφ Δλ − M sinφ Δφ Δλ − ½ (M' sinφ + M cosφ) Δφ² Δλ − (N cosφ / 6) Δλ³
// (obtained by expanding the exact ECEF -> ENU expressions; the first-order terms alone are the
// familiar "flat earth" M Δφ, N cosφ Δλ, which are off by metres at 5 km: the second-order
// Δλ² term is the convergence of the meridians). to_geodetic() inverts the series by Newton's
// method (converges in 3-4 steps, since the non-linear terms are ~1e-3 of the linear ones).
//
// Accuracy (against the exact ECEF -> ENU route, tests/common/geodesy_test.cpp): the truncated
// fourth-order terms grow like d⁴ and steeply with latitude: for points within d = 5 km of the
// origin the error is below 0.001 mm at latitude 56°, 0.03 mm at 80° and 0.2 mm at 85°; 1 cm is
// reached near d = 13 km at 85°, 20 km at 80° and 50 km at 56°. Validity: |origin latitude| <=
// kMaxOriginLatitudeDeg (the Δλ expansion degenerates towards the poles).
#include "common/vectors.h"

namespace sonarloop {

// WGS84 defining parameters (NIMA TR8350.2, 3rd ed., 2000, Table 3.1).
inline constexpr double kWgs84SemiMajorAxisM = 6378137.0;
inline constexpr double kWgs84InverseFlattening = 298.257223563;

// Origins closer to a pole than this are refused (see the header comment).
inline constexpr double kMaxOriginLatitudeDeg = 85.0;

struct GeoPoint {
  double latitude_deg = 0.0;   // WGS84 geodetic, + north
  double longitude_deg = 0.0;  // + east, (-180, 180]
};

class LocalTangentPlane {
 public:
  // Throws std::invalid_argument if the origin is not finite, |latitude| > kMaxOriginLatitudeDeg
  // or |longitude| > 180.
  explicit LocalTangentPlane(GeoPoint origin);

  const GeoPoint& origin() const { return origin_; }
  // Radii of curvature at the origin (m).
  double meridional_radius_m() const { return m_; }
  double prime_vertical_radius_m() const { return n_; }

  // Latitude/longitude (longitude wrapped to (-180, 180]) of the ellipsoid point at (north_m,
  // east_m) in the tangent plane.
  GeoPoint to_geodetic(double north_m, double east_m) const;
  // (north, east) in metres of a geodetic point (its height is ignored). The longitude difference
  // to the origin is taken modulo 360°.
  Vec2 to_local(GeoPoint point) const;

 private:
  // (north, east) of the offset (dlat, dlon) in radians from the origin: the series above.
  Vec2 series(double dlat, double dlon) const;

  GeoPoint origin_;
  double sin_ = 0.0;
  double cos_ = 1.0;
  double m_ = 0.0;   // M
  double m1_ = 0.0;  // dM/dφ
  double m2_ = 0.0;  // d²M/dφ²
  double n_ = 0.0;   // N
};

// Heading in degrees clockwise from north in [0, 360) from a yaw ψ in radians (frames.h).
double heading_deg_from_yaw(double yaw_rad);

}  // namespace sonarloop
