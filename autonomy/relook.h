#pragma once
// The re-look leg planner (ours): a straight pass that sees a contact again from another aspect.
//
// Geometry. The first look saw the contact at C from a track of heading h1. The re-look passes C
// on a straight line of heading h2 = h1 ± 90° (the aspect that sidescan sees least alike: the
// highlight and shadow of an elongated object change most), offset `pass_range_m` across track
// from C, so that C lies abeam at that ground range, mid-swath on one side. The leg begins
// `run_in_m` before the point abeam C (long enough to finish the turn onto the line, so that the
// vehicle is straight and level when it passes) and ends `run_out_m` after it (the onboard
// consumer needs the pings past the object, its shadow and the chip's last rows).
//
// Of the four such passes (two headings, C to port or to starboard), the planner takes the
// cheapest for a vehicle at p with heading h: the distance to the run-in start, plus the turns
// (at the turn radius) onto that course and then onto the leg; a pass whose run-in start or end
// leaves `bounds` (the area the vehicle may use) costs kOutOfBoundsPenalty_m more.
#include <optional>

#include "autonomy/geometry.h"
#include "autonomy/survey.h"

namespace sonarloop::autonomy {

struct RelookParams {
  double pass_range_m = 25.0;  // ground range of the contact at the pass (mid-swath)
  double run_in_m = 50.0;      // straight line before the pass point
  double run_out_m = 20.0;     // straight line after it
  double aspect_change_rad = std::numbers::pi / 2;  // |h2 - h1|
  double turn_radius_m = 19.0;                      // the vehicle's (VehicleParams::turn_radius_m)
};

inline constexpr double kOutOfBoundsPenalty_m = 1e4;

struct RelookPlan {
  Leg leg;                 // kind kRelook: run-in start -> run-out end
  Point2 pass_point;       // abeam the contact
  double heading_rad = 0;  // of the leg
  int side = 1;            // where the contact lies: 0 port, 1 starboard
  double cost_m = 0;       // the planner's cost of it
};

// The re-look of contact `c` (object id `object`) first seen from heading `first_look_heading_rad`,
// for a vehicle at p with heading h. bounds: optional area the legs should stay in.
RelookPlan plan_relook(Point2 c, double first_look_heading_rad, std::uint64_t object, Point2 p,
                       double heading_rad, const RelookParams& params,
                       const std::optional<SurveyArea>& bounds = std::nullopt);

}  // namespace sonarloop::autonomy
