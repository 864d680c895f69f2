// The closed loop in lock-step (mission/lockstep.h): no ping dropped, the same contacts and
// pings on one or two render threads, contacts reach the agent, the loop ends after the plan.
#include "mission/lockstep.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "mission/agent_setup.h"
#include "sim/scene/scene.h"
#include "study/survey_score.h"
#include "tests/mission/mission_fixtures.h"

using namespace sonarloop;

namespace {

struct Flown {
  mission::LockstepResult result;
  std::size_t agent_objects = 0;
  double travelled_m = 0.0;
  std::string contacts;  // every contact's JSON line
};

Flown fly(int threads) {
  const Scenario sc = testing::two_targets_scenario();
  const scene::Scene scene(sc.scene);
  const mission::AgentSetup setup = mission::make_agent_setup(sc, testing::one_line());
  autonomy::Agent agent(setup.params, setup.survey, setup.start);
  mission::LockstepOptions o;
  o.threads = threads;
  o.drain_s = 5.0;
  atr::OnboardOptions onboard;
  onboard.detector.min_height_m = 0.12;  // the cylinder's shadow gives 0.18 m on this line
  Flown f;
  f.result = mission::run_lockstep(sc, scene, std::nullopt, onboard, agent, o);
  for (const atr::Contact& c : f.result.contacts)
    f.contacts += atr::contact_json(c) + "\n";
  f.agent_objects = agent.objects().size();
  f.travelled_m = agent.travelled_m();
  return f;
}

}  // namespace

TEST_CASE("lock-step: every ping flown, the same contacts on 1 or 2 threads, both targets seen") {
  const Flown one = fly(1);
  const Flown two = fly(2);
  const auto& p = one.result.pings;
  REQUIRE(p.size() > 100);
  // every ping of the mission, in order, none dropped: the stream's ping times are k * period
  const double period_s = p[1].t_s - p[0].t_s;
  for (std::size_t k = 0; k < p.size(); ++k)
    CHECK(p[k].t_s == Approx(static_cast<double>(k) * period_s).margin(1e-9));
  CHECK(one.result.onboard.receiver.pings == p.size());
  CHECK(one.result.onboard.receiver.lost == 0);
  // the same on two threads
  CHECK(two.result.pings.size() == p.size());
  CHECK(two.contacts == one.contacts);
  CHECK(two.travelled_m == one.travelled_m);
  // the survey line flown (80 m and the approach), then the drain
  CHECK(one.result.mission_s >= 40.0);
  CHECK_FALSE(one.result.stopped);
  // both targets among the contact stream's objects (no model: unclassified)
  const auto objects = study::stream_objects(one.result.contacts);
  int found = 0;
  for (const auto& [n, e] : {std::pair{0.0, 20.0}, std::pair{15.0, -20.0}}) {
    for (const auto& o : objects)
      if (std::hypot(o.north_m - n, o.east_m - e) < study::kSurveyMatchRadius_m) {
        ++found;
        break;
      }
  }
  CHECK(found == 2);
  CHECK(one.result.contacts.front().status == "no_model");
  // every contact reached the agent
  CHECK(one.agent_objects >= 2);
  CHECK(one.agent_objects <= one.result.contacts.size());
}

TEST_CASE("lock-step: a stop request ends the mission at the next batch") {
  const Scenario sc = testing::two_targets_scenario();
  const scene::Scene scene(sc.scene);
  const mission::AgentSetup setup = mission::make_agent_setup(sc, testing::one_line());
  autonomy::Agent agent(setup.params, setup.survey, setup.start);
  int batches = 0;
  mission::LockstepHooks hooks;
  hooks.on_batch = [&](const autonomy::Agent&) { ++batches; };
  hooks.stop_requested = [&] { return batches >= 3; };
  mission::LockstepOptions o;
  const auto r = mission::run_lockstep(sc, scene, std::nullopt, {}, agent, o, hooks);
  CHECK(r.stopped);
  CHECK(batches == 3);
  CHECK(r.mission_s == Approx(3 * o.batch_s));
  CHECK_THROWS_AS(([&] {
                    mission::LockstepOptions bad;
                    bad.threads = 0;
                    mission::run_lockstep(sc, scene, std::nullopt, {}, agent, bad);
                  }()),
                  std::invalid_argument);
}
