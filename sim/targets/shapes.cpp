#include "sim/targets/shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/targets/loft.h"
#include "sim/targets/rockan.h"

namespace sonarloop::targets {
namespace {

constexpr double kPi = std::numbers::pi;

// The shapes are built in a z-up build frame B (x forward, y left, z up, base on z = 0), where
// the usual counter-clockwise rings give outward normals; T = Rx(π)·B: (x, y, z)_T = (x, −y, −z)_B.
// A proper rotation, so orientation (outwardness) is kept.
TriangleMesh to_target_frame(TriangleMesh mesh) {
  for (auto& v : mesh.vertices)
    v = Eigen::Vector3f(v.x(), -v.y(), -v.z());
  return mesh;
}

int round_up_to_multiple_of_4(int n) {
  return (n + 3) / 4 * 4;
}

// Largest semi-axis of the curved surface (m) at the resolved size; 0 if there is none.
double curved_radius_m(TargetType type, const Vec3& s) {
  switch (type) {
    case TargetType::kManta:
    case TargetType::kStandingCylinder:
      return std::max(s.x(), s.y()) / 2.0;
    case TargetType::kCylinder:
      return std::max(s.y(), s.z()) / 2.0;
    case TargetType::kHemisphere:
    case TargetType::kSmallHemisphere:
      return std::max({s.x() / 2.0, s.y() / 2.0, s.z()});
    case TargetType::kRockan:
    case TargetType::kCuboid:
    case TargetType::kLargeCuboid:
    case TargetType::kBox:
      return 0.0;
  }
  return 0.0;
}

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();
const Eigen::Vector3d kY = Eigen::Vector3d::UnitY();
const Eigen::Vector3d kZ = Eigen::Vector3d::UnitZ();

// Loft of horizontal rings (axis +z) closed by flat caps at the end rings' centroids.
TriangleMesh loft_flat_capped(const std::vector<Ring>& rings) {
  return loft(rings, ring_centroid(rings.front()), ring_centroid(rings.back()));
}

// Truncated elliptic cone: base semi-axes (a, b) on z = 0, top (k·a, k·b) at z = h.
TriangleMesh build_frustum(double a, double b, double k, double h, int n) {
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  return loft_flat_capped(
      {ellipse_ring(zero, kX, kY, a, b, n), ellipse_ring(h * kZ, kX, kY, k * a, k * b, n)});
}

// Cylinder lying along x: length l, semi-axes (b along y, c along z), resting on z = 0. The loft
// axis is +x, and y × z = x makes the rings counter-clockwise about it.
TriangleMesh build_lying_cylinder(double l, double b, double c, int n) {
  const Eigen::Vector3d centre(0.0, 0.0, c);
  return loft({ellipse_ring(centre - l / 2.0 * kX, kY, kZ, b, c, n),
               ellipse_ring(centre + l / 2.0 * kX, kY, kZ, b, c, n)},
              centre - l / 2.0 * kX, centre + l / 2.0 * kX);
}

// Axis-aligned box L × W × H on z = 0: a loft of two rectangles.
TriangleMesh build_cuboid(const Vec3& s) {
  const double hx = s.x() / 2.0;
  const double hy = s.y() / 2.0;
  const std::vector<Eigen::Vector2d> rect{{hx, -hy}, {hx, hy}, {-hx, hy}, {-hx, -hy}};
  return loft_flat_capped({polygon_ring(rect, 0.0), polygon_ring(rect, s.z())});
}

// Half ellipsoid, semi-axes (a, b) on z = 0 and height c: n longitudes and n/4 latitude steps of
// (π/2)/(n/4) = 2π/n each; rings at latitudes 0 .. (n/4 − 1) steps, the pole as the end cap and
// the centre of the equator as the flat base cap.
TriangleMesh build_hemisphere(double a, double b, double c, int n) {
  const int bands = n / 4;
  std::vector<Ring> rings;
  rings.reserve(static_cast<std::size_t>(bands));
  for (int j = 0; j < bands; ++j) {
    const double lat = (kPi / 2.0) * j / bands;
    rings.push_back(
        ellipse_ring(c * std::sin(lat) * kZ, kX, kY, a * std::cos(lat), b * std::cos(lat), n));
  }
  return loft(rings, Eigen::Vector3d::Zero(), c * kZ);
}

TriangleMesh build_rockan(const Vec3& s) {
  std::vector<Ring> rings;
  for (const auto& level : rockan_levels(s)) {
    rings.push_back(polygon_ring({level.outline_m.begin(), level.outline_m.end()}, level.height_m));
  }
  return loft_flat_capped(rings);
}

// Guards the table lookups against an enum value outside the table (e.g. cast from a file).
void check_type(TargetType type) {
  const int id = static_cast<int>(type);
  if (id < 0 || id >= static_cast<int>(target_type_table().size())) {
    throw std::invalid_argument("unknown target type id " + std::to_string(id) +
                                " (allowed: " + target_type_keys_list() + ")");
  }
}

}  // namespace

Vec3 resolve_target_size(TargetType type, const Vec3& size_m) {
  check_type(type);
  const TargetTypeInfo& info = target_type_info(type);
  static constexpr const char* kAxis[3] = {"length", "width", "height"};
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    const double v = size_m[i];
    if (!std::isfinite(v) || v < 0.0) {
      throw std::invalid_argument("target '" + std::string(info.key) + "': size " + kAxis[i] + " " +
                                  std::to_string(v) +
                                  " m is not allowed (positive metres, or 0 for nominal)");
    }
    out[i] = v == 0.0 ? info.size_m[i] : v;
  }
  return out;
}

