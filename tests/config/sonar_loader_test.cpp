// Tests of the sonar loader (config/loader/sonar_loader.h): every key and its unit conversion,
// the defaults (the pailhas_strip preset), the built-in presets, preset + override, reading files
// and writing YAML. What the loader refuses is in sonar_loader_errors_test.cpp, the seeded
// randomized test in sonar_loader_random_test.cpp.
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
#include "tests/sim/render/strip_sonar.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop::config;
namespace render = sonarloop::render;
namespace acoustics = sonarloop::acoustics;
namespace scene = sonarloop::scene;

using sonarloop::testing::check_same_sonar;
using sonarloop::testing::contains;
using sonarloop::testing::expect_sonar_error;
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
                                        "speckle_model",
                                        "raw_samples_per_bin",
                                        "downsample",
                                        "noise_floor_db_fs",
                                        "ringdown_us",
                                        "rays_per_bin",
                                        "along_track_rays"};

double deg(double rad) {
  return rad * 180.0 / std::numbers::pi;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// defaults and keys

TEST_CASE("sonar_loader: absent, empty and null give the pailhas_strip preset") {
  const auto expect = sonarloop::testing::pailhas_strip_sonar();
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
