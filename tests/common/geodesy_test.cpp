// Local tangent plane <-> WGS84: the series of common/geodesy.h against the exact ellipsoidal
// route geodetic -> ECEF -> ENU, written here independently (test oracle only).
#include "common/geodesy.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace {

using sonarloop::GeoPoint;
using sonarloop::LocalTangentPlane;
using sonarloop::Vec2;
using sonarloop::Vec3;

constexpr double kPi = std::numbers::pi;
constexpr double kA = 6378137.0;            // WGS84 semi-major axis (TR8350.2 Table 3.1)
constexpr double kF = 1.0 / 298.257223563;  // WGS84 flattening
constexpr double kE2 = kF * (2.0 - kF);     // first eccentricity squared
constexpr double kB = kA * (1.0 - kF);      // semi-minor axis
double rad(double deg) {
  return deg * kPi / 180.0;
}

// Geodetic (height h) -> ECEF, the closed form (e.g. TR8350.2 / any geodesy text).
Vec3 ecef(double lat_deg, double lon_deg, double h_m) {
  const double phi = rad(lat_deg);
  const double lam = rad(lon_deg);
  const double n = kA / std::sqrt(1.0 - kE2 * std::sin(phi) * std::sin(phi));
  return {(n + h_m) * std::cos(phi) * std::cos(lam), (n + h_m) * std::cos(phi) * std::sin(lam),
          (n * (1.0 - kE2) + h_m) * std::sin(phi)};
}

// East, north, up of `p` (height 0) in the ENU frame of `o` (height 0): rotate the ECEF offset.
Vec3 exact_enu(GeoPoint o, GeoPoint p) {
  const Vec3 d =
      ecef(p.latitude_deg, p.longitude_deg, 0.0) - ecef(o.latitude_deg, o.longitude_deg, 0.0);
  const double sp = std::sin(rad(o.latitude_deg));
  const double cp = std::cos(rad(o.latitude_deg));
  const double sl = std::sin(rad(o.longitude_deg));
  const double cl = std::cos(rad(o.longitude_deg));
  const double east = -sl * d.x() + cl * d.y();
  const double north = -sp * cl * d.x() - sp * sl * d.y() + cp * d.z();
  const double up = cp * cl * d.x() + cp * sl * d.y() + sp * d.z();
  return {east, north, up};
}

// Horizontal error (m) between the exact ENU of `p` and the local (north, east) `local`.
double horizontal_error_m(GeoPoint o, GeoPoint p, Vec2 local) {
  const Vec3 enu = exact_enu(o, p);
  return std::hypot(enu.y() - local.x(), enu.x() - local.y());
}

struct Worst {
  double to_local_m = 0.0;
  double to_geodetic_m = 0.0;
  double round_trip_m = 0.0;
};

// Sweeps points on circles of radius 0.1-5 km around `origin` (every 5° of azimuth) and returns
// the largest errors of to_local, to_geodetic and of the round trip.
Worst sweep(GeoPoint origin, double max_radius_m) {
  const LocalTangentPlane ltp(origin);
  Worst w;
  for (double r : {100.0, 1000.0, 2500.0, max_radius_m}) {
    for (int k = 0; k < 72; ++k) {
      const double az = rad(5.0 * k);
      const double north = r * std::cos(az);
      const double east = r * std::sin(az);
      // to_geodetic: the returned point must have exactly these ENU coordinates
      const GeoPoint g = ltp.to_geodetic(north, east);
      w.to_geodetic_m = std::max(w.to_geodetic_m, horizontal_error_m(origin, g, Vec2(north, east)));
      // to_local of a point given by latitude/longitude (a grid-like point, not from the series)
      const GeoPoint q{
          origin.latitude_deg + north / 111000.0,
          origin.longitude_deg + east / (111000.0 * std::cos(rad(origin.latitude_deg)))};
      w.to_local_m = std::max(w.to_local_m, horizontal_error_m(origin, q, ltp.to_local(q)));
      // round trip local -> geodetic -> local
      const Vec2 back = ltp.to_local(g);
      w.round_trip_m = std::max(w.round_trip_m, std::hypot(back.x() - north, back.y() - east));
    }
  }
  return w;
}

}  // namespace

