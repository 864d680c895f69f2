// Tests of the scene loader (config/loader/scene_loader.h): the reference file gives the
// defaults, every validation rule has a case, and a seeded randomized test (docs/style.md habit 22)
// round-trips random valid scenarios and checks that single-key corruptions are always rejected
// with a ConfigError.
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

#include "config/default_scenario.h"
#include "config/loader/scenario_loader.h"
#include "sim/core/rng.h"
#include "sim/seabed/sediment.h"
#include "sim/targets/material.h"
#include "sim/targets/target_type.h"
#include "tests/support/temp_dir.h"

using sonarloop::Rng;
using sonarloop::RngStream;
using sonarloop::Vec2;
using sonarloop::Vec3;
using namespace sonarloop::config;
namespace scene = sonarloop::scene;
namespace seabed = sonarloop::seabed;
namespace targets = sonarloop::targets;

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Parses `yaml` as "scenario.yaml", which must fail; checks the message form and that the
// first issue is at `path` with every `parts` string somewhere in the message.
ConfigIssue expect_error(const std::string& yaml, const std::string& path,
                         const std::vector<std::string>& parts = {}) {
  INFO("yaml:\n" << yaml);
  try {
    parse_scene(yaml, "scenario.yaml");
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    INFO("message: " << msg);
    const std::string shown = path.empty() ? "(top level)" : path;
    CHECK(msg.rfind("scenario.yaml: " + shown + ": ", 0) == 0);
    CHECK(e.first().path == path);
    CHECK(contains(msg, "; allowed: "));
    for (const auto& p : parts)
      CHECK(contains(msg, p));
    return e.first();
  }
  FAIL("accepted");
  return {};
}

// --- field-by-field comparison ---------------------------------------------------------------

