#include "config/loader/scenario_loader.h"

#include "config/loader/scene_loader.h"
#include "config/loader/sonar_loader.h"
#include "config/loader/vehicle_loader.h"

namespace sonarloop::config {

Scenario parse_scenario_node(const Field& f) {
  f.expect_map("a map with seed, name, origin, water, seabed, targets, " +
               std::string(kScenarioSections));
  Scenario s;
  s.scene = parse_scene_node(f, /*check_unknown_keys=*/false);
  // one line per section beside the scene keys (keep kScenarioSections in step)
  s.sonar = parse_sonar_node(f.child("sonar"));
  const Field vehicle = f.child("vehicle");
  s.vehicle = parse_vehicle_node(vehicle);
  f.finish();
  // rules between sections
  check_vehicle_over_seabed(vehicle, s.vehicle, s.scene.seabed);
  return s;
}

Scenario parse_scenario(const std::string& yaml_text, const std::string& source_name) {
  return with_yaml_errors(
      source_name, [&] { return parse_scenario_node(parse_document(yaml_text, source_name)); });
}

Scenario load_scenario(const std::string& path) {
  return parse_scenario(read_text_file(path), path);
}

}  // namespace sonarloop::config
