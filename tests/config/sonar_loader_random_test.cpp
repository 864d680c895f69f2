// The sonar loader's seeded randomized test (docs/style.md habit 22): random valid sonars (a
// preset or none, with random keys in random order), written as YAML in every layout the loader
// reads, round-trip exactly; corruptions of them are always rejected with a ConfigError; and
// random byte edits give a sonar or a ConfigError, never a crash. (The fixed cases are in
// sonar_loader_test.cpp.)
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/rng.h"
#include "config/loader/scenario_loader.h"
#include "config/loader/sonar_loader.h"
#include "sim/render/sonar.h"
#include "tests/config/config_error_checks.h"
#include "tests/config/config_test_text.h"
#include "tests/config/scenario_checks.h"

using sonarloop::Rng;
using sonarloop::RngStream;
using namespace sonarloop::config;
namespace render = sonarloop::render;
namespace acoustics = sonarloop::acoustics;
namespace scene = sonarloop::scene;

using sonarloop::testing::check_same_sonar;
using sonarloop::testing::contains;
using sonarloop::testing::feed_byte_edits;
using sonarloop::testing::real_text;

namespace {

// How a key's value is read, for drawing valid values and corrupting them.
enum class Kind { kReal, kInt, kBool, kWord, kText };

struct KeySpec {
  std::string key;
  Kind kind;
  double lo = 0, hi = 0;           // kReal, kInt
  std::vector<std::string> words;  // kWord
};

const std::vector<KeySpec>& key_specs() {
  static const std::vector<KeySpec> specs = {
      {"name", Kind::kText, 0, 0, {}},
      {"frequency_khz", Kind::kReal, 50, 1000, {}},
      {"source_level_db", Kind::kReal, 150, 250, {}},
      {"pulse_length_us", Kind::kReal, 0, 10000, {}},
      {"chirp_bandwidth_khz", Kind::kReal, 0, 500, {}},
      {"array_length_m", Kind::kReal, 0.02, 10, {}},
      {"array_height_m", Kind::kReal, 0.001, 1, {}},
      {"depression_deg", Kind::kReal, 0, 60, {}},
      {"max_range_m", Kind::kReal, 1, 1000, {}},
      {"bin_size_cm", Kind::kReal, 1, 100, {}},
      {"ping_period_s", Kind::kReal, 0, 10, {}},
      {"along_track", Kind::kWord, 0, 0, {"beam", "strip"}},
      {"along_track_resolution_cm", Kind::kReal, 0, 500, {}},
      {"sample_type", Kind::kWord, 0, 0, {"uint8", "uint16", "int16", "float32"}},
      {"tvg", Kind::kWord, 0, 0, {"auto", "area", "point", "spherical"}},
      {"gain_db", Kind::kReal, -100, 100, {}},
      {"bottom_model", Kind::kWord, 0, 0, {"apl", "lambert"}},
      {"lambert_mu_db", Kind::kReal, -60, -4.97, {}},
      {"target_specular_fraction", Kind::kReal, 0, 1, {}},
      {"target_rms_slope", Kind::kReal, 0.02, 0.5, {}},
      {"speckle", Kind::kBool, 0, 0, {}},
      {"noise", Kind::kBool, 0, 0, {}},
      {"speckle_model", Kind::kWord, 0, 0, {"per_bin", "pulse"}},
      {"raw_samples_per_bin", Kind::kInt, 1, 16, {}},
      {"downsample", Kind::kWord, 0, 0, {"rms", "max", "decimate"}},
      {"noise_floor_db_fs", Kind::kReal, -150, 0, {}},
      {"ringdown_us", Kind::kReal, 0, 10000, {}},
      {"rays_per_bin", Kind::kInt, 0, 64, {}},
      {"along_track_rays", Kind::kInt, 0, 256, {}},
  };
  return specs;
}

// Applies one key (its YAML text already validated by the generator) to the expected SonarDesc.
void apply(render::SonarDesc& d, const std::string& key, const std::string& text) {
  const auto num = [&] { return std::stod(text); };
  if (key == "name") {
    if (!text.empty()) d.name = text;
  } else if (key == "frequency_khz") {
    d.frequency_hz = num() * 1e3;
  } else if (key == "source_level_db") {
    d.source_level_db = num();
  } else if (key == "pulse_length_us") {
    d.pulse_length_s = num() / 1e6;
  } else if (key == "chirp_bandwidth_khz") {
    d.chirp_bandwidth_hz = num() * 1e3;
  } else if (key == "array_length_m") {
    d.array_length_m = num();
  } else if (key == "array_height_m") {
    d.array_height_m = num();
  } else if (key == "depression_deg") {
    d.depression_deg = num();
  } else if (key == "max_range_m") {
    d.max_range_m = num();
  } else if (key == "bin_size_cm") {
    d.bin_size_m = num() / 100;
  } else if (key == "ping_period_s") {
    d.ping_period_s = num();
  } else if (key == "along_track") {
    d.along_track =
        text == "beam" ? render::AlongTrackModel::kBeam : render::AlongTrackModel::kStrip;
  } else if (key == "along_track_resolution_cm") {
    d.along_track_resolution_m = num() / 100;
  } else if (key == "sample_type") {
    d.sample_type = text == "uint8"    ? render::SampleType::kUint8
                    : text == "uint16" ? render::SampleType::kUint16
                    : text == "int16"  ? render::SampleType::kInt16
                                       : render::SampleType::kFloat32;
  } else if (key == "tvg") {
    if (text == "auto") d.tvg = std::nullopt;
    if (text == "area") d.tvg = acoustics::TvgLaw::kArea;
    if (text == "point") d.tvg = acoustics::TvgLaw::kPoint;
    if (text == "spherical") d.tvg = acoustics::TvgLaw::kSpherical;
  } else if (key == "gain_db") {
    d.gain_db = num();
  } else if (key == "bottom_model") {
    d.bottom_model =
        text == "apl" ? acoustics::BottomModel::kApl : acoustics::BottomModel::kLambert;
  } else if (key == "lambert_mu_db") {
    d.lambert_mu_db = num();
  } else if (key == "target_specular_fraction") {
    d.target_specular_fraction = num();
  } else if (key == "target_rms_slope") {
    d.target_rms_slope = num();
  } else if (key == "speckle") {
    d.speckle = text == "true";
  } else if (key == "noise") {
    d.noise = text == "true";
  } else if (key == "speckle_model") {
    d.speckle_model =
        text == "pulse" ? render::SpeckleModel::kPulse : render::SpeckleModel::kPerBin;
  } else if (key == "raw_samples_per_bin") {
    d.raw_samples_per_bin = std::stoi(text);
  } else if (key == "downsample") {
    d.downsample = text == "max"        ? acoustics::Downsample::kMax
                   : text == "decimate" ? acoustics::Downsample::kDecimate
                                        : acoustics::Downsample::kRms;
  } else if (key == "noise_floor_db_fs") {
    d.noise_floor_db_fs = num();
  } else if (key == "ringdown_us") {
    d.ringdown_s = num() / 1e6;
  } else if (key == "rays_per_bin") {
    d.rays_per_bin = std::stoi(text);
  } else if (key == "along_track_rays") {
    d.along_track_rays = std::stoi(text);
  }
}

// The cross-field rules, written independently of the loader (sonar_loader.h).
bool rules_hold(const render::SonarDesc& d) {
  const double c = 1500.0;
  if (!(d.bin_size_m < d.max_range_m)) return false;
  if (std::floor(d.max_range_m / d.bin_size_m + 1e-9) > 65535) return false;
  if (!(c / d.frequency_hz < d.array_length_m)) return false;
  if (d.ping_period_s > 0 && d.ping_period_s < 2 * d.max_range_m / c * (1 - 1e-12)) return false;
  if (d.chirp_bandwidth_hz > 0) {
    if (!(d.chirp_bandwidth_hz < 2 * d.frequency_hz)) return false;
    if (c / (2 * d.chirp_bandwidth_hz) > 4 * d.bin_size_m) return false;
  }
  if (d.raw_samples_per_bin > 1 && d.speckle_model != render::SpeckleModel::kPulse) return false;
  return true;
}

bool near(double a, double b) {
  return a == b || std::fabs(a - b) <= 1e-14 * std::max(std::fabs(a), std::fabs(b));
}

void check_near(const render::SonarDesc& a, const render::SonarDesc& b) {
  CHECK(a.name == b.name);
  CHECK(near(a.frequency_hz, b.frequency_hz));
  CHECK(a.source_level_db == b.source_level_db);
  CHECK(near(a.pulse_length_s, b.pulse_length_s));
  CHECK(near(a.chirp_bandwidth_hz, b.chirp_bandwidth_hz));
  CHECK(a.array_length_m == b.array_length_m);
  CHECK(a.array_height_m == b.array_height_m);
  CHECK(a.depression_deg == b.depression_deg);
  CHECK(a.max_range_m == b.max_range_m);
  CHECK(near(a.bin_size_m, b.bin_size_m));
  CHECK(a.ping_period_s == b.ping_period_s);
  CHECK(a.along_track == b.along_track);
  CHECK(near(a.along_track_resolution_m, b.along_track_resolution_m));
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
  CHECK(near(a.ringdown_s, b.ringdown_s));
  CHECK(a.rays_per_bin == b.rays_per_bin);
  CHECK(a.along_track_rays == b.along_track_rays);
}

struct Entry {
  std::string key;
  std::string text;
};

class SonarGenerator {
 public:
  explicit SonarGenerator(std::uint64_t sample) : rng_(20240612, RngStream::kDataset, sample) {}