void check_same(const scene::RegionDesc& a, const scene::RegionDesc& b) {
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

void check_same(const scene::TargetDesc& a, const scene::TargetDesc& b) {
  CHECK(a.name == b.name);
  CHECK(a.type == b.type);
  CHECK(a.position_m == b.position_m);
  CHECK(a.heading_deg == b.heading_deg);
  CHECK(a.size_m == b.size_m);
  CHECK(a.material.density_kg_m3 == b.material.density_kg_m3);
  CHECK(a.material.sound_speed_m_s == b.material.sound_speed_m_s);
  CHECK(a.burial_m == b.burial_m);
}

void check_same(const scene::SceneDesc& a, const scene::SceneDesc& b) {
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

seabed::SedimentId sediment(const char* name) {
  return *seabed::find_sediment(name);
}

scene::SceneDesc documented_defaults(const std::string& name) {
  scene::SceneDesc d;
  d.name = name;
  scene::RegionDesc r;
  r.sediment = sediment("medium_sand");
  d.seabed.regions = {r};
  return d;
}

}  // namespace

namespace {

// A scenario that sets every key somewhere.
const std::string kFullScenario = R"(seed: 99
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

}  // namespace

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

// ---------------------------------------------------------------------------------------------
// validation rules

TEST_CASE("scene_loader: unknown keys, at the top level and nested, with suggestions") {
  expect_error("sede: 3\n", "sede",
               {"unknown key 'sede' (line 1, column 1)",
                "allowed: seed, name, origin, water, seabed, targets (did you mean 'seed'?)"});
  expect_error("seabed:\n  elevation:\n    inner_scale: 2\n", "seabed.elevation.inner_scale",
               {"(line 3, column 5)", "(did you mean 'inner_scale_m'?)"});
  expect_error(
      "seabed:\n  regions:\n    - sediment: rock\n      texture:\n        ripples:\n"
      "          wavelenght_m: 1\n",
      "seabed.regions[0].texture.ripples.wavelenght_m", {"did you mean 'wavelength_m'?"});
  expect_error("targets:\n  - type: box\n  - type: box\n    headng_deg: 3\n",
               "targets[1].headng_deg", {"did you mean 'heading_deg'?"});
  expect_error("seabed: {regions: [{texture: {ripple: {}}}]}", "seabed.regions[0].texture.ripple",
               {"allowed: ripples, rocky, clutter (did you mean 'ripples'?)"});
  expect_error("targets: [{material: {density_kg_m3: 900, speed: 1}}]", "targets[0].material.speed",
               {"allowed: density_kg_m3, sound_speed_m_s"});
  // a far-off key gets the allowed list and no suggestion
  const auto far = expect_error("vehicle: {}\n", "vehicle");
  CHECK(far.suggestion.empty());
  // every unknown key of one map is reported
  try {
    parse_scene("water: {depth: 3, temp: 4}\n", "scenario.yaml");
    FAIL("accepted unknown keys");
  } catch (const ConfigError& e) {
    REQUIRE(e.issues().size() == 2);
    CHECK(e.issues()[0].path == "water.depth");
    CHECK(e.issues()[0].suggestion == "depth_m");
    CHECK(e.issues()[1].path == "water.temp");
  }
}

TEST_CASE("scene_loader: wrong types") {
  // a string for a number
  expect_error("water:\n  depth_m: deep\n", "water.depth_m",
               {"'deep' is not a number (line 2, column 12)", "allowed: a number 2 .. 1000"});
  expect_error("seed: abc\n", "seed", {"'abc' is not an integer"});
  // a scalar for a list, a map for a list, a list of the wrong length
  expect_error("seabed:\n  extent_m: 100\n", "seabed.extent_m",
               {"'100' is a single value, not a list", "[north, east]"});
  expect_error("seabed: {regions: {sediment: sand}}", "seabed.regions",
               {"a map {sediment: sand} is not a list", "1 .. 3 regions"});
  expect_error("targets: 3\n", "targets", {"'3' is not a list"});
  expect_error("seabed: {extent_m: [1, 2, 3]}", "seabed.extent_m",
               {"a list [1, 2, 3] has 3 values, not 2"});
  expect_error("targets: [{size_m: [1, 1]}]", "targets[0].size_m",
               {"has 2 values, not 3", "[length, width, height]"});
  // a list or scalar for a map
  expect_error("water: [1, 2]\n", "water", {"a list [1, 2] is not a map"});
  expect_error("seabed: {regions: [sand]}", "seabed.regions[0]",
               {"'sand' is not a map", "sediment, centre_m, texture"});
  expect_error("- a\n- b\n", "", {"a list [a, b] is not a map"});
  // non-finite and quoted numbers
  expect_error("water: {ph: .nan}", "water.ph", {"'.nan' is not a finite number"});
  expect_error("seabed: {origin_m: [.inf, 0]}", "seabed.origin_m[0]",
               {"'.inf' is not a finite number"});
  expect_error("water: {ph: \"8\"}", "water.ph", {"quoted string"});
  expect_error("water: {ph: }", "water.ph", {"has no value"});
  expect_error("name: [a]\n", "name", {"a list [a] is not text"});
  expect_error("seabed: {regions: [{texture: [ripples]}]}", "seabed.regions[0].texture",
               {"a list [ripples] is not a map", "flat, or a map with any of ripples, rocky"});
  expect_error("seabed: {regions: [{texture: bumpy}]}", "seabed.regions[0].texture",
               {"'bumpy' is not a texture"});
  expect_error("seabed: {regions: [{texture: flatt}]}", "seabed.regions[0].texture",
               {"(did you mean 'flat'?)"});
  expect_error("targets: [{material: [steel]}]", "targets[0].material",
               {"a list [steel] is not a map"});
}

TEST_CASE("scene_loader: out-of-range values name the file, key, value and range") {
  struct Case {
    std::string yaml;
    std::string path;
    std::string value;
    std::string allowed;
  };
  const std::vector<Case> cases = {
      {"origin: {latitude_deg: 90}", "origin.latitude_deg", "90", "-89 .. 89"},
      {"origin: {longitude_deg: -180.5}", "origin.longitude_deg", "-180.5", "-180 .. 180"},
      {"water: {temperature_c: -3}", "water.temperature_c", "-3", "-2 .. 35"},
      {"water: {salinity_ppt: 46}", "water.salinity_ppt", "46", "0 .. 45"},
      {"water: {ph: 6.9}", "water.ph", "6.9", "7 .. 9"},
      {"water: {depth_m: 1001}", "water.depth_m", "1001", "2 .. 1000"},
      {"seabed: {extent_m: [100, 0.5]}", "seabed.extent_m[1]", "0.5", "1 .. 100000"},
      {"seabed: {extent_m: [100001, 5]}", "seabed.extent_m[0]", "100001", "1 .. 100000"},
      {"seabed: {grid_spacing_m: 0.001}", "seabed.grid_spacing_m", "0.001", "0.005 .. 1"},
      {"seabed: {elevation: {slope: [0, 0.6]}}", "seabed.elevation.slope[1]", "0.6", "-0.5 .. 0.5"},
      {"seabed: {elevation: {rms_m: 51}}", "seabed.elevation.rms_m", "51", "0 .. 50"},
      {"seabed: {elevation: {beta: 3.6}}", "seabed.elevation.beta", "3.6", "0.5 .. 3.5"},
      {"seabed: {elevation: {outer_scale_m: 10001}}", "seabed.elevation.outer_scale_m", "10001",
       "> 5 and <= 10000"},
      {"seabed: {elevation: {spacing_m: 11}}", "seabed.elevation.spacing_m", "11", "0.025 .. 10"},
      {"seabed: {partition: {border_warp_m: -1}}", "seabed.partition.border_warp_m", "-1",
       "0 .. 1000"},
      {"seabed: {partition: {border_beta: 0.9}}", "seabed.partition.border_beta", "0.9",
       "1 .. 3.5"},
      {"seabed: {partition: {border_scale_m: 0.05}}", "seabed.partition.border_scale_m", "0.05",
       "0.1 .. 10000"},
      {"seabed: {partition: {blend_width_m: 101}}", "seabed.partition.blend_width_m", "101",
       "0 .. 100"},
      {"seabed: {regions: [{texture: {ripples: {wavelength_m: 0.04}}}]}",
       "seabed.regions[0].texture.ripples.wavelength_m", "0.04", "0.05 .. 20"},
      {"seabed: {regions: [{texture: {ripples: {direction_deg: 361}}}]}",
       "seabed.regions[0].texture.ripples.direction_deg", "361", "0 .. 360"},
      {"seabed: {regions: [{texture: {ripples: {beta1: 7}}}]}",
       "seabed.regions[0].texture.ripples.beta1", "7", "0.5 .. 6"},
      {"seabed: {regions: [{texture: {ripples: {beta: 0.1}}}]}",
       "seabed.regions[0].texture.ripples.beta", "0.1", "0.5 .. 6"},
      {"seabed: {regions: [{texture: {ripples: {height_m: 2.5}}}]}",
       "seabed.regions[0].texture.ripples.height_m", "2.5", "0 .. 2"},
      {"seabed: {regions: [{texture: {rocky: {rms_m: 6}}}]}",
       "seabed.regions[0].texture.rocky.rms_m", "6", "0 .. 5"},
      {"seabed: {regions: [{texture: {rocky: {beta: 1}}}]}", "seabed.regions[0].texture.rocky.beta",
       "1", "2 .. 5"},
      {"seabed: {regions: [{texture: {rocky: {anisotropy: 0.5}}}]}",
       "seabed.regions[0].texture.rocky.anisotropy", "0.5", "1 .. 20"},
      {"seabed: {regions: [{texture: {rocky: {direction_deg: -1}}}]}",
       "seabed.regions[0].texture.rocky.direction_deg", "-1", "0 .. 360"},
      {"seabed: {regions: [{texture: {rocky: {outer_scale_m: 101}}}]}",
       "seabed.regions[0].texture.rocky.outer_scale_m", "101", "0.1 .. 100"},
      {"seabed: {regions: [{texture: {clutter: {density_per_m2: 11}}}]}",
       "seabed.regions[0].texture.clutter.density_per_m2", "11", "0 .. 10"},
      {"seabed: {regions: [{texture: {clutter: {median_diameter_m: 0.01}}}]}",
       "seabed.regions[0].texture.clutter.median_diameter_m", "0.01", "0.02 .. 5"},
      {"seabed: {regions: [{texture: {clutter: {sigma_ln: 2.1}}}]}",
       "seabed.regions[0].texture.clutter.sigma_ln", "2.1", "0 .. 2"},
      {"seabed: {regions: [{texture: {clutter: {height_ratio: 0.04}}}]}",
       "seabed.regions[0].texture.clutter.height_ratio", "0.04", "0.05 .. 2"},
      {"targets: [{heading_deg: 360.5}]", "targets[0].heading_deg", "360.5", "0 .. 360"},
      {"targets: [{size_m: [1, 1, 21]}]", "targets[0].size_m[2]", "21", "0.05 .. 20"},
      {"targets: [{scale: 0.05}]", "targets[0].scale", "0.05", "0.1 .. 10"},
      {"targets: [{material: {density_kg_m3: 400}}]", "targets[0].material.density_kg_m3", "400",
       "500 .. 25000"},
      {"targets: [{material: {sound_speed_m_s: 16000}}]", "targets[0].material.sound_speed_m_s",
       "16000", "300 .. 15000"},
      {"seed: -5", "seed", "-5", "an integer >= 0"},
  };
  for (const auto& c : cases) {
    const auto i =
        expect_error(c.yaml, c.path, {c.value + " is out of range", "; allowed: " + c.allowed});
    CHECK(i.line == 1);
  }
}

TEST_CASE("scene_loader: unknown sediment, target type and material") {
  const auto sed =
      expect_error("seabed:\n  regions:\n    - sediment: sandd\n", "seabed.regions[0].sediment",
                   {"'sandd' is not a sediment (line 3, column 17)",
                    "allowed: rough_rock, rock, cobble", "(did you mean 'sand'?)"});
  CHECK(sed.suggestion == "sand");
  expect_error("targets: [{type: mantta}]", "targets[0].type",
               {"'mantta' is not a target type", "allowed: manta, rockan, cylinder",
                "(did you mean 'manta'?)"});
  expect_error("targets: [{type: submarine}]", "targets[0].type", {"'submarine'"});
  expect_error("targets: [{material: titanium}]", "targets[0].material",
               {"'titanium' is not a material", "steel, aluminium, concrete, grp, rubber"});
  expect_error("targets: [{material: stell}]", "targets[0].material", {"did you mean 'steel'?"});
}

TEST_CASE("scene_loader: malformed YAML reports the line") {
  const auto i =
      expect_error("seed: 1\nwater:\n  depth_m: [30\n  ph: 8\n", "", {"YAML syntax error"});
  CHECK(i.line >= 3);
  const auto tab = expect_error("water:\n\tdepth_m: 3\n", "", {"YAML syntax error"});
  CHECK(tab.line == 2);
  expect_error("seed: 1\nseed: 2\n", "seed", {"duplicate key 'seed'", "(line 2, column 1)"});
  expect_error("a: 1\n---\nb: 2\n", "",
               {"holds more than one YAML document", "(line 2, column 1)"});
  // a stray ',' at the top level (yaml-cpp 0.7 alone would loop for ever on it)
  expect_error("# comment\n, seed: 1\n", "",
               {"YAML syntax error: unexpected ','", "(line 2, column 1)"});
}

TEST_CASE("scene_loader: region count and centres") {
  expect_error("seabed: {regions: []}", "seabed.regions", {"has no regions", "1 .. 3 regions"});
  expect_error("seabed:\n  regions:\n", "seabed.regions", {"has no regions"});
  expect_error(
      "seabed:\n  regions:\n    - centre_m: [0, 0]\n    - centre_m: [0, 10]\n"
      "    - centre_m: [10, 0]\n    - centre_m: [10, 10]\n",
      "seabed.regions", {"has 4 regions", "allowed: a list of 1 .. 3 regions"});
  const auto dup = expect_error(
      "seabed:\n  regions:\n    - centre_m: [5, 5]\n    - centre_m: [0, 0]\n"
      "    - centre_m: [5, 5]\n",
      "seabed.regions[2].centre_m", {"[5, 5] is also the centre of seabed.regions[0]"});
  CHECK(dup.line == 5);
  // two regions left at the default centre
  expect_error("seabed: {regions: [{sediment: rock}, {sediment: clay}]}",
               "seabed.regions[1].centre_m", {"[0, 0] is also the centre"});
}

TEST_CASE("scene_loader: target names are unique") {
  expect_error("targets:\n  - {name: a}\n  - {name: b}\n  - {name: a}\n", "targets[2].name",
               {"'a' is already used by targets[0]"});
  // an explicit name may take a default name
  expect_error("targets:\n  - {name: manta-2}\n  - {type: manta}\n", "targets[1].name",
               {"the default name 'manta-2' is already used by targets[0]"});
  const auto ok = parse_scene(
      "targets: [{type: box, position_m: [0, 0]}, {type: rockan, position_m: [0, 1]}, "
      "{type: box, position_m: [0, 2]}, {name: x, position_m: [0, 3]}]",
      "t.yaml");
  REQUIRE(ok.targets.size() == 4);
  CHECK(ok.targets[0].name == "box-1");
  CHECK(ok.targets[1].name == "rockan-1");
  CHECK(ok.targets[2].name == "box-2");
  CHECK(ok.targets[3].name == "x");
}

TEST_CASE("scene_loader: size_m and scale, burial and position rules") {
  expect_error("targets:\n  - {size_m: [1, 1, 1], scale: 2}\n", "targets[0].scale",
               {"'2' is given together with size_m", "either size_m or scale, not both"});
  // burial up to the height: nominal, scaled and explicit sizes
  CHECK(parse_scene("targets: [{type: manta, position_m: [0, 0], burial_m: 0.47}]", "b.yaml")
            .targets[0]
            .burial_m == 0.47);
  expect_error("targets: [{type: manta, burial_m: 0.48}]", "targets[0].burial_m",
               {"0.48 is out of range", "0 .. 0.47 (the target's height)"});
  expect_error("targets: [{type: manta, scale: 0.5, burial_m: 0.3}]", "targets[0].burial_m",
               {"0 .. 0.235"});
  expect_error("targets: [{size_m: [1, 1, 0.2], burial_m: 0.25}]", "targets[0].burial_m",
               {"0 .. 0.2"});
  expect_error("targets: [{burial_m: -0.1}]", "targets[0].burial_m", {"-0.1 is out of range"});
  // positions inside the extent, edges included
  const auto edge = parse_scene("targets: [{position_m: [50, -50]}]", "p.yaml");
  CHECK(edge.targets[0].position_m == Vec2(50, -50));
  expect_error("targets: [{position_m: [50.01, 0]}]", "targets[0].position_m[0]",
               {"50.01 is out of range", "-50 .. 50 (inside the seabed extent)"});
  expect_error("seabed: {origin_m: [0, 0], extent_m: [10, 20]}\ntargets: [{position_m: [5, 21]}]",
               "targets[0].position_m[1]", {"21 is out of range", "0 .. 20"});
  // the default position [0, 0] must be inside the extent too
  expect_error("seabed: {origin_m: [10, 10]}\ntargets: [{type: box}]", "targets[0].position_m",
               {"default [0, 0] is out of range"});
}

TEST_CASE("scene_loader: errors in list entries name their index") {
  expect_error("targets:\n  - {}\n  - {}\n  - {heading_deg: x}\n", "targets[2].heading_deg",
               {"(line 4, column 19)"});
  expect_error("seabed:\n  regions:\n    - {centre_m: [0, 1]}\n    - {sediment: mud}\n",
               "seabed.regions[1].sediment", {"'mud' is not a sediment"});
  expect_error("targets: [{}, {position_m: [0, zero]}]", "targets[1].position_m[1]");
}

TEST_CASE("scene_loader: seabed grid and elevation scale rules") {
  // elevation spacing_m >= grid_spacing_m (also when spacing_m is left at its default)
  expect_error("seabed: {grid_spacing_m: 0.1, elevation: {spacing_m: 0.05}}",
               "seabed.elevation.spacing_m", {"0.05 is out of range", "0.1 .. 10"});
  expect_error("seabed: {grid_spacing_m: 0.8}", "seabed.elevation.spacing_m",
               {"is not set, and its default 0.5 is out of range"});
  // inner_scale_m >= spacing_m
  expect_error("seabed: {elevation: {spacing_m: 6}}", "seabed.elevation.inner_scale_m",
               {"default 5 is out of range", ">= 6 and < 10000"});
  expect_error("seabed: {elevation: {spacing_m: 0.5, inner_scale_m: 0.4}}",
               "seabed.elevation.inner_scale_m", {"0.4 is out of range"});
  // outer_scale_m > inner_scale_m
  expect_error("seabed: {elevation: {inner_scale_m: 5, outer_scale_m: 5}}",
               "seabed.elevation.outer_scale_m", {"5 is out of range", "> 5 and <= 10000"});
  expect_error("seabed: {elevation: {inner_scale_m: 50}}", "seabed.elevation.outer_scale_m",
               {"default 40"});
  // clutter max_diameter_m >= median_diameter_m
  expect_error(
      "seabed: {regions: [{texture: {clutter: {median_diameter_m: 0.5, "
      "max_diameter_m: 0.4}}}]}",
      "seabed.regions[0].texture.clutter.max_diameter_m", {"0.4 is out of range", ">= 0.5"});
  // grid cells: up to 1e12 allowed, beyond that rejected
  const auto big = parse_scene(
      "seabed: {extent_m: [100000, 100000], grid_spacing_m: 0.1, "
      "elevation: {spacing_m: 1}}",
      "big.yaml");
  CHECK(big.seabed.grid_spacing_m == 0.1);
  expect_error("seabed: {extent_m: [100000, 100000], grid_spacing_m: 0.09}",
               "seabed.grid_spacing_m",
               {"0.09 gives", "grid cells over the 100000 x 100000 m extent", ">= 0.1"});
  expect_error("seabed: {extent_m: [100000, 50000]}", "seabed.grid_spacing_m",
               {"its default 0.025 gives"});
  // no spacing larger than the extent
  expect_error("seabed: {extent_m: [5, 2], elevation: {spacing_m: 3}}",
               "seabed.elevation.spacing_m", {"3 is out of range", "0.025 .. 2"});
  CHECK(parse_scene("seabed: {extent_m: [1, 1], grid_spacing_m: 1, elevation: {spacing_m: 1}}",
                    "one.yaml")
            .seabed.grid_spacing_m == 1);
}

TEST_CASE("scene_loader: parse_scene_node on part of a larger document") {
  const Field root = parse_document("scene:\n  seed: 5\nsonar: {}\nbogus: 1\n", "mission.yaml");
  const auto s = parse_scene_node(root.child("scene"));
  CHECK(s.seed == 5);
  CHECK(s.name == "mission");
  root.child("sonar");
  try {
    root.finish();
    FAIL("bogus accepted");
  } catch (const ConfigError& e) {
    CHECK(e.first().path == "bogus");
    CHECK(e.first().allowed == "scene, sonar");
  }
  // scene keys beside the caller's own keys: the caller finishes the map
  const Field flat = parse_document("seed: 3\nsonar: {}\n", "flat.yaml");
  CHECK(parse_scene_node(flat, false).seed == 3);
  flat.child("sonar");
  flat.finish();
  CHECK_THROWS_AS(parse_scene_node(parse_document("seed: 3\nsonar: {}\n", "f.yaml")), ConfigError);
}

// ---------------------------------------------------------------------------------------------
// seeded randomized test (docs/style.md habit 22)

namespace {

struct YEntry;

// A YAML tree built by the generator, written out as text, and mutated for corruptions.
struct YNode {
  enum class Kind { kScalar, kMap, kList };
  // what the loader accepts at this node, so that a corruption can be made that it must reject
  enum class Accepts { kNothing, kReal, kUInt, kName, kText, kVector, kSection };
  Kind kind = Kind::kScalar;
  std::string text;
  std::vector<YEntry> map;  // in order
  std::vector<YNode> list;
  bool flow = false;
  Accepts accepts = Accepts::kNothing;
  std::vector<Range> ranges;    // kReal: one; kVector: one per component
  bool map_or_null_ok = false;  // material, texture: a map or no value is valid too
};

struct YEntry {
  std::string key;
  YNode value;
};

std::string real_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

YNode scalar(std::string text, YNode::Accepts a) {
  YNode n;
  n.text = std::move(text);
  n.accepts = a;
  return n;
}

YNode real(double v, const Range& r) {
  YNode n = scalar(real_text(v), YNode::Accepts::kReal);
  n.ranges = {r};
  return n;
}

YNode vec(const std::vector<double>& v, const std::vector<Range>& r) {
  YNode n;
  n.kind = YNode::Kind::kList;
  n.flow = true;
  n.accepts = YNode::Accepts::kVector;
  n.ranges = r;
  for (double x : v)
    n.list.push_back(scalar(real_text(x), YNode::Accepts::kNothing));
  return n;
}

YNode map_node() {
  YNode n;
  n.kind = YNode::Kind::kMap;
  return n;
}

YNode section_list() {
  YNode n;
  n.kind = YNode::Kind::kList;
  n.accepts = YNode::Accepts::kSection;
  return n;
}

std::string flow_text(const YNode& n) {
  switch (n.kind) {
    case YNode::Kind::kScalar:
      return n.text.empty() ? "~" : n.text;
    case YNode::Kind::kList: {
      std::string out = "[";
      for (std::size_t i = 0; i < n.list.size(); ++i)
        out += (i ? ", " : "") + flow_text(n.list[i]);
      return out + "]";
    }
    case YNode::Kind::kMap: {
      std::string out = "{";
      for (std::size_t i = 0; i < n.map.size(); ++i) {
        out += (i ? ", " : "") + n.map[i].key + ": " + flow_text(n.map[i].value);
      }
      return out + "}";
    }
  }
  return "";
}

bool is_block(const YNode& n) {
  return n.kind != YNode::Kind::kScalar && !n.flow &&
         !(n.kind == YNode::Kind::kMap ? n.map.empty() : n.list.empty());
}

void write_block(const YNode& n, int indent, std::string& out) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  if (n.kind == YNode::Kind::kMap) {
    for (const auto& [key, v] : n.map) {
      out += pad + key + ":";
      if (is_block(v)) {
        out += "\n";
        write_block(v, indent + 2, out);
      } else {
        const std::string t = v.kind == YNode::Kind::kScalar ? v.text : flow_text(v);
        out += (t.empty() ? "" : " " + t) + "\n";
      }
    }
    return;
  }
  for (const auto& item : n.list) {
    if (is_block(item)) {
      // the item's first line starts with "- " in place of two spaces of indentation
      std::string sub;
      write_block(item, indent + 2, sub);
      out += pad + "- " + sub.substr(static_cast<std::size_t>(indent) + 2);
    } else {
      out += pad + "- " + flow_text(item) + "\n";
    }
  }
}

std::string to_yaml(const YNode& root) {
  std::string out = "# generated\n";
  write_block(root, 0, out);
  return out;
}

class ScenarioGenerator {
 public:
  explicit ScenarioGenerator(std::uint64_t sample) : rng_(20240611, RngStream::kDataset, sample) {}

  Rng& rng() { return rng_; }

  // Fills `expect` with a random valid scene and `root` with the YAML that describes it.
  void generate(scene::SceneDesc& expect, YNode& root, const std::string& stem) {
    root = map_node();
    if (chance(0.75)) {
      expect.seed = chance(0.5) ? rng_.next_u64() : rng_.below(1000);
      root.map.push_back({"seed", scalar(std::to_string(expect.seed), YNode::Accepts::kUInt)});
    }
    expect.name = stem;
    if (chance(0.5)) {
      expect.name = "survey " + std::to_string(rng_.below(100000));
      root.map.push_back({"name", scalar(chance(0.5) ? "\"" + expect.name + "\"" : expect.name,
                                         YNode::Accepts::kText)});
    }
    section(root, "origin", [&](YNode& m) {
      auto& o = expect.origin;
      o.latitude_deg = num(m, "latitude_deg", o.latitude_deg, Range::closed(-89, 89));
      o.longitude_deg = num(m, "longitude_deg", o.longitude_deg, Range::closed(-180, 180));
    });
    section(root, "water", [&](YNode& m) {
      auto& w = expect.water;
      w.temperature_c = num(m, "temperature_c", w.temperature_c, Range::closed(-2, 35));
      w.salinity_ppt = num(m, "salinity_ppt", w.salinity_ppt, Range::closed(0, 45));
      w.ph = num(m, "ph", w.ph, Range::closed(7, 9));
      w.depth_m = num(m, "depth_m", w.depth_m, Range::closed(2, 1000));
    });
    section(root, "seabed", [&](YNode& m) { seabed_section(m, expect.seabed); });
    targets_section(root, expect);
    shuffle(root);
  }

 private:
  bool chance(double p) { return rng_.uniform() < p; }

  // a value in r: often an end point, log-uniform over wide positive ranges
  double draw(const Range& r) {
    for (;;) {
      double v = 0;
      const double u = rng_.uniform();
      if (u < 0.1) {
        v = r.lo;
      } else if (u < 0.2) {
        v = r.hi;
      } else if (r.lo > 0 && r.hi / r.lo > 1000) {
        v = std::exp(rng_.uniform(std::log(r.lo), std::log(r.hi)));
        v = std::min(std::max(v, r.lo), r.hi);
      } else {
        v = rng_.uniform(r.lo, r.hi);
      }
      if (r.contains(v)) return v;
    }
  }

  // adds `key` with a drawn value, or leaves it out (when the default is valid here)
  double num(YNode& m, const char* key, double def, const Range& valid) {
    return num(m, key, def, valid, valid);
  }
  double num(YNode& m, const char* key, double def, const Range& valid, const Range& gen) {
    if (valid.contains(def) && chance(0.25)) return def;
    const double v = draw(gen);
    m.map.push_back({key, real(v, valid)});
    return v;
  }
  Vec2 vec2(YNode& m, const char* key, const Vec2& def, const std::array<Range, 2>& valid,
            const Range& gen, bool required = false) {
    if (!required && valid[0].contains(def.x()) && valid[1].contains(def.y()) && chance(0.25))
      return def;
    // bounded components are drawn from their valid range, unbounded ones from `gen`
    const Vec2 v(draw(std::isfinite(valid[0].lo) ? valid[0] : gen),
                 draw(std::isfinite(valid[1].lo) ? valid[1] : gen));
    YNode n = vec({v.x(), v.y()}, {valid[0], valid[1]});
    if (chance(0.3)) n.flow = false;  // block list
    m.map.push_back({key, n});
    return v;
  }

  // a map section: filled by `fill`, written in block or flow style, or left out / empty
  template <class Fn>
  void section(YNode& parent, const char* key, Fn&& fill) {
    YNode m = map_node();
    fill(m);
    if (m.map.empty()) {
      const double u = rng_.uniform();
      if (u < 0.4) return;                                    // left out
      if (u < 0.7) m = scalar("", YNode::Accepts::kNothing);  // "key:" (null)
    }
    if (m.kind == YNode::Kind::kMap) {
      bool leaves = true;
      for (const auto& kv : m.map)
        leaves = leaves && !is_block(kv.value);
      m.flow = leaves && chance(0.3);
    }
    parent.map.push_back({key, m});
  }

  void seabed_section(YNode& m, scene::SeabedDesc& s) {
    s.origin_m =
        vec2(m, "origin_m", s.origin_m, {Range::any(), Range::any()}, Range::closed(-5000, 5000));
    const Range ext = Range::closed(1, 100000);
    s.extent_m = vec2(m, "extent_m", s.extent_m, {ext, ext}, ext);
    // at most 1e12 cells; a hair above the exact bound so that rounding cannot cross it
    const double cells_lo = std::sqrt(s.extent_m.x() * s.extent_m.y() / 1e12) * (1 + 1e-9);
    const Range grid =
        Range::closed(std::max(0.005, cells_lo), std::min(1.0, s.extent_m.minCoeff()));
    s.grid_spacing_m = num(m, "grid_spacing_m", s.grid_spacing_m, grid);
    section(m, "elevation", [&](YNode& e) {
      auto& el = s.elevation;
      el.slope = vec2(e, "slope", el.slope, {Range::closed(-0.5, 0.5), Range::closed(-0.5, 0.5)},
                      Range::closed(-0.5, 0.5));
      el.rms_m = num(e, "rms_m", el.rms_m, Range::closed(0, 50));
      el.beta = num(e, "beta", el.beta, Range::closed(0.5, 3.5));
      el.spacing_m = num(e, "spacing_m", el.spacing_m,
                         Range::closed(s.grid_spacing_m, std::min(10.0, s.extent_m.minCoeff())));
      const Range inner{el.spacing_m, 10000, false, true, {}};
      el.inner_scale_m = num(e, "inner_scale_m", el.inner_scale_m, inner,
                             Range::closed(el.spacing_m, std::min(el.spacing_m * 100, 9999.0)));
      el.outer_scale_m = num(e, "outer_scale_m", el.outer_scale_m,
                             Range{el.inner_scale_m, 10000, true, false, {}});
      shuffle(e);
    });
    section(m, "partition", [&](YNode& p) {
      auto& pa = s.partition;
      pa.border_warp_m = num(p, "border_warp_m", pa.border_warp_m, Range::closed(0, 1000));
      pa.border_beta = num(p, "border_beta", pa.border_beta, Range::closed(1, 3.5));
      pa.border_scale_m = num(p, "border_scale_m", pa.border_scale_m, Range::closed(0.1, 10000));
      pa.blend_width_m = num(p, "blend_width_m", pa.blend_width_m, Range::closed(0, 100));
    });
    regions(m, s);
  }

  void regions(YNode& m, scene::SeabedDesc& s) {
    s.regions.clear();
    if (chance(0.2)) {
      scene::RegionDesc r;
      r.sediment = sediment("medium_sand");
      s.regions.push_back(r);
      return;
    }
    YNode list = section_list();
    const auto n = 1 + rng_.below(3);
    std::vector<std::string> names;
    for (const auto& info : seabed::sediment_table())
      names.emplace_back(info.key);
    names.insert(names.end(), {"sand", "gravel", "pebble", "silty_sand", "clayey_silt"});
    for (std::uint64_t i = 0; i < n; ++i) {
      YNode r = map_node();
      scene::RegionDesc d;
      d.sediment = sediment("medium_sand");
      if (chance(0.8)) {
        const std::string name = names[rng_.below(names.size())];
        d.sediment = sediment(name.c_str());
        r.map.push_back({"sediment", scalar(name, YNode::Accepts::kName)});
      }
      if (i > 0 || chance(0.8)) {
        d.centre_m = Vec2(rng_.uniform(-500, 500), rng_.uniform(-500, 500));
        r.map.push_back(
            {"centre_m", vec({d.centre_m.x(), d.centre_m.y()}, {Range::any(), Range::any()})});
      }
      texture(r, d.texture);
      shuffle(r);
      if (chance(0.3)) r.flow = true;
      list.list.push_back(r);
      s.regions.push_back(d);
    }
    m.map.push_back({"regions", list});
  }

  void texture(YNode& region, scene::TextureDesc& t) {
    const double u = rng_.uniform();
    if (u < 0.2) return;  // left out
    if (u < 0.35) {
      YNode flat = scalar("flat", YNode::Accepts::kName);
      flat.map_or_null_ok = true;
      region.map.push_back({"texture", flat});
      return;
    }
    YNode tex = map_node();
    if (chance(0.5)) {
      t.ripples = scene::RipplesDesc{};
      kind(tex, "ripples", [&](YNode& m) {
        auto& r = *t.ripples;
        r.wavelength_m = num(m, "wavelength_m", r.wavelength_m, Range::closed(0.05, 20));
        r.direction_deg = num(m, "direction_deg", r.direction_deg, Range::closed(0, 360));
        r.beta1 = num(m, "beta1", r.beta1, Range::closed(0.5, 6));
        r.beta = num(m, "beta", r.beta, Range::closed(0.5, 6));
        r.height_m = num(m, "height_m", r.height_m, Range::closed(0, 2));
      });
    }
    if (chance(0.5)) {
      t.rocky = scene::RockyDesc{};
      kind(tex, "rocky", [&](YNode& m) {
        auto& r = *t.rocky;
        r.rms_m = num(m, "rms_m", r.rms_m, Range::closed(0, 5));
        r.beta = num(m, "beta", r.beta, Range::closed(2, 5));
        r.anisotropy = num(m, "anisotropy", r.anisotropy, Range::closed(1, 20));
        r.direction_deg = num(m, "direction_deg", r.direction_deg, Range::closed(0, 360));
        r.outer_scale_m = num(m, "outer_scale_m", r.outer_scale_m, Range::closed(0.1, 100));
      });
    }
    if (chance(0.5)) {
      t.clutter = scene::ClutterDesc{};
      kind(tex, "clutter", [&](YNode& m) {
        auto& c = *t.clutter;
        c.density_per_m2 = num(m, "density_per_m2", c.density_per_m2, Range::closed(0, 10));
        c.median_diameter_m =
            num(m, "median_diameter_m", c.median_diameter_m, Range::closed(0.02, 5));
        c.sigma_ln = num(m, "sigma_ln", c.sigma_ln, Range::closed(0, 2));
        c.height_ratio = num(m, "height_ratio", c.height_ratio, Range::closed(0.05, 2));
        c.max_diameter_m =
            num(m, "max_diameter_m", c.max_diameter_m, Range::at_least(c.median_diameter_m),
                Range::closed(c.median_diameter_m, c.median_diameter_m * 10));
      });
    }
    tex.map_or_null_ok = true;
    region.map.push_back({"texture", tex});
  }

  // a texture kind: a map of values, or "{}" / no value for all defaults
  template <class Fn>
  void kind(YNode& tex, const char* key, Fn&& fill) {
    YNode m = map_node();
    if (chance(0.7)) {
      fill(m);
      shuffle(m);
    }
    if (m.map.empty() && chance(0.5)) m = scalar("", YNode::Accepts::kNothing);
    tex.map.push_back({key, m});
  }

  void targets_section(YNode& root, scene::SceneDesc& s) {
    const double u = rng_.uniform();
    if (u < 0.25) return;
    YNode list = section_list();
    const auto n = u < 0.35 ? 0 : 1 + rng_.below(4);
    std::map<targets::TargetType, int> per_type;
    const auto types = targets::target_type_table();
    const auto materials = targets::material_table();
    const Vec2 lo = s.seabed.origin_m;
    const Vec2 hi = s.seabed.origin_m + s.seabed.extent_m;
    const std::array<Range, 2> inside{Range::closed(lo.x(), hi.x()), Range::closed(lo.y(), hi.y())};
    for (std::uint64_t i = 0; i < n; ++i) {
      YNode m = map_node();
      scene::TargetDesc t;
      if (chance(0.8)) {
        t.type = types[rng_.below(types.size())].type;
        m.map.push_back({"type", scalar(std::string(targets::target_type_info(t.type).key),
                                        YNode::Accepts::kName)});
      }
      const int ordinal = ++per_type[t.type];
      t.name = std::string(targets::target_type_info(t.type).key) + "-" + std::to_string(ordinal);
      if (chance(0.5)) {
        // formatted, then moved in: GCC 12 -O3 warns falsely (-Wrestrict) on string appends here
        char buf[48];
        std::snprintf(buf, sizeof buf, "t%d_%d", static_cast<int>(i),
                      static_cast<int>(rng_.below(1000)));
        t.name = std::string(buf);
        m.map.push_back({"name", scalar(t.name, YNode::Accepts::kText)});
      }
      t.position_m = vec2(m, "position_m", t.position_m, inside, Range::any(), true);
      t.heading_deg = num(m, "heading_deg", t.heading_deg, Range::closed(0, 360));
      const Vec3 nominal = targets::target_type_info(t.type).size_m;
      const double mode = rng_.uniform();
      if (mode < 0.33) {
        const Range each = Range::closed(0.05, 20);
        t.size_m = Vec3(draw(each), draw(each), draw(each));
        m.map.push_back(
            {"size_m", vec({t.size_m.x(), t.size_m.y(), t.size_m.z()}, {each, each, each})});
      } else if (mode < 0.66) {
        const double scale = draw(Range::closed(0.1, 10));
        t.size_m = nominal * scale;
        m.map.push_back({"scale", real(scale, Range::closed(0.1, 10))});
      } else {
        t.size_m = nominal;
      }
      material(m, t.material, materials);
      t.burial_m = num(m, "burial_m", t.burial_m, Range::closed(0, t.size_m.z()));
      shuffle(m);
      if (chance(0.3)) {
        bool leaves = true;
        for (const auto& kv : m.map)
          leaves = leaves && !is_block(kv.value);
        m.flow = leaves;
      }
      list.list.push_back(m);
      s.targets.push_back(t);
    }
    if (list.list.empty()) list.flow = true;
    root.map.push_back({"targets", list});
  }

  void material(YNode& m, scene::MaterialDesc& mat,
                std::span<const targets::NamedMaterial> materials) {
    const double u = rng_.uniform();
    if (u < 0.3) return;
    if (u < 0.7) {
      const auto& named = materials[rng_.below(materials.size())];
      mat.density_kg_m3 = named.density_kg_m3;
      mat.sound_speed_m_s = named.sound_speed_m_s;
      YNode n = scalar(std::string(named.key), YNode::Accepts::kName);
      n.map_or_null_ok = true;
      m.map.push_back({"material", n});
      return;
    }
    YNode n = map_node();
    mat.density_kg_m3 = num(n, "density_kg_m3", mat.density_kg_m3, Range::closed(500, 25000));
    mat.sound_speed_m_s = num(n, "sound_speed_m_s", mat.sound_speed_m_s, Range::closed(300, 15000));
    n.flow = chance(0.5);
    n.map_or_null_ok = true;
    m.map.push_back({"material", n});
  }

  // key order must not matter
  void shuffle(YNode& m) {
    for (std::size_t i = m.map.size(); i > 1; --i) {
      std::swap(m.map[i - 1], m.map[rng_.below(i)]);
    }
  }

  Rng rng_;
};

// Every place in the tree a corruption can be made.
struct Site {
  YNode* node;
  YNode* parent_map;  // the map holding `node` under a key, if any
  std::string path;
};

void collect_sites(YNode& n, YNode* parent_map, const std::string& path, std::vector<Site>& out) {
  out.push_back({&n, parent_map, path});
  if (n.kind == YNode::Kind::kMap) {
    for (auto& [key, v] : n.map)
      collect_sites(v, &n, path.empty() ? key : path + "." + key, out);
  } else if (n.kind == YNode::Kind::kList && n.accepts == YNode::Accepts::kSection) {
    for (std::size_t i = 0; i < n.list.size(); ++i) {
      collect_sites(n.list[i], nullptr, path + "[" + std::to_string(i) + "]", out);
    }
  }
}

// A value outside `r` (below or above), if r has a finite end.
std::optional<double> outside(const Range& r, Rng& rng) {
  std::vector<double> bad;
  if (std::isfinite(r.lo))
    bad.push_back(r.lo_open ? r.lo : r.lo - 0.5 * std::max(std::fabs(r.lo), 1.0));
  if (std::isfinite(r.hi))
    bad.push_back(r.hi_open ? r.hi : r.hi + 0.5 * std::max(std::fabs(r.hi), 1.0));
  if (bad.empty()) return std::nullopt;
  return bad[rng.below(bad.size())];
}

template <class T>
T one_of(const std::vector<T>& v, Rng& rng) {
  return v[rng.below(v.size())];
}

// Mutates one site so that the scene becomes invalid. Returns a description and sets
// `expect_path` to the path the error must name ("" = any path).
std::string corrupt(const Site& site, Rng& rng, std::string& expect_path) {
  YNode& n = *site.node;
  expect_path = site.path;
  using A = YNode::Accepts;
  const auto set_scalar = [&](const std::string& text) {
    n = scalar(text, A::kNothing);
    return "set " + site.path + " to '" + text + "'";
  };
  if (n.kind == YNode::Kind::kMap) {
    if (site.path.empty() || rng.uniform() < 0.5) {
      n.map.push_back({"zz_unknown_key", scalar("1", A::kNothing)});
      expect_path = site.path.empty() ? "zz_unknown_key" : site.path + ".zz_unknown_key";
      return "added " + expect_path;
    }
    if (!n.map.empty() && rng.uniform() < 0.5) {
      auto& entry = n.map[rng.below(n.map.size())];
      entry.key += "_x";
      expect_path.clear();  // the default of the renamed key may be what fails first
      return "renamed a key of " + site.path + " to " + entry.key;
    }
    return set_scalar(one_of<std::string>({"[1, 2]", "[]"}, rng));
  }
  switch (n.accepts) {
    case A::kReal: {
      std::vector<std::string> bad{"abc",    ".nan", ".inf",  "-.inf", "'5'",  "[1, 2]",
                                   "{a: 1}", "~",    "1e999", "0x1F",  "true", "1.2.3"};
      if (auto v = outside(n.ranges.front(), rng)) {
        for (int k = 0; k < 6; ++k)
          bad.push_back(real_text(*v));
      }
      return set_scalar(one_of(bad, rng));
    }
    case A::kUInt:
      return set_scalar(
          one_of<std::string>({"-1", "1.5", "abc", "99999999999999999999999", "[1]", "~"}, rng));
    case A::kName: {
      std::vector<std::string> bad{"zz_no_such_name", "[1, 2]"};
      if (!n.map_or_null_ok) bad.insert(bad.end(), {"{a: 1}", "~"});
      return set_scalar(one_of(bad, rng));
    }
    case A::kText:
      return set_scalar(one_of<std::string>({"[1, 2]", "{a: 1}", "~"}, rng));
    case A::kVector: {
      const double u = rng.uniform();
      if (u < 0.5) {
        const std::size_t k = rng.below(n.list.size());
        std::vector<std::string> bad{"abc", ".nan", "[1]", "'3'"};
        if (auto v = outside(n.ranges[k], rng)) {
          for (int j = 0; j < 4; ++j)
            bad.push_back(real_text(*v));
        }
        n.list[k].text = one_of(bad, rng);
        return "set " + site.path + "[" + std::to_string(k) + "] to '" + n.list[k].text + "'";
      }
      if (u < 0.7) {
        n.list.pop_back();
        return "shortened " + site.path;
      }
      if (u < 0.8) {
        n.list.push_back(scalar("1", A::kNothing));
        return "lengthened " + site.path;
      }
      return set_scalar(one_of<std::string>({"5", "{a: 1}", "~", "abc"}, rng));
    }
    case A::kSection:
      return set_scalar(one_of<std::string>({"5", "{a: 1}", "abc"}, rng));
    case A::kNothing:
      break;
  }
  return "";
}

}  // namespace

