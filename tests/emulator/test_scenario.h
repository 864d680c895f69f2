#pragma once
// A small scenario for the emulator's tests: a 60 m x 60 m seabed at 5 cm, a 20 m range sonar
// (400 samples per side, a ping every 26.7 ms), a vehicle flying a 50 m straight line north at
// 2 m/s and constant depth, with navigation errors. Quick to build and to render.
#include <string>

namespace sonarloop::testing {

inline std::string small_scenario_yaml() {
  return R"(seed: 7
name: emulator-test
water: {depth_m: 20.0}
seabed:
  origin_m: [-30.0, -30.0]
  extent_m: [60.0, 60.0]
  grid_spacing_m: 0.05
  elevation: {rms_m: 0.1, beta: 1.8, outer_scale_m: 20.0}
  regions:
    - sediment: very_fine_sand
      centre_m: [0.0, 0.0]
      texture: flat
targets:
  - {type: cylinder, position_m: [0.0, 8.0], heading_deg: 30.0}
sonar:
  preset: pailhas_strip
  max_range_m: 20
  bin_size_cm: 5
vehicle:
  trajectory:
    kind: straight
    start_m: [-25.0, 0.0]
    heading_deg: 0.0
    length_m: 50.0
    speed_m_s: 2.0
    depth: {mode: depth, depth_m: 14.0}
  nav:
    position_noise_m: 0.1
    position_drift_m_per_sqrt_s: 0.05
    heading_bias_deg: 0.5
    heading_noise_deg: 0.2
    attitude_noise_deg: 0.05
    speed_noise_m_s: 0.01
    yaw_rate_noise_deg_s: 0.05
    depth_noise_m: 0.02
)";
}

}  // namespace sonarloop::testing
