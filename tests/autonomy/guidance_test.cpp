// LOS guidance and the mission plan: legs flown in order, a re-look inserted cuts the survey
// where the vehicle is, and the survey resumes there.
#include <catch2/catch.hpp>

#include <cmath>

#include "autonomy/guidance.h"
#include "autonomy/vehicle_model.h"

using namespace sonarloop::autonomy;

namespace {

// Flies the plan with the vehicle model until it is done (or max_s); returns the final state.
VehicleState fly(MissionPlan& plan, VehicleState s, double max_s,
                 double* max_cross_on_leg = nullptr) {
  const VehicleParams p;
  const double dt = 0.05;
  while (!plan.done() && s.t_s < max_s) {
    const double h = plan.update(s.position);
    if (plan.done()) break;
    if (max_cross_on_leg && !plan.approaching() &&
        leg_progress(plan.current(), s.position).along_m > 80) {
      *max_cross_on_leg = std::max(
          *max_cross_on_leg, std::fabs(leg_progress(plan.current(), s.position).cross_track_m));
    }
    s = step_vehicle(s, VehicleCommand{h, 0.0}, p, dt);
  }
  return s;
}

}  // namespace

TEST_CASE("LOS steers towards the line") {
  Leg l{{0, 0}, {100, 0}};
  CHECK(los_heading_rad(l, {10, 0}, 25) == Approx(0.0).margin(1e-12));
  CHECK(los_heading_rad(l, {10, 10}, 25) < 0.0);  // starboard of a north leg: steer to port
  CHECK(los_heading_rad(l, {10, -10}, 25) > 0.0);
  CHECK(leg_progress(l, {30, 5}).along_m == Approx(30));
  CHECK(leg_progress(l, {30, 5}).cross_track_m == Approx(5));
}

TEST_CASE("the plan flies its legs in order and holds the lines") {
  const std::vector<Leg> survey = lawnmower(SurveyArea{{0, 0}, {200, 120}}, 40.0);
  MissionPlan plan(survey, {0, 20});
  double max_cross = 0.0;
  VehicleState s;
  s.position = {0, 20};
  s = fly(plan, s, 3600.0, &max_cross);
  CHECK(plan.done());
  CHECK(max_cross < 1.0);  // straight on the lines after the turn
  CHECK(distance_m(s.position, survey.back().end) < 10.0);
}

TEST_CASE("a re-look cuts the survey leg where the vehicle is and the survey resumes there") {
  const std::vector<Leg> survey{{{0, 0}, {300, 0}}};
  MissionPlan plan(survey, {0, 0});
  VehicleState s;
  const VehicleParams p;
  while (s.position.north_m < 100.0)
    s = step_vehicle(s, VehicleCommand{plan.update(s.position), 0}, p, 0.05);
  Leg relook{{120, 60}, {120, 140}, LegKind::kRelook, 7};
  plan.insert_relook(relook, s.position);
  REQUIRE(plan.legs().size() == 2);
  CHECK(plan.current().kind == LegKind::kRelook);
  CHECK(plan.on_detour());
  CHECK(plan.legs()[1].start.north_m == Approx(s.position.north_m).margin(0.1));
  // a second re-look queues behind the first
  Leg second{{0, 50}, {0, 10}, LegKind::kRelook, 8};
  plan.insert_relook(second, s.position);
  REQUIRE(plan.legs().size() == 3);
  CHECK(plan.legs()[1].object == 8);
  CHECK(plan.legs()[2].kind == LegKind::kSurvey);
  s = fly(plan, s, 3600.0);
  CHECK(plan.done());
  CHECK(distance_m(s.position, {300, 0}) < 10.0);
}
