// Tests of the sonar loader (config/loader/sonar_loader.h): every key and its unit conversion,
// the defaults (the pailhas_strip preset), the built-in presets, preset + override, every
// validation rule, reading files and writing YAML. The seeded randomized test is in
// sonar_loader_random_test.cpp.
#include "config/loader/sonar_loader.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/config_test_text.h"
#include "tests/config/scenario_checks.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sim/render/sonar.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop::config;
namespace render = sonarloop::render;
namespace acoustics = sonarloop::acoustics;
namespace scene = sonarloop::scene;

using sonarloop::testing::check_same_sonar;
using sonarloop::testing::contains;
using sonarloop::testing::real_text;
using sonarloop::testing::slurp;

namespace {

const std::vector<std::string> kPresetNames = {"sidescan_100khz", "sidescan_450khz", "sas_3cm",
                                               "pailhas_strip", "iver2_600khz"};

// every sonar key, in the documented order
const std::vector<std::string> kKeys = {"name",
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
                                        "rays_per_bin",
                                        "along_track_rays"};

// Parses `yaml` as "sonar.yaml", which must fail (testing::check_config_error).
ConfigIssue expect_sonar_error(const std::string& yaml, const std::string& path,
                               const std::vector<std::string>& parts = {}) {
  return sonarloop::testing::expect_config_error(parse_sonar, "sonar.yaml", yaml, path, parts);
}

// The documented pailhas_strip preset (config/sonars/pailhas_strip.yaml, config/reference.yaml).
render::SonarDesc documented_pailhas_strip() {
  render::SonarDesc d;
  d.name = "pailhas_strip";
  d.frequency_hz = 300e3;
  d.source_level_db = 210;
  d.pulse_length_s = 0;
  d.chirp_bandwidth_hz = 0;
  d.array_length_m = 0.5;
  d.array_height_m = 0.006;
  d.depression_deg = 15;
  d.max_range_m = 50;
  d.bin_size_m = 0.05;
  d.ping_period_s = 0;
  d.along_track = render::AlongTrackModel::kStrip;
  d.along_track_resolution_m = 0.05;
  d.sample_type = render::SampleType::kUint16;
  d.tvg = std::nullopt;
  d.gain_db = 0;
  d.bottom_model = acoustics::BottomModel::kApl;
  d.lambert_mu_db = -27;
  d.speckle = true;
  d.noise = true;
  d.rays_per_bin = 0;
  d.along_track_rays = 0;
  return d;
}

double deg(double rad) {
  return rad * 180.0 / std::numbers::pi;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// defaults and keys

TEST_CASE("sonar_loader: absent, empty and null give the pailhas_strip preset") {
  const auto expect = documented_pailhas_strip();
  check_same_sonar(builtin_sonar("pailhas_strip"), expect);
  check_same_sonar(builtin_sonar(kDefaultSonarPreset), expect);
  for (const std::string text :
       {"", "{}\n", "~\n", "# only a comment\n", "preset: pailhas_strip\n", "pailhas_strip\n"}) {
    INFO("text: " << text);
    check_same_sonar(parse_sonar(text, "s.yaml"), expect);
  }
  // a sonar key that is absent from a larger document
  const Field root = parse_document("other: 1\n", "doc.yaml");
  check_same_sonar(parse_sonar_node(root.child("sonar")), expect);
}

TEST_CASE("sonar_loader: every key is parsed and converted to SI") {
  const auto d = parse_sonar(R"(name: test sonar
preset: sidescan_100khz
frequency_khz: 123.5
source_level_db: 201.5
pulse_length_us: 80
chirp_bandwidth_khz: 0
array_length_m: 0.75
array_height_m: 0.03
depression_deg: 22.5
max_range_m: 80
bin_size_cm: 4
ping_period_s: 0.25
along_track: strip
along_track_resolution_cm: 7.5
sample_type: float32
tvg: spherical
gain_db: -12.5
bottom_model: lambert
lambert_mu_db: -30
speckle: false
noise: false
rays_per_bin: 3
along_track_rays: 9
)",
                             "full.yaml");
  CHECK(d.name == "test sonar");
  CHECK(d.frequency_hz == 123500.0);
  CHECK(d.source_level_db == 201.5);
  CHECK(d.pulse_length_s == 80e-6);
  CHECK(d.chirp_bandwidth_hz == 0.0);
  CHECK(d.array_length_m == 0.75);
  CHECK(d.array_height_m == 0.03);
  CHECK(d.depression_deg == 22.5);
  CHECK(d.max_range_m == 80.0);
  CHECK(d.bin_size_m == 0.04);
  CHECK(d.ping_period_s == 0.25);
  CHECK(d.along_track == render::AlongTrackModel::kStrip);
  CHECK(d.along_track_resolution_m == 0.075);
  CHECK(d.sample_type == render::SampleType::kFloat32);
  CHECK(d.tvg == acoustics::TvgLaw::kSpherical);
  CHECK(d.gain_db == -12.5);
  CHECK(d.bottom_model == acoustics::BottomModel::kLambert);
  CHECK(d.lambert_mu_db == -30.0);
  CHECK_FALSE(d.speckle);
  CHECK_FALSE(d.noise);
  CHECK(d.rays_per_bin == 3);
  CHECK(d.along_track_rays == 9);

  // a chirp, in kHz
  const auto c = parse_sonar("chirp_bandwidth_khz: 20\npulse_length_us: 2500\n", "chirp.yaml");
  CHECK(c.chirp_bandwidth_hz == 20000.0);
  CHECK(c.pulse_length_s == 2.5e-3);
  // integers are numbers too, fractions of kHz and cm convert
  const auto f = parse_sonar("frequency_khz: 455\nbin_size_cm: 2.5\nmax_range_m: 75.5\n", "f.yaml");
  CHECK(f.frequency_hz == 455000.0);
  CHECK(f.bin_size_m == 0.025);
  CHECK(f.max_range_m == 75.5);
}

TEST_CASE("sonar_loader: every word of the enumerated keys") {
  const auto at = [](const std::string& key, const std::string& word) {
    return parse_sonar(key + ": " + word + "\n", "w.yaml");
  };
  CHECK(at("along_track", "beam").along_track == render::AlongTrackModel::kBeam);
  CHECK(at("along_track", "strip").along_track == render::AlongTrackModel::kStrip);
  CHECK(at("sample_type", "uint8").sample_type == render::SampleType::kUint8);
  CHECK(at("sample_type", "uint16").sample_type == render::SampleType::kUint16);
  CHECK(at("sample_type", "int16").sample_type == render::SampleType::kInt16);
  CHECK(at("sample_type", "float32").sample_type == render::SampleType::kFloat32);
  CHECK(at("tvg", "auto").tvg == std::nullopt);
  CHECK(at("tvg", "area").tvg == acoustics::TvgLaw::kArea);
  CHECK(at("tvg", "point").tvg == acoustics::TvgLaw::kPoint);
  CHECK(at("tvg", "spherical").tvg == acoustics::TvgLaw::kSpherical);
  CHECK(at("bottom_model", "apl").bottom_model == acoustics::BottomModel::kApl);
  CHECK(at("bottom_model", "lambert").bottom_model == acoustics::BottomModel::kLambert);
  CHECK(at("speckle", "false").speckle == false);
  CHECK(at("speckle", "True").speckle == true);
  CHECK(at("noise", "FALSE").noise == false);
  // tvg auto overrides a preset's explicit law (none has one today: set it, then reset it)
  CHECK(parse_sonar("tvg: area\n", "t.yaml").tvg == acoustics::TvgLaw::kArea);
}

// ---------------------------------------------------------------------------------------------
// built-in presets

TEST_CASE("sonar_loader: the built-in presets are the files of config/sonars, embedded") {
  CHECK(builtin_sonar_names() == kPresetNames);
  REQUIRE(builtin_sonar_presets().size() == kPresetNames.size());
  // every YAML file of config/sonars is a listed preset (no file forgotten in CMakeLists.txt)
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(SONARLOOP_SOURCE_DIR "/config/sonars")) {
    if (e.path().extension() == ".yaml") files.push_back(e.path().stem().string());
  }
  std::sort(files.begin(), files.end());
  auto listed = kPresetNames;
  std::sort(listed.begin(), listed.end());
  CHECK(files == listed);
  // the embedded text is the file's text (the build regenerates it when a file changes)
  for (const auto& [name, text] : builtin_sonar_presets()) {
    INFO(name);
    CHECK(text == slurp(SONARLOOP_SOURCE_DIR "/config/sonars/" + name + ".yaml"));
  }
}

