// Tests of the scenario loader (config/loader/scenario_loader.h): scene keys, `sonar:` and
// `vehicle:` share the top level, the sonar is a preset name or a map (default: pailhas_strip),
// the vehicle is checked against the scene's seabed, unknown top-level keys are still reported,
// every shipped scenario loads, and config/reference.yaml gives exactly the documented defaults.
// (vehicle_loader_test covers the vehicle section key by key.)
#include "config/loader/scenario_loader.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/scenario_checks.h"
#include "tests/config/scene_loader_checks.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "config/default_scenario.h"
#include "config/loader/scene_loader.h"
#include "config/loader/sonar_loader.h"
#include "sim/render/chip_renderer.h"
#include "sim/render/ping_renderer.h"
#include "sim/scene/memory_estimate.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop::config;
namespace render = sonarloop::render;
namespace acoustics = sonarloop::acoustics;
namespace scene = sonarloop::scene;

using sonarloop::testing::check_same_sonar;
using sonarloop::testing::contains;
using sonarloop::testing::expect_scenario_error;

namespace {

// the scene fields a scenario test can tell apart (scene_loader_test compares every field)
void check_same_scene(const scene::SceneDesc& a, const scene::SceneDesc& b) {
  CHECK(a.seed == b.seed);
  CHECK(a.name == b.name);
  CHECK(a.water.depth_m == b.water.depth_m);
  CHECK(a.seabed.extent_m == b.seabed.extent_m);
  CHECK(a.seabed.regions.size() == b.seabed.regions.size());
  CHECK(a.targets.size() == b.targets.size());
}

const std::vector<std::string> kSonarKeys = {"name",
                                             "preset",
                                             "frequency_khz",
                                             "source_level_db",
                                             "pulse_length_us",
                                             "chirp_bandwidth_khz",
                                             "array_length_m",
                                             "array_height_m",
                                             "depression_deg",
                                             "max_range_m",
                                             "bin_size_cm",
                                             "ping_period_s",
                                             "along_track",
                                             "along_track_resolution_cm",
                                             "sample_type",
                                             "tvg",
                                             "gain_db",
                                             "bottom_model",
                                             "lambert_mu_db",
                                             "target_specular_fraction",
                                             "target_rms_slope",
                                             "speckle",
                                             "noise",
                                             "speckle_model",
                                             "raw_samples_per_bin",
                                             "downsample",
                                             "noise_floor_db_fs",
                                             "ringdown_us",
                                             "rays_per_bin",
                                             "along_track_rays"};

}  // namespace

TEST_CASE("scenario_loader: no sonar key gives the pailhas_strip preset") {
  const auto s = parse_scenario("seed: 4\nwater: {depth_m: 40}\n", "survey.yaml");
  CHECK(s.scene.seed == 4);
  CHECK(s.scene.water.depth_m == 40);
  CHECK(s.scene.name == "survey");
  check_same_sonar(s.sonar, builtin_sonar("pailhas_strip"));
  // the scene part is what the scene loader gives for the same text
  check_same_scene(s.scene, parse_scene("seed: 4\nwater: {depth_m: 40}\n", "survey.yaml"));
  // empty documents, empty or null sonar
  check_same_sonar(parse_scenario("", "e.yaml").sonar, builtin_sonar("pailhas_strip"));
  check_same_sonar(parse_scenario("sonar:\n", "e.yaml").sonar, builtin_sonar("pailhas_strip"));
  check_same_sonar(parse_scenario("sonar: {}\n", "e.yaml").sonar, builtin_sonar("pailhas_strip"));
}

