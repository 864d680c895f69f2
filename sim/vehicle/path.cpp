#include "sim/vehicle/path.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "units/angles.h"

namespace sonarloop::vehicle {

namespace {

constexpr double kMinLineM = 1e-9;     // shorter lines are rounding residue, not path
constexpr double kMinTurnRad = 1e-12;  // smaller turns likewise

// Chord of an arc of curvature kappa and length sigma: 2·sin(κσ/2)/κ (σ for a line). Written
// with the half angle so that it stays accurate for very small κσ.
double chord_length(double kappa, double sigma) {
  const double half = 0.5 * kappa * sigma;
  if (std::abs(half) < 1e-8) return sigma * (1.0 - half * half / 6.0);
  return std::sin(half) / (0.5 * kappa);
}

// Starboard unit normal of a heading: (-sin ψ, cos ψ) in (north, east).
Vec2 starboard_normal(double heading) {
  return {-std::sin(heading), std::cos(heading)};
}

}  // namespace

Path::Path(std::vector<PathSegment> segments, Vec2 start_NE, double start_heading, Vec2 end_NE,
           double end_heading)
    : segments_(std::move(segments)),
      start_NE_(start_NE),
      start_heading_(start_heading),
      end_NE_(end_NE),
      end_heading_(end_heading) {
  if (!segments_.empty()) length_m_ = segments_.back().s0_m + segments_.back().length_m;
}

int Path::segment_index(double s_m) const {
  if (s_m < 0.0) return -1;
  if (segments_.empty() || s_m > length_m_) return static_cast<int>(segments_.size());
  // last segment whose start is <= s
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), s_m,
                                   [](double s, const PathSegment& seg) { return s < seg.s0_m; });
  return static_cast<int>(std::max<std::ptrdiff_t>(0, (it - segments_.begin()) - 1));
}

PathPoint Path::at(double s_m) const {
  PathPoint p;
  const int i = segment_index(s_m);
  p.segment = i;
  if (i < 0) {
    // straight run-in before the start
    p.position_NE = start_NE_ + s_m * heading_vector(start_heading_);
    p.heading = start_heading_;
    return p;
  }
  if (i >= static_cast<int>(segments_.size())) {
    // straight run-out after the end
    p.position_NE = end_NE_ + (s_m - length_m_) * heading_vector(end_heading_);
    p.heading = end_heading_;
    return p;
  }
  const PathSegment& seg = segments_[static_cast<std::size_t>(i)];
  const double sigma = s_m - seg.s0_m;
  const double kappa = seg.curvature_per_m;
  // a circular arc moves along its chord, which points along the mean of the two headings
  p.position_NE = seg.start_NE + chord_length(kappa, sigma) *
                                     heading_vector(seg.start_heading + 0.5 * kappa * sigma);
  p.heading = seg.start_heading + kappa * sigma;
  p.curvature_per_m = kappa;
  return p;
}

PathBuilder::PathBuilder(Vec2 start_NE, double heading)
    : start_(start_NE), start_heading_(heading), position_(start_NE), heading_(heading) {}

void PathBuilder::add(double length_m, double curvature_per_m, int leg) {
  PathSegment seg;
  seg.s0_m = s_;
  seg.length_m = length_m;
  seg.start_NE = position_;
  seg.start_heading = heading_;
  seg.curvature_per_m = curvature_per_m;
  seg.leg = leg;
  segments_.push_back(seg);
  position_ += chord_length(curvature_per_m, length_m) *
               heading_vector(heading_ + 0.5 * curvature_per_m * length_m);
  heading_ += curvature_per_m * length_m;
  s_ += length_m;
}

void PathBuilder::line(double length_m, int leg) {
  if (!(length_m > kMinLineM)) return;
  add(length_m, 0.0, leg);
}

void PathBuilder::arc(double turn_angle, double radius_m) {
  if (!(std::abs(turn_angle) > kMinTurnRad)) return;
  const double kappa = std::copysign(1.0 / radius_m, turn_angle);
  add(std::abs(turn_angle) * radius_m, kappa, -1);
}