TEST_CASE("sonar_loader: each preset loads, is complete and named, and round-trips") {
  for (const auto& [name, text] : builtin_sonar_presets()) {
    INFO(name);
    const auto d = builtin_sonar(name);
    CHECK(d.name == name);
    // the preset sets every key but preset (so it does not depend on SonarDesc's defaults)
    const Field root = parse_document(text, name);
    for (const auto& key : kKeys) {
      INFO(key);
      CHECK(root.has(key) == (key != "preset"));
    }
    // as a file, as text, by name as a scalar node, and written back out
    check_same_sonar(load_sonar(SONARLOOP_SOURCE_DIR "/config/sonars/" + name + ".yaml"), d);
    check_same_sonar(parse_sonar(text, name + ".yaml"), d);
    check_same_sonar(parse_sonar(name, "by-name.yaml"), d);
    const std::string yaml = format_sonar_yaml(d);
    INFO(yaml);
    check_same_sonar(parse_sonar(yaml, "written.yaml"), d);
    CHECK(format_sonar_yaml(parse_sonar(yaml, "written.yaml")) == yaml);
    // indented, as under a scenario's sonar: key
    const std::string nested = "sonar:\n" + format_sonar_yaml(d, 2);
    check_same_sonar(parse_sonar_node(parse_document(nested, "nested.yaml").child("sonar")), d);
    // the renderer accepts it
    CHECK_NOTHROW(render::make_sonar_setup(d, scene::WaterDesc{}));
  }
}

