// Tests of what the sonar loader (config/loader/sonar_loader.h) refuses: unknown presets and
// keys, wrong types, out-of-range values and the rules between keys (ping period, range bins,
// chirp resolution, array length), each error at its YAML key with the allowed values. The
// accepted documents are in sonar_loader_test.cpp.
#include "config/loader/sonar_loader.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/scenario_checks.h"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "sim/render/sonar.h"

using namespace sonarloop::config;
namespace render = sonarloop::render;
namespace scene = sonarloop::scene;

using sonarloop::testing::expect_sonar_error;

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
  expect_sonar_error("speckle_model: gauss\n", "speckle_model", {"per_bin", "pulse"});
  expect_sonar_error("downsample: mean\n", "downsample", {"rms", "max", "decimate"});
  expect_sonar_error("raw_samples_per_bin: 17\n", "raw_samples_per_bin", {"1 .. 16"});
  // raw samples are the pulse model's
  expect_sonar_error("raw_samples_per_bin: 3\n", "raw_samples_per_bin",
                     {"3 raw samples per bin with speckle_model per_bin", "speckle_model: pulse"});
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
      {"array_height_m", "0.0009", "0.001 .. 1"},
      {"array_height_m", "1.5", "0.001 .. 1"},
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