void PathBuilder::fly_over(Vec2 waypoint_NE, double radius_m) {
  const Vec2 d = waypoint_NE - position_;
  const double distance = d.norm();
  if (distance < kMinLineM) return;
  const Vec2 ahead = heading_vector(heading_);
  const Vec2 starboard = starboard_normal(heading_);
  const double lateral = d.dot(starboard);
  const double forward = d.dot(ahead);

  // dead ahead (to rounding): no turn
  if (std::abs(lateral) <= 1e-12 * distance && forward > 0.0) {
    line(forward);
    return;
  }
  // turn towards the waypoint's side (dead astern: starboard); if the waypoint lies inside that
  // turning circle it cannot be reached that way, so turn the other way: the opposite circle
  // lies wholly on the other side of the track, so the waypoint is outside it
  double side = lateral >= 0.0 ? 1.0 : -1.0;
  Vec2 centre = position_ + side * radius_m * starboard;
  if ((waypoint_NE - centre).norm() < radius_m) {
    side = -side;
    centre = position_ + side * radius_m * starboard;
  }

  // tangent from the waypoint to the circle: the vehicle leaves the circle at the tangent point
  // T, heading straight at the waypoint; T - centre is at right angles to that heading
  const Vec2 cw = waypoint_NE - centre;
  const double dc = cw.norm();
  const double tangent_m = std::sqrt(std::max(0.0, dc * dc - radius_m * radius_m));
  const double bearing = std::atan2(cw.y(), cw.x());
  const double final_heading =
      bearing - side * std::atan2(tangent_m, radius_m) + side * std::numbers::pi / 2;

  // turn by the angle, in the chosen direction, from the present heading to the final one
  double turn = std::fmod(side * (final_heading - heading_), kTwoPi);
  if (turn < 0.0) turn += kTwoPi;
  if (turn > kTwoPi - 1e-9) turn = 0.0;  // already pointing at it, up to rounding
  arc(side * turn, radius_m);

  // the straight run from the tangent point to the waypoint
  line((waypoint_NE - position_).dot(heading_vector(heading_)));
}

void PathBuilder::u_turn(double spacing_m, double radius_m, TurnDirection side) {
  const double sign = side == TurnDirection::kStarboard ? 1.0 : -1.0;
  if (spacing_m >= 2.0 * radius_m) {
    arc(sign * std::numbers::pi / 2, radius_m);
    line(spacing_m - 2.0 * radius_m);
    arc(sign * std::numbers::pi / 2, radius_m);
    return;
  }
  const double alpha = keyhole_angle(spacing_m, radius_m);
  arc(-sign * alpha, radius_m);
  arc(sign * (std::numbers::pi + 2.0 * alpha), radius_m);
  arc(-sign * alpha, radius_m);
}

Path PathBuilder::build() const {
  return Path(segments_, start_, start_heading_, position_, heading_);
}

double turn_radius_m(double speed_m_s, double max_turn_rate_rad_s) {
  return speed_m_s / max_turn_rate_rad_s;
}

double keyhole_angle(double spacing_m, double radius_m) {
  if (spacing_m >= 2.0 * radius_m) return 0.0;
  return std::acos(std::clamp((radius_m + 0.5 * spacing_m) / (2.0 * radius_m), -1.0, 1.0));
}

double u_turn_length_m(double spacing_m, double radius_m) {
  if (spacing_m >= 2.0 * radius_m) return std::numbers::pi * radius_m + spacing_m - 2.0 * radius_m;
  return radius_m * (std::numbers::pi + 4.0 * keyhole_angle(spacing_m, radius_m));
}

double u_turn_overshoot_m(double spacing_m, double radius_m) {
  return radius_m * (1.0 + 2.0 * std::sin(keyhole_angle(spacing_m, radius_m)));
}

Path plan_path(const TrajectoryDesc& desc) {
  const double radius = turn_radius_m(desc.speed_m_s, desc.max_turn_rate_rad_s);
  switch (desc.kind) {
    case TrajectoryKind::kStraight: {
      PathBuilder b({desc.start.north_m, desc.start.east_m}, desc.start_heading);
      b.line(desc.straight_length_m);
      return b.build();
    }
    case TrajectoryKind::kWaypoints: {
      PathBuilder b({desc.start.north_m, desc.start.east_m}, desc.start_heading);
      for (const NorthEast& w : desc.waypoints)
        b.fly_over({w.north_m, w.east_m}, radius);
      return b.build();
    }
    case TrajectoryKind::kLawnmower: {
      const LawnmowerDesc& m = desc.lawnmower;
      PathBuilder b({m.origin.north_m, m.origin.east_m}, m.first_leg_heading);
      const TurnDirection other = m.first_turn == TurnDirection::kStarboard
                                      ? TurnDirection::kPort
                                      : TurnDirection::kStarboard;
      for (int leg = 0; leg < m.legs; ++leg) {
        b.line(m.leg_length_m, leg);
        if (leg + 1 < m.legs)
          b.u_turn(m.line_spacing_m, radius, leg % 2 == 0 ? m.first_turn : other);
      }
      return b.build();
    }
  }
  return {};
}

}  // namespace sonarloop::vehicle