TEST_CASE("sonar_loader: the presets' documented numbers") {
  // (c = 1500 m/s, as in the presets' comments)
  scene::WaterDesc water;
  struct Row {
    std::string name;
    double freq_hz, length_m, range_m, bin_m, chirp_hz;
    render::AlongTrackModel model;
    int samples;
    double horizontal_one_way_deg, vertical_deg;
  };
  const std::vector<Row> rows = {
      {"sidescan_100khz", 100e3, 1.2, 150, 0.10, 0, render::AlongTrackModel::kBeam, 1500, 0.634,
       49.1},
      {"sidescan_450khz", 450e3, 0.8, 50, 0.03, 0, render::AlongTrackModel::kBeam, 1666, 0.211,
       34.35},
      {"sas_3cm", 100e3, 1.0, 75, 0.03, 30e3, render::AlongTrackModel::kStrip, 2500, 0.761, 49.1},
      {"pailhas_strip", 300e3, 0.5, 50, 0.05, 0, render::AlongTrackModel::kStrip, 1000, 0.508,
       43.3},
      // the real Iver2 / Sea Scan file's 1024 samples over 29.9835 m
      {"iver2_600khz", 600e3, 0.5, 29.9835015, 0.029280763, 0, render::AlongTrackModel::kBeam, 1024,
       0.254, 25.59},
  };
  for (const auto& r : rows) {
    INFO(r.name);
    const auto d = builtin_sonar(r.name);
    CHECK(d.frequency_hz == r.freq_hz);
    CHECK(d.array_length_m == r.length_m);
    CHECK(d.max_range_m == r.range_m);
    CHECK(d.bin_size_m == Approx(r.bin_m).epsilon(1e-15));  // cm -> m may round the last bit
    CHECK(d.chirp_bandwidth_hz == r.chirp_hz);
    CHECK(d.along_track == r.model);
    const double c = kNominalSoundSpeed_m_s;
    CHECK(deg(acoustics::beamwidth_3db_one_way_rad(d.array_length_m, c / d.frequency_hz)) ==
          Approx(r.horizontal_one_way_deg).margin(0.001));
    CHECK(deg(acoustics::beamwidth_3db_one_way_rad(d.array_height_m, c / d.frequency_hz)) ==
          Approx(r.vertical_deg).margin(0.05));
    const auto setup = render::make_sonar_setup(d, water);
    CHECK(setup.bins == r.samples);
    if (d.along_track == render::AlongTrackModel::kStrip) {
      CHECK(setup.along_track_resolution_m == d.bin_size_m);  // isotropic pixels
    }
    // range resolution: one bin for the auto CW pulse, c·tau/2 for a given one; c/(2B) = 2.5 cm
    // for the SAS chirp
    const double expect_res = r.chirp_hz > 0 ? setup.sound_speed_m_s / (2 * r.chirp_hz)
                              : d.pulse_length_s > 0.0
                                  ? setup.sound_speed_m_s * d.pulse_length_s / 2
                                  : r.bin_m;
    CHECK(setup.range_resolution_m == Approx(expect_res).epsilon(1e-12));
  }
  // the 100 kHz beam: 1.2 m along track at 150 m (two-way width), as documented
  const auto s100 = builtin_sonar("sidescan_100khz");
  CHECK(150 * acoustics::beamwidth_3db_two_way_rad(1.2, 1500 / s100.frequency_hz) ==
        Approx(1.196).margin(0.001));
}

