// Training chips from a survey (mission/survey_chips.h): each target seen gives a chip of its
// type, centred on it, with its aspect; false alarms give clutter chips.
#include "mission/survey_chips.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "mission/agent_setup.h"
#include "mission/lockstep.h"
#include "sim/scene/scene.h"
#include "tests/mission/mission_fixtures.h"

using namespace sonarloop;

namespace {

double wrap360(double a) {
  return std::fmod(std::fmod(a, 360.0) + 360.0, 360.0);
}

}  // namespace

TEST_CASE("survey chips: the Manta and the cylinder of one line, centred, with their aspect") {
  const Scenario sc = testing::two_targets_scenario();
  const scene::Scene scene(sc.scene);
  const mission::AgentSetup setup = mission::make_agent_setup(sc, testing::one_line());
  autonomy::Agent agent(setup.params, setup.survey, setup.start);
  mission::SurveyChipCollector collector(scene, {});
  mission::LockstepHooks hooks;
  hooks.on_candidate = [&](const atr::Waterfall& w, const atr::CandidateReport& r) {
    collector.on_candidate(w, r);
  };
  mission::LockstepOptions o;
  o.drain_s = 5.0;
  (void)mission::run_lockstep(sc, scene, std::nullopt, {}, agent, o, hooks);

  int manta = 0, cylinder = 0;
  for (const atr::LabelledChip& c : collector.chips()) {
    REQUIRE(c.chip.width == 60);
    REQUIRE(c.chip.height == 60);
    REQUIRE(c.aspect_deg);
    if (c.label == "clutter") continue;
    // the line runs north: the Manta (heading 30) is seen to starboard (look 90), the cylinder
    // (heading 100) to port (look 270)
    const double expected = c.label == "manta" ? wrap360(30.0 - 90.0) : wrap360(100.0 - 270.0);
    CHECK(std::fabs(std::remainder(*c.aspect_deg - expected, 360.0)) < 5.0);
    manta += c.label == "manta";
    cylinder += c.label == "cylinder";
    // centred: the brightest pixel (the target's highlight) in the chip's middle third
    std::size_t best = 0;
    for (std::size_t i = 0; i < c.chip.pixels.size(); ++i)
      if (c.chip.pixels[i] > c.chip.pixels[best]) best = i;
    const int row = static_cast<int>(best) / c.chip.width,
              col = static_cast<int>(best) % c.chip.width;
    INFO(c.label << " brightest at row " << row << ", column " << col);
    CHECK(row >= 20);
    CHECK(row < 40);
    CHECK(col >= 20);
    CHECK(col < 40);
  }
  CHECK(manta >= 1);
  CHECK(cylinder >= 1);
  CHECK(collector.counts().targets == static_cast<std::uint64_t>(manta + cylinder));
  CHECK(collector.counts().clutter + collector.counts().targets == collector.chips().size());
}

TEST_CASE("survey chips: a point's place in the waterfall is its ping abeam and its slant range") {
  // locate_in_waterfall on the live waterfall of a flown line: the Manta 20 m to starboard at
  // 7.5 m altitude lies at a slant range of about sqrt(20^2 + (7.5 - 0.47 / 2)^2)
  const Scenario sc = testing::two_targets_scenario();
  const scene::Scene scene(sc.scene);
  const mission::AgentSetup setup = mission::make_agent_setup(sc, testing::one_line());
  autonomy::Agent agent(setup.params, setup.survey, setup.start);
  std::optional<mission::WaterfallPoint> manta, none;
  mission::LockstepHooks hooks;
  hooks.on_candidate = [&](const atr::Waterfall& w, const atr::CandidateReport& r) {
    // the Manta's own candidate: decided once the sonar is past it
    if (!manta && std::hypot(r.contact.north_m, r.contact.east_m - 20.0) < 3.0) {
      manta = mission::locate_in_waterfall(w, 0.0, 20.0, 0.47, 1);
      none = mission::locate_in_waterfall(w, 0.0, 20.0, 0.47, 0);  // to port: nothing
    }
  };
  mission::LockstepOptions o;
  o.drain_s = 2.0;
  (void)mission::run_lockstep(sc, scene, std::nullopt, {}, agent, o, hooks);
  REQUIRE(manta);
  CHECK_FALSE(none);
  CHECK(manta->centre.side == 1);
  CHECK(manta->centre.slant_m == Approx(std::hypot(20.0, 7.5 - 0.235)).margin(0.3));
  CHECK(manta->look_deg == Approx(90.0).margin(2.0));
}