TEST_CASE("scene_loader: random valid scenarios round-trip, corruptions are rejected") {
  constexpr int kSamples = 300;
  constexpr int kCorruptionsPerSample = 6;
  int corruptions = 0;
  for (int sample = 0; sample < kSamples; ++sample) {
    ScenarioGenerator gen(static_cast<std::uint64_t>(sample));
    scene::SceneDesc expect;
    YNode root;
    const std::string file = "random-" + std::to_string(sample) + ".yaml";
    gen.generate(expect, root, "random-" + std::to_string(sample));
    const std::string yaml = to_yaml(root);
    INFO("sample " << sample << ":\n" << yaml);
    scene::SceneDesc got;
    try {
      got = parse_scene(yaml, file);
    } catch (const ConfigError& e) {
      FAIL("valid scenario rejected: " << e.what());
    }
    check_same(got, expect);

    for (int c = 0; c < kCorruptionsPerSample; ++c) {
      YNode bad = root;
      std::vector<Site> sites;
      collect_sites(bad, nullptr, "", sites);
      // only sites where a corruption can be made
      std::vector<Site> usable;
      for (const auto& s : sites) {
        if (s.node->kind == YNode::Kind::kMap || s.node->accepts != YNode::Accepts::kNothing) {
          usable.push_back(s);
        }
      }
      REQUIRE_FALSE(usable.empty());
      std::string expect_path;
      const std::string what = corrupt(one_of(usable, gen.rng()), gen.rng(), expect_path);
      const std::string bad_yaml = to_yaml(bad);
      INFO("corruption: " << what << "\n" << bad_yaml);
      ++corruptions;
      try {
        parse_scene(bad_yaml, file);
        FAIL("corrupted scenario accepted");
      } catch (const ConfigError& e) {
        const std::string msg = e.what();
        INFO("message: " << msg);
        CHECK(msg.rfind(file + ": ", 0) == 0);
        CHECK(contains(msg, "; allowed: "));
        if (!expect_path.empty()) {
          const std::string& p = e.first().path;
          CHECK((p == expect_path || p.rfind(expect_path + "[", 0) == 0));
        }
      } catch (const std::exception& e) {
        FAIL("not a ConfigError: " << e.what());
      }
    }
  }
  CHECK(corruptions == kSamples * kCorruptionsPerSample);
}

