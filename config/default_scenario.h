#pragma once
// config/default.yaml, embedded in the binary at build time so that `sonarloop run` and
// friends work with no file at hand.
#include <string>

namespace sonarloop::config {

const std::string& default_scenario_yaml();

}  // namespace sonarloop::config