TEST_CASE("sonar_loader: a preset with overrides") {
  const auto base = builtin_sonar("sidescan_450khz");
  auto d = parse_sonar("preset: sidescan_450khz\nmax_range_m: 30\ngain_db: 6\n", "o.yaml");
  auto expect = base;
  expect.max_range_m = 30;
  expect.gain_db = 6;
  check_same_sonar(d, expect);
  // the name: the preset's unless given; empty = the preset's
  CHECK(parse_sonar("preset: sas_3cm\n", "a.yaml").name == "sas_3cm");
  CHECK(parse_sonar("preset: sas_3cm\nname: my sas\n", "a.yaml").name == "my sas");
  CHECK(parse_sonar("preset: sas_3cm\nname: \"\"\n", "a.yaml").name == "sas_3cm");
  CHECK(parse_sonar("bin_size_cm: 2\n", "a.yaml").name == "pailhas_strip");
  // key order does not matter: preset after the overrides
  check_same_sonar(parse_sonar("gain_db: 6\nmax_range_m: 30\npreset: sidescan_450khz\n", "o.yaml"),
                   expect);
  // switching a strip preset to a beam
  const auto beam = parse_sonar("along_track: beam\n", "b.yaml");
  CHECK(beam.along_track == render::AlongTrackModel::kBeam);
  CHECK(beam.frequency_hz == 300e3);
}

// ---------------------------------------------------------------------------------------------
// validation

TEST_CASE("sonar_loader: unknown presets list the available names") {
  auto i = expect_sonar_error("preset: sidescan_100\n", "preset",
                              {"'sidescan_100' is not a sonar preset", "(line 1, column 9)",
                               "allowed: sidescan_100khz, sidescan_450khz, sas_3cm, pailhas_strip, "
                               "iver2_600khz"});
  CHECK(i.suggestion == "sidescan_100khz");
  // a preset name as the whole node: a map is allowed too
  i = expect_sonar_error("sas3cm\n", "",
                         {"'sas3cm' is not a sonar preset", "or a map of sonar keys"});
  CHECK(i.suggestion == "sas_3cm");
  i = expect_sonar_error("preset: [a]\n", "preset", {"is not a sonar preset name"});
  i = expect_sonar_error("preset: ~\n", "preset", {"has no value"});
  // by name, from code
  try {
    builtin_sonar("pailhas");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    CHECK(msg.rfind("<built-in sonars>: preset: 'pailhas' is not a sonar preset; allowed: "
                    "sidescan_100khz, sidescan_450khz, sas_3cm, pailhas_strip, iver2_600khz",
                    0) == 0);
  }
  CHECK_THROWS_AS(builtin_sonar(""), ConfigError);
}

