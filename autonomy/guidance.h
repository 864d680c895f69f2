#pragma once
// Waypoint following for the autonomy agent (ours): line-of-sight (LOS) guidance along a leg, and
// the mission's list of legs, each flown as an approach (a straight line from where the vehicle
// was when the leg began to the leg's start; for a re-look leg, to a lead point before its start
// on its line, GuidanceParams::relook_lead_m) followed by the leg itself (a re-look leg's line
// followed from the lead point).
//
// LOS (Fossen, "Handbook of Marine Craft Hydrodynamics and Motion Control", 2011, Sec. 10.3.2,
// lookahead-based steering): with the leg's heading h, the cross-track error e (+ to starboard of
// the leg) and the lookahead distance L, the commanded heading is h - atan(e / L): the vehicle
// aims at a point L ahead on the line, converges without overshoot for L above about the turn
// radius, and flies the line exactly once on it.
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "autonomy/geometry.h"
#include "autonomy/survey.h"

namespace sonarloop::autonomy {

struct LegProgress {
  double along_m = 0.0;        // along the leg from its start
  double cross_track_m = 0.0;  // + to starboard of the leg's direction
};

LegProgress leg_progress(const Leg& leg, Point2 p);

// The LOS heading command for a vehicle at p following `leg` (lookahead_m > 0).
double los_heading_rad(const Leg& leg, Point2 p, double lookahead_m);

struct GuidanceParams {
  double lookahead_m = 15.0;           // LOS lookahead: settles on a line within ~3 lookaheads
  double approach_acceptance_m = 5.0;  // an approach ends this close to its end point
  // A re-look leg is approached at the point this far before its start on its line, and the
  // line is followed from there: the vehicle, arriving at any heading, then has this and the
  // run-in to settle on the line (2 turn radii of the default vehicle).
  double relook_lead_m = 40.0;
};

// The legs still to fly, front first, and where the vehicle is in the front one.
class MissionPlan {
 public:
  MissionPlan() = default;
  // The survey, flown from `from` (the vehicle's position).
  MissionPlan(std::vector<Leg> survey, Point2 from, GuidanceParams params = {});

  bool done() const { return legs_.empty(); }
  // The leg being flown (undefined when done()).
  const Leg& current() const { return legs_.front(); }
  bool approaching() const { return approaching_; }
  // What the vehicle steers on now: the approach segment, or the leg.
  Leg steering_leg() const;
  const std::deque<Leg>& legs() const { return legs_; }
  // Whether the vehicle is on a detour (re-look legs, their approaches, and the approach back
  // to the survey after one): its distance is the re-looks' cost.
  bool on_detour() const;

  // Advances past finished approaches and legs for a vehicle at p; returns the heading command.
  double update(Point2 p);

  // Inserts a re-look leg: now when the vehicle is on a survey leg (which is cut where the
  // vehicle is, so that the survey resumes there), after the re-look legs already queued
  // otherwise. p is the vehicle's position.
  void insert_relook(const Leg& relook, Point2 p);

 private:
  void begin_next(Point2 p);
  // Where the front leg's approach ends, and the start of the line steered on after it.
  Point2 line_start() const;

  GuidanceParams params_;
  std::deque<Leg> legs_;
  bool approaching_ = false;
  Point2 approach_from_;
  bool after_relook_ = false;  // the front leg follows a re-look (its approach is a detour)
};

}  // namespace sonarloop::autonomy
