// The re-look leg: ~90° from the first look, the contact abeam at the pass range, and the
// vehicle straight and level when it passes (flown with the vehicle model and LOS guidance).
#include <catch2/catch.hpp>

#include <cmath>

#include "autonomy/guidance.h"
#include "autonomy/relook.h"
#include "autonomy/vehicle_model.h"

using namespace sonarloop::autonomy;

namespace {

constexpr double kAspectToleranceDeg = 5.0;
constexpr double kRangeTolerance_m = 1.0;

struct Pass {
  double heading_rad = 0, range_m = 0, turn_rate_rad_s = 0;
};

// Flies from (p, heading) to and along the plan's leg; the vehicle at the pass point.
Pass fly_relook(const RelookPlan& r, Point2 c, Point2 p, double heading, const RelookParams& rp) {
  MissionPlan plan({}, p);
  plan.insert_relook(r.leg, p);
  VehicleState s;
  s.position = p;
  s.heading_rad = heading;
  const VehicleParams vp;
  Pass out;
  while (!plan.done() && s.t_s < 3600) {
    const double h = plan.update(s.position);
    if (plan.done()) break;
    s = step_vehicle(s, VehicleCommand{h, 0}, vp, 0.02);
    if (!plan.approaching() && leg_progress(r.leg, s.position).along_m >= rp.run_in_m) {
      out.heading_rad = s.heading_rad;
      out.turn_rate_rad_s = s.turn_rate_rad_s;
      out.range_m = std::fabs(leg_progress(r.leg, c).cross_track_m -
                              leg_progress(r.leg, s.position).cross_track_m);
      break;
    }
  }
  return out;
}

}  // namespace

TEST_CASE(
    "the re-look passes the contact at the pass range, about 90 degrees from the first look") {
  const RelookParams rp;
  const Point2 c{50.0, 30.0};
  // first looks from several headings, the vehicle at several places and headings
  for (const double first_deg : {0.0, 180.0, 37.0, -120.0}) {
    for (const Point2 p : {Point2{90.0, 5.0}, Point2{-20.0, -40.0}, Point2{50.0, 100.0}}) {
      for (const double heading_deg : {0.0, 90.0, 200.0}) {
        INFO("first look " << first_deg << " deg, vehicle at (" << p.north_m << ", " << p.east_m
                           << ") heading " << heading_deg);
        const RelookPlan r = plan_relook(c, radians(first_deg), 3, p, radians(heading_deg), rp);
        CHECK(r.leg.kind == LegKind::kRelook);
        CHECK(r.leg.object == 3);
        // geometry of the plan
        CHECK(degrees(heading_difference_rad(r.heading_rad, radians(first_deg))) ==
              Approx(90.0).margin(1e-9));
        CHECK(distance_m(r.pass_point, c) == Approx(rp.pass_range_m));
        const LegProgress g = leg_progress(r.leg, c);
        CHECK(g.along_m == Approx(rp.run_in_m));
        CHECK(std::fabs(g.cross_track_m) == Approx(rp.pass_range_m));
        CHECK((g.cross_track_m > 0) == (r.side == 1));
        CHECK(r.leg.length_m() == Approx(rp.run_in_m + rp.run_out_m));
        // flown: straight and level abeam the contact at the range
        const Pass pass = fly_relook(r, c, p, radians(heading_deg), rp);
        CHECK(degrees(heading_difference_rad(pass.heading_rad, radians(first_deg))) ==
              Approx(90.0).margin(kAspectToleranceDeg));
        CHECK(pass.range_m == Approx(rp.pass_range_m).margin(kRangeTolerance_m));
        CHECK(std::fabs(pass.turn_rate_rad_s) < 0.01);
      }
    }
  }
}

TEST_CASE("the planner prefers passes inside the bounds") {
  RelookParams rp;
  const SurveyArea bounds{{0, 0}, {100, 100}};
  // a contact near the western edge seen from a north-going track: the pass must not lie west
  const Point2 c{50.0, 20.0};
  const RelookPlan r = plan_relook(c, 0.0, 1, {60.0, 60.0}, 0.0, rp, bounds);
  CHECK(bounds.contains(r.leg.start));
  CHECK(bounds.contains(r.leg.end));
  CHECK(r.cost_m < kOutOfBoundsPenalty_m);
}
