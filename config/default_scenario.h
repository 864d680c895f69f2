#pragma once
// config/default.yaml and the built-in scenarios, embedded in the binary at build time so that
// `sonarloop run` and friends work with no file at hand.
#include <string>
#include <utility>
#include <vector>

namespace sonarloop::config {

const std::string& default_scenario_yaml();

// The built-in scenarios (name, YAML text), in config/CMakeLists.txt's order: mission_20 and the
// survey scenarios of each seabed kind (survey_flat, survey_ripples, survey_clutter,
// survey_rocky), so that commands can name them without the files at hand.
const std::vector<std::pair<std::string, std::string>>& builtin_scenarios();

}  // namespace sonarloop::config