TEST_CASE("the test's exact ECEF route reproduces known WGS84 values", "[geodesy]") {
  // equator / prime meridian and the pole: X = a, Z = b = 6356752.314245 m (TR8350.2)
  CHECK(ecef(0.0, 0.0, 0.0).x() == Approx(kA).margin(1e-6));
  CHECK(ecef(90.0, 0.0, 0.0).z() == Approx(6356752.314245).margin(1e-5));
  CHECK(kB == Approx(6356752.314245).margin(1e-5));
  // the oracle sees what a flat-earth mapping misses: 5 km due east along the parallel of 55.9°,
  // the point lies ~2.9 m north of the tangent plane's east axis (meridian convergence)
  const GeoPoint o{55.9, -3.2};
  const LocalTangentPlane ltp(o);
  const double dlon_deg =
      5000.0 / (ltp.prime_vertical_radius_m() * std::cos(rad(55.9))) * 180.0 / kPi;
  const Vec3 enu = exact_enu(o, GeoPoint{55.9, -3.2 + dlon_deg});
  CHECK(enu.y() > 2.5);
  CHECK(enu.y() < 3.3);
}

TEST_CASE("radii of curvature match the published WGS84 values", "[geodesy]") {
  // at the equator M = b²/a and N = a; at high latitude both tend to the polar radius a²/b
  const LocalTangentPlane eq(GeoPoint{0.0, 0.0});
  CHECK(eq.meridional_radius_m() == Approx(6335439.327).margin(1e-3));
  CHECK(eq.prime_vertical_radius_m() == Approx(6378137.0).margin(1e-6));
  const LocalTangentPlane scot(GeoPoint{55.9, -3.2});
  CHECK(scot.meridional_radius_m() > 6335439.327);
  CHECK(scot.meridional_radius_m() < 6399593.626);
  CHECK(scot.prime_vertical_radius_m() > scot.meridional_radius_m());
}

TEST_CASE("local tangent plane matches the exact ECEF->ENU route to 1 cm within 5 km",
          "[geodesy]") {
  const GeoPoint origins[] = {{55.9, -3.2},   {0.0, 0.0},       {30.0, 120.0},
                              {-45.0, -60.0}, {70.0, 20.0},     {-80.0, 100.0},
                              {85.0, 10.0},   {-85.0, -179.99}, {43.1, 179.99}};
  for (const GeoPoint& o : origins) {
    const Worst w = sweep(o, 5000.0);
    std::printf(
        "geodesy: origin %+7.2f %+8.2f  max error to_local %.3g m  to_geodetic %.3g m  "
        "round trip %.3g m\n",
        o.latitude_deg, o.longitude_deg, w.to_local_m, w.to_geodetic_m, w.round_trip_m);
    INFO("origin " << o.latitude_deg << ", " << o.longitude_deg);
    CHECK(w.to_local_m < 0.01);
    CHECK(w.to_geodetic_m < 0.01);
    CHECK(w.round_trip_m < 1e-6);
    if (std::fabs(o.latitude_deg) <= 60.0) {
      // far better than asked away from the poles (fourth-order terms only)
      CHECK(w.to_local_m < 1e-5);
      CHECK(w.to_geodetic_m < 1e-5);
    }
  }
}

