// Tests of the scene loader (config/loader/scene_loader.h): the reference file gives the
// defaults, and every section parses its values. The rules are in scene_loader_errors_test.cpp,
// the seeded randomized tests (docs/style.md habit 22) in scene_loader_random_test.cpp.
#include "config/loader/scene_loader.h"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/rng.h"
#include "config/default_scenario.h"
#include "config/loader/scenario_loader.h"
#include "sim/seabed/sediment.h"
#include "sim/targets/material.h"
#include "sim/targets/target_type.h"
#include "tests/config/scene_loader_checks.h"
#include "tests/support/temp_dir.h"

using sonarloop::Rng;
using sonarloop::RngStream;
using sonarloop::Vec2;
using sonarloop::Vec3;
using namespace sonarloop::config;
namespace scene = sonarloop::scene;
namespace seabed = sonarloop::seabed;
namespace targets = sonarloop::targets;
using namespace sonarloop::config::scene_loader_checks;

// ---------------------------------------------------------------------------------------------
// defaults

TEST_CASE("scene_loader: config/reference.yaml gives exactly the defaults") {
  // reference.yaml documents the whole scenario (scene keys and sonar:), so it is read by the
  // scenario loader; its scene part must be the scene defaults
  const auto s = load_scenario(SONARLOOP_SOURCE_DIR "/config/reference.yaml").scene;
  check_same(s, documented_defaults("reference"));
  // and an empty scenario gives the same
  check_same(parse_scene("", "empty.yaml"), documented_defaults("empty"));
  check_same(parse_scene("{}\n", "x/y/braces.yaml"), documented_defaults("braces"));
}

TEST_CASE("scene_loader: every scenario shipped in config/ loads, and the embedded default") {
  // directory listing at run time, so that a newly added scenario is checked too
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(SONARLOOP_SOURCE_DIR "/config")) {
    if (e.path().extension() == ".yaml") files.push_back(e.path());
  }
  CHECK(files.size() >= 2);
  for (const auto& f : files) {
    INFO(f.string());
    CHECK_NOTHROW(load_scenario(f.string()));
  }
  const auto embedded = parse_scenario(default_scenario_yaml(), "<default scenario>").scene;
  auto from_file = load_scenario(SONARLOOP_SOURCE_DIR "/config/default.yaml").scene;
  from_file.name = embedded.name;  // the name may come from the file stem
  check_same(embedded, from_file);
}

TEST_CASE("scene_loader: name, seed and load_scene from a file") {
  CHECK(parse_scene("name: harbour survey\n", "a.yaml").name == "harbour survey");
  CHECK(parse_scene("name: \"\"\n", "dir/b.yaml").name == "b");
  CHECK(parse_scene("seed: 18446744073709551615\n", "a.yaml").seed == 18446744073709551615ULL);

  sonarloop::testing::TempDir dir("config-scene-loader");
  {
    std::ofstream out(dir.file("wreck_site.yaml"));
    out << "seed: 7\nwater:\n  depth_m: 45\n";
  }
  const auto s = load_scene(dir.file("wreck_site.yaml"));
  CHECK(s.name == "wreck_site");
  CHECK(s.seed == 7);
  CHECK(s.water.depth_m == 45);

  try {
    load_scene(dir.file("missing.yaml"));
    FAIL("loaded a missing file");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(dir.file("missing.yaml") + ": (file): no such file", 0) == 0);
  }
  // errors in a loaded file name the file as given
  {
    std::ofstream out(dir.file("bad.yaml"));
    out << "water:\n  depth_m: 1\n";
  }
  try {
    load_scene(dir.file("bad.yaml"));
    FAIL("accepted depth_m 1");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(dir.file("bad.yaml") + ": water.depth_m: 1 is out of range",
                                      0) == 0);
  }
}

