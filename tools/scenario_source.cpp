#include "tools/scenario_source.h"

#include <filesystem>

#include "config/default_scenario.h"

namespace sonarloop::tools {

config::Scenario load_scenario_or_default(const std::optional<std::string>& path) {
  if (path && !path->empty()) {
    if (!std::filesystem::exists(*path)) {
      for (const auto& [name, yaml] : config::builtin_scenarios())
        if (name == *path) return config::parse_scenario(yaml, name + ".yaml");
    }
    return config::load_scenario(*path);
  }
  return config::parse_scenario(config::default_scenario_yaml(), "default.yaml");
}

scene::SceneDesc load_scene_or_default(const std::optional<std::string>& path) {
  return load_scenario_or_default(path).scene;
}

}  // namespace sonarloop::tools
