#pragma once
// The example agent's set-up for a scenario (docs/autonomy.md): its survey area and lawnmower,
// its vehicle (speed, turn rate, climb rate, altitude) and re-look settings from the scenario,
// with the options a user may override. Shared by `sonarloop autonomy` (on the wire) and the
// lock-step mission (mission/lockstep.h), so that both fly the same plan.
#include <optional>
#include <vector>

#include "autonomy/agent.h"
#include "autonomy/survey.h"
#include "common/geodesy.h"
#include "sim/scenario.h"

namespace sonarloop::mission {

// What the user may set; unset values come from the scenario.
struct AgentOverrides {
  std::optional<autonomy::SurveyArea> area;  // default: the seabed less area_margin_m
  double area_margin_m = 50.0;
  double line_spacing_m = 40.0;
  std::optional<double> speed_m_s;
  std::optional<double> altitude_m;
  std::optional<double> pass_range_m;
  std::optional<double> threshold;
  bool relooks = true;
  bool relook_all = false;
  int max_relooks = 1 << 30;
  autonomy::RelookTiming relook_timing = autonomy::RelookTiming::kAfterSurvey;
  // after the survey: re-looks may take this fraction of the survey's planned time (0.5: the
  // mission at most 1.5 times the survey); infinity: no limit
  double relook_budget_fraction = 0.5;
};

struct AgentSetup {
  autonomy::AgentParams params;
  autonomy::SurveyArea area;
  GeoPoint origin;
  std::vector<autonomy::Leg> survey;
  autonomy::VehicleState start;  // at the first leg's start, on its heading, at altitude
};

// Throws std::invalid_argument when the margin leaves no area or the spacing is not > 0.
AgentSetup make_agent_setup(const Scenario& scenario, const AgentOverrides& o);

}  // namespace sonarloop::mission
