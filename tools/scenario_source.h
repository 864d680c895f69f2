#pragma once
// Where a subcommand's scenario comes from: a YAML file, or the embedded default scenario
// (config/default.yaml compiled into the binary) when no file is given.
#include <optional>
#include <string>

#include "config/loader/scenario_loader.h"
#include "sim/scene/scene_desc.h"

namespace sonarloop::tools {

// Loads `path` (scene and sonar), or the embedded default scenario if path is empty; a path that
// is no file but the name of a built-in scenario (config/default_scenario.h: mission_20,
// survey_flat, ...) loads that one. Throws config::ConfigError.
config::Scenario load_scenario_or_default(const std::optional<std::string>& path);

// The scene part of load_scenario_or_default(path).
scene::SceneDesc load_scene_or_default(const std::optional<std::string>& path);

}  // namespace sonarloop::tools