TEST_CASE("scenario_loader: sonar as a preset name and as a map") {
  for (const auto& name : builtin_sonar_names()) {
    INFO(name);
    const auto s = parse_scenario("seed: 1\nsonar: " + name + "\n", "s.yaml");
    check_same_sonar(s.sonar, builtin_sonar(name));
    CHECK(s.scene.seed == 1);
  }
  // a map with a preset and overrides, keys of the scene on either side
  const auto s = parse_scenario(R"(seed: 2
sonar:
  preset: sidescan_100khz
  name: towfish
  max_range_m: 100
  tvg: point
water:
  depth_m: 60
)",
                                "map.yaml");
  auto expect = builtin_sonar("sidescan_100khz");
  expect.name = "towfish";
  expect.max_range_m = 100;
  expect.tvg = acoustics::TvgLaw::kPoint;
  check_same_sonar(s.sonar, expect);
  CHECK(s.scene.seed == 2);
  CHECK(s.scene.water.depth_m == 60);
  // a map without a preset starts from pailhas_strip; flow style works
  const auto f = parse_scenario("sonar: {bin_size_cm: 3, along_track_resolution_cm: 3}\n", "f");
  auto pailhas = builtin_sonar("pailhas_strip");
  pailhas.bin_size_m = 0.03;
  pailhas.along_track_resolution_m = 0.03;
  check_same_sonar(f.sonar, pailhas);
}

TEST_CASE("scenario_loader: errors in the sonar section name their path") {
  expect_scenario_error("sonar:\n  frequency_khz: 20\n", "sonar.frequency_khz",
                        {"20 is out of range (line 2, column 18)", "allowed: 50 .. 1000"});
  auto i =
      expect_scenario_error("sonar:\n  frequncy_khz: 200\n", "sonar.frequncy_khz",
                            {"unknown key 'frequncy_khz'", "allowed: name, preset, frequency_khz"});
  CHECK(i.suggestion == "frequency_khz");
  i = expect_scenario_error("sonar: sidescan_450\n", "sonar",
                            {"'sidescan_450' is not a sonar preset",
                             "allowed: sidescan_100khz, sidescan_450khz, sas_3cm, pailhas_strip, "
                             "iver2_600khz, or a map of sonar keys"});
  CHECK(i.suggestion == "sidescan_450khz");
  expect_scenario_error("sonar:\n  preset: nope\n", "sonar.preset",
                        {"'nope' is not a sonar preset"});
  expect_scenario_error("sonar: [1, 2]\n", "sonar", {"is not a sonar preset name or a map"});
  expect_scenario_error("sonar:\n  max_range_m: 1000\n  bin_size_cm: 1\n", "sonar.bin_size_cm",
                        {"100000 samples per side"});
}

TEST_CASE("scenario_loader: the vehicle section beside the others") {
  // absent: VehicleDesc{}; present: parsed, wherever it stands among the other keys
  const auto d = parse_scenario("seed: 3\n", "s.yaml");
  CHECK(d.vehicle.trajectory.kind == sonarloop::vehicle::TrajectoryKind::kStraight);
  CHECK(d.vehicle.trajectory.straight_length_m == 1000);
  CHECK(d.vehicle.nav.position_noise_sd_m == 0);
  const auto s = parse_scenario(R"(vehicle:
  trajectory:
    kind: lawnmower
    lawnmower: {origin_m: [20, -80], leg_length_m: 150, legs: 2, line_spacing_m: 40}
    max_turn_rate_deg_s: 10
    depth: {mode: altitude, altitude_m: 8}
  nav: {heading_bias_deg: 1}
sonar: sas_3cm
seabed:
  origin_m: [0, -100]
  extent_m: [200, 200]
seed: 5
)",
                                "survey.yaml");
  CHECK(s.scene.seed == 5);
  CHECK(s.sonar.name == "sas_3cm");
  CHECK(s.vehicle.trajectory.lawnmower.legs == 2);
  CHECK(s.vehicle.trajectory.depth.altitude_m == 8);
  CHECK(s.vehicle.nav.heading_bias == Approx(0.0174532925199));
  // the seabed rule uses the scene read from the same file, even when it comes later: moved
  // 30 m south, the survey's U-turn leaves the seabed's northern edge
  const std::string moved = R"(vehicle:
  trajectory:
    kind: lawnmower
    lawnmower: {origin_m: [20, -80], leg_length_m: 150, legs: 2, line_spacing_m: 40}
    max_turn_rate_deg_s: 10
    depth: {mode: altitude, altitude_m: 8}
