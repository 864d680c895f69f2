#pragma once
// The pailhas_strip preset (config/sonars/pailhas_strip.yaml) as a SonarDesc built in code, for
// the renderer's tests, which do not link the YAML loader (config/ is a layer above sim/).
// tests/config/sonar_loader_test.cpp checks that the preset loads to exactly this.
#include "sim/render/sonar.h"

namespace sonarloop::testing {

inline render::SonarDesc pailhas_strip_sonar() {
  render::SonarDesc s;
  s.name = "pailhas_strip";
  s.frequency_hz = 300e3;
  s.source_level_db = 210.0;
  s.pulse_length_s = 0.0;
  s.chirp_bandwidth_hz = 0.0;
  s.array_length_m = 0.5;
  s.array_height_m = 0.006;
  s.depression_deg = 15.0;
  s.max_range_m = 50.0;
  s.bin_size_m = 0.05;
  s.ping_period_s = 0.0;
  s.along_track = render::AlongTrackModel::kStrip;
  s.along_track_resolution_m = 0.05;
  s.sample_type = render::SampleType::kUint16;
  s.tvg.reset();  // auto
  s.gain_db = 0.0;
  s.bottom_model = acoustics::BottomModel::kApl;
  s.lambert_mu_db = -27.0;
  s.target_specular_fraction = 0.0;
  s.target_rms_slope = 0.15;
  s.speckle = true;
  s.noise = true;
  s.rays_per_bin = 0;
  s.along_track_rays = 0;
  return s;
}

}  // namespace sonarloop::testing