TEST_CASE("scene_loader: random byte edits give a scene or a ConfigError, never a crash") {
  // yaml-cpp itself is exercised here too: this found the stray-',' endless loop of
  // yaml-cpp 0.7 that parse_document works around
  const std::string alphabet = "{}[]:,-#&*!|>'\"%@`? \n\t.0123456789abxyz~";
  Rng rng(7, RngStream::kDataset, 99);
  int accepted = 0;
  int rejected = 0;
  for (int k = 0; k < 5000; ++k) {
    std::string text = kFullScenario;
    const auto edits = 1 + rng.below(4);
    for (std::uint64_t j = 0; j < edits && !text.empty(); ++j) {
      const std::size_t pos = rng.below(text.size());
      const char c = alphabet[rng.below(alphabet.size())];
      switch (rng.below(3)) {
        case 0:
          text[pos] = c;
          break;
        case 1:
          text.erase(pos, 1 + rng.below(5));
          break;
        default:
          text.insert(pos, 1, c);
          break;
      }
    }
    try {
      parse_scene(text, "edited.yaml");
      ++accepted;
    } catch (const ConfigError& e) {
      ++rejected;
      const std::string msg = e.what();
      if (msg.rfind("edited.yaml: ", 0) != 0 || !contains(msg, "; allowed: ")) {
        FAIL("badly formed message: " << msg);
      }
    } catch (const std::exception& e) {
      FAIL("not a ConfigError: " << e.what() << "\n" << text);
    }
  }
  CHECK(accepted > 0);
  CHECK(rejected > accepted);
}