TEST_CASE("sonar_loader: unknown keys, with suggestions") {
  auto i =
      expect_sonar_error("frequency_hz: 100000\n", "frequency_hz",
                         {"unknown key 'frequency_hz'",
                          "allowed: name, preset, frequency_khz, source_level_db, pulse_length_us",
                          "rays_per_bin, along_track_rays", "(did you mean 'frequency_khz'?)"});
  i = expect_sonar_error("bin_size_m: 0.05\n", "bin_size_m", {"(did you mean 'bin_size_cm'?)"});
  i = expect_sonar_error("depresion_deg: 10\n", "depresion_deg",
                         {"(did you mean 'depression_deg'?)"});
  i = expect_sonar_error("beam_pattern: sinc\n", "beam_pattern", {"unknown key 'beam_pattern'"});
  CHECK(i.suggestion.empty());
  // every unknown key is listed
  try {
    parse_sonar("zz1: 1\nfrequency_khz: 100\nzz2: 2\n", "two.yaml");
    FAIL("accepted");
  } catch (const ConfigError& e) {
    REQUIRE(e.issues().size() == 2);
    CHECK(e.issues()[0].path == "zz1");
    CHECK(e.issues()[1].path == "zz2");
  }
}

TEST_CASE("sonar_loader: wrong types") {
  expect_sonar_error("frequency_khz: abc\n", "frequency_khz",
                     {"'abc' is not a number", "50 .. 1000"});
  expect_sonar_error("frequency_khz: '300'\n", "frequency_khz",
                     {"is a quoted string, not a number"});
  expect_sonar_error("frequency_khz: .nan\n", "frequency_khz", {"is not a finite number"});
  expect_sonar_error("frequency_khz: [300]\n", "frequency_khz", {"is not a number"});
  expect_sonar_error("max_range_m:\n", "max_range_m", {"has no value"});
  expect_sonar_error("speckle: yes\n", "speckle", {"'yes' is not true or false"});
  expect_sonar_error("noise: 1\n", "noise", {"true or false"});
  expect_sonar_error("rays_per_bin: 2.5\n", "rays_per_bin", {"'2.5' is not an integer", "0 .. 64"});
  expect_sonar_error("along_track_rays: abc\n", "along_track_rays", {"an integer 0 .. 256"});
  expect_sonar_error("along_track: [beam]\n", "along_track", {"beam, strip"});
  auto i = expect_sonar_error("along_track: beams\n", "along_track",
                              {"'beams' is not a known along-track model", "allowed: beam, strip"});
  CHECK(i.suggestion == "beam");
  i = expect_sonar_error("sample_type: uint32\n", "sample_type",
                         {"is not a sample type", "allowed: uint8, uint16, int16, float32"});
  CHECK(i.suggestion == "uint16");
  expect_sonar_error("tvg: 30log\n", "tvg",
                     {"is not a TVG law", "allowed: auto, area, point, spherical"});
  expect_sonar_error("bottom_model: apl-uw\n", "bottom_model",
                     {"is not a bottom model", "allowed: apl, lambert"});
  expect_sonar_error("name: [a, b]\n", "name", {"is not text"});
  expect_sonar_error("name: ~\n", "name", {"has no value"});
  // the whole node
  expect_sonar_error("[1, 2]\n", "", {"is not a sonar preset name or a map", "pailhas_strip"});
  expect_sonar_error("- frequency_khz: 100\n", "", {"is not a sonar preset name or a map"});
  // syntax errors and duplicate keys
  expect_sonar_error("frequency_khz: [100\n", "", {"YAML syntax error"});
  expect_sonar_error("gain_db: 1\ngain_db: 2\n", "gain_db", {"duplicate key 'gain_db'"});
}

