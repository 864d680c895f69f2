#include "autonomy/relook.h"

#include <limits>

namespace sonarloop::autonomy {
namespace {

// One candidate: heading h2, contact on `side` (1 starboard: the line lies to port of C).
RelookPlan candidate(Point2 c, double h2, int side, std::uint64_t object,
                     const RelookParams& params) {
  RelookPlan r;
  r.heading_rad = wrap_to_pi(h2);
  r.side = side;
  // starboard of the leg is heading + 90°: for the contact to starboard the line is to port of C
  const double to_line = r.heading_rad + (side == 1 ? -0.5 : 0.5) * std::numbers::pi;
  r.pass_point = c + params.pass_range_m * direction(to_line);
  const Point2 d = direction(r.heading_rad);
  r.leg.start = r.pass_point - params.run_in_m * d;
  r.leg.end = r.pass_point + params.run_out_m * d;
  r.leg.kind = LegKind::kRelook;
  r.leg.object = object;
  return r;
}

// Distance to the run-in start plus the arcs of the turns onto that course and onto the leg.
double cost_m(const RelookPlan& r, Point2 p, double heading_rad, double turn_radius_m) {
  const double to_start = distance_m(p, r.leg.start);
  const double course = bearing_rad(p, r.leg.start);
  return to_start + turn_radius_m * (heading_difference_rad(heading_rad, course) +
                                     heading_difference_rad(course, r.heading_rad));
}

}  // namespace

RelookPlan plan_relook(Point2 c, double first_look_heading_rad, std::uint64_t object, Point2 p,
                       double heading_rad, const RelookParams& params,
                       const std::optional<SurveyArea>& bounds) {
  RelookPlan best;
  best.cost_m = std::numeric_limits<double>::infinity();
  for (const double sign : {1.0, -1.0}) {
    for (const int side : {0, 1}) {
      RelookPlan r = candidate(c, first_look_heading_rad + sign * params.aspect_change_rad, side,
                               object, params);
      r.cost_m = cost_m(r, p, heading_rad, params.turn_radius_m);
      if (bounds && !(bounds->contains(r.leg.start) && bounds->contains(r.leg.end))) {
        r.cost_m += kOutOfBoundsPenalty_m;
      }
      if (r.cost_m < best.cost_m) best = r;
    }
  }
  return best;
}

}  // namespace sonarloop::autonomy