bool has_curved_surface(TargetType type) {
  check_type(type);
  return curved_radius_m(type, target_type_info(type).size_m) > 0.0;
}

int default_segments(TargetType type, const Vec3& size_m) {
  const double r_max = curved_radius_m(type, resolve_target_size(type, size_m));
  if (r_max <= 0.0) return 0;
  const bool hemisphere = type == TargetType::kHemisphere || type == TargetType::kSmallHemisphere;
  const double volume_rule = hemisphere ? kMinHemisphereSegments : kMinCurvedSegments;
  const double chord_rule = std::ceil(2.0 * kPi * r_max / kMaxFacetChordM);
  const double n = std::clamp(chord_rule, volume_rule, double{kMaxCurvedSegments});
  return round_up_to_multiple_of_4(static_cast<int>(n));
}

int effective_segments(TargetType type, const Vec3& size_m, int segments) {
  check_type(type);
  if (segments < 0 || segments > kMaxCurvedSegments) {
    throw std::invalid_argument("target '" + std::string(target_type_info(type).key) +
                                "': segments " + std::to_string(segments) +
                                " is not allowed (0 for the default rule, or 1.." +
                                std::to_string(kMaxCurvedSegments) + ")");
  }
  if (!has_curved_surface(type)) return 0;
  if (segments == 0) return default_segments(type, size_m);
  return std::max(8, round_up_to_multiple_of_4(segments));
}

double nominal_volume_m3(TargetType type, const Vec3& size_m) {
  const Vec3 s = resolve_target_size(type, size_m);
  const double a = s.x() / 2.0;
  const double b = s.y() / 2.0;
  switch (type) {
    case TargetType::kManta: {
      const double k = kMantaTopToBaseRatio;
      return kPi * s.z() * a * b * (1.0 + k + k * k) / 3.0;
    }
    case TargetType::kRockan:
      return rockan_volume_m3(s);
    case TargetType::kCylinder:
      return kPi * (s.y() / 2.0) * (s.z() / 2.0) * s.x();
    case TargetType::kStandingCylinder:
      return kPi * a * b * s.z();
    case TargetType::kCuboid:
    case TargetType::kLargeCuboid:
    case TargetType::kBox:
      return s.x() * s.y() * s.z();
    case TargetType::kHemisphere:
    case TargetType::kSmallHemisphere:
      return 2.0 / 3.0 * kPi * a * b * s.z();
  }
  throw std::invalid_argument("nominal_volume_m3: unknown target type " +
                              std::to_string(static_cast<int>(type)));
}

TriangleMesh build_target_mesh(TargetType type, const Eigen::Vector3d& size_m, int segments) {
  const Vec3 s = resolve_target_size(type, size_m);
  const int n = effective_segments(type, s, segments);
  switch (type) {
    case TargetType::kManta:
      return to_target_frame(
          build_frustum(s.x() / 2.0, s.y() / 2.0, kMantaTopToBaseRatio, s.z(), n));
    case TargetType::kRockan:
      return to_target_frame(build_rockan(s));
    case TargetType::kCylinder:
      return to_target_frame(build_lying_cylinder(s.x(), s.y() / 2.0, s.z() / 2.0, n));
    case TargetType::kStandingCylinder:
      return to_target_frame(build_frustum(s.x() / 2.0, s.y() / 2.0, 1.0, s.z(), n));
    case TargetType::kCuboid:
    case TargetType::kLargeCuboid:
    case TargetType::kBox:
      return to_target_frame(build_cuboid(s));
    case TargetType::kHemisphere:
    case TargetType::kSmallHemisphere:
      return to_target_frame(build_hemisphere(s.x() / 2.0, s.y() / 2.0, s.z(), n));
  }
  throw std::invalid_argument("build_target_mesh: unknown target type " +
                              std::to_string(static_cast<int>(type)));
}

}  // namespace sonarloop::targets