TEST_CASE("scene_loader: every section parses its values") {
  const std::string yaml = kFullScenario;
  const auto s = parse_scene(yaml, "full.yaml");
  CHECK(s.seed == 99);
  CHECK(s.origin.latitude_deg == -33.5);
  CHECK(s.origin.longitude_deg == 151.25);
  CHECK(s.water.temperature_c == 4);
  CHECK(s.water.salinity_ppt == 30);
  CHECK(s.water.ph == 7.5);
  CHECK(s.water.depth_m == 120);
  CHECK(s.seabed.origin_m == Vec2(-100, -200));
  CHECK(s.seabed.extent_m == Vec2(200, 400));
  CHECK(s.seabed.grid_spacing_m == 0.05);
  CHECK(s.seabed.elevation.slope == Vec2(0.01, -0.02));
  CHECK(s.seabed.elevation.rms_m == 1.5);
  CHECK(s.seabed.elevation.beta == 2.2);
  CHECK(s.seabed.elevation.outer_scale_m == 80);
  CHECK(s.seabed.elevation.inner_scale_m == 2);
  CHECK(s.seabed.elevation.spacing_m == 0.5);
  CHECK(s.seabed.partition.border_warp_m == 8);
  CHECK(s.seabed.partition.border_beta == 2.5);
  CHECK(s.seabed.partition.border_scale_m == 50);
  CHECK(s.seabed.partition.blend_width_m == 1);
  REQUIRE(s.seabed.regions.size() == 3);
  const auto& r0 = s.seabed.regions[0];
  CHECK(r0.sediment == sediment("fine_sand"));
  CHECK(r0.centre_m == Vec2(10, 10));
  REQUIRE(r0.texture.ripples);
  CHECK(r0.texture.ripples->wavelength_m == 0.8);
  CHECK(r0.texture.ripples->direction_deg == 90);
  CHECK(r0.texture.ripples->beta1 == 3);
  CHECK(r0.texture.ripples->beta == 2);
  CHECK(r0.texture.ripples->height_m == 0.05);
  CHECK_FALSE(r0.texture.rocky);
  REQUIRE(r0.texture.clutter);  // "clutter: {}" takes the defaults
  CHECK(r0.texture.clutter->density_per_m2 == scene::ClutterDesc{}.density_per_m2);
  CHECK(r0.texture.clutter->max_diameter_m == scene::ClutterDesc{}.max_diameter_m);
  const auto& r1 = s.seabed.regions[1];
  CHECK(r1.sediment == sediment("rock"));
  REQUIRE(r1.texture.rocky);  // "rocky:" with no value takes the defaults
  CHECK(r1.texture.rocky->anisotropy == scene::RockyDesc{}.anisotropy);
  REQUIRE(r1.texture.clutter);
  CHECK(r1.texture.clutter->density_per_m2 == 1);
  CHECK(r1.texture.clutter->median_diameter_m == 0.3);
  CHECK(r1.texture.clutter->sigma_ln == 0.2);
  CHECK(r1.texture.clutter->height_ratio == 0.4);
  CHECK(r1.texture.clutter->max_diameter_m == 0.9);
  const auto& r2 = s.seabed.regions[2];
  CHECK(r2.sediment == sediment("clay"));
  CHECK_FALSE(r2.texture.ripples);
  CHECK_FALSE(r2.texture.rocky);
  CHECK_FALSE(r2.texture.clutter);

  REQUIRE(s.targets.size() == 4);
  const auto& cyl = targets::target_type_info(targets::TargetType::kCylinder).size_m;
  CHECK(s.targets[0].name == "cylinder-1");
  CHECK(s.targets[0].type == targets::TargetType::kCylinder);
  CHECK(s.targets[0].position_m == Vec2(5, 5));
  CHECK(s.targets[0].heading_deg == 30);
  CHECK(s.targets[0].size_m == cyl);
  CHECK(s.targets[0].material.density_kg_m3 == targets::find_material("aluminium")->density_kg_m3);
  CHECK(s.targets[0].material.sound_speed_m_s ==
        targets::find_material("aluminium")->sound_speed_m_s);
  CHECK(s.targets[0].burial_m == 0.1);
  CHECK(s.targets[1].name == "crate");
  CHECK(s.targets[1].size_m == Vec3(1, 2, 0.5));
  CHECK(s.targets[1].material.density_kg_m3 == 900);
  CHECK(s.targets[1].material.sound_speed_m_s == scene::MaterialDesc{}.sound_speed_m_s);
  CHECK(s.targets[2].name == "cylinder-2");
  CHECK(s.targets[2].size_m == cyl * 2.0);
  CHECK(s.targets[2].position_m == Vec2(-100, 200));  // the extent's corner is inside
  CHECK(s.targets[3].name == "manta-1");
  CHECK(s.targets[3].type == targets::TargetType::kManta);
  CHECK(s.targets[3].size_m == targets::target_type_info(targets::TargetType::kManta).size_m);
  CHECK(s.targets[3].material.density_kg_m3 == 7850);
}

TEST_CASE("scene_loader: texture forms, sediment aliases, null sections") {
  auto texture_of = [](const std::string& t) {
    return parse_scene("seabed:\n  regions:\n    - texture: " + t + "\n", "t.yaml")
        .seabed.regions.at(0)
        .texture;
  };
  for (const char* flat : {"flat", "{}", "~", "\"flat\""}) {
    INFO(flat);
    const auto t = texture_of(flat);
    CHECK_FALSE(t.ripples);
    CHECK_FALSE(t.rocky);
    CHECK_FALSE(t.clutter);
  }
  const auto r = texture_of("{ripples: {}}");
  REQUIRE(r.ripples);
  CHECK(r.ripples->wavelength_m == 0.6);
  CHECK(r.ripples->direction_deg == 45.0);

  auto sediment_of = [](const std::string& name) {
    return parse_scene("seabed: {regions: [{sediment: " + name + "}]}", "s.yaml")
        .seabed.regions.at(0)
        .sediment;
  };
  CHECK(sediment_of("sand") == sediment("medium_sand"));
  CHECK(sediment_of("gravel") == sediment("cobble"));
  CHECK(sediment_of("Very-Fine-Sand") == sediment("very_fine_sand"));
  CHECK(sediment_of("clayey_silt") == sediment("fine_silt"));

  // sections with no value are empty maps or lists
  const auto s = parse_scene("origin:\nwater:\nseabed:\n  elevation:\ntargets:\n", "n.yaml");
  check_same(s, documented_defaults("n"));
}