seabed:
  origin_m: [-30, -100]
  extent_m: [200, 200]
)";
  expect_scenario_error(moved, "vehicle.trajectory",
                        {"the planned path leaves the seabed extent",
                         "U-turn after lawnmower leg 0", "north -30 .. 170, east -100 .. 100"});
  // errors in the section name their full path
  expect_scenario_error("vehicle:\n  trajectory:\n    kind: zigzag\n", "vehicle.trajectory.kind",
                        {"'zigzag' is not a trajectory kind (line 3, column 11)",
                         "allowed: straight, waypoints, lawnmower"});
  expect_scenario_error("vehicle: lawnmower\n", "vehicle",
                        {"'lawnmower' is not a map", "allowed: a map with trajectory, nav"});
}

TEST_CASE("scenario_loader: unknown top-level keys are still reported") {
  auto i = expect_scenario_error(
      "seed: 1\nsonr: sas_3cm\n", "sonr",
      {"unknown key 'sonr'", "allowed: seed, name, origin, water, seabed, targets, sonar, vehicle",
       "(did you mean 'sonar'?)"});
  CHECK(i.line == 2);
  i = expect_scenario_error("seeed: 1\n", "seeed", {"(did you mean 'seed'?)"});
  // every unknown key in one error, in file order
  try {
    parse_scenario("bogus: 1\nsonar: sas_3cm\nplatform: {}\n", "many.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    REQUIRE(e.issues().size() == 2);
    CHECK(e.issues()[0].path == "bogus");
    CHECK(e.issues()[1].path == "platform");
  }
  // the whole document must be a map
  expect_scenario_error("- 1\n", "",
                        {"is not a map",
                         "a map with seed, name, origin, water, seabed, "
                         "targets, sonar, vehicle"});
  // scene errors keep their paths
  expect_scenario_error("water: {depth_m: 1}\nsonar: sas_3cm\n", "water.depth_m",
                        {"1 is out of range"});
}

TEST_CASE("scenario_loader: every scenario shipped in config/ loads, and the embedded default") {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(SONARLOOP_SOURCE_DIR "/config")) {
    if (e.path().extension() == ".yaml") files.push_back(e.path());
  }
  CHECK(files.size() >= 6);
  for (const auto& f : files) {
    INFO(f.string());
    CHECK_NOTHROW(load_scenario(f.string()));
  }
  const auto embedded = parse_scenario(default_scenario_yaml(), "<default scenario>");
  const auto from_file = load_scenario(SONARLOOP_SOURCE_DIR "/config/default.yaml");
  check_same_sonar(embedded.sonar, from_file.sonar);
  CHECK(embedded.scene.seed == from_file.scene.seed);
  CHECK(embedded.scene.targets.size() == from_file.scene.targets.size());
}

TEST_CASE("scenario_loader: config/reference.yaml gives exactly the documented defaults") {
  const auto ref = load_scenario(SONARLOOP_SOURCE_DIR "/config/reference.yaml");
  // the sonar: the pailhas_strip preset, which is also the default of an empty scenario
  check_same_sonar(ref.sonar, builtin_sonar("pailhas_strip"));
  check_same_sonar(ref.sonar, parse_scenario("", "empty.yaml").sonar);
  // the scene: the defaults of an empty scenario (scene_loader_test checks every field)
  auto empty = parse_scenario("", "reference.yaml").scene;
  check_same_scene(ref.scene, empty);

  // the sonar section lists every key, each with a comment saying what is allowed
  const std::string path = SONARLOOP_SOURCE_DIR "/config/reference.yaml";
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const Field root = parse_document(text, path);
  const Field sonar = root.child("sonar");
  REQUIRE(sonar.is_map());
  for (const auto& key : kSonarKeys) {
    INFO(key);
    CHECK(sonar.has(key));
    const auto at = text.find("\n  " + key + ":");
    REQUIRE(at != std::string::npos);
    const auto eol = text.find('\n', at + 1);
    CHECK(contains(text.substr(at + 1, eol - at - 1), "#"));
  }
  CHECK_NOTHROW(sonar.finish());  // and no other key
  CHECK(sonar.child("preset").node().Scalar() == std::string(kDefaultSonarPreset));
  // the vehicle section is there too (vehicle_loader_test checks every key of it)
  CHECK(root.child("vehicle").is_map());
  CHECK(ref.vehicle.trajectory.straight_length_m == 1000);
}

