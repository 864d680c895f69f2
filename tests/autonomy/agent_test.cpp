// The agent's brain without sockets: a survey, a synthetic uncertain contact reported when the
// vehicle passes an object, a re-look flown at ~90° and the pass range, a second look that
// confirms it, and the survey finished.
#include <catch2/catch.hpp>

#include <cmath>

#include "autonomy/agent.h"

using namespace sonarloop;
using namespace sonarloop::autonomy;

namespace {

// A look at the object from wherever the vehicle is: classified "manta" with a small margin.
atr::Contact contact_seen(std::uint64_t id, Point2 object, const VehicleState& s) {
  atr::Contact c;
  c.id = id;
  c.north_m = object.north_m;
  c.east_m = object.east_m;
  const Point2 right = direction(s.heading_rad + 0.5 * std::numbers::pi);
  const Point2 rel = object - s.position;
  const double cross = rel.north_m * right.north_m + rel.east_m * right.east_m;
  c.side = cross > 0 ? 1 : 0;
  c.ground_range_m = std::fabs(cross);
  c.class_name = "manta";
  c.mine_like = true;
  c.scores = {{"manta", 40.0}, {"rockan", 40.4}};
  c.distance = 40.0;
  c.runner_up = "rockan";
  c.runner_up_distance = 40.4;
  c.mine_distance = c.non_mine_distance = std::nan("");
  return c;
}

// Along-track distance of the object ahead of the vehicle.
double along(Point2 object, const VehicleState& s) {
  const Point2 d = direction(s.heading_rad);
  const Point2 rel = object - s.position;
  return rel.north_m * d.north_m + rel.east_m * d.east_m;
}

// A survey with one object: its contacts reported 3 s after each pass within the swath (at most
// max_reports), "manta" and "rockan" in turn when `alternate` (two looks that disagree leave it
// uncertain); flown until done (or 4000 s) over a flat seabed at 22.5 m.
struct Flight {
  double survey_end_s = -1.0;  // when the survey's last leg ended
  int reported = 0;
};

Flight fly_survey(Agent& agent, Point2 object, bool alternate = true, int max_reports = 3) {
  Flight f;
  std::uint64_t next_id = 1;
  double due_s = -1.0;
  double previous_along = along(object, agent.state());
  while (!agent.mission_done() && agent.state().t_s < 4000) {
    const bool surveying = !agent.plan().done() && agent.plan().current().kind == LegKind::kSurvey;
    agent.step(0.5, 22.5);
    const VehicleState& s = agent.state();
    if (surveying && (agent.plan().done() || agent.plan().current().kind != LegKind::kSurvey) &&
        f.survey_end_s < 0) {
      f.survey_end_s = s.t_s;
    }
    const double a = along(object, s);
    if (previous_along > 0 && a <= 0 && distance_m(s.position, object) < 45.0 &&
        f.reported < max_reports)
      due_s = s.t_s + 3.0;
    previous_along = a;
    if (due_s > 0 && s.t_s >= due_s) {
      atr::Contact c = contact_seen(next_id++, object, s);
      if (alternate && next_id % 2 == 1) {  // the second, fourth ... look: the runner-up first
        c.class_name = "rockan";
        c.scores = {{"manta", 40.4}, {"rockan", 40.0}};
        c.runner_up = "manta";
      }
      agent.on_contact(c);
      ++f.reported;
      due_s = -1.0;
    }
  }
  return f;
}

// An agent on a 100 m leg north from the origin, 20 s into it.
Agent one_leg_agent(const AgentParams& p) {
  Agent agent(p, {Leg{{0, 0}, {100, 0}}}, VehicleState{});
  for (int i = 0; i < 20; ++i)
    agent.step(1.0, std::nullopt);
  return agent;
}

}  // namespace