TEST_CASE("sonar_loader: out-of-range values name the key, value and range") {
  struct Case {
    std::string key;
    std::string value;
    std::string allowed;
  };
  const std::vector<Case> cases = {
      {"frequency_khz", "49.9", "50 .. 1000"},
      {"frequency_khz", "1000.5", "50 .. 1000"},
      {"source_level_db", "149", "150 .. 250"},
      {"source_level_db", "251", "150 .. 250"},
      {"pulse_length_us", "-1", "0 .. 10000 (0 = auto)"},
      {"pulse_length_us", "10001", "0 .. 10000 (0 = auto)"},
      {"chirp_bandwidth_khz", "-5", "0 .. 500 (0 = CW)"},
      {"chirp_bandwidth_khz", "501", "0 .. 500 (0 = CW)"},
      {"array_length_m", "0.019", "0.02 .. 10"},
      {"array_length_m", "11", "0.02 .. 10"},
      {"array_height_m", "0.004", "0.005 .. 1"},
      {"array_height_m", "1.5", "0.005 .. 1"},
      {"depression_deg", "-1", "0 .. 60"},
      {"depression_deg", "61", "0 .. 60"},
      {"max_range_m", "0.5", "1 .. 1000"},
      {"max_range_m", "1001", "1 .. 1000"},
      {"bin_size_cm", "0.9", "1 .. 100"},
      {"bin_size_cm", "101", "1 .. 100"},
      {"ping_period_s", "-0.1", "0 .. 10 (0 = auto)"},
      {"ping_period_s", "11", "0 .. 10 (0 = auto)"},
      {"along_track_resolution_cm", "-1", "0 .. 500 (0 = bin_size_cm)"},
      {"along_track_resolution_cm", "501", "0 .. 500 (0 = bin_size_cm)"},
      {"gain_db", "-101", "-100 .. 100"},
      {"gain_db", "100.5", "-100 .. 100"},
      {"lambert_mu_db", "-61", "-60 .. -4.97"},
      {"lambert_mu_db", "-4.9", "-60 .. -4.97"},
      {"rays_per_bin", "-1", "an integer 0 .. 64"},
      {"rays_per_bin", "65", "an integer 0 .. 64"},
      {"along_track_rays", "-1", "an integer 0 .. 256"},
      {"along_track_rays", "257", "an integer 0 .. 256"},
  };
  for (const auto& c : cases) {
    INFO(c.key << ": " << c.value);
    const auto i =
        expect_sonar_error(c.key + ": " + c.value + "\n", c.key,
                           {c.value + " is out of range", "allowed: " + c.allowed,
                            "(line 1, column " + std::to_string(c.key.size() + 3) + ")"});
    CHECK(i.line == 1);
  }
  // each end is allowed
  CHECK_NOTHROW(parse_sonar("frequency_khz: 1000\nlambert_mu_db: -4.97\ngain_db: -100\n", "e"));
  CHECK_NOTHROW(parse_sonar(
      "frequency_khz: 50\narray_length_m: 10\narray_height_m: 1\ndepression_deg: 60\n"
      "ping_period_s: 10\npulse_length_us: 10000\nrays_per_bin: 64\nalong_track_rays: 256\n"
      "along_track_resolution_cm: 500\nsource_level_db: 250\nlambert_mu_db: -60\n",
      "e"));
  CHECK_NOTHROW(parse_sonar("max_range_m: 1\nbin_size_cm: 1\n", "e"));
  CHECK_NOTHROW(parse_sonar("max_range_m: 1000\nbin_size_cm: 100\n", "e"));
}

TEST_CASE("sonar_loader: the ping period is at least the two-way travel time of the range") {
  // issue 11: 1e-9 s was accepted ("1000000000.00 pings/s") and `run` never ended
  expect_sonar_error(
      "ping_period_s: 1e-9\n", "ping_period_s",
      {"1e-09 s is shorter than the two-way travel time 2 max_range_m / c = 0.0666667 s "
       "of max_range_m 50 (c = 1500 m/s)",
       "allowed: 0 (auto: 2 max_range_m / c), or 0.0667 .. 10 for max_range_m 50"});
  expect_sonar_error("max_range_m: 30\nping_period_s: 0.0399\n", "ping_period_s",
                     {"shorter than the two-way travel time", "0.04 .. 10 for max_range_m 30"});
  // exactly the two-way time, 0 (auto) and longer periods are fine
  CHECK(parse_sonar("max_range_m: 30\nping_period_s: 0.04\n", "p").ping_period_s == 0.04);
  CHECK(parse_sonar("ping_period_s: 0\n", "p").ping_period_s == 0.0);
  CHECK(parse_sonar("ping_period_s: 0.5\n", "p").ping_period_s == 0.5);
  // the preset's period with a longer range set here: max_range_m is to blame
  expect_sonar_error("preset: iver2_600khz\nmax_range_m: 100\n", "max_range_m",
                     {"100 has a two-way travel time 2 max_range_m / c = 0.133333 s, longer than "
                      "ping_period_s 0.1135",
                      "allowed: <= 85.125 for ping_period_s 0.1135; or ping_period_s 0 (auto)"});
}