  Rng& rng() { return rng_; }

  // A random valid sonar map (entries in random order) and the SonarDesc it describes.
  void generate(std::vector<Entry>& entries, render::SonarDesc& expect) {
    for (int attempt = 0;; ++attempt) {
      REQUIRE(attempt < 1000);
      entries.clear();
      std::string preset(kDefaultSonarPreset);
      if (rng_.uniform() < 0.6) {
        preset = presets_[rng_.below(presets_.size())];
        entries.push_back({"preset", preset});
      }
      expect = builtin_sonar(preset);
      const double p_key = rng_.uniform();  // how many keys this sample sets
      for (const auto& spec : key_specs()) {
        if (rng_.uniform() >= p_key) continue;
        const std::string text = draw(spec);
        entries.push_back({spec.key, text});
        apply(expect, spec.key, unquoted(text));
      }
      if (!rules_hold(expect)) continue;
      for (std::size_t i = entries.size(); i > 1; --i)
        std::swap(entries[i - 1], entries[rng_.below(i)]);
      return;
    }
  }

 private:
  static std::string unquoted(const std::string& t) {
    return t.size() >= 2 && t.front() == '"' ? t.substr(1, t.size() - 2) : t;
  }

  std::string draw(const KeySpec& s) {
    switch (s.kind) {
      case Kind::kReal: {
        const double u = rng_.uniform();
        if (u < 0.1) return real_text(s.lo);
        if (u < 0.2) return real_text(s.hi);
        if (u < 0.4 && std::floor(s.hi) >= std::ceil(s.lo))  // an integer, if the range has one
          return std::to_string(static_cast<int>(std::ceil(s.lo)) +
                                static_cast<int>(rng_.below(static_cast<std::uint64_t>(
                                    std::floor(s.hi) - std::ceil(s.lo) + 1))));
        if (s.lo > 0 && s.hi / s.lo >= 100) {
          return real_text(std::min(
              s.hi, std::max(s.lo, std::exp(rng_.uniform(std::log(s.lo), std::log(s.hi))))));
        }
        return real_text(rng_.uniform(s.lo, s.hi));
      }
      case Kind::kInt:
        return std::to_string(
            static_cast<int>(s.lo) +
            static_cast<int>(rng_.below(static_cast<std::uint64_t>(s.hi - s.lo + 1))));
      case Kind::kBool:
        return rng_.uniform() < 0.5 ? "true" : "false";
      case Kind::kWord:
        return s.words[rng_.below(s.words.size())];
      case Kind::kText: {
        const double u = rng_.uniform();
        if (u < 0.2) return "\"\"";
        if (u < 0.6) return "sonar " + std::to_string(rng_.below(1000));
        return "\"x: " + std::to_string(rng_.below(1000)) + "\"";
      }
    }
    return "";
  }