TEST_CASE("immediate: an uncertain contact is re-looked from ~90 degrees and confirmed") {
  AgentParams p;
  p.relook_timing = RelookTiming::kImmediate;
  p.margin_threshold = 0.05;  // the contacts' margin is 0.01: uncertain
  const SurveyArea area{{-100, -60}, {100, 60}};
  p.bounds = area;
  VehicleState start;
  start.position = {-100, -40};
  start.depth_m = 15.0;
  Agent agent(p, lawnmower(area, 40.0), start);
  const Point2 object{0.0, -20.0};    // 20 m to starboard of the first line (east -40)
  const double report_delay_s = 3.0;  // the onboard consumer's latency after the pass
  (void)fly_survey(agent, object, false, 2);
  CHECK(agent.mission_done());
  CHECK(agent.state().depth_m == Approx(15.0).margin(0.01));
  REQUIRE(agent.objects().size() == 1);
  const AgentObject& o = agent.objects()[0];
  CHECK(o.looks.size() >= 2);
  CHECK(o.decision.state == FinalState::kConfirmed);
  CHECK(o.decision.fused.class_name == "manta");
  REQUIRE(agent.relooks().size() == 1);
  const RelookRecord& r = agent.relooks()[0];
  CHECK(r.passed);
  CHECK(r.second_look);
  CHECK(degrees(r.first_heading_rad) == Approx(0.0).margin(2.0));  // the first line goes north
  CHECK(degrees(heading_difference_rad(r.pass_heading_rad, r.first_heading_rad)) ==
        Approx(90.0).margin(5.0));
  CHECK(r.pass_range_m == Approx(p.relook.pass_range_m).margin(1.0));
  CHECK(r.inserted_t_s - r.look_t_s == Approx(report_delay_s).margin(1.0));
  CHECK(agent.detour_distance_m() > p.relook.run_in_m);
  CHECK(agent.detour_time_s() ==
        Approx(agent.detour_distance_m() / p.vehicle.speed_m_s).epsilon(0.01));
  // the survey still ends at the last line's end
  CHECK(distance_m(agent.state().position, {100, 40}) < 10.0);
}

TEST_CASE("without re-looks the object keeps its uncertain first decision") {
  AgentParams p;
  p.relooks = false;
  Agent agent = one_leg_agent(p);
  agent.on_contact(contact_seen(1, {30.0, 20.0}, agent.state()));
  CHECK(agent.relooks().empty());
  REQUIRE(agent.objects().size() == 1);
  CHECK(agent.objects()[0].decision.state == FinalState::kUncertain);
  CHECK_FALSE(agent.take_events().empty());
}

TEST_CASE("an object non-mine either way is not re-looked, unless every doubt is") {
  // a rock unsure between the two hemispheres: class margin 0.01, but the non-mine group is 20 %
  // nearer than the mine-like one
  auto rock_seen = [](const VehicleState& s) {
    atr::Contact c = contact_seen(1, {30.0, 20.0}, s);
    c.class_name = "small_hemisphere";
    c.mine_like = false;
    c.scores = {{"small_hemisphere", 40.0}, {"hemisphere", 40.4}, {"manta", 48.0}};
    c.distance = 40.0;
    c.runner_up = "hemisphere";
    c.runner_up_distance = 40.4;
    c.non_mine_distance = 40.0;
    c.mine_distance = 48.0;
    return c;
  };
  for (const bool relook_all : {false, true}) {
    AgentParams p;
    p.relook_timing = RelookTiming::kImmediate;
    p.relook_mine_relevant_only = !relook_all;
    Agent agent = one_leg_agent(p);
    agent.on_contact(rock_seen(agent.state()));
    REQUIRE(agent.objects().size() == 1);
    CHECK(agent.objects()[0].decision.state == FinalState::kUncertain);
    CHECK(agent.objects()[0].decision.fused.mine_margin == Approx(0.2));
    CHECK(agent.relooks().size() == (relook_all ? 1u : 0u));
  }
  // a mine-like uncertain object is re-looked by default (the first test case), and so is a
  // non-mine one whose mine margin is itself below the threshold
  AgentParams p;
  p.relook_timing = RelookTiming::kImmediate;
  Agent agent = one_leg_agent(p);
  atr::Contact close = rock_seen(agent.state());
  close.mine_distance = 41.0;  // mine margin 0.025 < 0.05
  agent.on_contact(close);
  CHECK(agent.relooks().size() == 1);
}