TEST_CASE("scenario_loader: load_scenario reads a file") {
  sonarloop::testing::TempDir dir("config-scenario-loader");
  {
    std::ofstream out(dir.file("harbour.yaml"));
    out << "seed: 9\nsonar: sidescan_450khz\n";
  }
  const auto s = load_scenario(dir.file("harbour.yaml"));
  CHECK(s.scene.name == "harbour");
  CHECK(s.scene.seed == 9);
  CHECK(s.sonar.name == "sidescan_450khz");
  try {
    load_scenario(dir.file("missing.yaml"));
    FAIL("loaded a missing file");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(dir.file("missing.yaml") + ": (file): no such file", 0) == 0);
  }
  {
    std::ofstream out(dir.file("bad.yaml"));
    out << "seed: 9\nsonar:\n  bin_size_cm: 0\n";
  }
  try {
    load_scenario(dir.file("bad.yaml"));
    FAIL("accepted bin_size_cm 0");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(
              dir.file("bad.yaml") + ": sonar.bin_size_cm: 0 is out of range (line 3, column 16)",
              0) == 0);
  }
}

// ---------------------------------------------------------------------------------------------
// memory_limit_gb: huge scenarios refused before anything large is made

namespace {

// `count` Mantas in a row inside the default extent
std::string mantas(int count) {
  std::string yaml = "targets:\n";
  for (int i = 0; i < count; ++i)
    yaml += "  - {type: manta, position_m: [" + std::to_string(-49 + i % 98) + ", " +
            std::to_string(-49 + (i / 98) % 98) + "]}\n";
  return yaml;
}

}  // namespace

TEST_CASE("scenario_loader: the default scenario needs far less memory than the limit") {
  const auto s = load_scenario(SONARLOOP_SOURCE_DIR "/config/default.yaml");
  const render::SonarSetup setup = render::make_sonar_setup(s.sonar, s.scene.water);
  const render::Fidelity fidelity = render::default_fidelity(setup);
  const scene::MemoryEstimate e = scene::estimate_memory(
      s.scene, {setup.bins, fidelity.rays_per_bin, fidelity.along_track_rays, 2});
  INFO("targets " << e.targets_bytes << " B, tiles " << e.tiles_bytes << " B, pings "
                  << e.pings_bytes << " B");
  // four targets (~0.1 MB), 16 x 16 tiles of 256² points at 2.5 cm (84 MB), ray buffers
  CHECK(e.targets_bytes < 1e6);
  CHECK(e.tiles_bytes == Approx(256.0 * 65536 * 5));
  CHECK(e.total_bytes() < 0.05 * 4e9);  // under 5 % of the default 4 GB
}

