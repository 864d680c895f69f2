#pragma once
// A whole scenario as the simulation runs it: the scene (seabed, water, targets), the sonar and
// the vehicle. The emulator and the offline tools take this; config/loader/scenario_loader.h
// reads it from YAML (config::Scenario is this type), so the emulator needs no YAML.
#include "sim/render/sonar.h"
#include "sim/scene/scene_desc.h"
#include "sim/vehicle/vehicle_desc.h"

namespace sonarloop {

struct Scenario {
  scene::SceneDesc scene;        // the top-level scene keys
  render::SonarDesc sonar;       // sonar: (default: the kDefaultSonarPreset preset)
  vehicle::VehicleDesc vehicle;  // vehicle: (default: VehicleDesc{})
};

}  // namespace sonarloop
