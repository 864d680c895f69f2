// The lawnmower planner: every point of the area within half a line spacing of a line.
#include <catch2/catch.hpp>

#include <cmath>

#include "autonomy/guidance.h"
#include "autonomy/survey.h"

using namespace sonarloop::autonomy;

TEST_CASE("the lawnmower's legs cover the area") {
  const SurveyArea area{{-150.0, -150.0}, {150.0, 150.0}};
  for (const double spacing : {40.0, 35.0, 70.0, 400.0}) {
    const std::vector<Leg> legs = lawnmower(area, spacing);
    INFO("spacing " << spacing);
    REQUIRE(!legs.empty());
    // alternate directions, each the area's full north extent, inside it
    for (std::size_t i = 0; i < legs.size(); ++i) {
      CHECK(legs[i].length_m() == Approx(300.0));
      CHECK(std::fabs(std::cos(legs[i].heading_rad())) == Approx(1.0));
      CHECK((legs[i].end.north_m > legs[i].start.north_m) == (i % 2 == 0));
      CHECK(area.contains(legs[i].start));
      CHECK(area.contains(legs[i].end));
    }
    // every point of a grid over the area is within spacing/2 across track of a leg
    for (double n = -150; n <= 150; n += 7.5) {
      for (double e = -150; e <= 150; e += 2.5) {
        double nearest = 1e9;
        for (const Leg& l : legs)
          nearest = std::min(nearest, std::fabs(leg_progress(l, {n, e}).cross_track_m));
        INFO("(" << n << ", " << e << ")");
        CHECK(nearest <= 0.5 * spacing + 1e-9);
      }
    }
  }
  CHECK(lawnmower(area, 40.0).size() == 8);
  CHECK(plan_length_m(lawnmower(area, 40.0)) == Approx(8 * 300.0 + 7 * 40.0));
}

TEST_CASE("the lawnmower refuses bad input") {
  CHECK_THROWS_AS(lawnmower(SurveyArea{{0, 0}, {10, 10}}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(lawnmower(SurveyArea{{0, 0}, {0, 10}}, 5.0), std::invalid_argument);
}