TEST_CASE("scene_loader: issue 11, input that was silently accepted is refused") {
  // a name with invalid UTF-8 made scene.json / truth.json invalid JSON
  expect_error(
      "name: \"ab\xff\xfe"
      "c\"\n",
      "name", {"is not valid UTF-8 (byte 0xFF at byte 2 of the text)", "allowed: text in UTF-8"});
  expect_error("targets: [{position_m: [0, 0], name: \"\xc3\"}]\n", "targets[0].name",
               {"is not valid UTF-8 (byte 0xC3 at byte 0"});
  CHECK(parse_scene("name: \"caf\xc3\xa9 \xe2\x9a\x93\"\n", "u.yaml").name ==
        "caf\xc3\xa9 \xe2\x9a\x93");
  // an unclosed quote swallowed the next key: yaml-cpp folds it into the text "abc seed: 1 "
  expect_error("name: \"abc\nseed: 1\n", "name",
               {"closing quote is missing: it runs over 1 line to 'seed:' (line 2)",
                "allowed: text with its closing quote on the same line"});
  expect_error("seed: 3\nname: 'abc\n\n  seabed:\n", "name", {"runs over 2 lines to 'seabed:'"});
  // a quoted text may still run over lines that are not keys, and hold a ':' on its own line
  CHECK(parse_scene("name: \"abc\n  def\"\nseed: 2\n", "m.yaml").name == "abc def");
  CHECK(parse_scene("name: \"a: b\"\nseed: 2\n", "m.yaml").name == "a: b");
  CHECK(parse_scene("name: 'it''s: fine'\nseed: 2\n", "m.yaml").seed == 2);
  // a target without position_m was put at the origin
  expect_error(
      "targets: [{type: manta}]\n", "targets[0].position_m",
      {"is not set: every target needs its position",
       "allowed: [north, east] in metres inside the seabed extent ([-50, 50] x [-50, 50])"});
}