TEST_CASE("geodetic round trip is exact to 1e-9 degrees", "[geodesy]") {
  const LocalTangentPlane ltp(GeoPoint{55.9, -3.2});
  for (double dn : {-4000.0, -10.0, 0.0, 0.001, 3333.3}) {
    for (double de : {-4500.0, -0.5, 0.0, 2.0, 4000.0}) {
      const GeoPoint p{55.9 + dn / 111000.0, -3.2 + de / 62000.0};
      const GeoPoint back = ltp.to_geodetic(ltp.to_local(p).x(), ltp.to_local(p).y());
      CHECK(back.latitude_deg == Approx(p.latitude_deg).margin(1e-9));
      CHECK(back.longitude_deg == Approx(p.longitude_deg).margin(1e-9));
    }
  }
  // the origin maps to (0, 0) and back exactly
  const Vec2 o = ltp.to_local(GeoPoint{55.9, -3.2});
  CHECK(o.x() == 0.0);
  CHECK(o.y() == 0.0);
  const GeoPoint g = ltp.to_geodetic(0.0, 0.0);
  CHECK(g.latitude_deg == 55.9);
  CHECK(g.longitude_deg == -3.2);
}

TEST_CASE("longitude wraps across the antimeridian", "[geodesy]") {
  const LocalTangentPlane ltp(GeoPoint{-20.0, 179.99});
  const GeoPoint east = ltp.to_geodetic(0.0, 3000.0);  // ~0.0287° further east
  CHECK(east.longitude_deg < -179.9);
  CHECK(east.longitude_deg > -180.0);
  const Vec2 back = ltp.to_local(east);
  CHECK(back.y() == Approx(3000.0).margin(1e-6));
  CHECK(back.x() == Approx(0.0).margin(1e-6));
  // an origin given as 180 and one given as -180 are the same meridian
  const LocalTangentPlane a(GeoPoint{10.0, 180.0});
  const LocalTangentPlane b(GeoPoint{10.0, -180.0});
  const Vec2 pa = a.to_local(GeoPoint{10.01, -179.99});
  const Vec2 pb = b.to_local(GeoPoint{10.01, -179.99});
  CHECK(pa.x() == Approx(pb.x()).margin(1e-9));
  CHECK(pa.y() == Approx(pb.y()).margin(1e-9));
  CHECK(pa.y() > 1000.0);
}

TEST_CASE("invalid origins are refused with a clear message", "[geodesy]") {
  CHECK_THROWS_WITH(LocalTangentPlane(GeoPoint{86.0, 0.0}), Catch::Contains("latitude 86"));
  CHECK_THROWS_WITH(LocalTangentPlane(GeoPoint{-90.0, 0.0}), Catch::Contains("outside"));
  CHECK_THROWS_WITH(LocalTangentPlane(GeoPoint{10.0, 180.5}), Catch::Contains("longitude"));
  CHECK_THROWS_AS(LocalTangentPlane(GeoPoint{std::nan(""), 0.0}), std::invalid_argument);
  CHECK_NOTHROW(LocalTangentPlane(GeoPoint{85.0, -180.0}));
}

TEST_CASE("heading_deg_from_yaw normalises to [0, 360)", "[geodesy]") {
  using sonarloop::heading_deg_from_yaw;
  CHECK(heading_deg_from_yaw(0.0) == 0.0);
  CHECK(heading_deg_from_yaw(kPi / 2.0) == Approx(90.0));
  CHECK(heading_deg_from_yaw(-kPi / 2.0) == Approx(270.0));
  CHECK(heading_deg_from_yaw(kPi) == Approx(180.0));
  CHECK(heading_deg_from_yaw(-kPi) == Approx(180.0));
  CHECK(heading_deg_from_yaw(2.0 * kPi) == Approx(0.0).margin(1e-12));
  CHECK(heading_deg_from_yaw(7.0 * kPi) == Approx(180.0));
  CHECK(heading_deg_from_yaw(-100.0 * kPi - 0.1) == Approx(360.0 - 0.1 * 180.0 / kPi));
  for (double yaw : {-1e-18, -1e-15, 1e-300, -2.0 * kPi, 1e6, -1e6}) {
    const double h = heading_deg_from_yaw(yaw);
    INFO("yaw " << yaw << " -> " << h);
    CHECK(h >= 0.0);
    CHECK(h < 360.0);
  }
}
