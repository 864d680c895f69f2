// The rules on the planned path (vehicle_loader.h): its length, profile steps and duration, and
// in a scenario, that a terrain-following path stays over the seabed.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "config/loader/vehicle_loader.h"
#include "config/loader/vehicle_yaml.h"
#include "sim/vehicle/trajectory.h"

namespace sonarloop::config {
namespace {

using vehicle::DepthMode;
using vehicle::Path;
using vehicle::PathSegment;
using vehicle::TrajectoryDesc;
using vehicle::TrajectoryKind;
using vehicle::VehicleDesc;

// --- the path and the seabed extent -------------------------------------------------------------

bool inside(const Vec2& p, const Vec2& lo, const Vec2& hi) {
  return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
}

// Most samples taken along one arc when looking for its exit point.
constexpr double kMaxArcSamples = 1e6;
constexpr double kArcSampleStepM = 0.01;
constexpr double kArcSampleRadiusFraction = 0.01;

// Where an arc that starts inside first leaves the box; nullopt if it stays inside. Whether it
// leaves is decided exactly from its end point and its extreme points (the points of heading a
// multiple of π/2, where north or east is extreme); the exit point is then sampled and bisected.
std::optional<PathExit> arc_exit(const Path& path, const PathSegment& seg, const Vec2& lo,
                                 const Vec2& hi) {
  const double kappa = seg.curvature_per_m;
  const double length = seg.length_m;
  const auto at = [&](double u) { return path.at(seg.s0_m + u).position_NE; };
  std::optional<double> first_outside;  // smallest u of an extreme or end point outside
  const auto consider = [&](double u) {
    u = std::clamp(u, 0.0, length);
    if (!inside(at(u), lo, hi) && (!first_outside || u < *first_outside)) first_outside = u;
  };
  consider(length);
  const double h0 = seg.start_heading;
  const double h1 = seg.start_heading + kappa * length;
  const double quarter = 0.5 * std::numbers::pi;
  const double m_lo = std::ceil(std::min(h0, h1) / quarter);
  const double m_hi = std::floor(std::max(h0, h1) / quarter);
  for (double m = m_lo; m <= m_hi && m - m_lo < 64.0; m += 1.0)
    consider((m * quarter - h0) / kappa);
  if (!first_outside) return std::nullopt;

  // sample up to the first known outside point, then bisect the first step that leaves
  const double radius = 1.0 / std::abs(kappa);
  const double step = std::min(kArcSampleStepM, kArcSampleRadiusFraction * radius);
  const double n = std::clamp(std::ceil(*first_outside / step), 1.0, kMaxArcSamples);
  double u_in = 0.0;
  double u_out = *first_outside;
  for (double i = 1.0; i <= n; i += 1.0) {
    const double u = *first_outside * (i / n);
    if (!inside(at(u), lo, hi)) {
      u_out = u;
      break;
    }
    u_in = u;
  }
  for (int k = 0; k < 200 && u_out - u_in > 0.0; ++k) {
    const double mid = 0.5 * (u_in + u_out);
    if (mid <= u_in || mid >= u_out) break;
    (inside(at(mid), lo, hi) ? u_in : u_out) = mid;
  }
  return PathExit{seg.s0_m + u_out, at(u_out)};
}

// Where a line that starts inside first leaves the box (closed form); nullopt if it stays inside.
std::optional<PathExit> line_exit(const PathSegment& seg, const Vec2& lo, const Vec2& hi) {
  const Vec2 dir = heading_vector(seg.start_heading);
  const Vec2 end = seg.start_NE + seg.length_m * dir;
  if (inside(end, lo, hi)) return std::nullopt;
  double u = seg.length_m;
  for (int a = 0; a < 2; ++a) {
    if (dir[a] > 0.0 && end[a] > hi[a]) u = std::min(u, (hi[a] - seg.start_NE[a]) / dir[a]);
    if (dir[a] < 0.0 && end[a] < lo[a]) u = std::min(u, (lo[a] - seg.start_NE[a]) / dir[a]);
  }
  u = std::clamp(u, 0.0, seg.length_m);
  return PathExit{seg.s0_m + u, seg.start_NE + u * dir};
}

// Where along the path a point at arc length s lies, for a message.
std::string where_on_path(const Path& path, const TrajectoryDesc& t, double s) {
  const auto& segs = path.segments();
  if (segs.empty()) return "at the start";
  const int i = std::clamp(path.segment_index(s), 0, static_cast<int>(segs.size()) - 1);
  const PathSegment& seg = segs[static_cast<std::size_t>(i)];
  if (seg.leg >= 0) return "on lawnmower leg " + std::to_string(seg.leg);
  if (t.kind == TrajectoryKind::kLawnmower) {
    for (int j = i; j >= 0; --j) {
      const int leg = segs[static_cast<std::size_t>(j)].leg;
      if (leg >= 0) return "in the U-turn after lawnmower leg " + std::to_string(leg);
    }
  }
  return seg.curvature_per_m == 0.0 ? "on a straight" : "in a turn";
}

}  // namespace

namespace vehicle_yaml {

// The rules on the planned path (see vehicle_loader.h).
void check_path(const Field& f, const VehicleDesc& d) {
  const TrajectoryDesc& t = d.trajectory;
  const double length = vehicle::plan_path(t).length_m();
  const Field traj = f.child("trajectory");
  if (!std::isfinite(length)) {
    traj.fail("the planned path has no finite length (" + approx(length) + " m)",
              "lengths, spacings, speed and turn rate that give a path of finite length");
  }
  const double steps = std::max(1.0, std::ceil(length / t.depth.profile_step_m));
  if (!(steps <= vehicle::Trajectory::kMaxProfileSteps)) {
    const Field step = traj.child("depth").child("profile_step_m");
    step.fail((step.present() ? format_number(t.depth.profile_step_m)
                              : "the default " + format_number(t.depth.profile_step_m)) +
                  " gives " + approx(steps) + " profile steps over the planned path of " +
                  approx(length) + " m",
              ">= " + approx(length / vehicle::Trajectory::kMaxProfileSteps) +
                  " for this path (at most " + approx(vehicle::Trajectory::kMaxProfileSteps) +
                  " profile steps), or a shorter path");
  }
  const double duration = length / t.speed_m_s;
  if (!(duration <= kMaxMissionDurationS)) {
    const Field speed = traj.child("speed_m_s");
    speed.fail((speed.present() ? format_number(t.speed_m_s)
                                : "the default " + format_number(t.speed_m_s)) +
                   " gives a mission of " + approx(duration) + " s over the planned path of " +
                   approx(length) + " m",
               ">= " + approx(length / kMaxMissionDurationS) +
                   " for this path (missions of at most " + approx(kMaxMissionDurationS) + " s)");
  }
}

}  // namespace vehicle_yaml

std::optional<PathExit> find_path_exit(const Path& path, const Vec2& lo, const Vec2& hi) {
  const Vec2 start = path.at(0.0).position_NE;
  if (!inside(start, lo, hi)) return PathExit{0.0, start};
  for (const PathSegment& seg : path.segments()) {
    // every segment starts inside: where the previous one ended, or at the checked start
    const auto exit =
        seg.curvature_per_m == 0.0 ? line_exit(seg, lo, hi) : arc_exit(path, seg, lo, hi);
    if (exit) return exit;
  }
  return std::nullopt;
}

void check_vehicle_over_seabed(const Field& f, const VehicleDesc& v,
                               const scene::SeabedDesc& seabed) {
  const TrajectoryDesc& t = v.trajectory;
  if (t.depth.mode != DepthMode::kAltitude) return;
  const double margin = t.sway.amplitude_m;
  const Vec2 lo = seabed.origin_m + Vec2(margin, margin);
  const Vec2 hi = seabed.origin_m + seabed.extent_m - Vec2(margin, margin);
  const Path path = vehicle::plan_path(t);
  const auto exit = find_path_exit(path, lo, hi);
  if (!exit) return;

  const Vec2 box_lo = seabed.origin_m;
  const Vec2 box_hi = seabed.origin_m + seabed.extent_m;
  const double radius = vehicle::turn_radius_m(t.speed_m_s, t.max_turn_rate_rad_s);
  std::string allowed =
      "with depth.mode altitude (terrain following), a path that stays over the modelled seabed: "
      "north " +
      format_number(box_lo.x()) + " .. " + format_number(box_hi.x()) + ", east " +
      format_number(box_lo.y()) + " .. " + format_number(box_hi.y()) +
      " (seabed.origin_m, seabed.extent_m)";
  if (margin > 0.0) {
    allowed += ", less sway.amplitude_m " + format_number(margin) + " on every side";
  }
  allowed += "; turns have radius speed_m_s / max_turn_rate = " + approx(radius) + " m";
  if (t.kind == TrajectoryKind::kLawnmower && t.lawnmower.legs > 1) {
    allowed += ", and each U-turn reaches " +
               approx(vehicle::u_turn_overshoot_m(t.lawnmower.line_spacing_m, radius)) +
               " m beyond the leg ends";
  }
  const Field traj = f.child("trajectory");
  traj.fail("the planned path leaves the seabed extent at t = " + approx(exit->s_m / t.speed_m_s) +
                " s (" + approx(exit->s_m) + " m along the path, " +
                where_on_path(path, t, exit->s_m) + "), position [north, east] = [" +
                approx(exit->position_NE.x()) + ", " + approx(exit->position_NE.y()) + "] m",
            allowed);
}

}  // namespace sonarloop::config