TEST_CASE("after the survey: the survey is flown to its end, then the uncertain object") {
  AgentParams p;
  p.margin_threshold = 0.05;  // the contacts' margin is 0.01: uncertain
  const SurveyArea area{{-100, -60}, {100, 60}};
  p.bounds = area;
  VehicleState start;
  start.position = {-100, -40};
  start.depth_m = 15.0;
  const std::vector<Leg> survey = lawnmower(area, 40.0);
  Agent agent(p, survey, start);
  const Point2 object{0.0, -20.0};
  const Flight f = fly_survey(agent, object);
  CHECK(agent.mission_done());
  REQUIRE(agent.relooks().size() == 1);
  const RelookRecord& r = agent.relooks()[0];
  // inserted once the survey was done: after the vehicle reached the last line's end
  CHECK(r.inserted_t_s >= f.survey_end_s - 1.0);
  CHECK(r.passed);
  CHECK(r.second_look);
  CHECK(degrees(heading_difference_rad(r.pass_heading_rad, r.first_heading_rad)) ==
        Approx(90.0).margin(5.0));
  // the survey's lines saw it twice (lines 20 m either side), the re-look a third time
  REQUIRE(agent.objects().size() == 1);
  CHECK(agent.objects()[0].looks.size() >= 2);
  // the re-look's time is the detour, within the (unlimited) budget
  CHECK(agent.detour_time_s() > 0.0);
}

TEST_CASE("after the survey: a re-look that does not fit the budget is not flown") {
  AgentParams p;
  p.margin_threshold = 0.05;
  p.relook_budget_s = 30.0;  // a re-look costs a few minutes
  const SurveyArea area{{-100, -60}, {100, 60}};
  p.bounds = area;
  VehicleState start;
  start.position = {-100, -40};
  start.depth_m = 15.0;
  Agent agent(p, lawnmower(area, 40.0), start);
  (void)fly_survey(agent, {0.0, -20.0});
  CHECK(agent.mission_done());
  CHECK(agent.relooks().empty());
  REQUIRE(agent.objects().size() == 1);
  CHECK(agent.objects()[0].relook_over_budget);
  CHECK(agent.detour_time_s() == 0.0);
  bool said = false;
  for (const std::string& e : agent.take_events())
    said = said || e.find("budget") != std::string::npos;
  CHECK(said);
}

TEST_CASE("an object the gate doubts is uncertain however sure its class") {
  AgentParams p;
  p.relooks = false;
  Agent agent = one_leg_agent(p);
  atr::Contact c = contact_seen(1, {30.0, 20.0}, agent.state());
  c.runner_up_distance = 48.0;  // margin 0.2: sure of "manta"
  c.target_probability = 0.3;   // but maybe not a target at all
  agent.on_contact(c);
  REQUIRE(agent.objects().size() == 1);
  CHECK(agent.objects()[0].decision.state == FinalState::kUncertain);
  CHECK(agent.objects()[0].decision.fused.target_probability == Approx(0.3));
  c.id = 2;
  c.target_probability = 0.9;  // a second look: mean log-odds of 0.3 and 0.9 -> 0.66
  agent.on_contact(c);
  REQUIRE(agent.objects().size() == 1);
  CHECK(agent.objects()[0].decision.fused.target_probability ==
        Approx(1.0 / (1.0 + std::sqrt((0.7 / 0.3) * (0.1 / 0.9)))));
  CHECK(agent.objects()[0].decision.state == FinalState::kConfirmed);
}

TEST_CASE("a contact id is one look: a repeat is ignored, same content or not, and counted") {
  AgentParams p;
  p.relooks = false;
  Agent agent = one_leg_agent(p);
  const atr::Contact c = contact_seen(7, {30.0, 20.0}, agent.state());
  agent.on_contact(c);
  agent.take_events();
  // the same datagram delivered twice: still one look, the decision unchanged
  agent.on_contact(c);
  REQUIRE(agent.objects().size() == 1);
  CHECK(agent.objects()[0].looks.size() == 1);
  CHECK(agent.objects()[0].decision.state == FinalState::kUncertain);
  CHECK(agent.duplicate_contacts() == 1);
  CHECK(agent.take_events().empty());
  // the id again with another class: ignored, said once
  atr::Contact other = c;
  other.class_name = "rockan";
  agent.on_contact(other);
  CHECK(agent.objects()[0].looks.size() == 1);
  CHECK(agent.conflicting_contacts() == 1);
  const std::vector<std::string> events = agent.take_events();
  REQUIRE(events.size() == 1);
  CHECK_THAT(events[0], Catch::Contains("contact 7 reported again with other content"));
  // a new id is a second look
  agent.on_contact(contact_seen(8, {30.0, 20.0}, agent.state()));
  CHECK(agent.objects()[0].looks.size() == 2);
}
