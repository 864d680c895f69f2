#pragma once
// The planned horizontal path: straight lines joined by circular arcs, parameterised by arc
// length s (m, horizontal) from the start. Flown at constant speed u, an arc of radius R is a
// constant turn rate u/R, so the turn-rate bound r_max becomes a minimum radius R = u / r_max and
// every arc is flown at exactly that radius (the vehicle turns at its maximum rate).
//
// The path is C1: position and heading are continuous at every join; curvature (turn rate)
// steps there. trajectory.h smooths the attitude that follows from it.
//
// Planning rules (each a pure function of the TrajectoryDesc):
// * straight: one line from the start point along the start heading.
// * waypoints, "fly-over": from the current pose the vehicle turns at radius R towards the side
//   the next waypoint lies on, until it points at it, then runs straight to it and passes over it
//   exactly (then turns for the next). If the waypoint lies inside that turning circle (too close
//   to reach by turning towards it), it turns the other way round instead (a loop of up to 360
//   degrees + the tangent), which always reaches it. A waypoint dead ahead needs no turn; one
//   dead astern is turned for to starboard. Straight runs are therefore tangent-to-waypoint
//   lines, not the lines between waypoints: use the lawnmower for survey lines.
// * lawnmower: legs joined by U-turns towards the survey side. With line spacing d >= 2R the
//   U-turn is a quarter circle, a straight of d - 2R across, and a quarter circle (length
//   πR + d - 2R, reaching R beyond the leg end). With d < 2R a U-turn of radius R cannot join
//   the legs, so the vehicle flies a keyhole (omega) turn: it turns away from the survey side by
//   α, turns towards it by π + 2α, and away again by α, with cos α = (R + d/2) / (2R) (all three
//   arcs of radius R, mutually tangent; derived from the tangency of the first two circles,
//   centres 2R apart). Length R(π + 4α); it reaches R(1 + 2 sin α) beyond the leg end and
//   R - d/2 outside each of the two legs (the middle arc, centred midway between them). At
//   d = 2R, α = 0 and both turns coincide.
#include <vector>

#include "sim/frames.h"
#include "sim/vehicle/vehicle_desc.h"

namespace sonarloop::vehicle {

// One piece of the path: a line (curvature 0) or an arc of constant curvature.
struct PathSegment {
  double s0_m = 0.0;             // arc length at the start of the segment
  double length_m = 0.0;         // > 0
  Vec2 start_NE = Vec2::Zero();  // (north, east) of the segment start, m
  double start_heading = 0.0;    // rad clockwise from north, unwrapped (continuous along path)
  double curvature_per_m = 0.0;  // dψ/ds = 1/radius; > 0 turns to starboard (heading grows)
  int leg = -1;                  // lawnmower survey leg index (0-based) for leg lines, else -1
};

// A point on the path.
struct PathPoint {
  Vec2 position_NE = Vec2::Zero();
  double heading = 0.0;          // unwrapped
  double curvature_per_m = 0.0;  // of the segment containing s; 0 outside the path
  int segment = -1;              // segment index; -1 before the start, segments().size() after
};

class Path {
 public:
  Path() = default;  // empty: zero length at (0, 0), heading north
  Path(std::vector<PathSegment> segments, Vec2 start_NE, double start_heading, Vec2 end_NE,
       double end_heading);

  double length_m() const { return length_m_; }
  const std::vector<PathSegment>& segments() const { return segments_; }

  // The point at arc length s (closed form). Outside [0, length] the path continues as a straight
  // line along the start heading (s < 0) or the end heading (s > length).
  PathPoint at(double s_m) const;

  // Index of the segment containing s in [0, length] (the later one at a join); -1 for s < 0,
  // segments().size() for s > length.
  int segment_index(double s_m) const;

 private:
  std::vector<PathSegment> segments_;
  double length_m_ = 0.0;
  Vec2 start_NE_ = Vec2::Zero();
  double start_heading_ = 0.0;
  Vec2 end_NE_ = Vec2::Zero();
  double end_heading_ = 0.0;
};

// Builds a path piece by piece from a start pose, integrating each piece in closed form.
class PathBuilder {
 public:
  PathBuilder(Vec2 start_NE, double heading);

  // A straight line; lengths below 1e-9 m are skipped.
  void line(double length_m, int leg = -1);
  // An arc of the given radius turning by turn_angle (rad; > 0 = starboard); |turn_angle| below
  // 1e-12 is skipped.
  void arc(double turn_angle, double radius_m);
  // Fly-over to a waypoint (rules in the header comment).
  void fly_over(Vec2 waypoint_NE, double radius_m);
  // A U-turn onto the parallel line spacing_m to the given side, heading reversed (regular or
  // keyhole, header comment).
  void u_turn(double spacing_m, double radius_m, TurnDirection side);

  Vec2 position() const { return position_; }
  double heading() const { return heading_; }
  double length_m() const { return s_; }
  Path build() const;

 private:
  void add(double length_m, double curvature_per_m, int leg);

  std::vector<PathSegment> segments_;
  Vec2 start_;
  double start_heading_;
  Vec2 position_;
  double heading_;
  double s_ = 0.0;
};

// Turn radius of a path flown at speed_m_s with a turn-rate bound (R = u / r_max), m.
double turn_radius_m(double speed_m_s, double max_turn_rate_rad_s);

// Keyhole half-angle α (rad) for line spacing d < 2R: cos α = (R + d/2) / (2R); 0 if d >= 2R.
double keyhole_angle(double spacing_m, double radius_m);

// Length of the U-turn between two legs spacing_m apart: πR + d - 2R (d >= 2R) or R(π + 4α).
double u_turn_length_m(double spacing_m, double radius_m);

// How far the U-turn reaches beyond the end of the leg, along the leg: R or R(1 + 2 sin α).
double u_turn_overshoot_m(double spacing_m, double radius_m);

// The path of a (validated) description.
Path plan_path(const TrajectoryDesc& desc);

}  // namespace sonarloop::vehicle
