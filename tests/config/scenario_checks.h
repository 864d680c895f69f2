#pragma once
// Shared by the scenario, sonar and vehicle loader tests: the checks of a refused scenario or
// sonar document and the field-by-field comparison of two sonars.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "config/loader/scenario_loader.h"
#include "config/loader/sonar_loader.h"
#include "sim/render/sonar.h"
#include "tests/config/config_error_checks.h"

namespace sonarloop::testing {

// Parses `yaml` as "scenario.yaml", which must fail (check_config_error).
inline config::ConfigIssue expect_scenario_error(const std::string& yaml, const std::string& path,
                                                 const std::vector<std::string>& parts = {}) {
  return expect_config_error(config::parse_scenario, "scenario.yaml", yaml, path, parts);
}

// Parses `yaml` as a standalone sonar "sonar.yaml", which must fail (check_config_error).
inline config::ConfigIssue expect_sonar_error(const std::string& yaml, const std::string& path,
                                              const std::vector<std::string>& parts = {}) {
  return expect_config_error(config::parse_sonar, "sonar.yaml", yaml, path, parts);
}

// exact comparison, field by field
inline void check_same_sonar(const render::SonarDesc& a, const render::SonarDesc& b) {
  CHECK(a.name == b.name);
  CHECK(a.frequency_hz == b.frequency_hz);
  CHECK(a.source_level_db == b.source_level_db);
  CHECK(a.pulse_length_s == b.pulse_length_s);
  CHECK(a.chirp_bandwidth_hz == b.chirp_bandwidth_hz);
  CHECK(a.array_length_m == b.array_length_m);
  CHECK(a.array_height_m == b.array_height_m);
  CHECK(a.depression_deg == b.depression_deg);
  CHECK(a.max_range_m == b.max_range_m);
  CHECK(a.bin_size_m == b.bin_size_m);
  CHECK(a.ping_period_s == b.ping_period_s);
  CHECK(a.along_track == b.along_track);
  CHECK(a.along_track_resolution_m == b.along_track_resolution_m);
  CHECK(a.sample_type == b.sample_type);
  CHECK(a.tvg == b.tvg);
  CHECK(a.gain_db == b.gain_db);
  CHECK(a.bottom_model == b.bottom_model);
  CHECK(a.lambert_mu_db == b.lambert_mu_db);
  CHECK(a.target_specular_fraction == b.target_specular_fraction);
  CHECK(a.target_rms_slope == b.target_rms_slope);
  CHECK(a.speckle == b.speckle);
  CHECK(a.noise == b.noise);
  CHECK(a.speckle_model == b.speckle_model);
  CHECK(a.raw_samples_per_bin == b.raw_samples_per_bin);
  CHECK(a.downsample == b.downsample);
  CHECK(a.noise_floor_db_fs == b.noise_floor_db_fs);
  CHECK(a.ringdown_s == b.ringdown_s);
  CHECK(a.rays_per_bin == b.rays_per_bin);
  CHECK(a.along_track_rays == b.along_track_rays);
}

}  // namespace sonarloop::testing