  Rng rng_;
  // the presets a sample may start from (sonar_loader_test.cpp checks the list)
  const std::vector<std::string> presets_ = builtin_sonar_names();
};

// block ("key: value" lines, indented) or flow ("{key: value, ...}") text of a map
std::string map_text(const std::vector<Entry>& entries, bool flow, int indent) {
  std::string out;
  if (flow) {
    out = "{";
    for (std::size_t i = 0; i < entries.size(); ++i)
      out += (i ? ", " : "") + entries[i].key + ": " + entries[i].text;
    return out + "}\n";
  }
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  for (const auto& e : entries)
    out += pad + e.key + ": " + e.text + "\n";
  return out;
}

// Parses a sonar map either as a standalone document or under `sonar:` in a larger one.
render::SonarDesc parse_either(const std::vector<Entry>& entries, bool nested, bool flow,
                               const std::string& file) {
  if (!nested) return parse_sonar(entries.empty() && !flow ? "" : map_text(entries, flow, 0), file);
  const std::string text = "other: 1\nsonar:" + (flow ? " " + map_text(entries, true, 0)
                                                      : "\n" + map_text(entries, false, 2));
  const Field root = parse_document(text, file);
  return parse_sonar_node(root.child("sonar"));
}

}  // namespace

TEST_CASE("sonar_loader: random valid sonars round-trip, corruptions are rejected") {
  constexpr int kSamples = 400;
  constexpr int kCorruptionsPerSample = 6;
  int corruptions = 0;
  int with_chirp = 0;
  for (int sample = 0; sample < kSamples; ++sample) {
    SonarGenerator gen(static_cast<std::uint64_t>(sample));
    std::vector<Entry> entries;
    render::SonarDesc expect;
    gen.generate(entries, expect);
    const bool nested = gen.rng().uniform() < 0.5;
    const bool flow = gen.rng().uniform() < 0.3;
    const std::string file = "random-" + std::to_string(sample) + ".yaml";
    INFO("sample " << sample << " (nested " << nested << ", flow " << flow << "):\n"
                   << map_text(entries, flow, 0));
    render::SonarDesc got;
    try {
      got = parse_either(entries, nested, flow, file);
    } catch (const ConfigError& e) {
      FAIL("valid sonar rejected: " << e.what());
    }
    check_near(got, expect);
    if (got.chirp_bandwidth_hz > 0) ++with_chirp;
    // written out and read back, bit for bit
    check_same_sonar(parse_sonar(format_sonar_yaml(got), "written.yaml"), got);
    // the renderer accepts every sonar the loader accepts
    try {
      const auto setup = render::make_sonar_setup(got, scene::WaterDesc{});
      CHECK(setup.bins >= 1);
      CHECK(setup.bins <= kMaxSamplesPerSide);
    } catch (const std::exception& e) {
      FAIL("make_sonar_setup rejected a loaded sonar: " << e.what());
    }

    for (int c = 0; c < kCorruptionsPerSample; ++c) {
      std::vector<Entry> bad = entries;
      std::string expect_path;
      std::string what;
      Rng& rng = gen.rng();
      const double u = rng.uniform();
      if (u < 0.15 || bad.empty()) {
        bad.push_back({"zz_unknown", "1"});
        expect_path = "zz_unknown";
        what = "unknown key";
      } else if (u < 0.25) {
        // a rule broken on purpose with both of its keys set
        switch (rng.below(4)) {
          case 0:
            bad.push_back({"max_range_m", "1000"});
            bad.push_back({"bin_size_cm", "1"});
            expect_path = "bin_size_cm";
            break;
          case 1:
            bad.push_back({"frequency_khz", "50"});
            bad.push_back({"array_length_m", "0.025"});
            expect_path = "array_length_m";
            break;
          case 2:
            bad.push_back({"bin_size_cm", "2"});
            bad.push_back({"chirp_bandwidth_khz", "5"});
            expect_path = "chirp_bandwidth_khz";
            break;
          default:
            bad.push_back({"frequency_khz", "60"});
            bad.push_back({"array_length_m", "1"});
            bad.push_back({"bin_size_cm", "5"});
            bad.push_back({"chirp_bandwidth_khz", "130"});
            expect_path = "chirp_bandwidth_khz";
            break;
        }
        // the new entries replace any earlier ones of the same key (no duplicate keys)
        std::vector<Entry> dedup;
        for (std::size_t i = 0; i < bad.size(); ++i) {
          bool later = false;
          for (std::size_t j = i + 1; j < bad.size(); ++j)
            later = later || bad[j].key == bad[i].key;
          if (!later) dedup.push_back(bad[i]);
        }
        bad = dedup;
        what = "broken rule at " + expect_path;
      } else {
        Entry& e = bad[rng.below(bad.size())];
        expect_path = e.key;
        std::vector<std::string> options;
        if (e.key == "preset") {
          options = {"zz_no_such_preset", "[1, 2]", "{a: 1}", "~", "sidescan"};
        } else {
          const auto& specs = key_specs();
          const auto it = std::find_if(specs.begin(), specs.end(),
                                       [&](const KeySpec& s) { return s.key == e.key; });
          REQUIRE(it != specs.end());
          switch (it->kind) {
            case Kind::kReal:
              options = {"abc",
                         ".nan",
                         ".inf",
                         "'5'",
                         "[1, 2]",
                         "{a: 1}",
                         "~",
                         "1e999",
                         "true",
                         real_text(it->lo - 0.5 * std::max(std::fabs(it->lo), 1.0)),
                         real_text(it->hi + 0.5 * std::max(std::fabs(it->hi), 1.0)),
                         real_text(it->hi + 1e-9 * std::max(std::fabs(it->hi), 1.0))};
              break;
            case Kind::kInt:
              options = {"1.5", "abc", "-1",         std::to_string(static_cast<int>(it->hi) + 1),
                         "~",   "[1]", "99999999999"};
              break;
            case Kind::kBool:
              options = {"yes", "1", "~", "[true]", "'true'"};
              break;
            case Kind::kWord:
              options = {"zz_word", "[1, 2]", "{a: 1}", "~", "7"};
              break;
            case Kind::kText:
              options = {"[1, 2]", "{a: 1}", "~"};
              break;
          }
        }
        e.text = options[rng.below(options.size())];
        what = "set " + e.key + " to '" + e.text + "'";
      }
      INFO("corruption: " << what << "\n" << map_text(bad, flow, 0));
      ++corruptions;
      try {
        parse_either(bad, nested, flow, file);
        FAIL("corrupted sonar accepted");
      } catch (const ConfigError& e) {
        const std::string msg = e.what();
        INFO("message: " << msg);
        CHECK(msg.rfind(file + ": ", 0) == 0);
        CHECK(contains(msg, "; allowed: "));
        CHECK(e.first().path == (nested ? "sonar." : "") + expect_path);
      } catch (const std::exception& e) {
        FAIL("not a ConfigError: " << e.what());
      }
    }
  }
  CHECK(corruptions == kSamples * kCorruptionsPerSample);
  CHECK(with_chirp > 10);  // the chirp rules were exercised by valid samples too
}

TEST_CASE("sonar_loader: random byte edits give a sonar or a ConfigError, never a crash") {
  const std::string full = format_sonar_yaml(builtin_sonar("sas_3cm")) + "preset: sas_3cm\n";
  Rng rng(11, RngStream::kDataset, 7);
  const auto n = feed_byte_edits(full, rng, 3000, [](const std::string& text, const char* name) {
    const auto d = parse_sonar(text, name);
    CHECK_NOTHROW(render::make_sonar_setup(d, scene::WaterDesc{}));
  });
  CHECK(n.accepted > 0);
  CHECK(n.rejected > 0);
}
