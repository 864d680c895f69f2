#pragma once
// Loads a whole scenario file: the scene keys at the top level (seed, name, origin, water,
// seabed, targets: scene_loader.h) beside one section per further part of the simulation:
//   sonar:   a built-in preset name or a sonar map (sonar_loader.h); absent = the
//            kDefaultSonarPreset preset.
//   vehicle: the mission trajectory and the navigation errors (vehicle_loader.h); absent =
//            VehicleDesc{}. Checked against the scene: in altitude mode the planned path must
//            stay over the seabed extent (check_vehicle_over_seabed).
//   memory_limit_gb: the memory the scenario may need by the estimate of
//            sim/scene/memory_estimate.h (default 4, 0.1 .. 10000); a larger scenario is refused
//            before anything large is allocated: a target list too long for it before its
//            entries are read, otherwise once every section is read, naming the key of the
//            largest part (targets, seabed.grid_spacing_m or sonar), the estimate and the limit.
// Every key is documented in config/reference.yaml. Unknown top-level keys are reported together
// (one ConfigError listing each, with suggestions), after the sections have been read.
//
// Adding a section (e.g. `vehicle:`): a member of Scenario (sim/scenario.h), one line in
// parse_scenario_node that reads f.child("<key>") with its own parser, and the key in
// kScenarioSections.
#include <string>
#include <string_view>

#include "config/loader/yaml_fields.h"
#include "sim/scenario.h"

namespace sonarloop::config {

// The scenario type is the simulation's own (sim/scenario.h); the loader fills it.
using Scenario = sonarloop::Scenario;

// The top-level keys of a scenario besides the scene keys, comma-separated in reference order
// (for the "allowed" text of a document that is not a map).
inline constexpr std::string_view kScenarioSections = "sonar, vehicle, memory_limit_gb";

// Parses the scenario map `f` (the root of a document).
Scenario parse_scenario_node(const Field& f);

// Parses scenario text; `source_name` is used in messages and for the default scene name.
Scenario parse_scenario(const std::string& yaml_text, const std::string& source_name);

// Reads and parses a scenario file. A missing file -> ConfigError "<path>: (file): no such file".
Scenario load_scenario(const std::string& path);

}  // namespace sonarloop::config
