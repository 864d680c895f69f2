#include "common/geodesy.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "units/angles.h"

namespace sonarloop {
namespace {

// Newton's method on the series stops once a step is below this (rad; 1e-14 rad ≈ 0.06 µm on the
// ground) or after kMaxNewtonSteps steps (3-4 suffice within the validity range).
constexpr double kNewtonToleranceRad = 1e-14;
constexpr int kMaxNewtonSteps = 10;

// Wraps an angle in degrees to (-180, 180].
double wrap_longitude_deg(double deg) {
  double w = std::fmod(deg, 360.0);  // (-360, 360)
  if (w > 180.0) w -= 360.0;
  if (w <= -180.0) w += 360.0;
  return w;
}

}  // namespace

LocalTangentPlane::LocalTangentPlane(GeoPoint origin) : origin_(origin) {
  if (!std::isfinite(origin.latitude_deg) || !std::isfinite(origin.longitude_deg)) {
    throw std::invalid_argument("LocalTangentPlane: origin latitude/longitude must be finite");
  }
  if (std::fabs(origin.latitude_deg) > kMaxOriginLatitudeDeg) {
    throw std::invalid_argument("LocalTangentPlane: origin latitude " +
                                std::to_string(origin.latitude_deg) + " deg is outside [-" +
                                std::to_string(kMaxOriginLatitudeDeg) + ", " +
                                std::to_string(kMaxOriginLatitudeDeg) + "] deg");
  }
  if (std::fabs(origin.longitude_deg) > 180.0) {
    throw std::invalid_argument("LocalTangentPlane: origin longitude " +
                                std::to_string(origin.longitude_deg) +
                                " deg is outside [-180, 180] deg");
  }
  origin_.longitude_deg = wrap_longitude_deg(origin.longitude_deg);

  // radii of curvature and the derivatives of M (see the header)
  const double a = kWgs84SemiMajorAxisM;
  const double f = 1.0 / kWgs84InverseFlattening;
  const double e2 = f * (2.0 - f);  // first eccentricity squared
  const double lat0_rad = origin.latitude_deg * kRadPerDeg;
  sin_ = std::sin(lat0_rad);
  cos_ = std::cos(lat0_rad);
  const double w2 = 1.0 - e2 * sin_ * sin_;  // W²
  const double w = std::sqrt(w2);
  n_ = a / w;
  m_ = a * (1.0 - e2) / (w2 * w);
  // dM/dφ = 3 M e² sinφ cosφ / W²
  m1_ = 3.0 * m_ * e2 * sin_ * cos_ / w2;
  // d²M/dφ² = 3 a (1 − e²) e² [cos 2φ / W⁵ + 5 e² sin²φ cos²φ / W⁷]
  const double w5 = w2 * w2 * w;
  m2_ = 3.0 * a * (1.0 - e2) * e2 *
        ((cos_ * cos_ - sin_ * sin_) / w5 + 5.0 * e2 * sin_ * sin_ * cos_ * cos_ / (w5 * w2));
}

Vec2 LocalTangentPlane::series(double p, double l) const {
  const double s = sin_;
  const double c = cos_;
  const double north = m_ * p + 0.5 * m1_ * p * p + (m2_ - m_) / 6.0 * p * p * p +
                       0.5 * n_ * s * c * l * l - 0.5 * m_ * s * s * p * l * l;
  const double east =
      n_ * c * l - m_ * s * p * l - 0.5 * (m1_ * s + m_ * c) * p * p * l - n_ * c / 6.0 * l * l * l;
  return {north, east};
}

GeoPoint LocalTangentPlane::to_geodetic(double north_m, double east_m) const {
  const double s = sin_;
  const double c = cos_;
  // start from the flat-earth answer, then Newton on the series
  double p = north_m / m_;
  double l = east_m / (n_ * c);
  for (int step = 0; step < kMaxNewtonSteps; ++step) {
    const Vec2 r = series(p, l) - Vec2(north_m, east_m);
    // Jacobian of the series
    const double dn_dp = m_ + m1_ * p + 0.5 * (m2_ - m_) * p * p - 0.5 * m_ * s * s * l * l;
    const double dn_dl = n_ * s * c * l - m_ * s * s * p * l;
    const double de_dp = -m_ * s * l - (m1_ * s + m_ * c) * p * l;
    const double de_dl =
        n_ * c - m_ * s * p - 0.5 * (m1_ * s + m_ * c) * p * p - 0.5 * n_ * c * l * l;
    const double det = dn_dp * de_dl - dn_dl * de_dp;
    const double dp = (r.x() * de_dl - r.y() * dn_dl) / det;
    const double dl = (r.y() * dn_dp - r.x() * de_dp) / det;
    p -= dp;
    l -= dl;
    if (std::fabs(dp) < kNewtonToleranceRad && std::fabs(dl) < kNewtonToleranceRad) break;
  }
  return {origin_.latitude_deg + p * kDegPerRad,
          wrap_longitude_deg(origin_.longitude_deg + l * kDegPerRad)};
}

Vec2 LocalTangentPlane::to_local(GeoPoint point) const {
  const double p = (point.latitude_deg - origin_.latitude_deg) * kRadPerDeg;
  const double l = wrap_longitude_deg(point.longitude_deg - origin_.longitude_deg) * kRadPerDeg;
  return series(p, l);
}

double heading_deg_from_yaw(double yaw_rad) {
  double h = std::fmod(yaw_rad * kDegPerRad, 360.0);  // (-360, 360)
  if (h < 0.0) h += 360.0;
  // a tiny negative angle becomes 360 after the addition in floating point
  if (h >= 360.0) h = 0.0;
  return h;
}

}  // namespace sonarloop
