#pragma once
// Shared by the scene loader's tests (scene_loader_test.cpp: defaults and values,
// scene_loader_errors_test.cpp: every rule, scene_loader_random_test.cpp: the seeded randomized
// tests, with scene_yaml_tree.h): the error check, field-by-field comparison and a scenario that
// sets every key.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "config/loader/scene_loader.h"
#include "sim/seabed/sediment.h"
#include "tests/config/config_error_checks.h"

namespace sonarloop::config::scene_loader_checks {

namespace scene = sonarloop::scene;
namespace seabed = sonarloop::seabed;
using sonarloop::testing::contains;

// Parses `yaml` as "scenario.yaml", which must fail (testing::check_config_error).
inline ConfigIssue expect_error(const std::string& yaml, const std::string& path,
                                const std::vector<std::string>& parts = {}) {
  return sonarloop::testing::expect_config_error(parse_scene, "scenario.yaml", yaml, path, parts);
}

// --- field-by-field comparison ---------------------------------------------------------------

inline void check_same(const scene::RegionDesc& a, const scene::RegionDesc& b) {
  CHECK(a.sediment == b.sediment);
  CHECK(a.centre_m == b.centre_m);
  REQUIRE(a.texture.ripples.has_value() == b.texture.ripples.has_value());
  if (a.texture.ripples) {
    CHECK(a.texture.ripples->wavelength_m == b.texture.ripples->wavelength_m);
    CHECK(a.texture.ripples->direction_deg == b.texture.ripples->direction_deg);
    CHECK(a.texture.ripples->beta1 == b.texture.ripples->beta1);
    CHECK(a.texture.ripples->beta == b.texture.ripples->beta);
    CHECK(a.texture.ripples->height_m == b.texture.ripples->height_m);
  }
  REQUIRE(a.texture.rocky.has_value() == b.texture.rocky.has_value());
  if (a.texture.rocky) {
    CHECK(a.texture.rocky->rms_m == b.texture.rocky->rms_m);
    CHECK(a.texture.rocky->beta == b.texture.rocky->beta);
    CHECK(a.texture.rocky->anisotropy == b.texture.rocky->anisotropy);
    CHECK(a.texture.rocky->direction_deg == b.texture.rocky->direction_deg);
    CHECK(a.texture.rocky->outer_scale_m == b.texture.rocky->outer_scale_m);
  }
  REQUIRE(a.texture.clutter.has_value() == b.texture.clutter.has_value());
  if (a.texture.clutter) {
    CHECK(a.texture.clutter->density_per_m2 == b.texture.clutter->density_per_m2);
    CHECK(a.texture.clutter->median_diameter_m == b.texture.clutter->median_diameter_m);
    CHECK(a.texture.clutter->sigma_ln == b.texture.clutter->sigma_ln);
    CHECK(a.texture.clutter->height_ratio == b.texture.clutter->height_ratio);
    CHECK(a.texture.clutter->max_diameter_m == b.texture.clutter->max_diameter_m);
  }
}

inline void check_same(const scene::TargetDesc& a, const scene::TargetDesc& b) {
  CHECK(a.name == b.name);
  CHECK(a.type == b.type);
  CHECK(a.position_m == b.position_m);
  CHECK(a.heading_deg == b.heading_deg);
  CHECK(a.size_m == b.size_m);
  CHECK(a.material.density_kg_m3 == b.material.density_kg_m3);
  CHECK(a.material.sound_speed_m_s == b.material.sound_speed_m_s);
  CHECK(a.burial_m == b.burial_m);
}

inline void check_same(const scene::SceneDesc& a, const scene::SceneDesc& b) {
  CHECK(a.seed == b.seed);
  CHECK(a.name == b.name);
  CHECK(a.origin.latitude_deg == b.origin.latitude_deg);
  CHECK(a.origin.longitude_deg == b.origin.longitude_deg);
  CHECK(a.water.temperature_c == b.water.temperature_c);
  CHECK(a.water.salinity_ppt == b.water.salinity_ppt);
  CHECK(a.water.ph == b.water.ph);
  CHECK(a.water.depth_m == b.water.depth_m);
  const auto& sa = a.seabed;
  const auto& sb = b.seabed;
  CHECK(sa.origin_m == sb.origin_m);
  CHECK(sa.extent_m == sb.extent_m);
  CHECK(sa.grid_spacing_m == sb.grid_spacing_m);
  CHECK(sa.elevation.slope == sb.elevation.slope);
  CHECK(sa.elevation.rms_m == sb.elevation.rms_m);
  CHECK(sa.elevation.beta == sb.elevation.beta);
  CHECK(sa.elevation.outer_scale_m == sb.elevation.outer_scale_m);
  CHECK(sa.elevation.inner_scale_m == sb.elevation.inner_scale_m);
  CHECK(sa.elevation.spacing_m == sb.elevation.spacing_m);
  CHECK(sa.partition.border_warp_m == sb.partition.border_warp_m);
  CHECK(sa.partition.border_beta == sb.partition.border_beta);
  CHECK(sa.partition.border_scale_m == sb.partition.border_scale_m);
  CHECK(sa.partition.blend_width_m == sb.partition.blend_width_m);
  REQUIRE(sa.regions.size() == sb.regions.size());
  for (std::size_t i = 0; i < sa.regions.size(); ++i) {
    INFO("region " << i);
    check_same(sa.regions[i], sb.regions[i]);
  }
  REQUIRE(a.targets.size() == b.targets.size());
  for (std::size_t i = 0; i < a.targets.size(); ++i) {
    INFO("target " << i);
    check_same(a.targets[i], b.targets[i]);
  }
}

inline seabed::SedimentId sediment(const char* name) {
  return *seabed::find_sediment(name);
}

inline scene::SceneDesc documented_defaults(const std::string& name) {
  scene::SceneDesc d;
  d.name = name;
  scene::RegionDesc r;
  r.sediment = sediment("medium_sand");
  d.seabed.regions = {r};
  return d;
}

// A scenario that sets every key somewhere.
inline const std::string kFullScenario = R"(seed: 99
origin: {latitude_deg: -33.5, longitude_deg: 151.25}
water: {temperature_c: 4, salinity_ppt: 30, ph: 7.5, depth_m: 120}
seabed:
  origin_m: [-100, -200]
  extent_m: [200, 400]
  grid_spacing_m: 0.05
  elevation:
    slope: [0.01, -0.02]
    rms_m: 1.5
    beta: 2.2
    outer_scale_m: 80
    inner_scale_m: 2
    spacing_m: 0.5
  partition: {border_warp_m: 8, border_beta: 2.5, border_scale_m: 50, blend_width_m: 1}
  regions:
    - sediment: Fine Sand
      centre_m: [10, 10]
      texture:
        ripples: {wavelength_m: 0.8, direction_deg: 90, beta1: 3, beta: 2, height_m: 0.05}
        clutter: {}
    - sediment: rock
      centre_m: [-10, 10]
      texture:
        rocky:
        clutter: {density_per_m2: 1, median_diameter_m: 0.3, sigma_ln: 0.2, height_ratio: 0.4,
                  max_diameter_m: 0.9}
    - {sediment: clay, centre_m: [0, -50], texture: {}}
targets:
  - {type: cylinder, position_m: [5, 5], heading_deg: 30, material: aluminium, burial_m: 0.1}
  - {type: box, name: crate, position_m: [0, 0], size_m: [1, 2, 0.5], material: {density_kg_m3: 900}}
  - {type: cylinder, scale: 2, position_m: [-100, 200]}
  - {position_m: [1, 1]}
)";

}  // namespace sonarloop::config::scene_loader_checks