TEST_CASE("sonar_loader: range bin below the maximum range, at most 65535 samples") {
  expect_sonar_error("max_range_m: 1\nbin_size_cm: 100\n", "bin_size_cm",
                     {"100 is not below max_range_m 1", "allowed: below max_range_m (100 cm)"});
  CHECK(parse_sonar("max_range_m: 1\nbin_size_cm: 99\n", "b").bin_size_m == 0.99);

  const auto i = expect_sonar_error(
      "max_range_m: 1000\nbin_size_cm: 1\n", "bin_size_cm",
      {"1 gives 100000 samples per side over max_range_m 1000",
       "allowed: >= 1.526 for max_range_m 1000 (at most 65535 samples per side, the XTF "
       "WORD-safe limit)",
       "(line 2, column 14)"});
  CHECK(i.line == 2);
  // the suggested bound works
  const auto ok = parse_sonar("max_range_m: 1000\nbin_size_cm: 1.526\n", "b");
  CHECK(render::make_sonar_setup(ok, scene::WaterDesc{}).bins <= kMaxSamplesPerSide);
  // exactly 65535 samples is allowed, 65536 is not
  const auto edge = parse_sonar("max_range_m: 655.35\nbin_size_cm: 1\n", "b");
  CHECK(render::make_sonar_setup(edge, scene::WaterDesc{}).bins == 65535);
  expect_sonar_error("max_range_m: 655.36\nbin_size_cm: 1\n", "bin_size_cm",
                     {"gives 65536 samples"});
}

TEST_CASE("sonar_loader: a chirp's range resolution spans at most 4 bins") {
  // pailhas_strip has 5 cm bins: c/(2B) <= 20 cm needs B >= 3.75 kHz
  expect_sonar_error(
      "chirp_bandwidth_khz: 2\n", "chirp_bandwidth_khz",
      {"2 gives a range resolution c/(2B) = 37.5 cm (c = 1500 m/s), coarser than 4 range "
       "bins of bin_size_cm 5",
       "allowed: 0 (CW), or >= 3.75 for bin_size_cm 5; or larger bins (bin_size_cm >= "
       "9.375)"});
  CHECK(parse_sonar("chirp_bandwidth_khz: 3.75\n", "c").chirp_bandwidth_hz == 3750.0);
  CHECK(parse_sonar("chirp_bandwidth_khz: 2\nbin_size_cm: 9.375\n", "c").bin_size_m == 0.09375);
  // both set: the bandwidth is named
  expect_sonar_error("chirp_bandwidth_khz: 2\nbin_size_cm: 9\n", "chirp_bandwidth_khz",
                     {"coarser than 4 range bins of bin_size_cm 9"});
  // the hint's bound is sufficient after rounding
  expect_sonar_error("chirp_bandwidth_khz: 1\nbin_size_cm: 3\n", "chirp_bandwidth_khz",
                     {">= 6.25 for bin_size_cm 3"});
  CHECK_NOTHROW(parse_sonar("chirp_bandwidth_khz: 6.25\nbin_size_cm: 3\n", "c"));
  // a chirp's band stays above 0 Hz: B < 2 f
  expect_sonar_error("frequency_khz: 50\narray_length_m: 1\nchirp_bandwidth_khz: 100\n",
                     "chirp_bandwidth_khz",
                     {"100 is not below twice frequency_khz 50", "allowed: 0 (CW), or below 100"});
  CHECK_NOTHROW(
      parse_sonar("frequency_khz: 50\narray_length_m: 1\nchirp_bandwidth_khz: 99.5\n", "c"));
}