TEST_CASE("scenario_loader: 1e5 targets are refused naming the key, the estimate and the limit") {
  // a long list of the cheapest targets is refused from its length alone, before its entries
  // are read (the entries here are not even valid targets)
  std::string boxes = "memory_limit_gb: 0.5\ntargets:\n";
  for (int i = 0; i < 100'000; ++i)
    boxes += "  - {}\n";
  sonarloop::testing::expect_config_error(
      parse_scenario, "huge.yaml", boxes, "targets",
      {"100000 targets need an estimated", "more than memory_limit_gb 0.5 GB",
       "memory_limit_gb (a top-level key, now 0.5) raised"});
  // 10,000 Mantas (~54 KB each) at a 0.5 GB limit: refused once read, with the parts of the
  // estimate (1e5 at the default 4 GB behave alike, at ten times the test's time)
  const std::string many = "memory_limit_gb: 0.5\n" + mantas(10'000);
  sonarloop::testing::expect_config_error(
      parse_scenario, "mantas.yaml", many, "targets",
      {"the scenario needs an estimated", "targets 0.539 GB", "heightmap tiles 0.0839 GB",
       "more than memory_limit_gb 0.5 GB", "memory_limit_gb (a top-level key, now 0.5)"});
  // a limit can be raised: 2,000 Mantas (~0.19 GB with the tiles) refused at 0.15 GB, accepted
  // at 0.3 GB (nothing is built by loading)
  const std::string some = mantas(2'000);
  sonarloop::testing::expect_config_error(parse_scenario, "some.yaml",
                                          "memory_limit_gb: 0.15\n" + some, "targets",
                                          {"more than memory_limit_gb 0.15 GB"});
  CHECK(parse_scenario("memory_limit_gb: 0.3\n" + some, "some.yaml").scene.targets.size() == 2'000);
}

TEST_CASE("scenario_loader: a huge extent at a fine spacing and a huge ray fan are refused") {
  // 1e9 m and 1e-6 m are outside the keys' ranges (scene_loader_errors_test); inside them the
  // tile caches are what grows, up to their budget (192 MB: seabed_model.h), allowed by default
  const std::string wide = "seabed: {extent_m: [100000, 100000], grid_spacing_m: 0.1}\n";
  CHECK_NOTHROW(parse_scenario(wide, "wide.yaml"));
  sonarloop::testing::expect_config_error(
      parse_scenario, "wide.yaml", "memory_limit_gb: 0.2\n" + wide, "seabed.grid_spacing_m",
      {"heightmap tiles 0.201 GB", "more than memory_limit_gb 0.2 GB", "now 0.2"});
  // the largest ray fan allowed per key: 64 x 256 rays per bin over both sides and 2 threads
  const std::string fan =
      "sonar: {preset: pailhas_strip, rays_per_bin: 64, along_track_rays: 256}\n";
  sonarloop::testing::expect_config_error(parse_scenario, "fan.yaml", fan, "sonar",
                                          {"ping buffers", "more than memory_limit_gb 4 GB"});
  sonarloop::testing::expect_config_error(parse_scenario, "limit.yaml", "memory_limit_gb: 0.01\n",
                                          "memory_limit_gb", {"0.1 .. 10000"});
}

TEST_CASE(
    "scenario_loader: the chip renderer's built-in seabed kinds are config/seabed_<kind>.yaml") {
  const std::map<std::string, std::string> files = {{"flat", "seabed_flat.yaml"},
                                                    {"ripples", "seabed_ripples.yaml"},
                                                    {"clutter", "seabed_cluttered.yaml"},
                                                    {"rocky", "seabed_rocky.yaml"}};
  REQUIRE(sonarloop::render::builtin_dataset_seabed_names().size() == files.size());
  for (const auto& name : sonarloop::render::builtin_dataset_seabed_names()) {
    INFO(name);
    const sonarloop::scene::SceneDesc a = sonarloop::render::builtin_dataset_seabed(name).desc;
    const sonarloop::scene::SceneDesc b =
        load_scenario(std::string(SONARLOOP_SOURCE_DIR) + "/config/" + files.at(name)).scene;
    CHECK(a.seed == b.seed);
    CHECK(a.water.depth_m == b.water.depth_m);
    CHECK(a.water.temperature_c == b.water.temperature_c);
    CHECK(a.water.salinity_ppt == b.water.salinity_ppt);
    CHECK(a.seabed.grid_spacing_m == b.seabed.grid_spacing_m);
    const auto& ea = a.seabed.elevation;
    const auto& eb = b.seabed.elevation;
    CHECK(ea.slope == eb.slope);
    CHECK(ea.rms_m == eb.rms_m);
    CHECK(ea.beta == eb.beta);
    CHECK(ea.outer_scale_m == eb.outer_scale_m);
    CHECK(ea.inner_scale_m == eb.inner_scale_m);
    CHECK(ea.spacing_m == eb.spacing_m);
    REQUIRE(a.seabed.regions.size() == 1);
    REQUIRE(b.seabed.regions.size() == 1);
    // the region, field by field (its centre and every texture parameter)
    scene_loader_checks::check_same(a.seabed.regions[0], b.seabed.regions[0]);
  }
}
