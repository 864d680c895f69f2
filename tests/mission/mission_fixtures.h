#pragma once
// The lock-step mission tests' scenario: tests/data/autonomy/two_targets.yaml (a Manta 20 m to
// starboard and a cylinder 20 m to port of one survey line along east = 0, north -40 to 40),
// flown as a survey of that line only.
#include <string>

#include "config/loader/scenario_loader.h"
#include "mission/agent_setup.h"

namespace sonarloop::testing {

inline Scenario two_targets_scenario() {
  return config::load_scenario(std::string(SONARLOOP_SOURCE_DIR) +
                               "/tests/data/autonomy/two_targets.yaml");
}

// The one line, no re-looks.
inline mission::AgentOverrides one_line() {
  mission::AgentOverrides o;
  o.area = autonomy::SurveyArea{{-40.0, -20.0}, {40.0, 20.0}};
  o.line_spacing_m = 40.0;
  o.relooks = false;
  return o;
}

}  // namespace sonarloop::testing