TEST_CASE("sonar_loader: the array must be longer than a wavelength") {
  // at 50 kHz the wavelength is 1500/50e3 = 3 cm
  expect_sonar_error("frequency_khz: 50\narray_length_m: 0.03\n", "array_length_m",
                     {"0.03 is not longer than the wavelength c/f = 0.03 m at frequency_khz 50 "
                      "(c = 1500 m/s): the array would form no beam",
                      "allowed: more than 0.03 for frequency_khz 50"});
  expect_sonar_error("frequency_khz: 50\narray_length_m: 0.02\n", "array_length_m", {"no beam"});
  CHECK_NOTHROW(parse_sonar("frequency_khz: 50\narray_length_m: 0.031\n", "a"));
  CHECK_NOTHROW(parse_sonar("frequency_khz: 75.1\narray_length_m: 0.02\n", "a"));
  expect_sonar_error("frequency_khz: 75\narray_length_m: 0.02\n", "array_length_m",
                     {"more than 0.02 for frequency_khz 75"});
}

TEST_CASE("sonar_loader: load_sonar reads a file and names it in errors") {
  sonarloop::testing::TempDir dir("config-sonar-loader");
  {
    std::ofstream out(dir.file("towfish.yaml"));
    out << "# a towfish\npreset: sidescan_100khz\nname: towfish\nmax_range_m: 100\n";
  }
  const auto d = load_sonar(dir.file("towfish.yaml"));
  CHECK(d.name == "towfish");
  CHECK(d.max_range_m == 100);
  CHECK(d.frequency_hz == 100e3);
  try {
    load_sonar(dir.file("missing.yaml"));
    FAIL("loaded a missing file");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(dir.file("missing.yaml") + ": (file): no such file", 0) == 0);
  }
  {
    std::ofstream out(dir.file("bad.yaml"));
    out << "preset: sidescan_100khz\nfrequency_khz: 20\n";
  }
  try {
    load_sonar(dir.file("bad.yaml"));
    FAIL("accepted 20 kHz");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind(
              dir.file("bad.yaml") + ": frequency_khz: 20 is out of range (line 2, column 16)",
              0) == 0);
  }
}

TEST_CASE("sonar_loader: format_sonar_yaml quotes names and round-trips unusual values") {
  auto d = builtin_sonar("sidescan_450khz");
  d.name = "a: \"quoted\" # name\\ with\ttab";
  d.tvg = acoustics::TvgLaw::kPoint;
  d.pulse_length_s = 123.456e-6;
  d.frequency_hz = 123456.789;
  d.bin_size_m = 0.0123;
  const std::string yaml = format_sonar_yaml(d, 4);
  INFO(yaml);
  CHECK(yaml.rfind("    name: ", 0) == 0);
  const auto back = parse_sonar("\n" + yaml, "w.yaml");
  CHECK(back.name == d.name);
  CHECK(back.tvg == acoustics::TvgLaw::kPoint);
  CHECK(back.pulse_length_s == Approx(d.pulse_length_s).epsilon(1e-15));
  CHECK(back.frequency_hz == Approx(d.frequency_hz).epsilon(1e-15));
  CHECK(back.bin_size_m == Approx(d.bin_size_m).epsilon(1e-15));

  // the shortest text that converts back exactly: 0.07 m is "7" cm, although 0.07 * 100 is
  // 7.000000000000001 in binary
  auto s = builtin_sonar("pailhas_strip");
  s.bin_size_m = 0.07;
  s.along_track_resolution_m = 0.07;
  s.pulse_length_s = 70e-6;
  s.frequency_hz = 123.4e3;
  const std::string short_yaml = format_sonar_yaml(s);
  INFO(short_yaml);
  CHECK(contains(short_yaml, "\nbin_size_cm: 7\n"));
  CHECK(contains(short_yaml, "\nalong_track_resolution_cm: 7\n"));
  CHECK(contains(short_yaml, "\npulse_length_us: 70\n"));
  CHECK(contains(short_yaml, "\nfrequency_khz: 123.4\n"));
  check_same_sonar(parse_sonar(short_yaml, "short.yaml"), s);
  // and messages quote values the same way
  expect_sonar_error("bin_size_cm: 7\nchirp_bandwidth_khz: 1\n", "chirp_bandwidth_khz",
                     {"coarser than 4 range bins of bin_size_cm 7"});
}
