// Tests of the scene loader (config/loader/scene_loader.h): every validation rule has a case,
// and each error names the file, the key, the value and what is allowed.
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
